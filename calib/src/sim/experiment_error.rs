//! Why a simulated experiment could not run.

use super::campaign::SimError;
use crate::kinematics::identify::IdentifyError;

/// Every failure of a simulated experiment, by stage.
#[derive(Debug, thiserror::Error)]
pub enum ExperimentError {
    #[error(transparent)]
    Sim(#[from] SimError),
    #[error(transparent)]
    Identify(#[from] IdentifyError),
    #[error("pose fit: {0}")]
    PoseFit(#[from] crate::camera::error::CameraError),
    #[error("the camera bundle is degenerate")]
    Degenerate,
    #[error("compensation: {0}")]
    Compensation(#[from] crate::kinematics::ik::IkError),
    #[error("truth: {0}")]
    Truth(#[from] crate::geometry::GeometryError),
    #[error(transparent)]
    Kinematics(#[from] crate::kinematics::KinematicsError),
}
