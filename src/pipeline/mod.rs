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
//!
//! What a job runs is decided once, by [`jobs::Plan::of`]; each kind of
//! job is one file under `jobs/`, after the shared stages of `prelude.rs`.

use std::sync::atomic::AtomicBool;

mod board_turn;
mod camera_stage;
mod detections;
mod flange_stage;
mod gate;
pub mod hand_eye_results;
mod hand_eye_sigmas;
mod identify_stage;
mod input;
mod jobs;
mod measure;
mod measuring;
mod model_selection;
mod output;
mod pose_errors;
mod position_selection;
mod prelude;
mod regions_results;
pub mod results;
mod screen_stage;
mod session_cause;
mod stage;
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

use crate::store::PoseDetection;

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
    let within = |stage: Stage, message: &str, fraction: f64| {
        let (lo, hi) = stage_span(stage);
        progress(stage, message, lo + (hi - lo) * fraction.clamp(0.0, 1.0));
    };
    jobs::run(input, &within, detected, cancel, &mut cause)
        .map_err(|e| session_cause::name_in(e, cause))
}
