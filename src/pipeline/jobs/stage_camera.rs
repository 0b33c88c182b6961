//! A stage session's job (issue 18, paper section 4): after the detect
//! stage, the stage calibration of `robocal-calib` (the intrinsics fitted
//! with the stage's translations as constraints, every image's camera
//! position, the paper's assessment per sequence), then its parameter set
//! and report ([`crate::pipeline::stage_results`]). No robot is identified.

use nalgebra::Vector3;
use robocal_calib::camera::calibrate::CalibrationOptions;
use robocal_calib::camera::observations::ImageSize;
use robocal_calib::stage::{calibrate_stage, StageError, StageView};

use crate::domain::{CalibratedSet, Target};
use crate::pipeline::camera_stage::view_of;
use crate::pipeline::measure::Measured;
use crate::pipeline::stage_results::stage_output;
use crate::pipeline::{Input, Output, PipelineError, Stage};
use crate::schema::session::CameraDoc;

/// The rest of a stage session's job after the detect stage.
pub fn run(
    input: &Input,
    measured: &Measured,
    target: &Target,
    camera: &CameraDoc,
    notes: Vec<String>,
    within: &dyn Fn(Stage, &str, f64),
) -> Result<Output, PipelineError> {
    within(Stage::CalibrateCamera, "stage bundle", 0.0);
    let size = ImageSize {
        width: camera.width,
        height: camera.height,
    };
    let (mut views, mut view_pose) = (Vec::new(), Vec::new());
    for (i, points) in measured.points.iter().enumerate() {
        let (Some(points), Some(reading)) = (points, input.poses[i].stage_reading) else {
            continue;
        };
        views.push(StageView {
            sequence: reading.sequence,
            stage_position_mm: Vector3::from(reading.stage_position_mm),
            observations: view_of(points, target, size),
        });
        view_pose.push(i);
    }
    let options = CalibrationOptions {
        dot_diameter_mm: target.dot_diameter_mm(),
        ..CalibrationOptions::default()
    };
    let fit = calibrate_stage(&views, &options).map_err(|e| stage_error(e, &view_pose, input))?;
    within(Stage::Report, "building the report", 0.0);
    let out = stage_output(input, measured, &fit, &view_pose, notes);
    // A stage set holds a camera, no robot model: nothing to be better
    // than, so only a non-finite result is held back (as a hand–eye set).
    let after = out.report.after.norm.mean_mm;
    let gate = crate::pipeline::gate::outcome(
        after,
        f64::INFINITY,
        "no earlier set (a stage calibration of the camera)".into(),
        f64::INFINITY,
        Vec::new(),
        false,
    );
    let mut report = out.report;
    report.gate = Some(gate.report);
    within(Stage::Report, "done", 1.0);
    Ok(Output {
        parameter_set: Some(crate::pipeline::output::new_set(
            CalibratedSet::StageCamera(out.parameters),
            &report,
            gate.release,
        )?),
        summary: out.summary,
        detections: Vec::new(),
        check: None,
    })
}

/// The stage layout's refusals name the request field (422 at the job's
/// start, [`crate::service::stage_layout`], so a job rarely meets them:
/// here when failed detections left a sequence short); the camera's are
/// numerical, with the pose ids for view indices.
fn stage_error(e: StageError, view_pose: &[usize], input: &Input) -> PipelineError {
    match e {
        StageError::TooFewPositions { .. }
        | StageError::CollinearPositions { .. }
        | StageError::NonFinitePosition { .. } => PipelineError::invalid(e.field(), e.to_string()),
        other => {
            let mut message = other.to_string();
            for (view, &pose) in view_pose.iter().enumerate().rev() {
                message = message.replace(
                    &format!("view {view}"),
                    &format!("pose {}", input.poses[pose].id),
                );
            }
            PipelineError::numerical(Stage::CalibrateCamera, message)
        }
    }
}
