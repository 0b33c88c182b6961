//! One file per kind of job, each returning the job's [`Output`], and the
//! one dispatch: [`Plan::of`] decides what a loaded job runs, once, from
//! its queue kind, its session and its options; [`run`] runs it. Adding a
//! kind: a variant of [`Plan`], its rule in [`Plan::of`], its file here and
//! its arm in [`run`].

use std::sync::atomic::AtomicBool;

use super::{prelude, regions_results, Input, Output, PipelineError, Stage};
use crate::domain::JobKind;
use crate::schema::session::Instrument;
use crate::store::PoseDetection;

mod calibration;
mod check;
mod hand_eye;
pub(super) mod regions;
mod scoped;
mod stage_camera;

/// What a job runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plan {
    /// Several sessions of one robot fitted together (`sessions`).
    Regions,
    /// Stop after validation (a test hook).
    ValidateOnly,
    /// A stage session: the camera calibrated on a translation stage.
    StageCamera,
    /// A camera session of controller flange poses: hand–eye, no kinematics.
    HandEye,
    /// A quick re-check against the latest approved set.
    Check,
    /// A partial re-fit (`scope` `base` or `hand_eye`).
    Scoped,
    /// A full calibration of one session.
    Calibration,
}

impl Plan {
    /// The plan of a loaded job. The session decides before the queue kind:
    /// a stage or flange-pose session calibrates what it can measure
    /// whatever the job was queued as.
    pub fn of(input: &Input) -> Plan {
        let instrument = input.session.instrument;
        if !input.regions.is_empty() {
            Plan::Regions
        } else if input.validate_only {
            Plan::ValidateOnly
        } else if instrument == Instrument::Stage {
            Plan::StageCamera
        } else if instrument == Instrument::Camera && input.is_flange_session() {
            Plan::HandEye
        } else if input.kind == JobKind::Check {
            Plan::Check
        } else if !input.options.scope.is_full() {
            Plan::Scoped
        } else {
            Plan::Calibration
        }
    }
}

/// Runs the job `input`'s plan; `cause` receives the session-level cause
/// of the detection failures when most images failed for one reason.
pub fn run(
    input: &Input,
    within: &dyn Fn(Stage, &str, f64),
    detected: &dyn Fn(Vec<PoseDetection>),
    cancel: &AtomicBool,
    cause: &mut Option<String>,
) -> Result<Output, PipelineError> {
    match Plan::of(input) {
        Plan::Regions => {
            let fitted = regions::run(input, within, detected, cancel, cause)?;
            prelude::check_cancelled(cancel)?;
            within(Stage::Report, "building the report", 0.0);
            let output = regions_results::output(input, fitted)?;
            within(Stage::Report, "done", 1.0);
            Ok(output)
        }
        Plan::ValidateOnly => Ok(Output {
            parameter_set: None,
            summary: prelude::validated(input, within, cancel)?,
            detections: Vec::new(),
            check: None,
        }),
        Plan::StageCamera => {
            let p = prelude::run_stage(input, within, detected, cancel, cause)?;
            stage_camera::run(input, &p.measured, &p.target, p.camera, p.notes, within)
        }
        Plan::HandEye => {
            let p = prelude::run(input, within, detected, cancel, cause)?;
            let (measured, camera) = p.camera_parts()?;
            hand_eye::run(input, measured, camera, p.notes.clone(), within)
        }
        Plan::Check => {
            let p = prelude::run(input, within, detected, cancel, cause)?;
            check::run(input, p.camera.as_ref(), within)
        }
        Plan::Scoped => {
            let p = prelude::run(input, within, detected, cancel, cause)?;
            scoped::run(
                input,
                p.measured.as_ref(),
                p.camera.as_ref(),
                p.notes,
                within,
            )
        }
        Plan::Calibration => {
            let p = prelude::run(input, within, detected, cancel, cause)?;
            calibration::run(input, p, within, cancel)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The plan follows the session first, then the queue kind, then the
    /// scope; adding a kind shows here.
    /// A one-session calibration of a tracker session without poses.
    fn input() -> Input {
        let kinematics = crate::schema::robot::preset_doc(crate::schema::robot::Preset::Irb2400);
        Input {
            serial: "PLAN-1".into(),
            session_id: "s".into(),
            robot: crate::schema::robot::doc_to_model(&kinematics),
            prior: Default::default(),
            kinematics,
            session: Default::default(),
            poses: Vec::new(),
            options: Default::default(),
            fixed_camera: None,
            images: crate::pipeline::ImageSource::none(),
            test_stage_delay: std::time::Duration::ZERO,
            validate_only: false,
            regions: Vec::new(),
            local_models: Vec::new(),
            approved: None,
            kind: JobKind::Calibration,
        }
    }

    #[test]
    fn the_plan_is_decided_once_from_kind_session_and_options() {
        let input = input();
        assert_eq!(Plan::of(&input), Plan::Calibration);
        let check = Input {
            kind: JobKind::Check,
            ..input.clone()
        };
        assert_eq!(Plan::of(&check), Plan::Check);
        let mut scoped = input.clone();
        scoped.options.scope = crate::schema::job::CalibrationScope::Base;
        assert_eq!(Plan::of(&scoped), Plan::Scoped);
        let mut stage = check.clone();
        stage.session.instrument = Instrument::Stage;
        assert_eq!(Plan::of(&stage), Plan::StageCamera);
        let validate_only = Input {
            validate_only: true,
            ..stage
        };
        assert_eq!(Plan::of(&validate_only), Plan::ValidateOnly);
    }
}
