//! The image points a job measured on each camera pose, in the form stored
//! on the pose rows and served by `GET /v1/sessions/{id}/poses/{pose_id}`
//! (api.md "Measurement sessions"): the detected (or uploaded) dot centres
//! right after the detect stage, and once the job succeeds each point's
//! reprojection residual under the final model.
//!
//! A residual is observed minus predicted, in pixels; "observed" is the dot
//! centre after the camera stage's perspective/distortion bias correction
//! (method.md §4 **beyond**), which is what the fits use. The prediction is
//! the calibrated robot model's (method.md §5: `target_to_camera` at the
//! pose's joints) through the final intrinsics, the residual the joint
//! refinement minimises (method.md §6 **beyond**). Position-only
//! identification leaves the camera's orientation undetermined: no
//! residuals then.

use nalgebra::{Isometry3, Point3};
use robocal_calib::camera::Intrinsics;
use robocal_calib::kinematics::term_model::TermModel;

use super::camera_stage::CameraStep;
use super::measure::{GridPoint, Measured};
use super::PoseInput;
use crate::domain::{MeasuredPoint, MeasuredPose};
use crate::store::PoseDetection;

fn source(pose: &PoseInput) -> &'static str {
    if pose.image.is_some() {
        "image"
    } else {
        "image_points"
    }
}

fn plain(p: &GridPoint) -> MeasuredPoint {
    MeasuredPoint {
        row: p.row,
        col: p.col,
        x: p.x,
        y: p.y,
        raw_x: None,
        raw_y: None,
        residual_px: None,
        outlier: false,
    }
}

fn stored(pose: &PoseInput, doc: MeasuredPose, measured: &Measured, i: usize) -> PoseDetection {
    let fresh = measured.detected_now.get(i).copied().unwrap_or(false);
    PoseDetection {
        pose_id: pose.id.clone(),
        detection: doc,
        image_detection: measured
            .detections
            .get(i)
            .and_then(Option::as_ref)
            .filter(|_| fresh)
            .cloned(),
    }
}

/// The detect stage's outcome per pose, without residuals.
pub fn detected(poses: &[PoseInput], measured: &Measured) -> Vec<PoseDetection> {
    poses
        .iter()
        .zip(&measured.points)
        .enumerate()
        .map(|(i, (pose, points))| {
            let doc = MeasuredPose {
                source: source(pose),
                points: points.iter().flatten().map(plain).collect(),
                error: points.is_none().then(|| failure(measured, &pose.id)),
                residual_rms_px: None,
                job_id: None,
            };
            stored(pose, doc, measured, i)
        })
        .collect()
}

fn failure(measured: &Measured, pose_id: &str) -> String {
    measured
        .failures
        .iter()
        .find(|f| f.pose_id == pose_id)
        .map_or_else(|| "no dots detected".to_string(), |f| f.reason.clone())
}

/// The final points: [`detected`] with the camera stage's bias-corrected
/// centres as `x`, `y` (the raw ones kept as `raw_x`, `raw_y`) plus, when
/// the job identified full poses (`full_pose`), every point's residual
/// under the calibrated `model` (with its kept non-geometric terms: the
/// pose's joints are the commanded ones) and `intrinsics`.
pub fn with_residuals(
    poses: &[PoseInput],
    measured: &Measured,
    step: &CameraStep,
    model: &TermModel,
    intrinsics: &Intrinsics,
    full_pose: bool,
) -> Vec<PoseDetection> {
    let mut out = detected(poses, measured);
    for (view, &i) in step.view_pose.iter().enumerate() {
        let pose = &poses[i];
        let joints_rad: Vec<f64> = pose.joints_deg.to_radians();
        let target_to_camera = match model.world_to_tool(&joints_rad) {
            Ok(t) if full_pose => Some(t),
            _ => None,
        };
        let outliers: Vec<(u32, u32)> = step
            .calibration
            .outliers
            .iter()
            .filter(|o| o.view == view)
            .map(|o| (o.row, o.col))
            .collect();
        let residuals = target_to_camera
            .map(|t| residuals_of(step, view, &t.inverse(), intrinsics))
            .unwrap_or_default();
        // Paper mode fits the raw centres: nothing corrected to serve.
        let corrected = if step.calibration.paper_mode {
            Vec::new()
        } else {
            corrected_of(step, view)
        };
        let points = measured.points[i].iter().flatten().map(|p| {
            let at = (p.row, p.col);
            let fitted = corrected.iter().find(|(grid, _)| *grid == at);
            MeasuredPoint {
                residual_px: residuals
                    .iter()
                    .find(|(grid, _)| *grid == at)
                    .map(|(_, r)| *r),
                outlier: outliers.contains(&at),
                x: fitted.map_or(p.x, |(_, c)| c[0]),
                y: fitted.map_or(p.y, |(_, c)| c[1]),
                raw_x: fitted.map(|_| p.x),
                raw_y: fitted.map(|_| p.y),
                ..plain(p)
            }
        });
        let points: Vec<MeasuredPoint> = points.collect();
        let used: Vec<[f64; 2]> = points
            .iter()
            .filter(|p| !p.outlier)
            .filter_map(|p| p.residual_px)
            .collect();
        let rms = (used.iter().map(|[x, y]| x * x + y * y).sum::<f64>() / used.len().max(1) as f64)
            .sqrt();
        let doc = MeasuredPose {
            source: source(pose),
            points,
            error: None,
            residual_rms_px: (!used.is_empty()).then_some(rms),
            job_id: None,
        };
        out[i] = stored(pose, doc, measured, i);
    }
    out
}

/// `((row, col), [x, y])`: the bias-corrected centre of every dot the
/// camera stage used in `view` (the origin marker is not among them).
fn corrected_of(step: &CameraStep, view: usize) -> Vec<((u32, u32), [f64; 2])> {
    step.grid[view]
        .iter()
        .zip(&step.observations[view])
        .map(|(&grid, (_, px))| (grid, [px.x, px.y]))
        .collect()
}

/// `((row, col), [dx, dy])` of every dot the camera stage used in `view`.
fn residuals_of(
    step: &CameraStep,
    view: usize,
    camera_to_target: &Isometry3<f64>,
    intrinsics: &Intrinsics,
) -> Vec<((u32, u32), [f64; 2])> {
    step.grid[view]
        .iter()
        .zip(&step.observations[view])
        .filter_map(|(&grid, (p, observed)): (_, &(Point3<f64>, _))| {
            let predicted = intrinsics.project(&(camera_to_target * p))?;
            Some((grid, [observed.x - predicted.x, observed.y - predicted.y]))
        })
        .collect()
}
