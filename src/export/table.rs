//! The identified table in the robot's own convention (DH or Hayati per
//! joint, api.md "Robots"), with a standard deviation per parameter and
//! which parameters were held and why: as JSON (`dh-json`) and CSV.

use std::fmt::Write;

use serde::Serialize;

use crate::domain::{CovarianceDoc, ParameterSet, TermsDoc};
use crate::report::{IdentifiabilityReport, ParameterReport};
use crate::schema::robot::Convention;
use crate::schema::session::Instrument;
use crate::schema::PoseOut;

/// Why a parameter the identifiability analysis fixed was held (method.md §6).
pub const HELD_REDUNDANT: &str =
    "structurally redundant: it trades against other parameters (the base or tool frame, a neighbouring joint), so it keeps its nominal value";
pub const HELD_WEAK: &str =
    "not determined by this campaign's poses: vary the poses (move the joints involved further) to identify it";

/// One joint's row: value and 1σ of each link parameter, robot convention.
#[derive(Debug, Clone, Serialize)]
pub struct JointRow {
    pub joint: usize,
    pub convention: Convention,
    pub a_mm: f64,
    pub a_mm_std: f64,
    pub alpha_deg: f64,
    pub alpha_deg_std: f64,
    /// DH links only (zero on Hayati links).
    pub d_mm: f64,
    pub d_mm_std: f64,
    pub theta_offset_deg: f64,
    pub theta_offset_deg_std: f64,
    /// Hayati links only (zero on DH links).
    pub beta_deg: f64,
    pub beta_deg_std: f64,
    pub min_deg: f64,
    pub max_deg: f64,
}

/// Every estimated parameter, as the identification reported it.
#[derive(Debug, Clone, Serialize)]
pub struct ParameterRow {
    pub name: String,
    pub unit: String,
    pub nominal: f64,
    pub identified: f64,
    pub std: f64,
    pub held: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub held_because: Option<&'static str>,
}

/// The `dh-json` document.
#[derive(Debug, Clone, Serialize)]
pub struct DhTable {
    pub serial: String,
    pub version: i64,
    pub instrument: Instrument,
    pub joints: Vec<JointRow>,
    /// `target_to_base` (camera) or `instrument_to_base` (tracker).
    pub world_to_base: PoseOut,
    /// `flange_to_camera` (camera) or `flange_to_tool` (tracker).
    pub flange_to_tool: PoseOut,
    pub parameters: Vec<ParameterRow>,
    /// The identified parameters' full covariance (`names`, `units`,
    /// `matrix`); absent for sets stored before it was kept.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub covariance: Option<CovarianceDoc>,
    /// The kept non-geometric terms with σ and units; absent
    /// when the set keeps none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub terms: Option<TermsDoc>,
}

/// The table of a stored parameter set; `identifiability` from its report
/// (absent in sets stored without one: held parameters then give no reason).
pub fn dh_table(
    serial: &str,
    version: i64,
    set: &ParameterSet,
    identifiability: Option<&IdentifiabilityReport>,
) -> DhTable {
    let std_of = |name: String| {
        set.parameters
            .iter()
            .find(|p| p.name == name)
            .map_or(0.0, |p| p.std)
    };
    let joints = set
        .kinematics
        .joints
        .iter()
        .enumerate()
        .map(|(i, j)| {
            let n = i + 1;
            JointRow {
                joint: n,
                convention: j.convention.unwrap_or(Convention::Dh),
                a_mm: j.a_mm,
                a_mm_std: std_of(format!("a_{n}")),
                alpha_deg: j.alpha_deg,
                alpha_deg_std: std_of(format!("alpha_{n}")),
                d_mm: j.d_mm,
                d_mm_std: std_of(format!("d_{n}")),
                theta_offset_deg: j.theta_offset_deg,
                theta_offset_deg_std: std_of(format!("dtheta_{n}")),
                beta_deg: j.beta_deg,
                beta_deg_std: std_of(format!("beta_{n}")),
                min_deg: j.min_deg,
                max_deg: j.max_deg,
            }
        })
        .collect();
    let parameters = set
        .parameters
        .iter()
        .map(|p| parameter_row(p, identifiability))
        .collect();
    DhTable {
        serial: serial.into(),
        version,
        instrument: set.instrument,
        joints,
        world_to_base: set.world_to_base.clone(),
        flange_to_tool: set.flange_to_tool.clone(),
        parameters,
        covariance: set.covariance.clone(),
        terms: set.terms.clone(),
    }
}

fn parameter_row(p: &ParameterReport, ident: Option<&IdentifiabilityReport>) -> ParameterRow {
    let held_because = match ident {
        Some(id) if p.fixed && id.weak.contains(&p.name) => Some(HELD_WEAK),
        Some(_) if p.fixed => Some(HELD_REDUNDANT),
        _ => None,
    };
    ParameterRow {
        name: p.name.clone(),
        unit: p.unit.clone(),
        nominal: p.nominal,
        identified: p.identified,
        std: p.std,
        held: p.fixed,
        held_because,
    }
}

/// Column names of the CSV: units in the names.
pub const CSV_HEADER: &str = "joint,convention,a_mm,a_mm_std,alpha_deg,alpha_deg_std,d_mm,d_mm_std,theta_offset_deg,theta_offset_deg_std,beta_deg,beta_deg_std,min_deg,max_deg";

/// Column names of the CSV's second table, the kept non-geometric terms
/// (after one empty line; only when the set keeps terms).
pub const CSV_TERMS_HEADER: &str = "term,value,value_std,unit";

/// The joint table as CSV, one row per joint, then the kept terms' table
/// when there are any; numbers in shortest round-trip form.
pub fn write_csv(table: &DhTable) -> String {
    let mut s = String::from(CSV_HEADER);
    s.push('\n');
    for j in &table.joints {
        let convention = match j.convention {
            Convention::Dh => "dh",
            Convention::Hayati => "hayati",
        };
        let _ = writeln!(
            s,
            "{},{convention},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?}",
            j.joint,
            j.a_mm,
            j.a_mm_std,
            j.alpha_deg,
            j.alpha_deg_std,
            j.d_mm,
            j.d_mm_std,
            j.theta_offset_deg,
            j.theta_offset_deg_std,
            j.beta_deg,
            j.beta_deg_std,
            j.min_deg,
            j.max_deg
        );
    }
    if let Some(terms) = &table.terms {
        s.push('\n');
        s.push_str(CSV_TERMS_HEADER);
        s.push('\n');
        for k in &terms.terms {
            let _ = writeln!(s, "{},{:?},{:?},{}", k.name, k.value, k.std_dev, k.unit);
        }
    }
    s
}
