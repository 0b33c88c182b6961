//! Stage "report" of a multi-session job (issue 18): the parameter set
//! with every session's board, and the report with the per-session
//! (region) accuracy. The report's pose lists run over all sessions' poses
//! in job order; `before`/`after` are over all validation poses, each
//! judged with its own session's board.

use robocal_calib::kinematics::term_model::TermModel;
use robocal_calib::stats::AccuracyStats;

use super::identify_stage::Identified;
use super::jobs::regions::{Fitted, JointFit, SessionValidation};
use super::screen_stage::Outlier;
use super::{detections, gate, results, Input, Output, PipelineError, PoseInput};
use crate::domain::{CalibratedSet, CovarianceDoc, SessionBoard};
use crate::report::regions::RegionReport;
use crate::schema::PoseOut;

/// The set, its report and the detections of a multi-session job.
pub(super) fn output(input: &Input, fitted: Fitted) -> Result<Output, PipelineError> {
    let Fitted {
        fits,
        joint,
        validations,
        mut notes,
    } = fitted;
    let joint = &joint;
    let offsets: Vec<usize> = fits
        .iter()
        .scan(0, |at, f| {
            let start = *at;
            *at += f.input.poses.len();
            Some(start)
        })
        .collect();
    let poses: Vec<PoseInput> = fits.iter().flat_map(|f| f.input.poses.clone()).collect();
    let outliers: Vec<Outlier> = fits
        .iter()
        .zip(&offsets)
        .flat_map(|(f, &at)| {
            f.outliers.iter().map(move |o| Outlier {
                pose: o.pose + at,
                reason: o.reason.clone(),
            })
        })
        .collect();
    let detections: Vec<_> = fits
        .iter()
        .enumerate()
        .flat_map(|(s, f)| {
            detections::with_residuals(
                &f.input.poses,
                &f.measured,
                &f.step,
                // Multi-session jobs keep no terms (non_geometric is refused).
                &TermModel::geometric(joint.model_of(s)),
                &joint.refined.intrinsics,
                true,
            )
        })
        .collect();
    let regions: Vec<RegionReport> = fits
        .iter()
        .zip(&validations)
        .map(|(f, v)| RegionReport {
            session_id: f.input.session_id.clone(),
            region: f.input.session.region.clone(),
            volume: f.input.session.volume.clone(),
            before: v.before,
            after: v.after,
            local: input
                .local_models
                .iter()
                .find(|(id, _)| *id == f.input.session_id)
                .map(|(_, local)| local.clone()),
        })
        .collect();
    let mut boards: Vec<SessionBoard> = fits
        .iter()
        .zip(&joint.refined.session_target_to_base)
        .map(|(f, board)| SessionBoard {
            session_id: f.input.session_id.clone(),
            target_to_base: PoseOut::new(board),
            covariance: None,
        })
        .collect();
    notes.insert(
        0,
        format!(
            "Calibrated over {} sessions (board placements): one kinematic model, hand–eye and \
             camera intrinsics, one target_to_base per session (session_target_to_base; the first \
             session's is target_to_base). Each session's validation poses are judged with its own \
             board (regions); the release gate compares on the first session's poses.",
            fits.len()
        ),
    );
    let cal: Vec<usize> = fits
        .iter()
        .zip(&offsets)
        .flat_map(|(f, &at)| f.identified.cal.iter().map(move |i| i + at))
        .collect();
    let mut fits = fits;
    let first = fits.remove(0);
    let mut combined = combined(first.identified, joint, &validations, &offsets);
    combined.cal = cal;
    let context = results::Context {
        serial: &input.serial,
        session_id: &input.session_id,
        controller: input.session.controller.as_ref(),
        instrument: crate::schema::session::Instrument::Camera,
        measuring: super::measuring::Measuring::camera_pose(),
        poses: &poses,
        measured: Some(&first.measured),
        camera: Some(&first.step),
        outliers: &outliers,
        notes,
    };
    let mut set = results::parameter_set(&context, &combined);
    // Each board with the covariance as its session sees it (`forward`'s
    // σ with that `session_id`), in the layout the set's own uses.
    let ident = &combined.identification;
    for (board, covariance) in boards.iter_mut().zip(&joint.session_covariances) {
        board.covariance = Some(CovarianceDoc::from_layout(
            &ident.layout,
            covariance,
            &ident.identifiability.free,
        ));
    }
    set.session_target_to_base = boards;
    let mut report = results::report(&context, &combined, &set);
    // Per-pose reprojection of the further sessions' poses: their own
    // camera steps' views (the context's is the first session's).
    for f in &fits {
        for line in report.per_pose.iter_mut() {
            if let Some(i) = f.input.poses.iter().position(|p| p.id == line.pose_id) {
                let view = f.step.view_pose.iter().position(|&p| p == i);
                line.reprojection_rms_px = view.map(|v| f.step.calibration.views[v].rms_px);
            }
        }
    }
    report.regions = regions;
    // The gate compares on the first session's poses (`cal_data`,
    // `val_data` are its own), so with its figures.
    let (all_before, all_after) = (combined.before, combined.after);
    combined.before = validations[0].before;
    combined.after = validations[0].after;
    let decision = gate::decide(
        &combined,
        &set,
        crate::schema::session::Instrument::Camera,
        input.approved.as_ref(),
        false,
    );
    (combined.before, combined.after) = (all_before, all_after);
    report.gate = Some(decision.report);
    Ok(Output {
        parameter_set: Some(super::output::new_set(
            CalibratedSet::Kinematic(set),
            &report,
            decision.release,
        )?),
        summary: results::summary(&combined),
        detections,
        check: None,
    })
}

/// The first session's identification carrying the joint fit: the shared
/// model, its σ and covariance, the refined intrinsics, and the poses and
/// errors of every session (indices into the concatenated poses).
fn combined(
    mut first: Identified,
    joint: &JointFit,
    validations: &[SessionValidation],
    offsets: &[usize],
) -> Identified {
    let r = &joint.refined;
    first.model = r.model.clone();
    first.std_devs = r.std_devs.clone();
    first.covariance = joint.session_covariances[0].clone();
    first.refined_intrinsics =
        (!joint.intrinsics_held).then_some((r.intrinsics, r.intrinsics_std, r.reprojection_rms_px));
    first.joint_noise_rad = Some(r.joint_sigma_rad);
    first.val_errors = validations
        .iter()
        .zip(offsets)
        .flat_map(|(v, &at)| v.errors.iter().map(move |(i, b, a)| (i + at, *b, *a)))
        .collect();
    first.val = first.val_errors.iter().map(|(i, _, _)| *i).collect();
    first.outlier_errors = validations
        .iter()
        .zip(offsets)
        .flat_map(|(v, &at)| {
            v.outlier_errors
                .iter()
                .map(move |(i, b, a)| (i + at, *b, *a))
        })
        .collect();
    let before: Vec<_> = first.val_errors.iter().map(|(_, b, _)| *b).collect();
    let after: Vec<_> = first.val_errors.iter().map(|(_, _, a)| *a).collect();
    first.before = AccuracyStats::from_errors(&before);
    first.after = AccuracyStats::from_errors(&after);
    first
}
