//! The calibration job: one synchronous function joining the numerics of
//! `robocal-calib` for a session (validate → detect → camera → poses →
//! identify → report). It runs on a blocking thread, reports progress
//! through a callback and stops when `cancel` becomes true.
//!
//! The identified parameter set and its report come back in
//! [`Output::parameter_set`], every pose's image points with their
//! residuals in [`Output::detections`]; the worker stores both in the
//! transaction that finishes the job. The points are also handed out right
//! after the detect stage ([`run_observed`]), so they are visible even when
//! a later stage fails.

use std::sync::atomic::{AtomicBool, Ordering};

mod board_turn;
mod camera_stage;
mod check_job;
mod detections;
mod flange_job;
mod flange_stage;
mod gate;
pub mod hand_eye_results;
mod hand_eye_sigmas;
mod identify_stage;
mod input;
mod measure;
mod measuring;
mod model_selection;
mod output;
mod position_selection;
mod regions_job;
mod regions_results;
pub mod results;
mod scoped_job;
mod screen_stage;
mod session_cause;
mod stage;
mod stage_job;
pub mod stage_results;
mod uncertainty_map;
mod validate;

pub use input::{
    ApprovedSet, FixedCamera, ImageSource, Input, PoseImage, PoseInput, ReadImage, RegionInput,
};
pub use output::{Output, PipelineError, Summary};
use stage::stage_span;
pub use stage::Stage;
pub use validate::validate;

use robocal_calib::kinematics::nongeometric::CandidateOptions;

use crate::schema::session::Instrument;
use crate::schema::{FieldError, PoseDoc};
use crate::store::{NewParameterSet, PoseDetection};

/// Fewest calibration poses a job accepts. Identification needs more
/// observations than unknowns; the identification stage refines this check.
pub const MIN_CALIBRATION_POSES: usize = 3;
/// Runs the calibration job: validate, detect, calibrate the camera,
/// measure the poses, identify, report. `progress(stage, message,
/// fraction)` is called with `fraction` in `[0, 1]` for the whole job.
pub fn run(
    input: &Input,
    progress: &dyn Fn(Stage, &str, f64),
    cancel: &AtomicBool,
) -> Result<Output, PipelineError> {
    run_observed(input, progress, &|_| {}, cancel)
}

/// [`run`], handing every camera pose's image points to `detected` as soon
/// as the detect stage has them (before the numerics that may fail).
pub fn run_observed(
    input: &Input,
    progress: &dyn Fn(Stage, &str, f64),
    detected: &dyn Fn(Vec<PoseDetection>),
    cancel: &AtomicBool,
) -> Result<Output, PipelineError> {
    let mut cause = None;
    run_stages(input, progress, detected, cancel, &mut cause)
        .map_err(|e| session_cause::name_in(e, cause))
}

/// [`run_observed`]'s stages; `cause` receives the session-level cause of
/// the detection failures when most images failed for one reason.
fn run_stages(
    input: &Input,
    progress: &dyn Fn(Stage, &str, f64),
    detected: &dyn Fn(Vec<PoseDetection>),
    cancel: &AtomicBool,
    cause: &mut Option<String>,
) -> Result<Output, PipelineError> {
    let within = |stage: Stage, message: &str, fraction: f64| {
        let (lo, hi) = stage_span(stage);
        progress(stage, message, lo + (hi - lo) * fraction.clamp(0.0, 1.0));
    };
    if !input.regions.is_empty() {
        let fitted = regions_job::run(input, &within, detected, cancel, cause)?;
        check_cancelled(cancel)?;
        within(Stage::Report, "building the report", 0.0);
        let output = regions_results::output(input, fitted)?;
        within(Stage::Report, "done", 1.0);
        return Ok(output);
    }
    let checked = validate(input, &within, cancel)?;
    within(Stage::Validate, "inputs valid", 1.0);
    if input.validate_only {
        return Ok(Output {
            parameter_set: None,
            summary: checked,
            detections: Vec::new(),
            check: None,
        });
    }
    // Intrinsics not re-estimated (fixed from an earlier calibration, or the
    // paper's sequence values): the joint refinement, which re-fits them
    // together with the kinematics, is left out.
    let intrinsics_held = input.fixed_camera.is_some() || !input.options.refine_intrinsics;
    let mut notes = Vec::new();
    let (measured, camera) = match input.session.instrument {
        Instrument::Stage => {
            let (target, camera_doc) = board_and_camera(input)?;
            let measured = detect(input, &target, &within, detected, cancel, cause)?;
            notes.extend(cause.as_ref().map(|c| format!("{c}.")));
            return stage_job::run(input, &measured, &target, camera_doc, notes, &within);
        }
        Instrument::Camera => {
            let (measured, step) =
                camera_session(input, &within, detected, cancel, cause, &mut notes)?;
            (Some(measured), Some(step))
        }
        Instrument::Tracker => (None, None),
    };
    check_cancelled(cancel)?;
    within(Stage::MeasurePoses, "camera poses measured", 1.0);
    if let (true, Some(m), Some(step)) = (input.is_flange_session(), &measured, &camera) {
        return flange_job::run(input, m, step, notes, &within);
    }
    if input.check {
        return check_job::run(input, camera.as_ref(), &within);
    }
    if !input.options.scope.is_full() {
        return scoped_job::run(input, measured.as_ref(), camera.as_ref(), notes, &within);
    }
    let usable: Vec<usize> = (0..input.poses.len())
        .filter(|&i| camera.as_ref().is_none_or(|c| c.view_pose.contains(&i)))
        .collect();
    let (usable, outliers) = match &camera {
        Some(step) => {
            let (kept, outliers, note) =
                screen_stage::screen_poses(&input.robot, &input.poses, step, &usable);
            notes.extend(note);
            (kept, outliers)
        }
        None => (usable, Vec::new()),
    };
    let measuring =
        measuring::Measuring::for_job(&input.session, input.options.measurement, &input.poses)?;
    let guess = flange_guess(input);
    // Paper mode keeps the paper's pipeline: its Tsai intrinsics are not
    // the joint refinement's camera model, so refining on the image points
    // with them held fits the model error instead (tens of px). A reused
    // camera is held fixed.
    let paper_camera = !input.options.refine_intrinsics && input.fixed_camera.is_none();
    let joint_refinement = input.options.joint_refinement && !paper_camera;
    if camera.is_some() && input.options.joint_refinement && intrinsics_held {
        notes.push(if paper_camera {
            "Joint refinement skipped: paper mode (refine_intrinsics: false) keeps the paper's pose-level identification.".to_string()
        } else {
            "Joint refinement held the camera intrinsics fixed at the reused calibration's.".to_string()
        });
    }
    within(Stage::Identify, "kinematic identification", 0.0);
    // Term selection: default on for trackers, opt-in for cameras (there
    // the terms are selected again on the image points; see
    // `CalibrationOptions::non_geometric_for`).
    let candidates = input
        .options
        .non_geometric_for(input.session.instrument)
        .then(|| CandidateOptions {
            payload_kg: input.session.payload_kg.unwrap_or(0.0),
            ..CandidateOptions::for_robot(&input.robot)
        });
    let identify = |usable: &[usize], outliers: &[screen_stage::Outlier]| {
        identify_stage::identify_robot(
            &input.robot,
            &input.poses,
            camera.as_ref(),
            guess,
            measuring,
            input.options.validation,
            joint_refinement,
            intrinsics_held,
            usable,
            &outliers.iter().map(|o| o.pose).collect::<Vec<_>>(),
            candidates.as_ref(),
            input.prior,
        )
    };
    let (identified, outliers) = screen_stage::identify_confirmed(usable, outliers, identify)?;
    notes.extend(screen_stage::note(&input.poses, &outliers));
    notes.extend(identified.terms.as_ref().and_then(|t| t.range_note()));
    if let Some(sigma) = identified.joint_noise_rad {
        notes.push(format!(
            "Joint noise (encoders, repeatability) estimated from the images: {:.1e} deg per joint; the parameter standard deviations include it.",
            sigma.to_degrees()
        ));
    }
    check_cancelled(cancel)?;
    within(Stage::Report, "building the report", 0.0);
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
        controller: input.session.controller.as_ref(),
        instrument: input.session.instrument,
        measuring,
        poses: &input.poses,
        measured: measured.as_ref(),
        camera: camera.as_ref(),
        outliers: &outliers,
        notes,
    };
    let set = results::parameter_set(&context, &identified);
    let mut report = results::report(&context, &identified, &set);
    let gate = gate::decide(
        &identified,
        context.instrument,
        input.approved.as_ref(),
        paper_camera && camera.is_some(),
    );
    report.gate = Some(gate.report);
    let detections = match (&measured, &camera) {
        (Some(m), Some(step)) => detections::with_residuals(
            &input.poses,
            m,
            step,
            &identified
                .term_model()
                .map_err(|e| PipelineError::numerical(Stage::Report, e))?,
            &set.camera.unwrap_or(step.intrinsics()),
            measuring.kind == crate::schema::job::Measurement::Pose,
        ),
        _ => Vec::new(),
    };
    within(Stage::Report, "done", 1.0);
    Ok(Output {
        parameter_set: Some(NewParameterSet {
            parameters: serde_json::to_value(&set).unwrap_or_default(),
            report: serde_json::to_value(&report).unwrap_or_default(),
            release: gate.release,
        }),
        summary: results::summary(&identified),
        detections,
        check: None,
    })
}

/// A camera session's detect and camera stages: every image's dots, the
/// camera calibration and the half-turn resolution, with their notes.
fn camera_session(
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
fn detect(
    input: &Input,
    target: &crate::domain::Target,
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
fn board_and_camera(
    input: &Input,
) -> Result<(crate::domain::Target, &crate::schema::session::CameraDoc), PipelineError> {
    match (&input.session.target, &input.session.camera) {
        (Some(t), Some(c)) => Ok((
            crate::domain::Target::from_doc(t).map_err(PipelineError::Invalid)?,
            c,
        )),
        _ => Err(PipelineError::Invalid(vec![FieldError::new(
            "session",
            "a camera or stage session needs target and camera",
        )])),
    }
}

/// The session's `flange_to_camera_guess`, else identity.
fn flange_guess(input: &Input) -> robocal_calib::geometry::Pose {
    match &input.session.flange_to_camera_guess {
        Some(p) => pose_of(p),
        None => robocal_calib::geometry::Pose::identity(),
    }
}

/// `Cancelled` once `cancel` is set.
fn check_cancelled(cancel: &AtomicBool) -> Result<(), PipelineError> {
    if cancel.load(Ordering::Relaxed) {
        Err(PipelineError::Cancelled)
    } else {
        Ok(())
    }
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
