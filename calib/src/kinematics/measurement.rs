//! What a campaign measured at one pose (method.md §6): the recorded
//! joints and the tool's pose or position in the world frame, with the
//! default uncertainty of a measurement given without covariance.

use nalgebra::{Matrix3, Matrix6, Vector3};

use crate::geometry::Pose;

/// Position standard deviation assumed for a pose given without covariance.
pub const DEFAULT_POSITION_SIGMA_MM: f64 = 0.1;
/// Orientation standard deviation assumed for a pose given without covariance.
pub const DEFAULT_ROTATION_SIGMA_RAD: f64 = 1e-4;

/// What was measured at one pose, in the world (target or instrument) frame.
// A few thousand measurements at most: the 6x6 covariance stays inline.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum Observed {
    /// Full tool pose with an optional 6x6 covariance in the
    /// [`pose_error`] parameterisation (`[dp mm; dr rad]`, world frame).
    Pose {
        world_to_tool: Pose,
        covariance: Option<Matrix6<f64>>,
    },
    /// Tool position with an optional 3x3 covariance (mm^2).
    Position {
        position_mm: Vector3<f64>,
        covariance: Option<Matrix3<f64>>,
    },
}

impl Observed {
    pub fn position_mm(&self) -> Vector3<f64> {
        match self {
            Observed::Pose { world_to_tool, .. } => world_to_tool.translation.vector,
            Observed::Position { position_mm, .. } => *position_mm,
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct Measurement {
    pub joints_rad: Vec<f64>,
    pub observed: Observed,
}

impl Measurement {
    /// The same measurement as the tool point's position only: a full
    /// pose's covariance reduced to its position block. Two sets of one
    /// tracker, one fitted with a probe's orientation, compare on it.
    pub fn position_only(&self) -> Measurement {
        let observed = match &self.observed {
            Observed::Pose {
                world_to_tool,
                covariance,
            } => Observed::Position {
                position_mm: world_to_tool.translation.vector,
                covariance: covariance.map(|c| c.fixed_view::<3, 3>(0, 0).into_owned()),
            },
            position => position.clone(),
        };
        Measurement {
            joints_rad: self.joints_rad.clone(),
            observed,
        }
    }
}
