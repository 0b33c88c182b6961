//! Stage "validate": enough poses, joint vectors matching the robot, images
//! of the session camera's size, before any numerics run.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use super::{Input, PipelineError, Stage, Summary, MIN_CALIBRATION_POSES};
use crate::schema::job::Validation;
use crate::schema::session::{Instrument, PoseSet};
use crate::schema::FieldError;

/// The validation stage; returns a summary of what was checked.
pub fn validate(
    input: &Input,
    progress: &dyn Fn(Stage, &str, f64),
    cancel: &AtomicBool,
) -> Result<Summary, PipelineError> {
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
    // A hand–eye session judges on its "val" poses when it has some, else
    // on the calibration poses in the fit: no holdout is needed.
    if input.options.validation == Validation::Named(crate::schema::job::ValidationNamed::ValSet)
        && !input.is_flange_session()
        && input.session.instrument != Instrument::Stage
        && val == 0
        && !input.poses.is_empty()
    {
        errors.push(FieldError::new(
            "validation",
            "\"val_set\" needs poses uploaded with set \"val\" (or use holdout_fraction)",
        ));
    }
    let camera = input.session.camera.as_ref();
    let flange_session = input.is_flange_session();
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
        if input.session.instrument == Instrument::Stage {
            // A stage pose carries the stage's reading instead of joints.
            if pose.stage_reading.is_none() {
                errors.push(FieldError::new(
                    field("stage_position_mm"),
                    "missing: a stage session's images carry the stage's reading",
                ));
            }
        } else if flange_session != pose.flange_pose.is_some() {
            let (has, session) = if flange_session {
                ("joints_deg", "flange_pose")
            } else {
                ("flange_pose", "joints_deg")
            };
            errors.push(FieldError::new(
                field(has),
                format!("the session's first pose carries {session}; a session does not mix joint angles and flange poses"),
            ));
        } else if flange_session {
            if input.session.instrument != Instrument::Camera {
                errors.push(FieldError::new(
                    field("flange_pose"),
                    "flange poses need a camera session",
                ));
            }
        } else if pose.joints_deg.len() != joint_count {
            errors.push(FieldError::new(
                field("joints_deg"),
                format!(
                    "{} values for a {joint_count}-joint robot",
                    pose.joints_deg.len()
                ),
            ));
        }
        match input.session.instrument {
            Instrument::Camera | Instrument::Stage => match &pose.image {
                // Decodability was proven at upload (or is the detect
                // stage's to find out): only the stored size is checked, no
                // image is read here.
                Some(image) => {
                    if let Some(c) =
                        camera.filter(|c| (c.width, c.height) != (image.width, image.height))
                    {
                        errors.push(FieldError::new(
                            field("image"),
                            format!(
                                "image is {}x{}, the session camera is {}x{}",
                                image.width, image.height, c.width, c.height
                            ),
                        ));
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
    Ok(Summary {
        stage: Some(Stage::Validate.as_str().into()),
        calibration_poses: cal,
        validation_poses: val,
        joints: Some(joint_count),
        ..Summary::default()
    })
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
