//! The calibration over several sessions of one robot (issue 18; the
//! paper's regions, section 5; method.md §6–7): every session is one
//! placement of the board. Each session runs its own detect and camera
//! stages, screening and pose-level identification (its start and its
//! "before"); then one joint refinement on the image points of all of them
//! ([`joint_refine_regions`]) fits one kinematic model, one hand–eye and
//! one set of intrinsics with one `target_to_base` per session. Each
//! session's validation poses are judged with its own board.

use std::sync::atomic::AtomicBool;

use robocal_calib::kinematics::identify::{validate, JointNoise, Measurement};
use robocal_calib::kinematics::initial::initial_world_to_base;
use robocal_calib::kinematics::joint_covariance::session_covariances;
use robocal_calib::kinematics::joint_refine::{ImageNoise, ImagePose, JointRefinement};
use robocal_calib::kinematics::regions::{joint_refine_regions, session_of, RegionPoses};
use robocal_calib::kinematics::CalibratedModel;
use robocal_calib::stats::AccuracyStats;

use crate::pipeline::camera_stage::CameraStep;
use crate::pipeline::identify_stage::{identify_robot, Identified};
use crate::pipeline::measure::Measured;
use crate::pipeline::measuring::Measuring;
use crate::pipeline::prelude::{camera_session, check_cancelled, flange_guess};
use crate::pipeline::screen_stage::{self, Outlier};
use crate::pipeline::{validate as validate_input, Input, PipelineError, Stage};
use crate::schema::session::Instrument;
use crate::store::PoseDetection;

/// Smallest dot noise the joint refinement is weighted with (px), as in a
/// one-session job.
const MIN_SIGMA_PX: f64 = 1e-3;

/// One session's own stages: its camera, its screening and its pose-level
/// identification (the joint fit's start, and its "before").
pub(in crate::pipeline) struct SessionFit {
    pub input: Input,
    pub measured: Measured,
    pub step: CameraStep,
    pub outliers: Vec<Outlier>,
    pub identified: Identified,
}

/// One session's validation in the joint fit's model.
pub(in crate::pipeline) struct SessionValidation {
    pub before: AccuracyStats,
    pub after: AccuracyStats,
    /// (pose index in the session, error before, error after), mm.
    pub errors: Vec<(usize, nalgebra::Vector3<f64>, nalgebra::Vector3<f64>)>,
    /// The same for the session's screened-out poses (how far their
    /// joints and images disagree under the shared model), so the report
    /// lists them with `outlier: true` as a one-session report does.
    pub outlier_errors: Vec<(usize, nalgebra::Vector3<f64>, nalgebra::Vector3<f64>)>,
}

/// The joint fit and what goes with it.
pub(in crate::pipeline) struct JointFit {
    pub refined: JointRefinement,
    /// The covariance as each session sees it (its own board's base values
    /// in the base slots); the first is the set's own.
    pub session_covariances: Vec<nalgebra::DMatrix<f64>>,
    /// Whether the intrinsics were held (a reused camera).
    pub intrinsics_held: bool,
}

impl JointFit {
    /// The shared model on session `s`'s board.
    pub fn model_of(&self, s: usize) -> CalibratedModel {
        CalibratedModel {
            world_to_base: self.refined.session_target_to_base[s],
            ..self.refined.model.clone()
        }
    }
}

/// Everything the multi-session job found, for the report stage
/// (`regions_results`).
pub(in crate::pipeline) struct Fitted {
    pub fits: Vec<SessionFit>,
    pub joint: JointFit,
    pub validations: Vec<SessionValidation>,
    pub notes: Vec<String>,
}

/// Runs the multi-session job's fits (`input` is the first session, its
/// `regions` the others).
pub(in crate::pipeline) fn run(
    input: &Input,
    within: &dyn Fn(Stage, &str, f64),
    detected: &dyn Fn(Vec<PoseDetection>),
    cancel: &AtomicBool,
    cause: &mut Option<String>,
) -> Result<Fitted, PipelineError> {
    let sessions = input.sessions();
    let count = sessions.len();
    let mut notes = Vec::new();
    let mut fits = Vec::with_capacity(count);
    for (s, one) in sessions.into_iter().enumerate() {
        let label = format!("session {}/{count}", s + 1);
        let session_within = |stage: Stage, message: &str, fraction: f64| {
            within(stage, &format!("{label}: {message}"), fraction)
        };
        let (fit, session_notes) = fit_session(one, s, &session_within, detected, cancel, cause)?;
        notes.extend(
            session_notes
                .into_iter()
                .map(|n| format!("Session {}: {n}", fit.input.session_id)),
        );
        fits.push(fit);
    }
    check_cancelled(cancel)?;
    within(Stage::Identify, "joint refinement over every session", 0.5);
    let joint = joint_fit(&fits)?;
    let validations = fits
        .iter()
        .enumerate()
        .map(|(s, f)| validate_session(f, &joint, s))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Fitted {
        fits,
        joint,
        validations,
        notes,
    })
}

/// The invalid-input error of session `s`, naming `sessions` (and the
/// entry, `[s]`, in the message).
fn in_session(s: usize, message: impl std::fmt::Display) -> PipelineError {
    PipelineError::invalid("sessions", format!("[{s}]: {message}"))
}

/// Session `s`'s own stages, up to its pose-level identification.
fn fit_session(
    input: Input,
    s: usize,
    within: &dyn Fn(Stage, &str, f64),
    detected: &dyn Fn(Vec<PoseDetection>),
    cancel: &AtomicBool,
    cause: &mut Option<String>,
) -> Result<(SessionFit, Vec<String>), PipelineError> {
    if input.session.instrument != Instrument::Camera || input.is_flange_session() {
        return Err(in_session(
            s,
            format!(
                "session {} is not a camera session with joints: several sessions are fitted together on their images",
                input.session_id
            ),
        ));
    }
    validate_input(&input, within, cancel).map_err(|e| match e {
        PipelineError::Invalid(errors) => in_session(
            s,
            errors
                .iter()
                .map(|f| format!("{}: {}", f.field, f.message))
                .collect::<Vec<_>>()
                .join("; "),
        ),
        e => e,
    })?;
    let mut notes = Vec::new();
    let (measured, step) = camera_session(&input, within, detected, cancel, cause, &mut notes)?;
    *cause = None;
    let usable: Vec<usize> = (0..input.poses.len())
        .filter(|i| step.view_pose.contains(i))
        .collect();
    let (usable, outliers, note) =
        screen_stage::screen_poses(&input.robot, &input.poses, &step, &usable);
    notes.extend(note);
    let identify = |usable: &[usize], outliers: &[Outlier]| {
        identify_robot(
            &input.robot,
            &input.poses,
            Some(&step),
            flange_guess(&input),
            Measuring::camera_pose(),
            input.options.validation,
            false,
            true,
            usable,
            &outliers.iter().map(|o| o.pose).collect::<Vec<_>>(),
            None,
            robocal_calib::kinematics::prior::KinematicPrior::default(),
        )
    };
    let (identified, outliers) = screen_stage::identify_confirmed(usable, outliers, identify)?;
    notes.extend(screen_stage::note(&input.poses, &outliers));
    Ok((
        SessionFit {
            input,
            measured,
            step,
            outliers,
            identified,
        },
        notes,
    ))
}

/// A session's calibration poses as the joint refinement takes them.
pub(in crate::pipeline) fn images_of(fit: &SessionFit) -> Vec<ImagePose> {
    fit.identified
        .cal
        .iter()
        .filter_map(|&i| {
            Some(ImagePose {
                joints_rad: fit.input.poses[i].joints_deg.to_radians(),
                observations: fit.step.observations_of(i)?.to_vec(),
            })
        })
        .collect()
}

/// The one joint refinement over every session. Its start is the first
/// session's pose-level model; every other board is registered with that
/// model on its own session's calibration poses, so all boards start in
/// one base frame. The free set is the parameters every session
/// identifies (a value held in one is held in all).
fn joint_fit(fits: &[SessionFit]) -> Result<JointFit, PipelineError> {
    let numerical = |e: &dyn std::fmt::Display| PipelineError::Numerical {
        stage: Stage::Identify.as_str(),
        message: e.to_string(),
    };
    let start = &fits[0].identified.model;
    let free: Vec<usize> = fits[0]
        .identified
        .identification
        .identifiability
        .free
        .iter()
        .copied()
        .filter(|i| {
            fits.iter()
                .all(|f| f.identified.identification.identifiability.free.contains(i))
        })
        .collect();
    let mut regions = Vec::with_capacity(fits.len());
    for (s, f) in fits.iter().enumerate() {
        let target_to_base_start = if s == 0 {
            start.world_to_base
        } else {
            initial_world_to_base(start, &f.identified.cal_data).map_err(|e| numerical(&e))?
        };
        regions.push(RegionPoses {
            target_to_base_start,
            poses: images_of(f),
        });
    }
    let sigma_px = fits
        .iter()
        .map(|f| f.step.calibration.rms_px)
        .fold(MIN_SIGMA_PX, f64::max);
    let intrinsics_held = fits[0].input.fixed_camera.is_some();
    let noise = ImageNoise {
        sigma_px,
        joint: JointNoise::Estimate,
    };
    let refined = joint_refine_regions(
        start,
        &fits[0].step.intrinsics(),
        &regions,
        &free,
        noise,
        intrinsics_held,
    )
    .map_err(|e| numerical(&e))?;
    let images: Vec<ImagePose> = regions.iter().flat_map(|r| r.poses.clone()).collect();
    let session_of = session_of(&regions);
    let session_covariances =
        session_covariances(&refined, &images, &free, intrinsics_held, &session_of)
            .map_err(|e| numerical(&e))?;
    Ok(JointFit {
        refined,
        session_covariances,
        intrinsics_held,
    })
}

/// Session `s`'s validation poses, measured with the joint fit's
/// intrinsics, judged by the nominal model (frames fitted on the session:
/// its "before") and by the shared model on the session's board.
fn validate_session(
    fit: &SessionFit,
    joint: &JointFit,
    s: usize,
) -> Result<SessionValidation, PipelineError> {
    let numerical = |e: &dyn std::fmt::Display| PipelineError::Numerical {
        stage: Stage::Identify.as_str(),
        message: format!("session {}: {e}", fit.input.session_id),
    };
    let intrinsics = joint.refined.intrinsics;
    let measure = |i: usize| {
        Measuring::camera_pose().of(&fit.input.poses[i], i, Some(&fit.step), Some(&intrinsics))
    };
    let (mut index, mut data): (Vec<usize>, Vec<Measurement>) = (Vec::new(), Vec::new());
    for &i in &fit.identified.val {
        if let Some(m) = measure(i) {
            index.push(i);
            data.push(m);
        }
    }
    let model = joint.model_of(s);
    let outlier_errors = fit
        .outliers
        .iter()
        .filter_map(|o| {
            let one = [measure(o.pose)?];
            let (_, b) = validate(&fit.identified.identification.before, &one).ok()?;
            let (_, a) = validate(&model, &one).ok()?;
            Some((o.pose, b[0], a[0]))
        })
        .collect();
    if data.is_empty() {
        return Err(numerical(&"no validation pose could be measured"));
    }
    let (before, before_errors) =
        validate(&fit.identified.identification.before, &data).map_err(|e| numerical(&e))?;
    let (after, after_errors) = validate(&model, &data).map_err(|e| numerical(&e))?;
    let errors = index
        .into_iter()
        .zip(before_errors.into_iter().zip(after_errors))
        .map(|(i, (b, a))| (i, b, a))
        .collect();
    Ok(SessionValidation {
        before,
        after,
        errors,
        outlier_errors,
    })
}
