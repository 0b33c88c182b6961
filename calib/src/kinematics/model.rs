//! Serial revolute chains with per-joint Denavit–Hartenberg or Hayati link
//! transforms (method.md §5, paper section 2).
//!
//! - DH: `A_i = Rz(theta_i + offset_i) Tz(d_i) Tx(a_i) Rx(alpha_i)`;
//! - Hayati, for a link between parallel axes where DH is singular (a tiny
//!   misalignment moves `d` to infinity):
//!   `A_i = Rz(theta_i + offset_i) Tx(a_i) Rx(alpha_i) Ry(beta_i)`, no `d`.
//!
//! Lengths in millimetres, angles in radians (`_rad`); the REST layer
//! converts from the contract's degrees.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

use crate::geometry::Pose;

/// A link whose twist `alpha` is below this is between parallel axes and
/// gets Hayati's parameters (api.md "Robots").
pub const PARALLEL_AXIS_TOL_RAD: f64 = 1e-3;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Convention {
    Dh,
    Hayati,
}

/// One revolute joint and the link transform that follows it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Joint {
    pub convention: Convention,
    pub a_mm: f64,
    pub alpha_rad: f64,
    /// Unused (zero) on Hayati links.
    pub d_mm: f64,
    pub theta_offset_rad: f64,
    /// Unused (zero) on DH links.
    pub beta_rad: f64,
    pub min_rad: f64,
    pub max_rad: f64,
}

impl Joint {
    /// A DH joint with symmetric limits.
    pub fn dh(
        a_mm: f64,
        alpha_deg: f64,
        d_mm: f64,
        theta_offset_deg: f64,
        limits_deg: (f64, f64),
    ) -> Self {
        Self {
            convention: Convention::Dh,
            a_mm,
            alpha_rad: alpha_deg.to_radians(),
            d_mm,
            theta_offset_rad: theta_offset_deg.to_radians(),
            beta_rad: 0.0,
            min_rad: limits_deg.0.to_radians(),
            max_rad: limits_deg.1.to_radians(),
        }
    }

    /// The link transform `A_i(q)` (method.md §5).
    pub fn link_transform(&self, q_rad: f64) -> Pose {
        let theta =
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), q_rad + self.theta_offset_rad);
        let twist = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), self.alpha_rad);
        match self.convention {
            Convention::Dh => {
                // Rz(theta) Tz(d) Tx(a) Rx(alpha) = [Rz | Rz (a,0,d)] * Rx(alpha)
                let t = theta * Vector3::new(self.a_mm, 0.0, self.d_mm);
                Isometry3::from_parts(Translation3::from(t), theta * twist)
            }
            Convention::Hayati => {
                let tilt = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), self.beta_rad);
                let t = theta * Vector3::new(self.a_mm, 0.0, 0.0);
                Isometry3::from_parts(Translation3::from(t), theta * twist * tilt)
            }
        }
    }
}

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum KinematicsError {
    #[error("expected {expected} joint values, got {got}")]
    JointCount { expected: usize, got: usize },
    #[error("joint {joint} value is not finite")]
    NotFinite { joint: usize },
    #[error("joint {joint} at {value_deg:.3} deg is outside its limits [{min_deg:.3}, {max_deg:.3}] deg")]
    OutsideLimits {
        joint: usize,
        value_deg: f64,
        min_deg: f64,
        max_deg: f64,
    },
    #[error("the robot has no joints")]
    NoJoints,
    /// The commanded joints of a model with non-geometric terms were not
    /// found: the deflections are too large to invert (method.md §6).
    #[error(
        "joint deflections did not converge: {change_rad:.1e} rad left after {iterations} steps"
    )]
    DeflectionNotInverted { iterations: usize, change_rad: f64 },
}

/// A serial chain of revolute joints, base frame to flange frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RobotModel {
    pub joints: Vec<Joint>,
}

impl RobotModel {
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    fn check_input(&self, q_rad: &[f64]) -> Result<(), KinematicsError> {
        if self.joints.is_empty() {
            return Err(KinematicsError::NoJoints);
        }
        if q_rad.len() != self.joints.len() {
            return Err(KinematicsError::JointCount {
                expected: self.joints.len(),
                got: q_rad.len(),
            });
        }
        match q_rad.iter().position(|q| !q.is_finite()) {
            Some(joint) => Err(KinematicsError::NotFinite { joint: joint + 1 }),
            None => Ok(()),
        }
    }

    /// Forward kinematics `base_to_flange = A_1(q1) ... A_n(qn)`.
    pub fn base_to_flange(&self, q_rad: &[f64]) -> Result<Pose, KinematicsError> {
        self.check_input(q_rad)?;
        Ok(self
            .joints
            .iter()
            .zip(q_rad)
            .fold(Pose::identity(), |acc, (joint, &q)| {
                acc * joint.link_transform(q)
            }))
    }

    /// Every joint within its limits (1-based joint numbers in the error).
    pub fn check_limits(&self, q_rad: &[f64]) -> Result<(), KinematicsError> {
        self.check_input(q_rad)?;
        match self.limit_violations(q_rad).into_iter().next() {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// Each joint outside its limits, in joint order (1-based numbers): what
    /// `forward` warns about. Values beyond the joint count are ignored.
    pub fn limit_violations(&self, q_rad: &[f64]) -> Vec<KinematicsError> {
        self.joints
            .iter()
            .zip(q_rad)
            .enumerate()
            .filter(|(_, (joint, &q))| q < joint.min_rad || q > joint.max_rad)
            .map(|(i, (joint, &q))| KinematicsError::OutsideLimits {
                joint: i + 1,
                value_deg: q.to_degrees(),
                min_deg: joint.min_rad.to_degrees(),
                max_deg: joint.max_rad.to_degrees(),
            })
            .collect()
    }
}

/// The convention the service chooses for link `index` of `count` when the
/// user gives none: Hayati for a link between parallel axes (`alpha ~ 0`),
/// except the last link, whose `d` is the flange distance.
pub fn auto_convention(index: usize, count: usize, alpha_rad: f64) -> Convention {
    if index + 1 < count && alpha_rad.abs() < PARALLEL_AXIS_TOL_RAD {
        Convention::Hayati
    } else {
        Convention::Dh
    }
}

/// Apply [`auto_convention`] to the joints whose convention is not given
/// (`None`). A DH `d` on a link that becomes Hayati is moved to the next
/// link: with `alpha = 0` the translation along `z_{i-1}` is a translation
/// along `z_i` and commutes into the next link's `Tz(d)`, so the chain is
/// unchanged.
pub fn choose_conventions(joints: &[(Option<Convention>, Joint)]) -> Vec<Joint> {
    let count = joints.len();
    let mut out: Vec<Joint> = Vec::with_capacity(count);
    let mut carried_d_mm = 0.0;
    for (index, (given, joint)) in joints.iter().enumerate() {
        let mut joint = *joint;
        joint.d_mm += carried_d_mm;
        carried_d_mm = 0.0;
        joint.convention = given.unwrap_or_else(|| auto_convention(index, count, joint.alpha_rad));
        match joint.convention {
            Convention::Hayati if given.is_none() => {
                carried_d_mm = joint.d_mm;
                joint.d_mm = 0.0;
            }
            Convention::Dh => joint.beta_rad = 0.0,
            Convention::Hayati => {}
        }
        out.push(joint);
    }
    out
}

#[cfg(test)]
#[path = "link_proptests.rs"]
mod proptests;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::presets;

    #[test]
    fn auto_conventions_keep_the_chain_and_pick_hayati_on_parallel_links() {
        let mut with_d = presets::puma560();
        for j in with_d.joints.iter_mut() {
            j.convention = Convention::Dh;
        }
        with_d.joints[1].d_mm = 37.0; // parallel link with a DH offset
        let chosen = RobotModel {
            joints: choose_conventions(
                &with_d.joints.iter().map(|j| (None, *j)).collect::<Vec<_>>(),
            ),
        };
        let kinds: Vec<_> = chosen.joints.iter().map(|j| j.convention).collect();
        assert_eq!(kinds[1], Convention::Hayati);
        assert_eq!(kinds[5], Convention::Dh, "last link keeps DH");
        let q = [0.3, -0.7, 0.4, 1.1, -0.5, 2.0];
        let a = with_d.base_to_flange(&q).unwrap();
        let b = chosen.base_to_flange(&q).unwrap();
        assert!((a.to_homogeneous() - b.to_homogeneous()).amax() < 1e-9);
    }

    #[test]
    fn bad_joint_vectors_are_errors() {
        let robot = presets::irb2400();
        assert!(matches!(
            robot.base_to_flange(&[0.0; 5]),
            Err(KinematicsError::JointCount { .. })
        ));
        assert!(matches!(
            robot.base_to_flange(&[0.0, f64::NAN, 0.0, 0.0, 0.0, 0.0]),
            Err(KinematicsError::NotFinite { joint: 2 })
        ));
        assert!(matches!(
            robot.check_limits(&[0.0, 0.0, 3.0, 0.0, 0.0, 0.0]),
            Err(KinematicsError::OutsideLimits { joint: 3, .. })
        ));
    }
}
