//! Reg Willson's reference implementation of Tsai's method (release 3.0b3),
//! replayed to reproduce his published cameras (`shared/data/tsai/`):
//! his camera model ([`model`]), his normal-equation linear stages
//! ([`linear`]), the converged full optimisation ([`fit`]) and his staged
//! MINPACK run ([`stages`], on the [`minpack`] port). A wing of its own:
//! robocal's calibration never calls it; it exists to show that robocal
//! reproduces Tsai's published numbers (method.md §3).

pub mod fit;
mod linear;
pub mod minpack;
pub mod model;
pub mod stages;
#[cfg(test)]
mod test_data;

pub use fit::{calibrate_tsai_full, full_optimisation_cost, TsaiFit, MIN_POINTS_FULL_OPTIMISATION};
pub use model::{parse_points, ErrorStats, TsaiModel, TsaiPoint, TsaiSensor};
pub use stages::{calibrate_tsai_willson, WillsonCalibration, WillsonStage};
