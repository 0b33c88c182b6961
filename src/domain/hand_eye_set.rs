//! The set a flange-pose session calibrates: the hand–eye, the board in the
//! base frame and its scale, with the camera they were fitted with
//! (method.md §5). It holds no kinematics: `forward`, `compensate`,
//! `filter` and the exports refuse it (409), since evaluating the robot's
//! nominal joint table beside a measured hand–eye would present
//! uncalibrated kinematics as calibrated.

use robocal_calib::camera::Intrinsics;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::numerics_schema::IntrinsicsSchema;
use super::ParameterReport;
use super::PoseOut;

/// A hand–eye set (`kind` `hand_eye`), from a session of controller flange
/// poses.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct HandEyeSet {
    /// Always `camera`.
    pub instrument: String,
    /// The session the set was calibrated from.
    pub session_id: String,
    /// The board's frame in the robot base frame.
    pub target_to_base: PoseOut,
    /// The camera in the flange frame.
    pub flange_to_camera: PoseOut,
    /// The board in the robot base frame (the inverse of `target_to_base`).
    pub base_to_target: PoseOut,
    /// True board coordinates / configured ones.
    pub board_scale: f64,
    /// The camera intrinsics the hand–eye was fitted with.
    #[schema(value_type = IntrinsicsSchema)]
    pub camera: Intrinsics,
    /// How `camera` was obtained: `refined`, `paper` or `fixed`.
    pub camera_mode: String,
    /// The calibration (`"{serial}/{version}"`) whose intrinsics were held fixed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera_calibration_id: Option<String>,
    /// Parameters held fixed (none for a hand–eye fit).
    pub fixed: Vec<String>,
    /// Each frame's six parameters and the board scale, guess against fit.
    pub parameters: Vec<ParameterReport>,
}
