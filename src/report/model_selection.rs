//! The report's account of how much of the kinematics the campaign could
//! carry (docs/method.md §6.8 "Model selection by held-out groups"): the
//! arm configurations it has, whether its validation poses repeat them,
//! the ladder of models with each rung's prediction of configurations it
//! was not fitted to, the rung kept and why, and what the campaign could
//! not determine.

use serde::{Deserialize, Serialize};
use std::fmt::Write;
use utoipa::ToSchema;

use super::format::{escape_xml, significant};

/// One rung of the ladder.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct RungReport {
    /// `hand_eye`, `joint_offsets`, `joint_offsets_prior`, `full`,
    /// `full_prior` or `full_terms` (full geometry with the non-geometric
    /// terms the selection keeps).
    pub rung: String,
    pub description: String,
    /// Free parameters (kinematics, board and hand–eye).
    pub parameters: usize,
    /// RMS reprojection error of the held-out configurations' image points
    /// (px; camera jobs).
    pub heldout_rms_px: Option<f64>,
    /// RMS length of the held-out configurations' tool position errors
    /// (mm; tracker jobs, where the rungs are judged on it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub heldout_rms_mm: Option<f64>,
    /// Mean 3-D camera position error at the held-out poses (mm).
    pub heldout_mean_mm: Option<f64>,
    /// Why the rung could not be scored, if it could not.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub failed: Option<String>,
}

/// How the model was chosen and how it was validated.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct ModelSelectionReport {
    /// Distinct arm configurations (joints 1–3 within a few degrees, or
    /// the poses' `group`) among the poses compared.
    pub configurations: usize,
    /// Whether validation poses share configurations with calibration poses.
    pub val_shares_configurations: bool,
    /// `leave_group_out` (the headline before/after are held-out
    /// configurations' predictions) or `validation_poses`.
    pub validation: String,
    /// Folds of the held-out comparison.
    pub folds: usize,
    pub rungs: Vec<RungReport>,
    /// The rung kept.
    pub chosen: String,
    pub reason: String,
    /// Parameters the campaign could not determine: held at nominal (or
    /// at their prior) whatever the data said.
    pub undetermined: Vec<String>,
}

/// Leave-group-out validation (the headline figures are held-out).
pub const LEAVE_GROUP_OUT: &str = "leave_group_out";
/// The uploaded (or held-out) validation poses.
pub const VALIDATION_POSES: &str = "validation_poses";

/// The validation a report's headline uses: leave-group-out when the
/// validation poses share configurations with the calibration poses
/// (method.md §7.6), else the validation poses themselves.
pub fn validation_basis(val_shares_configurations: bool) -> String {
    if val_shares_configurations {
        LEAVE_GROUP_OUT
    } else {
        VALIDATION_POSES
    }
    .to_string()
}

fn cell(v: Option<f64>, digits: i32) -> String {
    v.map_or_else(|| "—".to_string(), |x| significant(x, digits))
}

/// The HTML section (inside the identifiability part of the page).
pub fn html(page: &mut String, m: &ModelSelectionReport) {
    let validation = if m.validation == LEAVE_GROUP_OUT {
        "the validation poses repeat calibration configurations, so the before/after figures above are predictions of held-out configurations (leave-group-out)"
    } else {
        "the validation poses are configurations the fit never saw"
    };
    // Tracker jobs judge the rungs on positions, camera jobs on pixels.
    let on_positions = m.rungs.iter().any(|r| r.heldout_rms_mm.is_some());
    let unit = if on_positions { "mm" } else { "px" };
    let _ = write!(
        page,
        "<section>\n<h3>Model chosen by held-out configurations</h3>\n<p>{} distinct arm configurations, {} folds; {}.</p>\n\
         <table class=\"data\"><tr><th>model</th><th class=\"num\">parameters</th>\
         <th class=\"num\">held-out RMS [{unit}]</th><th class=\"num\">held-out mean [mm]</th><th></th></tr>\n",
        m.configurations, m.folds, validation
    );
    for r in &m.rungs {
        let rms = if on_positions {
            r.heldout_rms_mm
        } else {
            r.heldout_rms_px
        };
        let mark = if r.rung == m.chosen { "kept" } else { "" };
        let _ = writeln!(
            page,
            "<tr><td>{} <span class=\"muted\">{}</span></td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td>{}</td></tr>",
            escape_xml(&r.rung),
            escape_xml(&r.description),
            r.parameters,
            cell(rms, 4),
            cell(r.heldout_mean_mm, 4),
            r.failed.as_deref().map(escape_xml).unwrap_or_else(|| mark.to_string())
        );
    }
    let _ = writeln!(page, "</table>\n<p>{}</p>", escape_xml(&m.reason));
    if !m.undetermined.is_empty() {
        let _ = writeln!(
            page,
            "<p>Not determined by this campaign: {}. Shoot more arm configurations that move these joints (a campaign plan with <code>extend_session</code> proposes them).</p>",
            escape_xml(&m.undetermined.join(", "))
        );
    }
    page.push_str("</section>\n");
}
