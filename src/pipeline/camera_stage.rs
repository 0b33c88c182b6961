//! Stage "calibrate_camera": intrinsics and every image's camera pose from
//! the detected dots (method.md §2–4; refined mode by default, the paper's
//! Tsai sequence when `refine_intrinsics` is false, and only the poses when
//! the session reuses an earlier calibration's intrinsics).

use nalgebra::{Point2, Point3};
use robocal_calib::camera::calibrate::{CalibrationMode, CalibrationOptions};
use robocal_calib::camera::leave_out::{calibrate_leaving_out, CalibrationLeavingOut};
use robocal_calib::camera::observations::{DotObservation, ImageSize, ViewObservations};
use robocal_calib::camera::pose::PoseEstimate;
use robocal_calib::camera::{CameraCalibration, Intrinsics};

use super::measure::{GridPoint, Measured};
use super::{FixedCamera, PipelineError, PoseInput, Stage};
use crate::domain::Target;
use crate::report::{CameraReport, CameraStd, ViewReport};
use crate::schema::session::CameraDoc;

/// The camera step's outcome, per pose where the pose had a usable image.
pub struct CameraStep {
    pub calibration: CameraCalibration,
    /// Index into the session's poses of each calibrated view.
    pub view_pose: Vec<usize>,
    /// Per view, `(board point mm, bias-corrected pixel)`.
    pub observations: Vec<Vec<(Point3<f64>, Point2<f64>)>>,
    /// Per view, the `(row, col)` of each of `observations`.
    pub grid: Vec<Vec<(u32, u32)>>,
    /// `"{serial}/{version}"` whose intrinsics were held fixed, if any.
    pub fixed_from: Option<String>,
    /// Poses whose view the camera calibration could not start from (no
    /// initial pose from the homography), left out with the reason.
    pub left_out: Vec<(usize, String)>,
}

impl CameraStep {
    pub fn intrinsics(&self) -> Intrinsics {
        self.calibration.intrinsics
    }

    /// The camera pose measured at `pose` (index into the session's poses).
    pub fn pose_estimate(&self, pose: usize) -> Option<&PoseEstimate> {
        let view = self.view_pose.iter().position(|&p| p == pose)?;
        Some(&self.calibration.views[view].pose)
    }

    pub fn observations_of(&self, pose: usize) -> Option<&[(Point3<f64>, Point2<f64>)]> {
        let view = self.view_pose.iter().position(|&p| p == pose)?;
        Some(&self.observations[view])
    }
}

pub(super) fn view_of(points: &[GridPoint], target: &Target, size: ImageSize) -> ViewObservations {
    ViewObservations {
        image_size: size,
        dots: points
            .iter()
            .filter(|p| !target.left_out(p.row, p.col))
            .map(|p| DotObservation {
                row: p.row,
                col: p.col,
                target_mm: Point3::from(target.point_mm(p.row, p.col)),
                pixel: Point2::new(p.x, p.y),
            })
            .collect(),
    }
}

pub fn calibrate_camera(
    poses: &[PoseInput],
    measured: &Measured,
    target: &Target,
    camera: &CameraDoc,
    refine_intrinsics: bool,
    fixed: Option<&FixedCamera>,
) -> Result<CameraStep, PipelineError> {
    let size = ImageSize {
        width: camera.width,
        height: camera.height,
    };
    let (mut views, mut view_pose) = (Vec::new(), Vec::<usize>::new());
    for (i, points) in measured.points.iter().enumerate() {
        if let Some(points) = points {
            views.push(view_of(points, target, size));
            view_pose.push(i);
        }
    }
    let options = CalibrationOptions {
        // Fixed intrinsics are honoured by the refined mode only (it fits
        // the poses and the bias correction around them); paper mode would
        // return its own sequence estimates.
        mode: if refine_intrinsics || fixed.is_some() {
            CalibrationMode::Refined
        } else {
            CalibrationMode::Paper
        },
        fixed_intrinsics: fixed.map(|f| f.intrinsics),
        dot_diameter_mm: target.dot_diameter_mm(),
        ..CalibrationOptions::default()
    };
    // A view the calibration cannot start from is left out and named
    // rather than failing the whole job, as long as most views remain.
    let CalibrationLeavingOut {
        calibration,
        kept,
        left_out,
    } = calibrate_leaving_out(&views, &options).map_err(|failed| {
        let seen: Vec<usize> = failed.kept.iter().map(|&v| view_pose[v]).collect();
        PipelineError::Numerical {
            stage: Stage::CalibrateCamera.as_str(),
            message: describe_camera_error(&failed.error.to_string(), &seen, poses),
        }
    })?;
    let left_out = left_out
        .into_iter()
        .map(|l| (view_pose[l.view], l.reason))
        .collect();
    let views: Vec<&ViewObservations> = kept.iter().map(|&v| &views[v]).collect();
    let view_pose: Vec<usize> = kept.iter().map(|&v| view_pose[v]).collect();
    let observations = views
        .iter()
        .zip(&calibration.views)
        .map(|(view, fit)| {
            view.dots
                .iter()
                .zip(&fit.corrected_pixels)
                .map(|(d, px)| (d.target_mm, *px))
                .collect()
        })
        .collect();
    let grid = views
        .iter()
        .map(|view| view.dots.iter().map(|d| (d.row, d.col)).collect())
        .collect();
    Ok(CameraStep {
        calibration,
        view_pose,
        observations,
        grid,
        fixed_from: fixed.map(|f| f.calibration_id.clone()),
        left_out,
    })
}

/// Camera errors name views by index; a cell engineer needs the pose id.
fn describe_camera_error(message: &str, view_pose: &[usize], poses: &[PoseInput]) -> String {
    let names: Vec<String> = view_pose.iter().map(|&i| poses[i].id.clone()).collect();
    let mut out = message.to_string();
    for (view, name) in names.iter().enumerate().rev() {
        out = out.replace(&format!("view {view}"), &format!("pose {name}"));
        out = out.replace(&format!("image {view}"), &format!("pose {name}"));
    }
    format!(
        "{out} (check the images of the named poses, or add views at 20-45 degrees to the board)"
    )
}

/// How the intrinsics were obtained: `"fixed"` (from an earlier
/// calibration), `"paper"` (the Tsai sequence only) or `"refined"`.
pub fn camera_mode(step: &CameraStep) -> &'static str {
    if step.fixed_from.is_some() {
        "fixed"
    } else if step.calibration.paper_mode {
        "paper"
    } else {
        "refined"
    }
}

/// The report's camera section; `final_intrinsics` may come from the joint
/// refinement.
pub fn camera_report(
    step: &CameraStep,
    final_intrinsics: &Intrinsics,
    std: Option<CameraStd>,
    poses: &[PoseInput],
) -> CameraReport {
    let c = &step.calibration;
    let views = c
        .views
        .iter()
        .zip(&step.view_pose)
        .map(|(v, &pose)| ViewReport {
            pose_id: poses[pose].id.clone(),
            label: poses[pose].label.clone(),
            rms_px: v.rms_px,
            board_angle_deg: v.board_angle_deg,
            warning: (v.board_angle_deg < robocal_calib::camera::calibrate::WARN_BOARD_ANGLE_DEG)
                .then(|| {
                    "board-to-image angle under 20 degrees: focal length poorly conditioned"
                        .to_string()
                }),
        })
        .collect();
    CameraReport {
        mode: camera_mode(step).to_string(),
        camera_calibration_id: step.fixed_from.clone(),
        image_width: c.image_size.width,
        image_height: c.image_size.height,
        intrinsics: *final_intrinsics,
        std: std.or(c.std_dev),
        reprojection_rms_px: c.rms_px,
        outliers_dropped: c.outliers.len(),
        views,
    }
}
