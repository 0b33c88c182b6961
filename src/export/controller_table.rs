//! The corrected joint table in the form controllers that accept an
//! external compensation table take it (issue 34, `dh-table`): `alpha`,
//! `a`, `d`, `theta`, `beta`, one value per joint, millimetres and degrees,
//! for the one chain `A_i = Rz(theta_i + q_i) Tz(d_i) Tx(a_i) Rx(alpha_i)
//! Ry(beta_i)`. A DH link has `beta = 0`, a Hayati link `d = 0`
//! (method.md §5), so one formula evaluates both and reproduces `forward`'s
//! flange exactly. As INI text (the default) or JSON naming its units.

use std::fmt::Write;

use serde::Serialize;

use super::header::ExportHeader;
use crate::schema::robot::{Convention, KinematicsDoc};

/// The chain the table's numbers mean, written into both forms.
pub const CHAIN: &str =
    "A_i = Rz(theta_i + q_i) Tz(d_i) Tx(a_i) Rx(alpha_i) Ry(beta_i), base_to_flange = A_1 ... A_n";

/// Units of the five rows.
#[derive(Debug, Clone, Serialize)]
pub struct TableUnits {
    pub alpha: &'static str,
    pub a: &'static str,
    pub d: &'static str,
    pub theta: &'static str,
    pub beta: &'static str,
}

const UNITS: TableUnits = TableUnits {
    alpha: "deg",
    a: "mm",
    d: "mm",
    theta: "deg",
    beta: "deg",
};

/// The `dh-table` document (JSON form).
#[derive(Debug, Clone, Serialize)]
pub struct ControllerTable {
    /// The set, its version, status and controller (the header comment of
    /// the text form).
    pub set: ExportHeader,
    pub chain: &'static str,
    pub units: TableUnits,
    /// Link twist per joint (deg).
    pub alpha: Vec<f64>,
    /// Link length per joint (mm).
    pub a: Vec<f64>,
    /// Link offset along the joint axis per joint (mm; 0 on Hayati links).
    pub d: Vec<f64>,
    /// Joint zero offset per joint (deg), added to the controller's angle.
    pub theta: Vec<f64>,
    /// Hayati tilt about y per joint (deg; 0 on DH links).
    pub beta: Vec<f64>,
}

/// The table of `kinematics` (a set's identified joints).
pub fn controller_table(header: ExportHeader, kinematics: &KinematicsDoc) -> ControllerTable {
    let joints = &kinematics.joints;
    let hayati = |c: Option<Convention>| matches!(c, Some(Convention::Hayati));
    ControllerTable {
        set: header,
        chain: CHAIN,
        units: UNITS,
        alpha: joints.iter().map(|j| j.alpha_deg).collect(),
        a: joints.iter().map(|j| j.a_mm).collect(),
        d: joints
            .iter()
            .map(|j| if hayati(j.convention) { 0.0 } else { j.d_mm })
            .collect(),
        theta: joints.iter().map(|j| j.theta_offset_deg).collect(),
        beta: joints
            .iter()
            .map(|j| {
                if hayati(j.convention) {
                    j.beta_deg
                } else {
                    0.0
                }
            })
            .collect(),
    }
}

/// The INI text: the header as `;` comments, a `[units]` section and the
/// `[dh_table]` rows, values comma-separated in joint order, each the
/// shortest decimal that reads back to the same f64.
pub fn write_ini(table: &ControllerTable) -> String {
    let mut s = table.set.comment("dh-table", ";");
    let _ = writeln!(s, "; {CHAIN}");
    let u = &table.units;
    let _ = writeln!(
        s,
        "\n[units]\nalpha = {}\na = {}\nd = {}\ntheta = {}\nbeta = {}",
        u.alpha, u.a, u.d, u.theta, u.beta
    );
    let _ = writeln!(s, "\n[dh_table]\njoints = {}", table.a.len());
    for (key, row) in [
        ("alpha", &table.alpha),
        ("a", &table.a),
        ("d", &table.d),
        ("theta", &table.theta),
        ("beta", &table.beta),
    ] {
        let values: Vec<String> = row.iter().map(|v| format!("{v}")).collect();
        let _ = writeln!(s, "{key} = {}", values.join(", "));
    }
    s
}
