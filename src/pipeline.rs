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

mod camera_stage;
mod identify_stage;
mod measure;
pub mod results;

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
    pub session_id: String,
    /// The robot's nominal model, as the numerics take it (radians).
    pub robot: RobotModel,
    /// The same joint table as stored and served (degrees, conventions explicit).
    pub kinematics: KinematicsDoc,
    pub session: SessionBody,
    pub poses: Vec<PoseInput>,
    pub options: CalibrationOptions,
    /// Test hook (`ROBOCAL_TEST_STAGE_DELAY_MS`): sleep per pose in validation.
    pub test_stage_delay: Duration,
    /// Test hook (`ROBOCAL_TEST_VALIDATE_ONLY`): stop after validation.
    pub validate_only: bool,
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

/// Fraction of the whole job at which each stage starts (progress bars).
const STAGE_START: [(Stage, f64); 6] = [
    (Stage::Validate, 0.0),
    (Stage::Detect, 0.05),
    (Stage::CalibrateCamera, 0.55),
    (Stage::MeasurePoses, 0.7),
    (Stage::Identify, 0.75),
    (Stage::Report, 0.97),
];

fn stage_span(stage: Stage) -> (f64, f64) {
    let i = STAGE_START
        .iter()
        .position(|(s, _)| *s == stage)
        .unwrap_or(0);
    let end = STAGE_START.get(i + 1).map_or(1.0, |(_, f)| *f);
    (STAGE_START[i].1, end)
}

/// Runs the calibration job: validate, detect, calibrate the camera,
/// measure the poses, identify, report. `progress(stage, message,
/// fraction)` is called with `fraction` in `[0, 1]` for the whole job.
pub fn run(
    input: &Input,
    progress: &dyn Fn(Stage, &str, f64),
    cancel: &AtomicBool,
) -> Result<Output, PipelineError> {
    let within = |stage: Stage, message: &str, fraction: f64| {
        let (lo, hi) = stage_span(stage);
        progress(stage, message, lo + (hi - lo) * fraction.clamp(0.0, 1.0));
    };
    let check_cancel = || {
        if cancel.load(Ordering::Relaxed) {
            Err(PipelineError::Cancelled)
        } else {
            Ok(())
        }
    };
    let checked = validate(input, &within, cancel)?;
    within(Stage::Validate, "inputs valid", 1.0);
    if input.validate_only {
        return Ok(Output {
            parameter_set: None,
            summary: checked,
        });
    }
    let (measured, camera) = match input.session.instrument {
        Instrument::Camera => {
            let (target, camera_doc) = match (&input.session.target, &input.session.camera) {
                (Some(t), Some(c)) => (t, c),
                _ => {
                    return Err(PipelineError::Invalid(vec![FieldError::new(
                        "session",
                        "a camera session needs target and camera",
                    )]))
                }
            };
            let measured = measure::measure(
                &input.poses,
                target,
                &|message, fraction| within(Stage::Detect, message, fraction),
                cancel,
            )?;
            check_cancel()?;
            within(
                Stage::CalibrateCamera,
                "Tsai start and joint refinement",
                0.0,
            );
            let step = camera_stage::calibrate_camera(
                &input.poses,
                &measured,
                target,
                camera_doc,
                input.options.refine_intrinsics,
            )?;
            (Some(measured), Some(step))
        }
        Instrument::Tracker => (None, None),
    };
    check_cancel()?;
    within(Stage::MeasurePoses, "camera poses measured", 1.0);
    let usable: Vec<usize> = (0..input.poses.len())
        .filter(|&i| camera.as_ref().is_none_or(|c| c.view_pose.contains(&i)))
        .collect();
    let kind = input
        .options
        .measurement
        .unwrap_or(match input.session.instrument {
            Instrument::Camera => crate::schema::job::Measurement::Pose,
            Instrument::Tracker => crate::schema::job::Measurement::Position,
        });
    let guess = match &input.session.flange_to_camera_guess {
        Some(p) => pose_of(p),
        None => robocal_calib::geometry::Pose::identity(),
    };
    within(Stage::Identify, "kinematic identification", 0.0);
    let identified = identify_stage::identify_robot(
        &input.robot,
        &input.poses,
        camera.as_ref(),
        guess,
        kind,
        input.options.validation,
        input.options.joint_refinement,
        &usable,
    )?;
    check_cancel()?;
    within(Stage::Report, "building the report", 0.0);
    let mut notes = Vec::new();
    if let Some(m) = &measured {
        if !m.failures.is_empty() {
            notes.push(format!(
                "{} of {} images were not used (see detection failures).",
                m.failures.len(),
                m.points.len()
            ));
        }
    }
    let context = results::Context {
        serial: &input.serial,
        session_id: &input.session_id,
        instrument: if camera.is_some() {
            robocal_calib::kinematics::Instrument::Camera
        } else {
            robocal_calib::kinematics::Instrument::Tracker
        },
        measurement: match kind {
            crate::schema::job::Measurement::Pose => "pose",
            crate::schema::job::Measurement::Position => "position",
        },
        poses: &input.poses,
        measured: measured.as_ref(),
        camera: camera.as_ref(),
        notes,
    };
    let set = results::parameter_set(&context, &identified);
    let report = results::report(&context, &identified, &set);
    within(Stage::Report, "done", 1.0);
    Ok(Output {
        parameter_set: Some(NewParameterSet {
            parameters: set.to_json(),
            report: serde_json::to_value(&report).unwrap_or_default(),
        }),
        summary: results::summary(&identified),
    })
}

/// A contract pose (the exact matrix when given).
fn pose_of(doc: &PoseDoc) -> robocal_calib::geometry::Pose {
    doc.matrix
        .and_then(|m| robocal_calib::geometry::pose_from_matrix_rows(&m).ok())
        .or_else(|| {
            robocal_calib::geometry::pose_from_xyz_rpy_deg(doc.translation_mm, doc.rotation_deg)
                .ok()
        })
        .unwrap_or_else(robocal_calib::geometry::Pose::identity)
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
