//! The calibration job: one synchronous function joining the numerics of
//! `robocal-calib` for a session (detect → camera → poses → identify →
//! report). It runs on a blocking thread, reports progress through a
//! callback and stops when `cancel` becomes true.
//!
//! Today only the input-validation stage exists: enough poses, joint vectors
//! matching the robot, images decodable at the session camera's size. The
//! numerical stages plug in after [`validate`], returning their parameter set
//! and report in [`Output::parameter_set`]; the worker stores them as the
//! serial's next version in the transaction that finishes the job.

use std::io::Cursor;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use serde_json::json;

use robocal_calib::kinematics::RobotModel;

use crate::domain::NewParameterSet;
use crate::schema::job::{CalibrationOptions, Validation};
use crate::schema::robot::KinematicsDoc;
use crate::schema::session::{ImagePointDoc, Instrument, PoseSet, SessionBody};
use crate::schema::{FieldError, PoseDoc};

/// Fewest calibration poses a job accepts. Identification needs more
/// observations than unknowns; the identification stage refines this check.
pub const MIN_CALIBRATION_POSES: usize = 3;
/// Memory a single image decode may use, bytes.
pub const MAX_DECODE_ALLOC_BYTES: u64 = 1 << 30;

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

/// Everything a job needs, loaded from the store by the worker.
#[derive(Debug, Clone)]
pub struct Input {
    pub serial: String,
    /// The robot's nominal model, as the numerics take it (radians).
    pub robot: RobotModel,
    /// The same joint table as stored and served (degrees, conventions explicit).
    pub kinematics: KinematicsDoc,
    pub session: SessionBody,
    pub poses: Vec<PoseInput>,
    pub options: CalibrationOptions,
    /// Test hook (`ROBOCAL_TEST_STAGE_DELAY_MS`): sleep per pose in validation.
    pub test_stage_delay: Duration,
}

#[derive(Debug, Clone)]
pub struct PoseInput {
    pub id: String,
    pub joints_deg: Vec<f64>,
    pub set: PoseSet,
    /// Encoded PNG/JPEG bytes when the pose was uploaded with an image.
    pub image: Option<Vec<u8>>,
    pub image_points: Vec<ImagePointDoc>,
    pub measured_position_mm: Option<[f64; 3]>,
    pub measured_pose: Option<PoseDoc>,
}

#[derive(Debug, Clone)]
pub struct Output {
    /// The identified parameter set and its accuracy report, when the job
    /// identified one (stored as the serial's next version).
    pub parameter_set: Option<NewParameterSet>,
    /// A short summary for the job's `result`.
    pub summary: serde_json::Value,
}

#[derive(Debug, Clone, thiserror::Error)]
pub enum PipelineError {
    /// The session's data cannot be calibrated as it is: not retried.
    #[error("invalid input: {}", describe(.0))]
    Invalid(Vec<FieldError>),
    /// A numerical stage failed (degenerate data): not retried.
    #[error("{stage}: {message}")]
    Numerical {
        stage: &'static str,
        message: String,
    },
    #[error("cancelled")]
    Cancelled,
}

fn describe(errors: &[FieldError]) -> String {
    errors
        .iter()
        .map(|e| format!("{}: {}", e.field, e.message))
        .collect::<Vec<_>>()
        .join("; ")
}

/// Runs the calibration job. `progress(stage, message, fraction)` is called
/// with `fraction` in `[0, 1]` for the whole job.
pub fn run(
    input: &Input,
    progress: &dyn Fn(Stage, &str, f64),
    cancel: &AtomicBool,
) -> Result<Output, PipelineError> {
    let summary = validate(input, progress, cancel)?;
    progress(Stage::Validate, "inputs valid", 1.0);
    Ok(Output {
        parameter_set: None,
        summary,
    })
}

/// The validation stage; returns a summary of what was checked.
pub fn validate(
    input: &Input,
    progress: &dyn Fn(Stage, &str, f64),
    cancel: &AtomicBool,
) -> Result<serde_json::Value, PipelineError> {
    let joint_count = input.robot.dof();
    let mut errors = Vec::new();
    let cal = input.poses.iter().filter(|p| p.set == PoseSet::Cal).count();
    let val = input.poses.len() - cal;
    if cal < MIN_CALIBRATION_POSES {
        errors.push(FieldError::new(
            "poses",
            format!("{cal} calibration poses; at least {MIN_CALIBRATION_POSES} are needed"),
        ));
    }
    if input.options.validation == Validation::Named(crate::schema::job::ValidationNamed::ValSet)
        && val == 0
        && !input.poses.is_empty()
    {
        errors.push(FieldError::new(
            "validation",
            "\"val_set\" needs poses uploaded with set \"val\" (or use holdout_fraction)",
        ));
    }
    let camera = input.session.camera.as_ref();
    let total = input.poses.len().max(1) as f64;
    for (i, pose) in input.poses.iter().enumerate() {
        if cancel.load(Ordering::Relaxed) {
            return Err(PipelineError::Cancelled);
        }
        progress(
            Stage::Validate,
            &format!("pose {} of {}", i + 1, input.poses.len()),
            i as f64 / total,
        );
        let field = |name: &str| format!("poses[{}].{name}", pose.id);
        if pose.joints_deg.len() != joint_count {
            errors.push(FieldError::new(
                field("joints_deg"),
                format!(
                    "{} values for a {joint_count}-joint robot",
                    pose.joints_deg.len()
                ),
            ));
        }
        match input.session.instrument {
            Instrument::Camera => match &pose.image {
                Some(bytes) => {
                    if let Err(message) = check_image(bytes, camera.map(|c| (c.width, c.height))) {
                        errors.push(FieldError::new(field("image"), message));
                    }
                }
                None if pose.image_points.is_empty() => errors.push(FieldError::new(
                    field("image"),
                    "neither image nor image points",
                )),
                None => {}
            },
            Instrument::Tracker => {
                if pose.measured_position_mm.is_none() {
                    errors.push(FieldError::new(field("measured_position_mm"), "missing"));
                }
            }
        }
        if !input.test_stage_delay.is_zero() {
            sleep_cancellable(input.test_stage_delay, cancel)?;
        }
    }
    if !errors.is_empty() {
        return Err(PipelineError::Invalid(errors));
    }
    Ok(json!({
        "stage": Stage::Validate.as_str(),
        "calibration_poses": cal,
        "validation_poses": val,
        "joints": joint_count,
    }))
}

fn sleep_cancellable(total: Duration, cancel: &AtomicBool) -> Result<(), PipelineError> {
    let step = Duration::from_millis(20);
    let mut slept = Duration::ZERO;
    while slept < total {
        if cancel.load(Ordering::Relaxed) {
            return Err(PipelineError::Cancelled);
        }
        std::thread::sleep(step.min(total - slept));
        slept += step;
    }
    Ok(())
}

/// Decodes an image (PNG or JPEG only, bounded memory) and checks its size
/// against the session camera's. Returns `(width, height)`.
pub fn check_image(bytes: &[u8], expected: Option<(u32, u32)>) -> Result<(u32, u32), String> {
    let format = image::guess_format(bytes).map_err(|_| "not a PNG or JPEG image".to_string())?;
    if !matches!(format, image::ImageFormat::Png | image::ImageFormat::Jpeg) {
        return Err(format!(
            "{format:?} images are not accepted; send PNG or JPEG"
        ));
    }
    let mut reader = image::ImageReader::with_format(Cursor::new(bytes), format);
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(MAX_DECODE_ALLOC_BYTES);
    limits.max_image_width = Some(crate::schema::session::MAX_IMAGE_SIDE);
    limits.max_image_height = Some(crate::schema::session::MAX_IMAGE_SIDE);
    reader.limits(limits);
    let img = reader
        .decode()
        .map_err(|e| format!("cannot decode image: {e}"))?;
    let (w, h) = (img.width(), img.height());
    if let Some((ew, eh)) = expected {
        if (w, h) != (ew, eh) {
            return Err(format!("image is {w}x{h}, the session camera is {ew}x{eh}"));
        }
    }
    Ok((w, h))
}
