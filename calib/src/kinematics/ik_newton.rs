//! The compensation IK's inner solver (method.md §8): Levenberg–Marquardt
//! on the 6-D pose error over the joint angles, with the joint Jacobian
//! computed analytically in the same pass as the forward kinematics.
//!
//! Why not the generic [`crate::solver::solve`]: that one serves the
//! identification (column scaling, a report with the covariance, the full
//! parameter Jacobian of [`super::jacobian`] with its base and tool
//! columns); for one target it spent most of its time on that machinery.
//! Here a run is a handful of `6 x n` Jacobians and `n x n` solves, which
//! is what deployment's ≥10,000 targets/s per core needs (BENCHMARKS).

use nalgebra::{DMatrix, DVector, Vector3, Vector6};

use super::params::CalibratedModel;
use crate::geometry::{pose_error, Pose};

/// Orientation residual rows are multiplied by this (mm per rad): the
/// weight of a radian against a millimetre in every IK residual.
pub const IK_ROTATION_SCALE_MM: f64 = 1000.0;

/// Nielsen's initial damping, relative to the largest diagonal of `J^T J`.
const TAU: f64 = 1e-6;
/// A step this small relative to the joints ends the run (rad).
const STEP_TOLERANCE: f64 = 1e-14;
/// Damping beyond this means no step reduces the error: give up.
const MAX_DAMPING: f64 = 1e30;

/// Where a run ended.
#[derive(Debug, Clone)]
pub struct NewtonRun {
    pub joints_rad: Vec<f64>,
    /// Jacobian evaluations (iterations).
    pub iterations: usize,
    /// `max(position mm, rotation rad x IK_ROTATION_SCALE_MM)` at the end.
    pub scaled_residual_mm: f64,
}

/// The target's pose error at `q` (rows 3..6 scaled to mm) and the world
/// frame's Jacobian of the reached pose, `[z_i x (p - o_i); z_i]` per
/// joint (a joint turns the chain about its axis `z_i` through `o_i`).
fn error_and_jacobian(
    model: &CalibratedModel,
    target: &Pose,
    q: &[f64],
    with_jacobian: bool,
    jac: &mut DMatrix<f64>,
) -> Vector6<f64> {
    let mut frame = model.world_to_base;
    let mut axes: [(Vector3<f64>, Vector3<f64>); MAX_AXES] =
        [(Vector3::zeros(), Vector3::zeros()); MAX_AXES];
    for (i, (joint, &qi)) in model.robot.joints.iter().zip(q).enumerate() {
        if with_jacobian && i < MAX_AXES {
            axes[i] = (frame.rotation * Vector3::z(), frame.translation.vector);
        }
        frame *= joint.link_transform(qi);
    }
    let tool = frame * model.flange_to_tool;
    if with_jacobian {
        let p = tool.translation.vector;
        for (i, (z, o)) in axes.iter().take(q.len().min(MAX_AXES)).enumerate() {
            let dp = z.cross(&(p - o));
            for r in 0..3 {
                // d(target - reached)/dq = -d(reached)/dq.
                jac[(r, i)] = -dp[r];
                jac[(r + 3, i)] = -z[r] * IK_ROTATION_SCALE_MM;
            }
        }
    }
    let mut e = pose_error(target, &tool);
    e.fixed_rows_mut::<3>(3).scale_mut(IK_ROTATION_SCALE_MM);
    e
}

/// Most joints the solver handles (the service's robots have 6 or 7).
pub const MAX_AXES: usize = 16;

fn scaled(e: &Vector6<f64>) -> f64 {
    e.fixed_rows::<3>(0).norm().max(e.fixed_rows::<3>(3).norm())
}

/// Runs from `start` until the scaled residual is at most `tolerance_mm`,
/// the step vanishes, or `max_iterations`. `None` for a chain longer than
/// [`MAX_AXES`] or joints of the wrong count (the caller checked them).
pub fn solve_joints(
    model: &CalibratedModel,
    target: &Pose,
    start: &[f64],
    tolerance_mm: f64,
    max_iterations: usize,
) -> Option<NewtonRun> {
    let n = model.robot.joints.len();
    if n == 0 || n > MAX_AXES || start.len() != n || start.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let mut q = DVector::from_column_slice(start);
    let mut jac = DMatrix::zeros(6, n);
    let mut e = error_and_jacobian(model, target, q.as_slice(), true, &mut jac);
    let mut cost = e.norm_squared();
    let mut mu: Option<f64> = None;
    let mut nu = 2.0;
    let mut iterations = 1;
    while scaled(&e) > tolerance_mm && iterations <= max_iterations {
        let jt = jac.transpose();
        let a = &jt * &jac;
        let g = &jt * DVector::from_column_slice(e.as_slice());
        let damping = *mu.get_or_insert_with(|| TAU * a.diagonal().max());
        let mut damped = a.clone();
        for i in 0..n {
            damped[(i, i)] += damping;
        }
        // Gauss–Newton on r(q) = target - reached(q), dr/dq = J: dq = -(J^T J + mu)^-1 J^T r.
        let Some(step) = damped.cholesky().map(|c| -c.solve(&g)) else {
            let next = damping * nu;
            if next.is_nan() || next > MAX_DAMPING {
                break;
            }
            mu = Some(next);
            nu *= 2.0;
            continue;
        };
        if step.norm() <= STEP_TOLERANCE * (q.norm() + STEP_TOLERANCE) {
            break;
        }
        let trial = &q + &step;
        let e_trial = error_and_jacobian(model, target, trial.as_slice(), false, &mut jac);
        let cost_trial = e_trial.norm_squared();
        let predicted = step.dot(&(step.scale(damping) - &g));
        let rho = (cost - cost_trial) / predicted.max(f64::MIN_POSITIVE);
        if cost_trial.is_finite() && cost_trial < cost && rho > 0.0 {
            q = trial;
            e = error_and_jacobian(model, target, q.as_slice(), true, &mut jac);
            cost = e.norm_squared();
            mu = Some(damping * (1.0 / 3.0f64).max(1.0 - (2.0 * rho - 1.0).powi(3)));
            nu = 2.0;
            iterations += 1;
        } else {
            let next = damping * nu;
            if next.is_nan() || next > MAX_DAMPING {
                break;
            }
            mu = Some(next);
            nu *= 2.0;
        }
    }
    Some(NewtonRun {
        joints_rad: q.iter().copied().collect(),
        iterations,
        scaled_residual_mm: scaled(&e),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::pose_from_xyz_rpy_deg;
    use crate::kinematics::presets;

    fn model() -> CalibratedModel {
        CalibratedModel {
            robot: presets::irb2400(),
            world_to_base: pose_from_xyz_rpy_deg([800.0, -300.0, 40.0], [2.0, -3.0, 170.0])
                .unwrap(),
            flange_to_tool: pose_from_xyz_rpy_deg([10.0, 0.0, 120.0], [0.0, 0.0, 90.0]).unwrap(),
        }
    }

    #[test]
    fn the_jacobian_matches_finite_differences() {
        let m = model();
        // At the solution, where the rotation error's Jacobian is exact.
        let q = [0.3, -0.2, 0.4, 1.0, -0.6, 0.8];
        let target = m.world_to_tool(&q).unwrap();
        let mut jac = DMatrix::zeros(6, 6);
        error_and_jacobian(&m, &target, &q, true, &mut jac);
        let h = 1e-7;
        let mut scratch = DMatrix::zeros(6, 6);
        for c in 0..6 {
            let mut qp = q;
            qp[c] += h;
            let ep = error_and_jacobian(&m, &target, &qp, false, &mut scratch);
            let mut qm = q;
            qm[c] -= h;
            let em = error_and_jacobian(&m, &target, &qm, false, &mut scratch);
            let fd = (ep - em) / (2.0 * h);
            for r in 0..6 {
                let tol = 1e-4 * (1.0 + fd[r].abs());
                assert!(
                    (fd[r] - jac[(r, c)]).abs() < tol,
                    "({r},{c}): {} vs {}",
                    fd[r],
                    jac[(r, c)]
                );
            }
        }
    }

    #[test]
    fn a_near_target_is_reached_in_a_few_iterations() {
        let m = model();
        let truth = [0.3, -0.2, 0.4, 1.0, -0.6, 0.8];
        let target = m.world_to_tool(&truth).unwrap();
        let start: Vec<f64> = truth.iter().map(|v| v + 0.2).collect();
        let run = solve_joints(&m, &target, &start, 1e-7, 100).unwrap();
        assert!(run.scaled_residual_mm < 1e-7, "{}", run.scaled_residual_mm);
        assert!(run.iterations < 15, "{} iterations", run.iterations);
        for (a, b) in run.joints_rad.iter().zip(truth) {
            assert!((a - b).abs() < 1e-8);
        }
        assert!(solve_joints(&m, &target, &[0.0; 3], 1e-7, 100).is_none());
        assert!(solve_joints(&m, &target, &[f64::NAN; 6], 1e-7, 100).is_none());
    }
}
