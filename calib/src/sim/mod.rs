//! Simulator: target images and whole campaigns with known truth.

pub mod campaign;
pub mod render;
pub mod views;
