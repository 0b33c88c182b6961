//! One pose's position errors before and after calibration, as the camera
//! and tracker model selections (`model_selection.rs`,
//! `position_selection.rs`) hand them to the report.

use nalgebra::Vector3;

/// One pose's position error (session pose index, before, after; mm).
pub type PoseErrors = (usize, Vector3<f64>, Vector3<f64>);
