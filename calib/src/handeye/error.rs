//! Errors of the flange-pose hand–eye: degenerate input is refused with a
//! reason, never answered wrongly.

use crate::camera::CameraError;
use crate::solver::SolverError;

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HandEyeError {
    #[error("{usable} poses agree with their images, at least {required} are needed")]
    TooFewPoses { usable: usize, required: usize },
    #[error("pose {pose}: {reason}")]
    BadPose { pose: usize, reason: String },
    #[error("the robot motions do not determine the hand–eye rotation (all rotations about one axis or none)")]
    DegenerateMotion,
    #[error("camera: {0}")]
    Camera(#[from] CameraError),
    #[error("solver: {0}")]
    Solver(#[from] SolverError),
}
