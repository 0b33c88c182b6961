//! What the flange-pose hand–eye reports (issue 14): reprojection, the
//! intrinsics, hand–eye and board with their standard deviations, and a
//! verdict per pose.

use nalgebra::Matrix6;
use serde::{Deserialize, Serialize};

use crate::camera::model::{Intrinsics, IntrinsicsStdDev};
use crate::geometry::Pose;

/// Standard deviations of a rigid transform in `geometry::pose_error`
/// coordinates: translation (mm) and small-angle rotation (deg), both in
/// the transform's outer frame.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct PoseSigma {
    pub translation_mm: [f64; 3],
    pub rotation_deg: [f64; 3],
}

impl PoseSigma {
    /// From a 6x6 covariance `[mm; rad]`.
    pub fn from_covariance(cov: &Matrix6<f64>) -> Self {
        let s = |i: usize| cov[(i, i)].max(0.0).sqrt();
        Self {
            translation_mm: [s(0), s(1), s(2)],
            rotation_deg: [s(3), s(4), s(5)].map(f64::to_degrees),
        }
    }
}

/// Jackknife standard deviations over the poses in the fit (leave one
/// pose out, refit): unlike the formal ones they include errors of the
/// robot poses themselves, which are not white pixel noise.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct JackknifeSigma {
    pub flange_to_camera: PoseSigma,
    pub target_to_base: PoseSigma,
    pub board_scale: Option<f64>,
}

/// How one pose fared.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PoseVerdict {
    /// Left out: its robot pose contradicts its image (or it had no usable
    /// image).
    pub outlier: bool,
    /// Why it was left out; `None` for a pose in the fit.
    pub reason: Option<String>,
    /// Reprojection RMS of this pose under the screening fit (flange poses
    /// as given; px, per point), predicted from its robot pose; infinite
    /// when it cannot be computed.
    pub rms_px: f64,
    /// Distance of this pose's own board estimate from the consensus (mm,
    /// largest over the board's corners); NaN without a PnP pose.
    pub board_deviation_mm: f64,
}

/// The result of [`super::calibrate_flange`].
#[derive(Debug, Clone, PartialEq)]
pub struct FlangeCalibration {
    pub intrinsics: Intrinsics,
    /// Zero where an intrinsic was held.
    pub intrinsics_sigma: IntrinsicsStdDev,
    /// The hand–eye transform: the camera in the flange frame.
    pub flange_to_camera: Pose,
    pub flange_to_camera_sigma: PoseSigma,
    pub flange_to_camera_covariance: Matrix6<f64>,
    /// The robot base in the board frame (the kinematics' `world_to_base`).
    pub target_to_base: Pose,
    pub target_to_base_sigma: PoseSigma,
    /// The board in the robot base frame (inverse of `target_to_base`).
    pub base_to_target: Pose,
    pub base_to_target_sigma: PoseSigma,
    /// True board coordinates / configured ones (1 unless fitted).
    pub board_scale: f64,
    pub board_scale_sigma: Option<f64>,
    /// The estimated noise when the flange poses were let carry noise.
    pub flange_noise: Option<super::noise::FlangeNoise>,
    /// Jackknife sigmas; `None` with too few poses to leave one out.
    pub jackknife: Option<JackknifeSigma>,
    /// RMS reprojection over the inlier poses (px, per point).
    pub rms_px: f64,
    /// Residual standard deviation per image axis (px).
    pub sigma_px: f64,
    pub points: usize,
    pub per_pose: Vec<PoseVerdict>,
    /// Fit / re-screen rounds run.
    pub rounds: usize,
}
