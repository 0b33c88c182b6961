//! The report's hand–eye section (issue 14): a camera session whose poses
//! carry the controller's flange poses identifies no kinematics; its
//! result is the camera in the flange frame, the board in the base frame
//! and the board's true scale, each with standard deviations.

use robocal_calib::geometry::{pose_to_matrix_rows, Pose, PoseXyzRpy};
use robocal_calib::handeye::PoseSigma;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// A fitted rigid transform: translation (mm), fixed-axis X-Y-Z angles
/// (deg, `R = Rz Ry Rx`), the 4x4 row-major matrix, and its standard
/// deviations (mm; small-angle rotation in deg about the outer frame's
/// axes).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct FrameReport {
    pub translation_mm: [f64; 3],
    pub rotation_deg: [f64; 3],
    pub matrix: [[f64; 4]; 4],
    /// The standard deviations the report stands by: the jackknife's (leave
    /// one pose out, refit), which include the controller poses' own
    /// errors, when there were enough poses, else the formal ones; the
    /// rotations widened by the held camera's principal-point uncertainty
    /// (`sigma_c / f`), which neither sees.
    pub std_translation_mm: [f64; 3],
    pub std_rotation_deg: [f64; 3],
    /// The formal standard deviations (white pixel noise, exact flange
    /// poses): too small when the controller poses carry errors.
    pub formal_std_translation_mm: [f64; 3],
    pub formal_std_rotation_deg: [f64; 3],
}

impl FrameReport {
    /// `pose` with its reported (`std`) and formal standard deviations.
    pub fn new(pose: &Pose, std: &PoseSigma, formal: &PoseSigma) -> Self {
        let form = PoseXyzRpy::from_pose(pose);
        Self {
            translation_mm: form.translation_mm,
            rotation_deg: form.rotation_deg,
            matrix: pose_to_matrix_rows(pose),
            std_translation_mm: std.translation_mm,
            std_rotation_deg: std.rotation_deg,
            formal_std_translation_mm: formal.translation_mm,
            formal_std_rotation_deg: formal.rotation_deg,
        }
    }
}

/// What the data say of the board's size: the fitted scale on the
/// configured one, and the feature spacing it implies.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct BoardScaleReport {
    /// True board coordinates / configured ones.
    pub scale: f64,
    pub std: f64,
    /// The spacing the session's target configures (dot pitch or square
    /// side), mm.
    pub configured_pitch_mm: f64,
    /// `scale * configured_pitch_mm`: the spacing as printed, mm.
    pub pitch_mm: f64,
    pub pitch_std_mm: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct HandEyeReport {
    /// The camera in the flange frame.
    pub flange_to_camera: FrameReport,
    /// The robot base in the board frame (`target_to_base`).
    pub target_to_base: FrameReport,
    /// The board in the robot base frame.
    pub base_to_target: FrameReport,
    pub board_scale: BoardScaleReport,
    /// `"jackknife"` or `"formal"`: which standard deviations `std_*` are.
    pub std_source: String,
    /// RMS reprojection over the poses in the fit (px, per point).
    pub reprojection_rms_px: f64,
    /// Residual standard deviation per image axis (px).
    pub sigma_px: f64,
    /// Calibration poses in the fit, and image points they hold.
    pub poses_used: usize,
    pub points: usize,
}
