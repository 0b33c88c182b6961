//! Simulator: target images and whole campaigns with known truth.

pub mod campaign;
pub mod campaign_io;
pub mod experiment;
pub mod pose_fit;
pub mod render;
pub mod views;
