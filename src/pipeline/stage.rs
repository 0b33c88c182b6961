//! The stages of a calibration job and the share of the progress bar each
//! one takes.

/// The stages a job goes through, in order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    Validate,
    Detect,
    CalibrateCamera,
    MeasurePoses,
    Identify,
    Report,
}

impl Stage {
    pub fn as_str(self) -> &'static str {
        match self {
            Stage::Validate => "validate",
            Stage::Detect => "detect",
            Stage::CalibrateCamera => "calibrate_camera",
            Stage::MeasurePoses => "measure_poses",
            Stage::Identify => "identify",
            Stage::Report => "report",
        }
    }
}

/// Fraction of the whole job at which each stage starts (progress bars).
const STAGE_START: [(Stage, f64); 6] = [
    (Stage::Validate, 0.0),
    (Stage::Detect, 0.05),
    (Stage::CalibrateCamera, 0.55),
    (Stage::MeasurePoses, 0.7),
    (Stage::Identify, 0.75),
    (Stage::Report, 0.97),
];

pub(super) fn stage_span(stage: Stage) -> (f64, f64) {
    let i = STAGE_START
        .iter()
        .position(|(s, _)| *s == stage)
        .unwrap_or(0);
    let end = STAGE_START.get(i + 1).map_or(1.0, |(_, f)| *f);
    (STAGE_START[i].1, end)
}
