//! Priors on the kinematic deviations (method.md §6.7 "Priors"): the
//! identification is a maximum a posteriori fit in which every kinematic
//! parameter's deviation from the nominal model carries a Gaussian prior of
//! the size manufacturing leaves (joint zeros from mastering, lengths and
//! twists from machining and assembly). A parameter the campaign cannot
//! determine then stays near nominal with σ close to its prior instead of
//! wandering by millimetres along a direction the data does not see, and
//! every covariance downstream is the posterior.
//!
//! The prior enters the least-squares problems as one pseudo-observation per
//! free kinematic parameter, `(x_i − x_i,nominal) / σ_i`; base and tool
//! frames have none (they are placed freely in every cell).

use serde::{Deserialize, Serialize};

use super::params::{CalibratedModel, ParamKind, ParamLayout};

/// Default prior σ of a joint zero (deg): mastering marks and the
/// reference-position procedures of industrial arms leave 0.05–0.2°.
pub const JOINT_OFFSET_PRIOR_DEG: f64 = 0.2;
/// Default prior σ of a link length or joint offset `a`, `d` (mm):
/// machining and assembly of 1–2 m arms.
pub const LENGTH_PRIOR_MM: f64 = 1.0;
/// Default prior σ of a twist `alpha` or Hayati tilt `beta` (deg).
pub const TWIST_PRIOR_DEG: f64 = 0.1;

/// Per parameter kind, the prior standard deviation of a kinematic
/// parameter's deviation from nominal. Overridable per robot (the robot
/// document's `prior`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct KinematicPrior {
    pub joint_offset_deg: f64,
    pub length_mm: f64,
    pub twist_deg: f64,
}

impl Default for KinematicPrior {
    fn default() -> Self {
        Self::MANUFACTURING
    }
}

impl KinematicPrior {
    /// Manufacturing tolerances of a typical industrial 6R arm.
    pub const MANUFACTURING: Self = Self {
        joint_offset_deg: JOINT_OFFSET_PRIOR_DEG,
        length_mm: LENGTH_PRIOR_MM,
        twist_deg: TWIST_PRIOR_DEG,
    };

    /// Whether every σ is finite and positive (a usable prior).
    pub fn is_valid(&self) -> bool {
        [self.joint_offset_deg, self.length_mm, self.twist_deg]
            .iter()
            .all(|s| s.is_finite() && *s > 0.0)
    }

    /// The prior σ of a parameter of `kind` in the layout's internal units
    /// (rad or mm); `None` for the base and tool frames.
    pub fn sigma(&self, kind: ParamKind) -> Option<f64> {
        match kind {
            ParamKind::JointOffset => Some(self.joint_offset_deg.to_radians()),
            ParamKind::Length | ParamKind::Offset => Some(self.length_mm),
            ParamKind::Twist | ParamKind::Tilt => Some(self.twist_deg.to_radians()),
            ParamKind::Base(_) | ParamKind::Tool(_) => None,
        }
    }

    /// Per layout parameter, the prior σ (internal units; `None`: no prior).
    pub fn sigmas(&self, layout: &ParamLayout) -> Vec<Option<f64>> {
        layout.params.iter().map(|p| self.sigma(p.kind)).collect()
    }
}

/// The prior as a fit over `free` (layout indices) around `reference` sees
/// it: per free parameter, where nominal lies relative to the reference
/// (`nominal − reference`) and the weight `1/σ` (0: no prior).
#[derive(Debug, Clone, PartialEq)]
pub struct PriorRows {
    pub centre: Vec<f64>,
    pub weight: Vec<f64>,
}

impl PriorRows {
    /// The rows of `prior` for a fit of `free` started at `reference`, the
    /// prior centred on `nominal` (same robot structure).
    pub fn new(
        prior: &KinematicPrior,
        layout: &ParamLayout,
        free: &[usize],
        reference: &CalibratedModel,
        nominal: &CalibratedModel,
    ) -> Self {
        let offset = layout.difference(nominal, reference);
        let (centre, weight) = free
            .iter()
            .map(|&i| match prior.sigma(layout.params[i].kind) {
                Some(s) if s > 0.0 => (offset[i], 1.0 / s),
                _ => (0.0, 0.0),
            })
            .unzip();
        Self { centre, weight }
    }

    /// Number of pseudo-observations (one per free parameter).
    pub fn len(&self) -> usize {
        self.weight.len()
    }

    pub fn is_empty(&self) -> bool {
        self.weight.is_empty()
    }

    /// The residual of free parameter `k` at the fit's value `x_k`.
    pub fn residual(&self, k: usize, x_k: f64) -> f64 {
        (x_k - self.centre[k]) * self.weight[k]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Pose;
    use crate::kinematics::{presets, Instrument};

    #[test]
    fn frames_have_no_prior_and_units_are_internal() {
        let p = KinematicPrior::default();
        assert!(p.is_valid());
        assert_eq!(p.sigma(ParamKind::Base(0)), None);
        assert_eq!(p.sigma(ParamKind::Tool(5)), None);
        assert!((p.sigma(ParamKind::JointOffset).unwrap() - 0.2f64.to_radians()).abs() < 1e-15);
        assert_eq!(p.sigma(ParamKind::Offset), Some(LENGTH_PRIOR_MM));
        let bad = KinematicPrior {
            length_mm: 0.0,
            ..p
        };
        assert!(!bad.is_valid());
    }

    #[test]
    fn rows_are_centred_on_nominal() {
        let robot = presets::irb2400();
        let layout = ParamLayout::new(&robot, Instrument::Camera);
        let nominal = CalibratedModel {
            robot,
            world_to_base: Pose::identity(),
            flange_to_tool: Pose::identity(),
        };
        let mut reference = nominal.clone();
        reference.robot.joints[1].a_mm += 2.5;
        let a2 = layout.index_of("a_2").unwrap();
        let tx = layout.index_of("target_to_base.tx").unwrap();
        let rows = PriorRows::new(
            &KinematicPrior::default(),
            &layout,
            &[a2, tx],
            &reference,
            &nominal,
        );
        // Nominal lies 2.5 mm below the reference: x = -2.5 is the centre.
        assert!((rows.residual(0, -2.5)).abs() < 1e-12);
        assert!((rows.residual(0, -1.5) - 1.0).abs() < 1e-12);
        assert_eq!(rows.weight[1], 0.0);
    }
}
