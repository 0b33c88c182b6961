//! Compensation (method.md §8): inverse kinematics of the calibrated model,
//! solved numerically by the project's Levenberg–Marquardt from one or more
//! seeds (the nominal joints of the off-line program are the natural seed),
//! so that the tool reaches the desired pose according to the *calibrated*
//! model.

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use super::jacobian::tool_pose_jacobian;
use super::model::KinematicsError;
use super::params::{CalibratedModel, Instrument, ParamLayout, PARAMS_PER_JOINT};
use crate::geometry::{pose_error, Pose};
use crate::solver::{solve, LeastSquaresProblem, LmOptions};

/// Orientation residual rows are multiplied by this (mm per rad).
pub const IK_ROTATION_SCALE_MM: f64 = 1000.0;
/// A solution whose (scaled) residual exceeds this is out of reach.
pub const IK_REACH_TOL_MM: f64 = 1e-3;
const IK_MAX_ITERATIONS: usize = 100;

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum IkError {
    #[error("no seed joints given")]
    NoSeed,
    #[error("target out of reach: best residual {residual_mm:.3} mm")]
    OutOfReach { residual_mm: f64 },
    #[error("the only solutions found leave joint limits: {0}")]
    Limits(KinematicsError),
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IkSolution {
    pub joints_rad: Vec<f64>,
    /// Position distance between target and reached tool (mm).
    pub residual_mm: f64,
    /// Orientation distance (rad).
    pub residual_rad: f64,
}

struct IkProblem<'a> {
    model: &'a CalibratedModel,
    layout: ParamLayout,
    target: &'a Pose,
}

impl IkProblem<'_> {
    fn error(&self, q: &DVector<f64>) -> Option<(Pose, nalgebra::Vector6<f64>)> {
        let pred = self.model.world_to_tool(q.as_slice()).ok()?;
        Some((pred, pose_error(self.target, &pred)))
    }
}

impl LeastSquaresProblem for IkProblem<'_> {
    fn residuals(&self, q: &DVector<f64>) -> Option<DVector<f64>> {
        let (_, mut e) = self.error(q)?;
        e.rows_mut(3, 3).scale_mut(IK_ROTATION_SCALE_MM);
        Some(DVector::from_column_slice(e.as_slice()))
    }

    /// The joint columns are the `dtheta_i` columns of the identification
    /// Jacobian (a joint angle and its offset move the chain alike).
    fn jacobian(&self, q: &DVector<f64>) -> Option<DMatrix<f64>> {
        let (_, j) = tool_pose_jacobian(&self.layout, self.model, q.as_slice()).ok()?;
        let n = q.len();
        Some(DMatrix::from_fn(6, n, |r, c| {
            let v = -j[(r, c * PARAMS_PER_JOINT)];
            if r >= 3 {
                v * IK_ROTATION_SCALE_MM
            } else {
                v
            }
        }))
    }
}

/// Fractions of each joint's range tried by [`default_seeds`].
const SEED_FRACTIONS: [f64; 3] = [0.25, 0.5, 0.75];
/// Joints (0-based) whose seed values are varied: the arm's three and the
/// wrist bend, which select the elbow, shoulder and wrist-flip branches.
const SEEDED_JOINTS: [usize; 4] = [0, 1, 2, 4];

/// Seeds for a target given without any: a grid over the branch-selecting
/// joints at [`SEED_FRACTIONS`] of their ranges (others mid-range). The
/// nearest solution to the first (mid-range) seed wins.
pub fn default_seeds(model: &CalibratedModel) -> Vec<Vec<f64>> {
    let joints = &model.robot.joints;
    let at = |i: usize, f: f64| {
        let j = &joints[i];
        j.min_rad + f * (j.max_rad - j.min_rad)
    };
    let varied: Vec<usize> = SEEDED_JOINTS
        .iter()
        .copied()
        .filter(|&i| i < joints.len())
        .collect();
    let count = SEED_FRACTIONS.len().pow(varied.len() as u32);
    // Index 0 of the odometer is the middle fraction, so the first seed is mid-range.
    let order = [1usize, 0, 2];
    (0..count)
        .map(|mut k| {
            let mut q: Vec<f64> = (0..joints.len()).map(|i| at(i, 0.5)).collect();
            for &i in &varied {
                q[i] = at(i, SEED_FRACTIONS[order[k % 3]]);
                k /= 3;
            }
            q
        })
        .collect()
}

/// Bring each angle into its joint's limits by whole turns where possible.
fn wrap_into_limits(model: &CalibratedModel, q: &mut [f64]) {
    for (v, j) in q.iter_mut().zip(&model.robot.joints) {
        let turn = std::f64::consts::TAU;
        while *v > j.max_rad && *v - turn >= j.min_rad {
            *v -= turn;
        }
        while *v < j.min_rad && *v + turn <= j.max_rad {
            *v += turn;
        }
    }
}

/// Joints that put the tool at `world_to_tool` according to `model`,
/// started from each seed; of the solutions within reach and limits, the
/// one closest to the first seed. Out of reach and beyond-limit targets are
/// errors.
pub fn inverse_kinematics(
    model: &CalibratedModel,
    world_to_tool: &Pose,
    seeds: &[Vec<f64>],
) -> Result<IkSolution, IkError> {
    if seeds.is_empty() {
        return Err(IkError::NoSeed);
    }
    let problem = IkProblem {
        model,
        layout: ParamLayout::new(&model.robot, Instrument::Camera),
        target: world_to_tool,
    };
    let options = LmOptions {
        max_iterations: IK_MAX_ITERATIONS,
        ..LmOptions::default()
    };
    let mut best_residual = f64::INFINITY;
    let mut limit_error = None;
    let mut found: Option<(f64, IkSolution)> = None;
    for seed in seeds {
        model.robot.base_to_flange(seed)?;
        let Ok(report) = solve(&problem, DVector::from_column_slice(seed), &options) else {
            continue;
        };
        let mut q: Vec<f64> = report.x.iter().copied().collect();
        wrap_into_limits(model, &mut q);
        let Some((_, e)) = problem.error(&DVector::from_column_slice(&q)) else {
            continue;
        };
        let (pos, rot) = (e.rows(0, 3).norm(), e.rows(3, 3).norm());
        let scaled = pos.max(rot * IK_ROTATION_SCALE_MM);
        best_residual = best_residual.min(scaled);
        if scaled > IK_REACH_TOL_MM {
            continue;
        }
        if let Err(e) = model.robot.check_limits(&q) {
            limit_error = Some(e);
            continue;
        }
        let distance: f64 = q.iter().zip(&seeds[0]).map(|(a, b)| (a - b).powi(2)).sum();
        if found.as_ref().is_none_or(|(d, _)| distance < *d) {
            found = Some((
                distance,
                IkSolution {
                    joints_rad: q,
                    residual_mm: pos,
                    residual_rad: rot,
                },
            ));
        }
    }
    match (found, limit_error) {
        (Some((_, s)), _) => Ok(s),
        (None, Some(e)) => Err(IkError::Limits(e)),
        (None, None) => Err(IkError::OutOfReach {
            residual_mm: best_residual,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::presets;

    #[test]
    fn ik_recovers_joints_and_rejects_unreachable_targets() {
        let model = CalibratedModel {
            robot: presets::irb2400(),
            world_to_base: Pose::translation(10.0, 20.0, 30.0),
            flange_to_tool: Pose::translation(0.0, 0.0, 120.0),
        };
        let q_true = [0.2, 0.3, -0.2, 0.5, 0.8, -0.4];
        let target = model.world_to_tool(&q_true).unwrap();
        let seed: Vec<f64> = q_true.iter().map(|q| q + 0.1).collect();
        let sol = inverse_kinematics(&model, &target, std::slice::from_ref(&seed)).unwrap();
        assert!(sol.residual_mm < 1e-6, "{sol:?}");
        let reached = model.world_to_tool(&sol.joints_rad).unwrap();
        assert!((reached.translation.vector - target.translation.vector).norm() < 1e-6);
        let far = Pose::translation(5000.0, 0.0, 0.0) * target;
        assert!(matches!(
            inverse_kinematics(&model, &far, &[seed]),
            Err(IkError::OutOfReach { .. })
        ));
        assert!(matches!(
            inverse_kinematics(&model, &target, &[]),
            Err(IkError::NoSeed)
        ));
    }

    #[test]
    fn default_seeds_find_a_solution_without_a_user_seed() {
        let model = CalibratedModel {
            robot: presets::puma560(),
            world_to_base: Pose::identity(),
            flange_to_tool: Pose::translation(0.0, 0.0, 100.0),
        };
        let seeds = default_seeds(&model);
        assert_eq!(seeds.len(), 81);
        let target = model
            .world_to_tool(&[0.4, 1.2, -2.0, 0.3, 0.9, -0.5])
            .unwrap();
        let sol = inverse_kinematics(&model, &target, &seeds).unwrap();
        assert!(sol.residual_mm < 1e-6);
        model.robot.check_limits(&sol.joints_rad).unwrap();
    }

    #[test]
    fn targets_needing_joints_beyond_limits_are_errors() {
        let mut model = CalibratedModel {
            robot: presets::irb2400(),
            world_to_base: Pose::identity(),
            flange_to_tool: Pose::translation(0.0, 0.0, 120.0),
        };
        let q = [0.2, 0.3, -0.2, 0.5, 0.8, -0.4];
        let target = model.world_to_tool(&q).unwrap();
        model.robot.joints[4].max_rad = 0.5; // joint 5 must reach 0.8
        assert!(matches!(
            inverse_kinematics(&model, &target, &[q.to_vec()]),
            Err(IkError::Limits(KinematicsError::OutsideLimits {
                joint: 5,
                ..
            }))
        ));
    }
}
