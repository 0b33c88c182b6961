//! A calibrated model with its kept non-geometric terms (issue 19,
//! method.md §6 "beyond"): what `forward`, `compensate`, `filter` and the
//! predicted uncertainty evaluate. The recorded (commanded) joints `q` are
//! deflected, `q' = q + Δθ(q)`, before the geometric chain; the inverse
//! (the commanded joints that land on given true joints) is a fixed-point
//! iteration, a contraction because `|∂Δθ/∂q|` is of the order of the term
//! values (≪ 1 rad/rad).

use super::ik::{nearest_within_limits, IkError, IkSolution};
use super::jacobian::tool_pose_jacobian;
use super::measurement::Measurement;
use super::model::KinematicsError;
use super::nongeometric::NonGeometric;
use super::params::{CalibratedModel, Instrument, ParamLayout, PARAMS_PER_JOINT};
use super::term_range::IdentifiedRange;
use crate::geometry::Pose;

/// Largest joint change (rad) at which the commanded joints are converged.
pub const COMMANDED_TOL_RAD: f64 = 1e-13;
/// Fixed-point steps before the inversion gives up.
pub const MAX_COMMANDED_STEPS: usize = 50;

/// Geometry plus the kept terms and their σ (same order as `terms.terms`).
#[derive(Debug, Clone, PartialEq)]
pub struct TermModel {
    pub model: CalibratedModel,
    pub terms: NonGeometric,
    /// σ of each term's value (its unit), 0 where unknown.
    pub term_std_devs: Vec<f64>,
    /// The terms' covariance with the geometry, when the fit gave it (the
    /// image-level refinement); `None`: terms and geometry taken as
    /// independent ([`Self::term_variance`]).
    pub covariance: Option<TermCovariance>,
    /// Where the kept periodic terms were identified ([`super::term_range`]);
    /// empty when unknown (sets stored before it was kept).
    pub ranges: Vec<IdentifiedRange>,
}

/// The covariance of the term values with the geometry and among
/// themselves (internal units: mm, rad, each term's unit).
#[derive(Debug, Clone, PartialEq)]
pub struct TermCovariance {
    /// Layout parameter (rows, zero where fixed) by term (columns).
    pub cross: nalgebra::DMatrix<f64>,
    /// Term by term.
    pub terms: nalgebra::DMatrix<f64>,
}

/// Predicted variances (position mm², rotation rad²) of one pose.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TermVariance {
    pub position_mm2: f64,
    pub rotation_rad2: f64,
}

impl TermModel {
    /// The geometric model alone (no terms).
    pub fn geometric(model: CalibratedModel) -> Self {
        Self {
            terms: NonGeometric::none(&model),
            model,
            term_std_devs: Vec::new(),
            covariance: None,
            ranges: Vec::new(),
        }
    }

    pub fn has_terms(&self) -> bool {
        !self.terms.terms.is_empty()
    }

    /// The same terms with another tool in the flange frame.
    pub fn with_tool(&self, flange_to_tool: Pose) -> Self {
        Self {
            model: self.model.with_tool(flange_to_tool),
            ..self.clone()
        }
    }

    /// The joints the geometric chain sees at commanded joints `q_rad`.
    pub fn deflected(&self, q_rad: &[f64]) -> Result<Vec<f64>, KinematicsError> {
        self.terms.deflected(q_rad)
    }

    /// `base_to_flange` at commanded joints.
    pub fn base_to_flange(&self, q_rad: &[f64]) -> Result<Pose, KinematicsError> {
        self.model.robot.base_to_flange(&self.deflected(q_rad)?)
    }

    /// `world_to_tool` at commanded joints.
    pub fn world_to_tool(&self, q_rad: &[f64]) -> Result<Pose, KinematicsError> {
        self.model.world_to_tool(&self.deflected(q_rad)?)
    }

    /// `data` as the geometric chain sees it: each pose's commanded joints
    /// replaced by the deflected ones. The deflections do not depend on the
    /// geometric parameters (the bases are evaluated on a fixed chain), so
    /// any geometric fit or residual on these (a frame re-fit, a re-check)
    /// is the one with the terms held at their values.
    pub fn deflect_measurements(
        &self,
        data: &[Measurement],
    ) -> Result<Vec<Measurement>, KinematicsError> {
        data.iter()
            .map(|m| {
                Ok(Measurement {
                    joints_rad: self.deflected(&m.joints_rad)?,
                    observed: m.observed.clone(),
                })
            })
            .collect()
    }

    /// The commanded joints `q` with `q + Δθ(q) = deflected_rad`.
    pub fn commanded(&self, deflected_rad: &[f64]) -> Result<Vec<f64>, KinematicsError> {
        let mut q = deflected_rad.to_vec();
        if !self.has_terms() {
            return Ok(q);
        }
        let mut change_rad = f64::INFINITY;
        for _ in 0..MAX_COMMANDED_STEPS {
            let bent = self.deflected(&q)?;
            change_rad = 0.0;
            for ((qi, b), target) in q.iter_mut().zip(&bent).zip(deflected_rad) {
                let step = target - b;
                *qi += step;
                change_rad = change_rad.max(step.abs());
            }
            if change_rad <= COMMANDED_TOL_RAD {
                return Ok(q);
            }
        }
        Err(KinematicsError::DeflectionNotInverted {
            iterations: MAX_COMMANDED_STEPS,
            change_rad,
        })
    }

    /// Commanded joints reaching `world_to_tool`, nearest `seed_rad` within
    /// the limits: the geometric inverse kinematics gives the true joints,
    /// [`Self::commanded`] the joints to send; the residual is re-measured
    /// through the deflections.
    pub fn nearest_within_limits(
        &self,
        world_to_tool: &Pose,
        seed_rad: &[f64],
    ) -> Result<IkSolution, IkError> {
        let mut solution = nearest_within_limits(&self.model, world_to_tool, seed_rad)?;
        if !self.has_terms() {
            return Ok(solution);
        }
        solution.joints_rad = self.commanded(&solution.joints_rad)?;
        self.model
            .robot
            .check_limits(&solution.joints_rad)
            .map_err(IkError::Limits)?;
        let reached = self.world_to_tool(&solution.joints_rad)?;
        solution.residual_mm =
            (reached.translation.vector - world_to_tool.translation.vector).norm();
        solution.residual_rad = reached.rotation.angle_to(&world_to_tool.rotation);
        Ok(solution)
    }

    /// Variance the terms' σ add to `end`'s pose at commanded joints
    /// `q_rad` (`end`: this model, or it with another tool or no base and
    /// tool for the flange): each term deflects one joint by `σ_k f_k(q)`,
    /// independently, through that joint's column of the pose Jacobian.
    pub fn term_variance(
        &self,
        end: &CalibratedModel,
        q_rad: &[f64],
    ) -> Result<TermVariance, KinematicsError> {
        let mut out = TermVariance::default();
        if !self.has_terms() {
            return Ok(out);
        }
        let layout = ParamLayout::new(&end.robot, Instrument::Camera);
        let (_, jac) = tool_pose_jacobian(&layout, end, &self.deflected(q_rad)?)?;
        let basis = self.terms.basis(q_rad)?;
        for ((term, f), sd) in self.terms.terms.iter().zip(basis).zip(&self.term_std_devs) {
            let column = jac.column(term.joint() * PARAMS_PER_JOINT);
            let deflection_var = (sd * f).powi(2);
            out.position_mm2 += deflection_var * column.rows(0, 3).norm_squared();
            out.rotation_rad2 += deflection_var * column.rows(3, 3).norm_squared();
        }
        Ok(out)
    }
}

#[cfg(test)]
#[path = "term_model_tests.rs"]
mod tests;
