//! The set a stage session calibrates: the camera's intrinsics fitted with
//! the stage's translations as constraints, and each sequence's frames
//! (method.md §3). It holds no robot model; a robot session reuses its
//! `camera` (`camera_calibration_id`), and `forward`, `compensate` and the
//! exports refuse it (409).

use robocal_calib::camera::{Intrinsics, IntrinsicsStdDev};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::numerics_schema::{IntrinsicsSchema, IntrinsicsStdSchema};
use super::PoseOut;

/// A stage camera set (`kind` `stage_camera`).
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct StageCameraSet {
    /// Always `stage`.
    pub instrument: String,
    /// The session the set was calibrated from.
    pub session_id: String,
    /// The calibrated camera intrinsics.
    #[schema(value_type = IntrinsicsSchema)]
    pub camera: Intrinsics,
    /// Always `stage`: fitted with the stage's translations as constraints.
    pub camera_mode: String,
    /// The intrinsics' standard deviations, when the fit gave them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(value_type = Option<IntrinsicsStdSchema>)]
    pub camera_std: Option<IntrinsicsStdDev>,
    /// Each fitted sequence (board placement).
    pub sequences: Vec<StageSequence>,
}

/// One fitted sequence of a stage camera set.
#[derive(Debug, Clone, Serialize, Deserialize, ToSchema)]
pub struct StageSequence {
    pub sequence: u32,
    /// The camera in the target frame at stage reading zero.
    pub target_to_camera: PoseOut,
    /// The stage's axes in the target frame, at the camera's position at
    /// stage reading zero.
    pub target_to_stage: PoseOut,
}
