//! Camera models and calibration (method.md §2–4).

pub mod model;

pub use model::Intrinsics;
