//! The release gate's comparison in a report (issue 17): what the set was
//! compared with on the same validation poses, and the first line every
//! rendering starts with when the set is worse than before.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::format::mm;
use super::Report;

/// What the gate compared at the end of the job.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct GateReport {
    /// The status the gate gave: `approved` or `candidate`.
    pub status: String,
    /// Why, in a sentence.
    pub reason: String,
    /// What it was compared with: `nominal`, or the approved set
    /// `"{serial}/{version}"` (its kinematics with the base and hand–eye
    /// frames re-fitted on this session's calibration poses, as the
    /// nominal "before" is).
    pub compared_with: String,
    /// Mean 3-D validation error of what it was compared with (mm).
    pub compared_mean_mm: f64,
    /// Mean 3-D validation error of this set (mm).
    pub mean_mm: f64,
    /// This set predicts the same validation poses worse than before.
    pub worse: bool,
}

/// The warning that opens every rendering of a set worse than before.
pub fn worse_line(report: &Report) -> Option<String> {
    let gate = report.gate.as_ref().filter(|g| g.worse)?;
    Some(format!(
        "WORSE THAN BEFORE: {} mm against {} mm for {} on the same validation poses; \
         held back as a candidate, not served as latest.",
        mm(gate.mean_mm),
        mm(gate.compared_mean_mm),
        gate.compared_with
    ))
}
