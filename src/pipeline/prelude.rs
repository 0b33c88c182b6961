//! The stages every one-session job shares before its own: validate, then
//! per instrument detect and calibrate the camera (a camera session) or
//! detect alone (a stage session); a tracker session measures no images.

use std::sync::atomic::{AtomicBool, Ordering};

use super::{
    board_turn, camera_stage, detections, measure, session_cause, validate, Input, PipelineError,
    Stage, Summary,
};
use crate::domain::Target;
use crate::schema::session::{CameraDoc, Instrument};
use crate::schema::{FieldError, PoseDoc};
use crate::store::PoseDetection;

/// What the shared stages hand a camera or tracker session's job.
pub struct Prelude {
    /// The notes the stages made, for the report.
    pub notes: Vec<String>,
    /// Every image's points (camera sessions).
    pub measured: Option<measure::Measured>,
    /// The camera calibration (camera sessions).
    pub camera: Option<camera_stage::CameraStep>,
}

impl Prelude {
    /// The camera's measurements, for a job that needs them (a hand–eye
    /// session is a camera session by its kind).
    pub fn camera_parts(
        &self,
    ) -> Result<(&measure::Measured, &camera_stage::CameraStep), PipelineError> {
        match (&self.measured, &self.camera) {
            (Some(m), Some(c)) => Ok((m, c)),
            _ => Err(PipelineError::invalid(
                "session",
                "this job needs a camera session (images of a target)",
            )),
        }
    }
}

/// What the shared stages hand a stage session's job.
pub struct StagePrelude<'a> {
    pub notes: Vec<String>,
    pub measured: measure::Measured,
    pub target: Target,
    pub camera: &'a CameraDoc,
}

/// The validate stage, reported done.
pub fn validated(
    input: &Input,
    within: &dyn Fn(Stage, &str, f64),
    cancel: &AtomicBool,
) -> Result<Summary, PipelineError> {
    let checked = validate(input, within, cancel)?;
    within(Stage::Validate, "inputs valid", 1.0);
    Ok(checked)
}

/// Validate, then a camera session's detect and camera stages (nothing
/// more for a tracker session).
pub fn run(
    input: &Input,
    within: &dyn Fn(Stage, &str, f64),
    detected: &dyn Fn(Vec<PoseDetection>),
    cancel: &AtomicBool,
    cause: &mut Option<String>,
) -> Result<Prelude, PipelineError> {
    validated(input, within, cancel)?;
    let mut notes = Vec::new();
    let (measured, camera) = match input.session.instrument {
        Instrument::Camera => {
            let (measured, step) =
                camera_session(input, within, detected, cancel, cause, &mut notes)?;
            (Some(measured), Some(step))
        }
        Instrument::Tracker | Instrument::Stage => (None, None),
    };
    check_cancelled(cancel)?;
    within(Stage::MeasurePoses, "camera poses measured", 1.0);
    Ok(Prelude {
        notes,
        measured,
        camera,
    })
}

/// Validate, then a stage session's detect stage.
pub fn run_stage<'a>(
    input: &'a Input,
    within: &dyn Fn(Stage, &str, f64),
    detected: &dyn Fn(Vec<PoseDetection>),
    cancel: &AtomicBool,
    cause: &mut Option<String>,
) -> Result<StagePrelude<'a>, PipelineError> {
    validated(input, within, cancel)?;
    let (target, camera) = board_and_camera(input)?;
    let measured = detect(input, &target, within, detected, cancel, cause)?;
    let notes = cause
        .as_ref()
        .map(|c| format!("{c}."))
        .into_iter()
        .collect();
    Ok(StagePrelude {
        notes,
        measured,
        target,
        camera,
    })
}
/// A camera session's detect and camera stages: every image's dots, the
/// camera calibration and the half-turn resolution, with their notes.
pub fn camera_session(
    input: &Input,
    within: &dyn Fn(Stage, &str, f64),
    detected: &dyn Fn(Vec<PoseDetection>),
    cancel: &AtomicBool,
    cause: &mut Option<String>,
    notes: &mut Vec<String>,
) -> Result<(measure::Measured, camera_stage::CameraStep), PipelineError> {
    let (target, camera_doc) = board_and_camera(input)?;
    let mut measured = detect(input, &target, within, detected, cancel, cause)?;
    notes.extend(cause.as_ref().map(|c| format!("{c}.")));
    within(
        Stage::CalibrateCamera,
        "Tsai start and joint refinement",
        0.0,
    );
    let mut step = camera_stage::calibrate_camera(
        &input.poses,
        &measured,
        &target,
        camera_doc,
        input.options.refine_intrinsics,
        input.fixed_camera.as_ref(),
    )?;
    let turned_note = board_turn::resolve(
        &input.robot,
        &input.poses,
        &target,
        &mut step,
        &mut measured,
    )?;
    if !step.left_out.is_empty() {
        let names: Vec<String> = step
            .left_out
            .iter()
            .map(|(i, why)| format!("{} ({why})", input.poses[*i].label))
            .collect();
        notes.push(format!(
            "{} image(s) left out of the camera calibration: {}.",
            names.len(),
            names.join(", ")
        ));
    }
    notes.extend(turned_note);
    if let Some(fixed) = &input.fixed_camera {
        notes.push(format!(
            "Camera intrinsics held fixed at those of calibration {} (camera_calibration_id); only the camera poses were fitted.",
            fixed.calibration_id
        ));
    } else if !input.options.refine_intrinsics {
        notes.push(
            "Camera intrinsics from the paper's Tsai sequence (refine_intrinsics: false), not refined.".to_string(),
        );
    }
    Ok((measured, step))
}

/// The detect stage of a camera or stage session: every image's dots,
/// handed to `detected` at once; `cause` gets the session-level cause of
/// the failures.
pub fn detect(
    input: &Input,
    target: &Target,
    within: &dyn Fn(Stage, &str, f64),
    detected: &dyn Fn(Vec<PoseDetection>),
    cancel: &AtomicBool,
    cause: &mut Option<String>,
) -> Result<measure::Measured, PipelineError> {
    let measured = measure::measure(
        &input.poses,
        target,
        &input.images,
        &|message, fraction| within(Stage::Detect, message, fraction),
        cancel,
    )?;
    if cancel.load(Ordering::Relaxed) {
        return Err(PipelineError::Cancelled);
    }
    detected(detections::detected(&input.poses, &measured));
    *cause = session_cause::of(&measured, target);
    Ok(measured)
}

/// The session's board, typed, and its camera (camera and stage sessions).
pub fn board_and_camera(input: &Input) -> Result<(Target, &CameraDoc), PipelineError> {
    match (&input.session.target, &input.session.camera) {
        (Some(t), Some(c)) => Ok((Target::from_doc(t).map_err(PipelineError::Invalid)?, c)),
        _ => Err(PipelineError::Invalid(vec![FieldError::new(
            "session",
            "a camera or stage session needs target and camera",
        )])),
    }
}

/// The session's `flange_to_camera_guess`, else identity.
pub fn flange_guess(input: &Input) -> robocal_calib::geometry::Pose {
    match &input.session.flange_to_camera_guess {
        Some(p) => pose_of(p),
        None => robocal_calib::geometry::Pose::identity(),
    }
}

/// `Cancelled` once `cancel` is set.
pub fn check_cancelled(cancel: &AtomicBool) -> Result<(), PipelineError> {
    if cancel.load(Ordering::Relaxed) {
        Err(PipelineError::Cancelled)
    } else {
        Ok(())
    }
}

/// A contract pose (the exact matrix when given).
pub fn pose_of(doc: &PoseDoc) -> robocal_calib::geometry::Pose {
    doc.matrix
        .and_then(|m| robocal_calib::geometry::pose_from_matrix_rows(&m).ok())
        .or_else(|| {
            robocal_calib::geometry::pose_from_xyz_rpy_deg(doc.translation_mm, doc.rotation_deg)
                .ok()
        })
        .unwrap_or_else(robocal_calib::geometry::Pose::identity)
}
