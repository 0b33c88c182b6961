//! robocal: the calibration service. The numerics live in the `robocal-calib`
//! crate (`calib/`), which knows nothing of HTTP, databases or jobs.
pub use robocal_calib as calib;

pub mod report;
