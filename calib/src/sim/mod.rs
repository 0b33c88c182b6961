//! Simulator: target images and whole campaigns with known truth.

pub mod camera_step;
pub mod campaign;
pub mod campaign_io;
pub mod experiment;
pub mod render;
pub mod views;
