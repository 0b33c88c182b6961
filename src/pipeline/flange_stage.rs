//! Stage "identify" of a flange-pose session (issue 14, "Poses from the
//! controller"): no kinematics are identified. The camera stage's
//! intrinsics (from the images alone) are held, and `calib`'s hand–eye
//! bundle fits `flange_to_camera`, `target_to_base` and the board scale on
//! the image points of the calibration poses, with the controller's flange
//! poses as given; poses whose flange pose contradicts their image are
//! screened out there (method.md §4 and §6 **beyond**).
//!
//! The intrinsics are held because the images determine the camera far
//! better than controller poses can: on the RCT wrist set a free bundle
//! bends `fx` by 5 % against the camera depth (docs/decisions/0003-flange-pose-sessions.md).

use nalgebra::Vector3;
use robocal_calib::handeye::{calibrate_flange, FlangeCalibration, FlangeOptions, FlangeView};
use robocal_calib::vision::BoardPoint;

use super::camera_stage::CameraStep;
use super::measure::Measured;
use super::screen_stage::Outlier;
use super::{PipelineError, PoseInput, Stage};
use crate::schema::session::PoseSet;

/// The hand–eye fit of a flange-pose session.
pub struct HandEyeStep {
    pub fit: FlangeCalibration,
    /// Indices (into the session's poses) of the calibration poses, in the
    /// order of `fit.per_pose`.
    pub cal: Vec<usize>,
    /// Calibration poses left out (no board, or a flange pose that
    /// contradicts the image), with why.
    pub outliers: Vec<Outlier>,
    /// Per pose with a camera view: the camera position its flange pose and
    /// the fit predict minus the one its image measures, board frame, mm.
    pub errors: Vec<(usize, Vector3<f64>)>,
}

impl HandEyeStep {
    /// The calibration poses in the fit.
    pub fn inliers(&self) -> impl Iterator<Item = usize> + '_ {
        self.cal
            .iter()
            .copied()
            .filter(|i| self.outliers.iter().all(|o| o.pose != *i))
    }
}

/// The board points of pose `i` as the camera stage measured them (bias
/// corrected), empty when its image gave none.
fn view_points(step: &CameraStep, i: usize) -> Vec<BoardPoint> {
    let view = match step.view_pose.iter().position(|&p| p == i) {
        Some(v) => v,
        None => return Vec::new(),
    };
    step.observations[view]
        .iter()
        .zip(&step.grid[view])
        .map(|((p, px), &(row, col))| BoardPoint {
            row: row as usize,
            col: col as usize,
            target_mm: [p.x, p.y, p.z],
            x_px: px.x,
            y_px: px.y,
        })
        .collect()
}

/// Why pose `i` had no board points: its detection failure, or why the
/// camera calibration left its view out (a board found, but no initial
/// pose from the homography), if either.
fn missing_view_reason(
    measured: &Measured,
    step: &CameraStep,
    poses: &[PoseInput],
    i: usize,
) -> Option<String> {
    let detection = measured
        .failures
        .iter()
        .find(|f| f.pose_id == poses[i].id)
        .map(|f| format!("no board in the image: {}", f.reason));
    detection.or_else(|| {
        step.left_out
            .iter()
            .find(|(pose, _)| *pose == i)
            .map(|(_, why)| format!("left out of the camera calibration: {why}"))
    })
}

/// Hand–eye and board from the calibration poses' flange poses and images.
pub fn hand_eye(
    poses: &[PoseInput],
    measured: &Measured,
    step: &CameraStep,
) -> Result<HandEyeStep, PipelineError> {
    let cal: Vec<usize> = (0..poses.len())
        .filter(|&i| poses[i].set == PoseSet::Cal)
        .collect();
    let views: Vec<FlangeView> = cal
        .iter()
        .filter_map(|&i| {
            Some(FlangeView {
                base_to_flange: poses[i].flange_pose?.base_to_flange(),
                points: view_points(step, i),
            })
        })
        .collect();
    if views.len() != cal.len() {
        return Err(PipelineError::Numerical {
            stage: Stage::Identify.as_str(),
            message: "every pose of a hand–eye session needs a flange_pose".into(),
        });
    }
    let options = FlangeOptions {
        start_intrinsics: step.intrinsics(),
        distortion: true,
        hold_intrinsics: true,
        fit_board_scale: true,
        estimate_flange_noise: false,
    };
    let fit = calibrate_flange(&views, &options).map_err(|e| PipelineError::Numerical {
        stage: Stage::Identify.as_str(),
        message: format!("hand–eye from flange poses: {e}"),
    })?;
    let outliers = cal
        .iter()
        .zip(&fit.per_pose)
        .filter(|(_, v)| v.outlier)
        .map(|(&i, v)| Outlier {
            pose: i,
            reason: missing_view_reason(measured, step, poses, i)
                .or_else(|| v.reason.clone())
                .unwrap_or_else(|| "left out by the screening".into()),
        })
        .collect();
    let errors = (0..poses.len())
        .filter_map(|i| {
            let measured = step.pose_estimate(i)?.target_to_camera;
            let predicted =
                fit.target_to_base * poses[i].flange_pose?.base_to_flange() * fit.flange_to_camera;
            // The camera stage measured on the configured board; the fit's
            // board is `board_scale` times it.
            Some((
                i,
                predicted.translation.vector - measured.translation.vector * fit.board_scale,
            ))
        })
        .collect();
    Ok(HandEyeStep {
        fit,
        cal,
        outliers,
        errors,
    })
}
