//! Simulator: target images and whole campaigns with known truth.

pub mod campaign;
/// Views as point observations (no image): camera-calibration tests.
pub mod point_views;
pub mod render;
/// Random board views for rendering: detector tests and benchmarks.
pub mod views;
