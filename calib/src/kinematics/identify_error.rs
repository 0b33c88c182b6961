//! Why an identification could not run.

use super::identifiability::IdentifiabilityError;
use super::model::KinematicsError;
use super::nongeometric::NonGeometricError;
use super::params::Instrument;
use crate::solver::SolverError;

/// Every failure of [`super::identify::identify`], by cause.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum IdentifyError {
    #[error("no calibration poses")]
    NoPoses,
    #[error("region {region} has no calibration poses")]
    EmptyRegion { region: usize },
    #[error("pose {pose}: {source}")]
    Pose {
        pose: usize,
        source: KinematicsError,
    },
    #[error("pose {pose}: a {instrument:?} session needs {expected} measurements")]
    WrongMeasurement {
        pose: usize,
        instrument: Instrument,
        expected: &'static str,
    },
    #[error("pose {pose}: covariance is not positive definite")]
    BadCovariance { pose: usize },
    #[error(transparent)]
    Identifiability(#[from] IdentifiabilityError),
    #[error(transparent)]
    NonGeometric(#[from] NonGeometricError),
    #[error("solver: {0}")]
    Solver(#[from] SolverError),
}
