//! Stage "report" of a flange-pose session (issue 14): the hand–eye
//! parameter set ([`HandEyeSet`]: no kinematics) and its report, from
//! the camera stage and the hand–eye fit ([`super::flange_stage`]).
//!
//! A hand–eye set holds no calibrated robot, so `forward`, `compensate`,
//! `filter` and the exports refuse it (409): evaluating the robot's nominal
//! joint table with a measured hand–eye would present uncalibrated
//! kinematics as calibrated.

use nalgebra::Vector3;
use robocal_calib::camera::Intrinsics;
use robocal_calib::geometry::{pose_from_xyz_rpy_deg, Pose, PoseXyzRpy};
use robocal_calib::handeye::PoseSigma;
use robocal_calib::stats::AccuracyStats;

use super::camera_stage::{camera_mode, camera_report, CameraStep};
use super::flange_stage::HandEyeStep;
use super::hand_eye_sigmas::{inverse_sigma, sigmas, Sigmas};
use super::measure::Measured;
use super::output::Summary;
use super::results::residual_field;
use super::{Input, PoseInput};
use crate::domain::HandEyeSet;
use crate::report::{
    BoardScaleReport, FrameReport, HandEyeReport, IdentifiabilityReport, ParameterReport,
    PoseReport, Report,
};
use crate::schema::session::PoseSet;
use crate::schema::PoseOut;

/// The data contradict the configured board spacing when the fitted scale
/// is this many standard deviations from 1.
const SCALE_DOUBT_SIGMAS: f64 = 3.0;
/// Names of a frame's six parameters in the report's rows.
const FRAME_PARAMS: [(&str, &str); 6] = [
    ("tx_mm", "mm"),
    ("ty_mm", "mm"),
    ("tz_mm", "mm"),
    ("rx_deg", "deg"),
    ("ry_deg", "deg"),
    ("rz_deg", "deg"),
];

/// The six rows of a frame: its guess (identity without one) against the
/// fitted value, with the reported standard deviations.
fn frame_rows(name: &str, guess: &Pose, fitted: &Pose, std: &PoseSigma) -> Vec<ParameterReport> {
    let (g, f) = (PoseXyzRpy::from_pose(guess), PoseXyzRpy::from_pose(fitted));
    let values = |p: &PoseXyzRpy| {
        [
            p.translation_mm[0],
            p.translation_mm[1],
            p.translation_mm[2],
            p.rotation_deg[0],
            p.rotation_deg[1],
            p.rotation_deg[2],
        ]
    };
    let (gv, fv) = (values(&g), values(&f));
    let sv = [
        std.translation_mm[0],
        std.translation_mm[1],
        std.translation_mm[2],
        std.rotation_deg[0],
        std.rotation_deg[1],
        std.rotation_deg[2],
    ];
    FRAME_PARAMS
        .iter()
        .enumerate()
        .map(|(k, (param, unit))| ParameterReport {
            name: format!("{name}.{param}"),
            unit: (*unit).into(),
            nominal: gv[k],
            identified: fv[k],
            std: sv[k],
            fixed: false,
        })
        .collect()
}

/// The spacing the session's board configures (dot pitch or square), mm.
fn configured_pitch_mm(input: &Input) -> f64 {
    input
        .session
        .target
        .as_ref()
        .and_then(|t| t.pitch_mm.or(t.square_mm))
        .unwrap_or(0.0)
}

/// Everything the report stage produces for a flange-pose session.
pub struct HandEyeOutput {
    pub parameters: HandEyeSet,
    pub report: Report,
    pub summary: Summary,
}

pub fn hand_eye_output(
    input: &Input,
    measured: &Measured,
    camera: &CameraStep,
    step: &HandEyeStep,
    mut notes: Vec<String>,
) -> HandEyeOutput {
    let fit = &step.fit;
    let s = sigmas(step, camera);
    let guess = input
        .session
        .flange_to_camera_guess
        .as_ref()
        .and_then(|p| pose_from_xyz_rpy_deg(p.translation_mm, p.rotation_deg).ok())
        .unwrap_or_else(Pose::identity);
    let mut rows = frame_rows(
        "flange_to_camera",
        &guess,
        &fit.flange_to_camera,
        &s.flange_to_camera,
    );
    rows.extend(frame_rows(
        "target_to_base",
        &Pose::identity(),
        &fit.target_to_base,
        &s.target_to_base,
    ));
    rows.push(ParameterReport {
        name: "board_scale".into(),
        unit: "".into(),
        nominal: 1.0,
        identified: fit.board_scale,
        std: s.board_scale,
        fixed: false,
    });
    let set = HandEyeSet {
        instrument: "camera".into(),
        session_id: input.session_id.clone(),
        target_to_base: PoseOut::new(&fit.target_to_base),
        flange_to_camera: PoseOut::new(&fit.flange_to_camera),
        base_to_target: PoseOut::new(&fit.base_to_target),
        board_scale: fit.board_scale,
        camera: fit.intrinsics,
        camera_mode: camera_mode(camera).into(),
        camera_calibration_id: camera.fixed_from.clone(),
        fixed: Vec::new(),
        parameters: rows.clone(),
    };
    let pitch = configured_pitch_mm(input);
    let board_scale = BoardScaleReport {
        scale: fit.board_scale,
        std: s.board_scale,
        configured_pitch_mm: pitch,
        pitch_mm: fit.board_scale * pitch,
        pitch_std_mm: s.board_scale * pitch,
    };
    notes.insert(
        0,
        "The poses carry the controller's flange poses: no kinematics were identified. The camera was calibrated on the images alone and held; the hand–eye, the board in the base frame and the board's scale were fitted as one bundle on the image points. `before` and `after` compare the camera position each flange pose predicts with the one its image measures.".into(),
    );
    if (fit.board_scale - 1.0).abs() > SCALE_DOUBT_SIGMAS * s.board_scale {
        notes.push(format!(
            "The data put the board spacing at {:.2} ± {:.2} mm, not the configured {pitch} mm (scale {:.4} ± {:.4}): the hand–eye and the board are given at the measured spacing; check the print.",
            board_scale.pitch_mm, board_scale.pitch_std_mm, fit.board_scale, s.board_scale
        ));
    } else {
        notes.push(format!(
            "The data confirm the configured board spacing: {:.2} ± {:.2} mm (configured {pitch} mm).",
            board_scale.pitch_mm, board_scale.pitch_std_mm
        ));
    }
    if !step.outliers.is_empty() {
        let names: Vec<String> = step
            .outliers
            .iter()
            .map(|o| input.poses[o.pose].label.clone())
            .collect();
        notes.push(format!(
            "{} poses left out (their flange pose contradicts their image, or their image shows no board): {}.",
            names.len(),
            names.join(", ")
        ));
    }
    let report = report(
        input,
        measured,
        camera,
        step,
        &s,
        set.camera,
        rows,
        board_scale,
        notes,
    );
    let summary = Summary {
        calibration_poses: step.cal.len(),
        validation_poses: input.poses.len() - step.cal.len(),
        outliers: Some(step.outliers.len()),
        reprojection_rms_px: Some(fit.rms_px),
        board_scale: Some(fit.board_scale),
        after_mean_mm: Some(report.after.norm.mean_mm),
        ..Summary::default()
    };
    HandEyeOutput {
        parameters: set,
        report,
        summary,
    }
}

#[allow(clippy::too_many_arguments)]
fn report(
    input: &Input,
    measured: &Measured,
    camera: &CameraStep,
    step: &HandEyeStep,
    s: &Sigmas,
    intrinsics: Intrinsics,
    rows: Vec<ParameterReport>,
    board_scale: BoardScaleReport,
    notes: Vec<String>,
) -> Report {
    let fit = &step.fit;
    let poses: &[PoseInput] = &input.poses;
    let reason_of = |i: usize| {
        step.outliers
            .iter()
            .find(|o| o.pose == i)
            .map(|o| o.reason.clone())
    };
    let error_of = |i: usize| step.errors.iter().find(|(p, _)| *p == i).map(|(_, e)| *e);
    let rms_of = |i: usize| match step.cal.iter().position(|&c| c == i) {
        Some(k) => Some(fit.per_pose[k].rms_px).filter(|v| v.is_finite()),
        None => {
            let view = camera.view_pose.iter().position(|&p| p == i)?;
            Some(camera.calibration.views[view].rms_px)
        }
    };
    let per_pose = (0..poses.len())
        .map(|i| {
            let e = error_of(i).unwrap_or_else(Vector3::zeros);
            PoseReport {
                pose_id: poses[i].id.clone(),
                label: poses[i].label.clone(),
                set: poses[i].set.as_str().into(),
                joints_deg: Vec::new(),
                before_error_mm: [e.x, e.y, e.z],
                after_error_mm: [e.x, e.y, e.z],
                before_mm: e.norm(),
                after_mm: e.norm(),
                reprojection_rms_px: rms_of(i),
                outlier: reason_of(i).is_some(),
                reason: reason_of(i),
                camera_in_target: None,
            }
        })
        .collect();
    // Validation poses when there are any, else the calibration poses in
    // the fit.
    let val: Vec<Vector3<f64>> = (0..poses.len())
        .filter(|&i| poses[i].set == PoseSet::Val)
        .filter_map(error_of)
        .collect();
    let judged = if val.is_empty() {
        step.inliers().filter_map(error_of).collect()
    } else {
        val
    };
    let stats = AccuracyStats::from_errors(&judged);
    Report {
        serial: input.serial.clone(),
        version: 0,
        job_id: String::new(),
        session_id: input.session_id.clone(),
        created_at: crate::domain::now_rfc3339(),
        instrument: "camera".into(),
        measurement: "pose".into(),
        camera: Some(camera_report(camera, &intrinsics, None, poses)),
        detection: Some(measured.report()),
        before: stats,
        after: stats,
        per_pose,
        parameters: rows.clone(),
        identifiability: IdentifiabilityReport {
            parameters: rows.len(),
            rank: rows.len(),
            ..IdentifiabilityReport::default()
        },
        residual_field: residual_field(camera),
        hand_eye: Some(HandEyeReport {
            flange_to_camera: FrameReport::new(
                &fit.flange_to_camera,
                &s.flange_to_camera,
                &fit.flange_to_camera_sigma,
            ),
            target_to_base: FrameReport::new(
                &fit.target_to_base,
                &s.target_to_base,
                &fit.target_to_base_sigma,
            ),
            base_to_target: FrameReport::new(
                &fit.base_to_target,
                &inverse_sigma(&fit.target_to_base, &s.target_to_base),
                &fit.base_to_target_sigma,
            ),
            board_scale,
            std_source: s.source.into(),
            reprojection_rms_px: fit.rms_px,
            sigma_px: fit.sigma_px,
            poses_used: step.inliers().count(),
            points: fit.points,
        }),
        notes,
        uncertainty_map: None,
        terms: None,
        gate: None,
        model_selection: None,
        release: Default::default(),
        measurement_accuracy: None,
        regions: Vec::new(),
    }
}
