//! A frame's pose as the contract serves it (`FramePose`): translation in
//! mm, fixed-axis X-Y-Z angles in degrees, and the exact 4x4 matrix.

use robocal_calib::geometry::{pose_from_matrix_rows, pose_to_matrix_rows, Pose, PoseXyzRpy};
use serde::{Deserialize, Serialize};

/// A pose in the contract's form plus its exact matrix: translation in mm,
/// fixed-axis X-Y-Z angles in degrees, the 4x4 row-major matrix.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, utoipa::ToSchema)]
#[schema(as = FramePose)]
pub struct PoseOut {
    pub translation_mm: [f64; 3],
    pub rotation_deg: [f64; 3],
    pub matrix: [[f64; 4]; 4],
}

impl PoseOut {
    pub fn new(pose: &Pose) -> Self {
        let form = PoseXyzRpy::from_pose(pose);
        Self {
            translation_mm: form.translation_mm,
            rotation_deg: form.rotation_deg,
            matrix: pose_to_matrix_rows(pose),
        }
    }

    /// The pose back from its matrix (the exact form; the angles are for
    /// people).
    pub fn pose(&self) -> Result<Pose, String> {
        pose_from_matrix_rows(&self.matrix).map_err(|e| e.to_string())
    }
}
