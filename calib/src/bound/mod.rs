//! The Cramér–Rao bound of a camera campaign (method.md §6.9 "The
//! Cramér–Rao bound"): the best validation error any unbiased estimator
//! with the correct model could reach on the campaign's data. The yardstick
//! for the service's own fit (`examples/crb_ratio.rs` prints the ratio per
//! simulated campaign kind).
//!
//! [`cramer_rao`] computes it from any model and poses; [`campaign_bound`]
//! from a simulated campaign's truth.

pub mod campaign;
pub mod cramer_rao;
#[cfg(test)]
mod ladder_bound_tests;
#[cfg(test)]
mod monte_carlo_tests;

pub use campaign::{campaign_bound, identifiable};
pub use cramer_rao::{cramer_rao, BoundInput, CramerRao, PoseBound, ValidationBound};

/// Why a bound could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BoundError {
    #[error("the campaign's joint compliance has no model parameter: no bound for it")]
    Unmodelled,
    #[error(transparent)]
    Identify(#[from] crate::kinematics::identify_error::IdentifyError),
    #[error(transparent)]
    Kinematics(#[from] crate::kinematics::KinematicsError),
    #[error("truth: {0}")]
    Truth(#[from] crate::geometry::GeometryError),
}
