//! Compensation (method.md §8): inverse kinematics of the calibrated model,
//! solved numerically by the project's Levenberg–Marquardt from one or more
//! seeds (the nominal joints of the off-line program are the natural seed),
//! so that the tool reaches the desired pose according to the *calibrated*
//! model.

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use super::ik_branches::SphericalWristArm;
use super::ik_newton::solve_joints;
pub use super::ik_newton::IK_ROTATION_SCALE_MM;
pub use super::ik_seeds::default_seeds;
use super::ik_seeds::{move_by_turns, squared_distance, Turns};
use super::jacobian::tool_pose_jacobian;
use super::model::KinematicsError;
use super::params::{CalibratedModel, Instrument, ParamLayout, PARAMS_PER_JOINT};
use crate::geometry::{pose_error, Pose};
use crate::solver::{solve, LeastSquaresProblem, LmOptions};

/// A solution whose (scaled) residual exceeds this is out of reach.
pub const IK_REACH_TOL_MM: f64 = 1e-3;
const IK_MAX_ITERATIONS: usize = 100;
/// Compensation's answers are solved to this residual (mm, scaled) ...
const IK_POLISHED_MM: f64 = 1e-7;
/// ... with at most this many fresh runs (only near singularities).
const IK_POLISH_RUNS: usize = 5;

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

/// Where the Levenberg–Marquardt run that found a solution started.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum IkStart {
    /// The caller's seed (the first one, when several were given), or
    /// for compensation of a far target on a spherical-wrist arm the
    /// closed-form solution nearest it: the seed's own branch.
    #[default]
    Seed,
    /// A closed-form branch seed of a spherical-wrist arm.
    Branch,
    /// Another seed of a list, or the grid of [`default_seeds`].
    MultiStart,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IkSolution {
    pub joints_rad: Vec<f64>,
    /// Position distance between target and reached tool (mm).
    pub residual_mm: f64,
    /// Orientation distance (rad).
    pub residual_rad: f64,
    #[serde(default)]
    pub start: IkStart,
    /// Levenberg–Marquardt iterations (Jacobian evaluations) over every
    /// run this target took (compensation's solver only; 0 otherwise).
    #[serde(default)]
    pub iterations: usize,
}

struct IkProblem<'a> {
    model: &'a CalibratedModel,
    /// Built on first use: only the generic solver's Jacobian needs it.
    layout: std::cell::OnceCell<ParamLayout>,
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
        let layout = self
            .layout
            .get_or_init(|| ParamLayout::new(&self.model.robot, Instrument::Camera));
        let (_, j) = tool_pose_jacobian(layout, self.model, q.as_slice()).ok()?;
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

/// Levenberg–Marquardt runs toward one target from several starts, keeping
/// the in-limit solution nearest a reference seed.
struct Search<'a> {
    problem: IkProblem<'a>,
    options: LmOptions,
    reference: &'a [f64],
    turns: Turns,
    best_residual: f64,
    /// Iterations of the compensation solver over all runs.
    iterations: usize,
    /// The out-of-limit solution nearest the reference, and why.
    limit_error: Option<(f64, KinematicsError)>,
    found: Option<(f64, IkSolution)>,
}

impl<'a> Search<'a> {
    fn new(
        model: &'a CalibratedModel,
        target: &'a Pose,
        reference: &'a [f64],
        turns: Turns,
    ) -> Self {
        Self {
            problem: IkProblem {
                model,
                layout: std::cell::OnceCell::new(),
                target,
            },
            options: LmOptions {
                max_iterations: IK_MAX_ITERATIONS,
                ..LmOptions::default()
            },
            reference,
            turns,
            best_residual: f64::INFINITY,
            iterations: 0,
            limit_error: None,
            found: None,
        }
    }

    /// One run from `start`; true when it reached the target within limits.
    fn run(&mut self, start: &[f64], how: IkStart) -> bool {
        let model = self.problem.model;
        let mut q: Vec<f64> = match self.turns {
            // Compensation: the dedicated solver, run to the polished residual.
            Turns::TowardReference => {
                let Some(mut run) = solve_joints(
                    model,
                    self.problem.target,
                    start,
                    IK_POLISHED_MM,
                    IK_MAX_ITERATIONS,
                ) else {
                    return false;
                };
                self.iterations += run.iterations;
                // Near a singularity the damping grows and the run creeps;
                // a fresh run from where it stopped (damping reset) goes on.
                for _ in 0..IK_POLISH_RUNS {
                    let residual = run.scaled_residual_mm;
                    if residual <= IK_POLISHED_MM || residual > IK_REACH_TOL_MM {
                        break;
                    }
                    let Some(next) = solve_joints(
                        model,
                        self.problem.target,
                        &run.joints_rad,
                        IK_POLISHED_MM,
                        IK_MAX_ITERATIONS,
                    ) else {
                        break;
                    };
                    self.iterations += next.iterations;
                    if next.scaled_residual_mm >= residual {
                        break;
                    }
                    run = next;
                }
                run.joints_rad
            }
            // The simulator's station placement: the generic solver, as its
            // campaigns were generated.
            Turns::IntoLimits => {
                let Ok(report) = solve(
                    &self.problem,
                    DVector::from_column_slice(start),
                    &self.options,
                ) else {
                    return false;
                };
                report.x.iter().copied().collect()
            }
        };
        move_by_turns(model, &mut q, self.reference, self.turns);
        let Some((_, e)) = self.problem.error(&DVector::from_column_slice(&q)) else {
            return false;
        };
        let (pos, rot) = (e.rows(0, 3).norm(), e.rows(3, 3).norm());
        let scaled = pos.max(rot * IK_ROTATION_SCALE_MM);
        self.best_residual = self.best_residual.min(scaled);
        if scaled > IK_REACH_TOL_MM {
            return false;
        }
        let distance = squared_distance(&q, self.reference);
        if let Err(e) = model.robot.check_limits(&q) {
            if self.limit_error.as_ref().is_none_or(|(d, _)| distance < *d) {
                self.limit_error = Some((distance, e));
            }
            return false;
        }
        if self.found.as_ref().is_none_or(|(d, _)| distance < *d) {
            self.found = Some((
                distance,
                IkSolution {
                    joints_rad: q,
                    residual_mm: pos,
                    residual_rad: rot,
                    start: how,
                    iterations: 0,
                },
            ));
        }
        true
    }

    /// Runs from `starts` (ordered by their distance from the seed) until
    /// none can refine to a nearer in-limit answer than the best so far;
    /// the run from index `own_branch` counts as the seed's.
    fn run_branches(&mut self, starts: &[(f64, Vec<f64>)], own_branch: Option<usize>) {
        for (k, (distance, start)) in starts.iter().enumerate() {
            if let Some((best, _)) = &self.found {
                if *distance > best.sqrt() + BRANCH_MARGIN_RAD {
                    break;
                }
            }
            let how = if own_branch == Some(k) {
                IkStart::Seed
            } else {
                IkStart::Branch
            };
            self.run(start, how);
        }
    }

    fn finish(self) -> Result<IkSolution, IkError> {
        match (self.found, self.limit_error) {
            (Some((_, s)), _) => Ok(IkSolution {
                iterations: self.iterations,
                ..s
            }),
            (None, Some((_, e))) => Err(IkError::Limits(e)),
            (None, None) => Err(IkError::OutOfReach {
                residual_mm: self.best_residual,
            }),
        }
    }
}

/// Joints that put the tool at `world_to_tool` according to `model`,
/// started from each seed; of the solutions within reach and limits, the
/// one closest to the first seed. Out of reach and beyond-limit targets are
/// errors. The simulator places its stations with this (its home seed's
/// branch only); compensation uses [`nearest_within_limits`].
pub fn inverse_kinematics(
    model: &CalibratedModel,
    world_to_tool: &Pose,
    seeds: &[Vec<f64>],
) -> Result<IkSolution, IkError> {
    let Some(first) = seeds.first() else {
        return Err(IkError::NoSeed);
    };
    let mut search = Search::new(model, world_to_tool, first, Turns::IntoLimits);
    for (k, seed) in seeds.iter().enumerate() {
        model.robot.base_to_flange(seed)?;
        let how = if k == 0 {
            IkStart::Seed
        } else {
            IkStart::MultiStart
        };
        search.run(seed, how);
    }
    search.finish()
}

/// A seed this close (rad, joint-space norm) to the nearest closed-form
/// solution is near its target: its own run answers in a few iterations.
/// Farther seeds start from the closed-form solutions instead (a run from
/// a far seed takes tens of iterations, or wanders into another branch).
const NEAR_SEED_RAD: f64 = 0.5;
/// A closed-form start farther (rad) from the seed than the best answer
/// so far plus this cannot refine to a nearer one: the calibrated model's
/// solution lies within milliradians of the nominal formula's, except near
/// the shoulder singularity, which the ring of shoulder seeds covers.
const BRANCH_MARGIN_RAD: f64 = 0.5;
/// Shoulder x elbow x wrist: the closed form's solutions before any ring.
const BRANCHES: usize = 8;

/// Compensation (api.md "compensate"): the in-limit joints nearest `seed`
/// (joint-space distance, whole turns included) that put the tool at
/// `world_to_tool`.
///
/// A spherical-wrist arm first gets its closed-form solutions (Pieper's
/// decomposition of its own link geometry), turned toward the seed and
/// ordered by their distance from it. A seed near the nearest one runs
/// itself (a few iterations); otherwise the nearest closed-form solution
/// starts the run, reported as the seed's ([`IkStart::Seed`]: its own
/// branch). When that answer leaves the limits, the other branches are
/// refined in order of distance until none can be nearer than the best
/// in-limit answer; near the shoulder singularity, the ring of shoulder
/// seeds follows when none of the eight answers. Other arms: the seed's
/// run, then the [`default_seeds`]
/// grid. A target no start reaches within limits is an error naming the
/// nearest solution's offending joint.
pub fn nearest_within_limits(
    model: &CalibratedModel,
    world_to_tool: &Pose,
    seed: &[f64],
) -> Result<IkSolution, IkError> {
    model.robot.base_to_flange(seed)?;
    let mut search = Search::new(model, world_to_tool, seed, Turns::TowardReference);
    let Some(arm) = SphericalWristArm::of(&model.robot) else {
        if !search.run(seed, IkStart::Seed) {
            for mut start in default_seeds(model) {
                move_by_turns(model, &mut start, seed, Turns::TowardReference);
                search.run(&start, IkStart::MultiStart);
            }
        }
        return search.finish();
    };
    let base_to_flange =
        model.world_to_base.inverse() * world_to_tool * model.flange_to_tool.inverse();
    let mut starts: Vec<(f64, Vec<f64>)> = arm
        .branch_seeds(&base_to_flange)
        .into_iter()
        .map(|mut start| {
            move_by_turns(model, &mut start, seed, Turns::TowardReference);
            (squared_distance(&start, seed).sqrt(), start)
        })
        .collect();
    // The eight branches of the formula's own shoulder angles first; the
    // ring near the shoulder singularity only when none of them answers.
    let ring = starts.split_off(starts.len().min(BRANCHES));
    let by_distance = |v: &mut Vec<(f64, Vec<f64>)>| v.sort_by(|a, b| a.0.total_cmp(&b.0));
    by_distance(&mut starts);
    let near = starts.first().is_none_or(|(d, _)| *d <= NEAR_SEED_RAD);
    if near && search.run(seed, IkStart::Seed) {
        return search.finish();
    }
    let own_branch = (!near).then_some(0);
    search.run_branches(&starts, own_branch);
    if search.found.is_none() && !ring.is_empty() {
        let mut ring = ring;
        by_distance(&mut ring);
        search.run_branches(&ring, None);
    }
    // The closed form missed (a calibrated model far from its structure):
    // the seed's own run, as for other arms.
    if search.found.is_none() && !near {
        search.run(seed, IkStart::Seed);
    }
    search.finish()
}
