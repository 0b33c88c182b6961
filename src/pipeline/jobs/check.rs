//! A quick re-check job (issue 17): the session's few poses measured with
//! the camera held at the approved set's intrinsics, then judged against
//! that set by `robocal_calib::kinematics::recheck` (a chi-square test of
//! the residuals against the set's covariance and the measurement noise).
//! No parameter set is stored; the verdict is the job's `result`.

use robocal_calib::kinematics::recheck::{
    recheck, RecheckInput, SuspectKind, Verdict, SIGNIFICANCE,
};
use robocal_calib::kinematics::ParamLayout;

use crate::domain::{controller_change, CheckDoc, CheckSuspect, CheckVerdict};
use crate::pipeline::camera_stage::CameraStep;
use crate::pipeline::measuring::Measuring;
use crate::pipeline::{Input, Output, PipelineError, Stage, Summary};

/// Joint noise (encoders, repeatability) assumed in the check's
/// covariance for a set that does not carry the joint refinement's
/// estimate (`joint_noise_deg`: sets stored before it was kept, tracker
/// sets, paper-mode sets): an industrial robot's repeatability is about
/// this (0.02 mm at 1 m). Larger than the estimates of the simulated
/// campaigns, so such a check is lenient, never alarmist.
const FALLBACK_JOINT_SIGMA_DEG: f64 = 1e-3;

/// The joint noise (rad) a check of `set` assumes: the set's own estimate
/// (method.md §6, the joint refinement), else [`FALLBACK_JOINT_SIGMA_DEG`].
fn joint_sigma_rad(set: &crate::domain::ParameterSet) -> f64 {
    set.joint_noise_deg
        .filter(|d| d.is_finite() && *d >= 0.0)
        .unwrap_or(FALLBACK_JOINT_SIGMA_DEG)
        .to_radians()
}

fn numerical(message: impl std::fmt::Display) -> PipelineError {
    PipelineError::numerical(Stage::Identify, message)
}

/// Runs the re-check after the camera stage (camera sessions) or directly
/// (tracker sessions).
pub fn run(
    input: &Input,
    camera: Option<&CameraStep>,
    within: &dyn Fn(Stage, &str, f64),
) -> Result<Output, PipelineError> {
    let approved = input.approved.as_ref().ok_or_else(|| {
        PipelineError::invalid(
            "serial",
            format!(
                "robot {} has no approved parameter set to check against",
                input.serial
            ),
        )
    })?;
    let (instrument, measuring) =
        Measuring::for_approved(approved, &input.session, &input.poses, "session")?;
    // A set with kept terms (issue 19) is checked with them.
    let model = approved.set.term_model().map_err(numerical)?;
    let covariance = approved
        .set
        .covariance_matrix()
        .ok_or_else(|| {
            PipelineError::invalid(
                "serial",
                format!(
                    "the approved set {} was stored without its covariance: calibrate again to check against it",
                    approved.id
                ),
            )
        })?
        .map_err(numerical)?;
    within(Stage::Identify, "re-check against the approved set", 0.0);
    let data: Vec<_> = (0..input.poses.len())
        .filter_map(|i| measuring.of(&input.poses[i], i, camera, None))
        .collect();
    let joint_sigma_rad = joint_sigma_rad(&approved.set);
    let found = recheck(&RecheckInput {
        model: &model,
        instrument,
        covariance: &covariance,
        joint_sigma_rad,
        data: &data,
    })
    .map_err(numerical)?;
    let layout = ParamLayout::new(&model.model.robot, instrument);
    let suspects = found
        .suspects
        .iter()
        .map(|s| {
            let (unit, change) = match s.kind {
                // A kept term: its own unit (rad for a periodic term).
                SuspectKind::Term(term) => (term.unit(), s.change),
                SuspectKind::Parameter(_) => {
                    if layout.index_of(&s.name).is_some_and(|i| layout.is_angle(i)) {
                        ("deg", s.change.to_degrees())
                    } else {
                        ("mm", s.change)
                    }
                }
            };
            CheckSuspect {
                name: s.name.clone(),
                unit: unit.into(),
                change,
                change_sigmas: s.change_sigmas,
                chi2_drop: s.chi2_drop,
            }
        })
        .collect();
    // A set applied on another controller than its own is the verdict,
    // whatever the residuals say (issue 34).
    let controller_change = controller_change(
        approved.set.controller.as_ref(),
        input.session.controller.as_ref(),
    );
    let doc = CheckDoc {
        verdict: match found.verdict {
            _ if controller_change.is_some() => CheckVerdict::ControllerChanged,
            Verdict::Pass => CheckVerdict::Pass,
            Verdict::Drift => CheckVerdict::Drift,
            Verdict::BaseMoved => CheckVerdict::BaseMoved,
        },
        mean_mm: found.mean_mm,
        expected_mean_mm: found.expected_mean_mm,
        p_value: found.p_value,
        base_p_value: found.base_p_value,
        chi2: found.chi2,
        dof: found.dof,
        significance: SIGNIFICANCE,
        test: format!(
            "chi-square of the residuals whitened by J Σ Jᵀ + R (the set's parameter covariance \
             propagated to the poses, plus each pose's measurement and joint noise), {} degrees \
             of freedom: pass at p ≥ {SIGNIFICANCE}; base_moved when the base transform re-fitted \
             alone passes the same test",
            found.dof
        ),
        checked_against: approved.id.clone(),
        checked_version: approved.version,
        joint_noise_deg: joint_sigma_rad.to_degrees(),
        poses: data.len(),
        suspects,
        controller_change,
    };
    within(Stage::Report, "done", 1.0);
    Ok(Output {
        parameter_set: None,
        summary: Summary {
            validation_poses: data.len(),
            ..Summary::default()
        },
        detections: Vec::new(),
        check: Some(doc),
    })
}
