//! Stage "report" of a stage session (issue 18): the camera set
//! ([`StageCameraSet`]: intrinsics, no robot model) and its report, whose
//! `measurement_accuracy` is the paper's Table 1 per sequence and whose
//! `per_pose[i].camera_in_target` is each image's measured camera pose.
//!
//! The set's `camera` is what a robot session reuses
//! (`camera_calibration_id`, [`crate::service::camera_reuse`]); `forward`,
//! `compensate` and the exports refuse it (409: it holds no model).

use nalgebra::Vector3;
use robocal_calib::geometry::Pose;
use robocal_calib::stage::StageCalibration;
use robocal_calib::stats::AccuracyStats;

use super::measure::Measured;
use super::output::Summary;
use super::Input;
use crate::domain::{StageCameraSet, StageSequence};
use crate::report::{
    CameraReport, IdentifiabilityReport, MeasurementAccuracyReport, PoseReport, Report,
    SequenceAccuracyReport, ViewReport,
};
use crate::schema::PoseOut;

/// Everything the report stage produces for a stage session.
pub struct StageOutput {
    pub parameters: StageCameraSet,
    pub report: Report,
    pub summary: Summary,
}

/// The set, report and summary of a stage calibration; `view_pose[v]` is
/// the session pose of the calibration's view `v`.
pub fn stage_output(
    input: &Input,
    measured: &Measured,
    fit: &StageCalibration,
    view_pose: &[usize],
    mut notes: Vec<String>,
) -> StageOutput {
    let sequences = fit
        .sequences
        .iter()
        .map(|s| {
            let at_zero = s.fit.target_to_camera(&Vector3::zeros());
            StageSequence {
                sequence: s.sequence,
                target_to_camera: PoseOut::new(&at_zero),
                target_to_stage: PoseOut::new(&Pose::from_parts(
                    at_zero.translation,
                    s.fit.target_to_stage_rotation,
                )),
            }
        })
        .collect();
    let parameters = StageCameraSet {
        instrument: "stage".into(),
        session_id: input.session_id.clone(),
        camera: fit.intrinsics,
        camera_mode: "stage".into(),
        camera_std: fit.std_dev,
        sequences,
    };
    let errors: Vec<Vector3<f64>> = fit
        .views
        .iter()
        .map(|v| v.average_rotation_error_mm)
        .collect();
    let stats = AccuracyStats::from_errors(&errors);
    if !measured.failures.is_empty() {
        notes.push(format!(
            "{} of {} images were not used (see detection failures).",
            measured.failures.len(),
            measured.points.len()
        ));
    }
    notes.push(
        "Stage calibration (paper section 4): the intrinsics were fitted with the stage's translations as constraints; `before` and `after` are the images' position errors by the paper's average-rotation method, which sees the orientation's scatter but not a common depth error (the travelled-distance error checks the scale).".into(),
    );
    let report = Report {
        serial: input.serial.clone(),
        version: 0,
        job_id: String::new(),
        session_id: input.session_id.clone(),
        created_at: crate::domain::now_rfc3339(),
        instrument: "stage".into(),
        measurement: "pose".into(),
        camera: Some(camera_report(input, fit, view_pose)),
        detection: Some(measured.report()),
        before: stats,
        after: stats,
        per_pose: per_pose(input, fit, view_pose),
        parameters: Vec::new(),
        identifiability: IdentifiabilityReport::default(),
        residual_field: Vec::new(),
        hand_eye: None,
        notes,
        uncertainty_map: None,
        gate: None,
        model_selection: None,
        release: Default::default(),
        terms: None,
        regions: Vec::new(),
        measurement_accuracy: Some(MeasurementAccuracyReport {
            sequences: fit
                .accuracy
                .iter()
                .map(SequenceAccuracyReport::from)
                .collect(),
        }),
    };
    let summary = Summary {
        calibration_poses: fit.views.len(),
        before_mean_mm: Some(stats.norm.mean_mm),
        after_mean_mm: Some(stats.norm.mean_mm),
        reprojection_rms_px: Some(fit.rms_px),
        ..Summary::default()
    };
    StageOutput {
        parameters,
        report,
        summary,
    }
}

fn per_pose(input: &Input, fit: &StageCalibration, view_pose: &[usize]) -> Vec<PoseReport> {
    fit.views
        .iter()
        .zip(view_pose)
        .map(|(v, &i)| {
            let e = v.average_rotation_error_mm;
            PoseReport {
                pose_id: input.poses[i].id.clone(),
                label: input.poses[i].label.clone(),
                set: input.poses[i].set.as_str().into(),
                joints_deg: Vec::new(),
                before_error_mm: [e.x, e.y, e.z],
                after_error_mm: [e.x, e.y, e.z],
                before_mm: e.norm(),
                after_mm: e.norm(),
                reprojection_rms_px: Some(v.pose.rms_px),
                outlier: false,
                reason: None,
                camera_in_target: Some(PoseOut::new(&v.pose.target_to_camera)),
            }
        })
        .collect()
}

fn camera_report(input: &Input, fit: &StageCalibration, view_pose: &[usize]) -> CameraReport {
    CameraReport {
        mode: "stage".into(),
        camera_calibration_id: None,
        image_width: fit.image_size.width,
        image_height: fit.image_size.height,
        intrinsics: fit.intrinsics,
        std: fit.std_dev,
        reprojection_rms_px: fit.rms_px,
        outliers_dropped: fit.start.outliers.len(),
        views: fit
            .views
            .iter()
            .zip(view_pose)
            .zip(&fit.start.views)
            .map(|((v, &i), start)| ViewReport {
                pose_id: input.poses[i].id.clone(),
                label: input.poses[i].label.clone(),
                rms_px: v.pose.rms_px,
                board_angle_deg: start.board_angle_deg,
                warning: None,
            })
            .collect(),
    }
}
