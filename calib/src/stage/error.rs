//! Why a stage campaign is refused: each names the field a user fixes.

use crate::camera::CameraError;
use crate::solver::SolverError;

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StageError {
    #[error("sequence {sequence}: {count} stage positions, at least {required} are needed")]
    TooFewPositions {
        sequence: u32,
        count: usize,
        required: usize,
    },
    #[error("sequence {sequence}: the stage positions are collinear; the stage's orientation about their line is then unknown")]
    CollinearPositions { sequence: u32 },
    #[error("view {view}: stage_position_mm is not finite")]
    NonFinitePosition { view: usize },
    #[error("camera: {0}")]
    Camera(#[from] CameraError),
    #[error("stage bundle: {0}")]
    Solver(#[from] SolverError),
}

impl StageError {
    /// The request field the error is about.
    pub fn field(&self) -> &'static str {
        match self {
            Self::TooFewPositions { .. } => "sequence",
            Self::CollinearPositions { .. } | Self::NonFinitePosition { .. } => "stage_position_mm",
            Self::Camera(_) | Self::Solver(_) => "images",
        }
    }
}
