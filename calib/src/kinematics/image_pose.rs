//! One pose of a camera campaign as the joint refinement reads it
//! (method.md §6.4), and the noise it weighs the data with.

use nalgebra::{Point2, Point3};

use super::identify_options::JointNoise;

/// One pose of a camera campaign: recorded joints and the detected dots.
#[derive(Debug, Clone, PartialEq)]
pub struct ImagePose {
    pub joints_rad: Vec<f64>,
    /// `(dot centre in the target frame mm, observed pixel)`.
    pub observations: Vec<(Point3<f64>, Point2<f64>)>,
}

/// The noise the joint refinement weighs the data with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImageNoise {
    /// Dot-centre noise per image axis (px); re-estimated with the joint
    /// noise when that is estimated.
    pub sigma_px: f64,
    /// Noise of every recorded joint angle.
    pub joint: JointNoise,
}

impl ImageNoise {
    /// The joint noise in use (rad); 0 while it is still to be estimated.
    pub(super) fn joint_sigma_rad(&self) -> f64 {
        match self.joint {
            JointNoise::Known { sigma_rad } => sigma_rad.abs(),
            JointNoise::Estimate => 0.0,
        }
    }
}
