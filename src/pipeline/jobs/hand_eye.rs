//! A flange-pose session's job after the camera stage (issue 14): the
//! hand–eye fit ([`crate::pipeline::flange_stage`]), then its parameter set and
//! report ([`crate::pipeline::hand_eye_results`]); no kinematics are identified.

use crate::domain::CalibratedSet;
use crate::pipeline::camera_stage::CameraStep;
use crate::pipeline::flange_stage::hand_eye;
use crate::pipeline::measure::Measured;
use crate::pipeline::{PipelineError, Stage};

/// The rest of a flange-pose session's job after the camera stage: the
/// hand–eye fit, then its parameter set and report.
pub fn run(
    input: &crate::pipeline::Input,
    measured: &Measured,
    camera: &CameraStep,
    mut notes: Vec<String>,
    within: &dyn Fn(Stage, &str, f64),
) -> Result<crate::pipeline::Output, PipelineError> {
    within(Stage::Identify, "hand–eye from flange poses", 0.0);
    let step = hand_eye(&input.poses, measured, camera)?;
    within(Stage::Report, "building the report", 0.0);
    if !measured.failures.is_empty() {
        notes.push(format!(
            "{} of {} images were not used (see detection failures).",
            measured.failures.len(),
            measured.points.len()
        ));
    }
    let mut out =
        crate::pipeline::hand_eye_results::hand_eye_output(input, measured, camera, &step, notes);
    // A hand–eye set holds no kinematics to evaluate on another set's
    // terms, and its `before` is its `after` (the flange poses against the
    // images): nothing to be better than, so only a non-finite result is
    // held back, as before the gate every such set was served.
    let after = out.report.after.norm.mean_mm;
    let gate = crate::pipeline::gate::outcome(
        after,
        f64::INFINITY,
        "no earlier set (a hand–eye calibration)".into(),
        f64::INFINITY,
        Vec::new(),
        false,
    );
    out.report.gate = Some(gate.report);
    within(Stage::Report, "done", 1.0);
    Ok(crate::pipeline::Output {
        parameter_set: Some(crate::pipeline::output::new_set(
            CalibratedSet::HandEye(out.parameters),
            &out.report,
            gate.release,
        )?),
        summary: out.summary,
        detections: Vec::new(),
        check: None,
    })
}
