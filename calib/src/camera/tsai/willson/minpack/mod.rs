//! A port of MINPACK's `lmdif` (with `lmpar`, `qrfac`, `qrsolv`, `enorm`),
//! kept only so that Willson's staged Tsai calibration takes the steps his
//! 1995 binary took. Everything else in robocal uses `crate::solver`.

mod lmdif;
mod lmpar;
mod norm;

pub use lmdif::{lmdif, LmdifFailure, LmdifOptions, LmdifReport};
