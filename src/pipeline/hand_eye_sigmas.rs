//! The standard deviations a hand–eye report states (issue 14): the
//! jackknife's when there were enough poses, else the bundle's formal ones,
//! widened by the camera's principal-point uncertainty the bundle cannot
//! see; and their propagation to the inverse frame (`base_to_target`).

use nalgebra::{Matrix6, Vector6};
use robocal_calib::geometry::Pose;
use robocal_calib::handeye::PoseSigma;

use super::camera_stage::CameraStep;
use super::flange_stage::HandEyeStep;

/// The standard deviations the report stands by (the jackknife's when
/// there were enough poses) and their source.
pub struct Sigmas {
    pub flange_to_camera: PoseSigma,
    pub target_to_base: PoseSigma,
    pub board_scale: f64,
    pub source: &'static str,
}

pub fn sigmas(step: &HandEyeStep, camera: &CameraStep) -> Sigmas {
    let fit = &step.fit;
    let formal_scale = fit.board_scale_sigma.unwrap_or(0.0);
    let s = match &fit.jackknife {
        Some(j) => Sigmas {
            flange_to_camera: j.flange_to_camera,
            target_to_base: j.target_to_base,
            board_scale: j.board_scale.unwrap_or(formal_scale),
            source: "jackknife",
        },
        None => Sigmas {
            flange_to_camera: fit.flange_to_camera_sigma,
            target_to_base: fit.target_to_base_sigma,
            board_scale: formal_scale,
            source: "formal",
        },
    };
    // The bundle holds the camera stage's intrinsics, so neither the
    // formal nor the jackknife sigmas see their error; the principal
    // point's turns every camera ray by sigma_c / f (rad), which goes
    // straight into the hand–eye and board rotations. Added in quadrature
    // about every axis (conservative: it acts about the camera's x and y).
    let principal_deg = camera.calibration.std_dev.map_or(0.0, |sd| {
        let i = camera.intrinsics();
        (sd.cx / i.fx).hypot(sd.cy / i.fy).to_degrees()
    });
    let widen = |p: PoseSigma| PoseSigma {
        rotation_deg: p.rotation_deg.map(|r| r.hypot(principal_deg)),
        ..p
    };
    Sigmas {
        flange_to_camera: widen(s.flange_to_camera),
        target_to_base: widen(s.target_to_base),
        ..s
    }
}

/// Standard deviations of `pose.inverse()` from those of `pose` (taken
/// uncorrelated), in `geometry::pose_error` coordinates: a left
/// perturbation `(v, w)` of `T = (R, t)` moves `T^-1` by
/// `(-R^T v - R^T [t]x w, -R^T w)`.
pub fn inverse_sigma(pose: &Pose, sigma: &PoseSigma) -> PoseSigma {
    let r_t = pose.rotation.to_rotation_matrix().into_inner().transpose();
    let t = pose.translation.vector;
    let mut j = Matrix6::zeros();
    j.fixed_view_mut::<3, 3>(0, 0).copy_from(&(-r_t));
    j.fixed_view_mut::<3, 3>(0, 3)
        .copy_from(&(-r_t * t.cross_matrix()));
    j.fixed_view_mut::<3, 3>(3, 3).copy_from(&(-r_t));
    let d = Vector6::new(
        sigma.translation_mm[0],
        sigma.translation_mm[1],
        sigma.translation_mm[2],
        sigma.rotation_deg[0].to_radians(),
        sigma.rotation_deg[1].to_radians(),
        sigma.rotation_deg[2].to_radians(),
    );
    let cov = Matrix6::from_diagonal(&d.component_mul(&d));
    PoseSigma::from_covariance(&(j * cov * j.transpose()))
}
