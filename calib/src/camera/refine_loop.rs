//! The refined-mode outer loop (method.md §4 **beyond**): joint LM
//! ([`super::refine::JointProblem`]), then outlier rejection (beyond
//! [`CalibrationOptions::outlier_sigmas`] robust sigmas), reference-distance
//! weighting and the dot-centre bias correction ([`super::bias`]), repeated
//! until the predicted centre offsets stop moving. Standard deviations come
//! from `sigma^2 (J^T J)^-1` at the solution.

use nalgebra::{DVector, Isometry3, Point2, Point3, Vector2};

use super::bias::{DiscBoundary, BOUNDARY_SAMPLES};
use super::error::CameraError;
use super::model::Intrinsics;
use super::model::IntrinsicsStdDev;
use super::observations::{Correspondences, MIN_DOTS_PER_VIEW};
use super::options::CalibrationOptions;
use super::refine::{IntrinsicsBlock, JointProblem};
use crate::solver::{solve, Damping, LmOptions, LmReport};

/// Median absolute residual to standard deviation for a Gaussian.
const MAD_TO_SIGMA: f64 = 1.4826;
/// LM stopping rules of each round: a relative cost change of 1e-10 is far
/// below the statistical resolution of any calibration (cost ~ n sigma^2).
const LM_COST_TOLERANCE: f64 = 1e-10;
const LM_STEP_TOLERANCE: f64 = 1e-10;
/// Start damping (on the column-scaled normal matrix, unit diagonal) and
/// its factor per rejected / accepted step (Marquardt's schedule). From the
/// Tsai start the joint problem is nearly linear: Gauss–Newton-like steps
/// converge in ~4 iterations and a later round (moved observations, started
/// at the previous solution) in ~2, where Nielsen's default start (1e-3 of
/// the largest diagonal, shrinking threefold per step) holds the weakly
/// determined directions back for 9 and 7. A rejected step is cheap (one
/// Schur solve, one residual evaluation, no new normal equations).
const START_DAMPING: f64 = 1e-7;
const DAMPING_FACTOR: f64 = 10.0;
/// Outliers are only looked for once the bias offsets move less than this (px).
const OUTLIER_BIAS_SETTLED_PX: f64 = 1e-3;
/// Extra rounds allowed for outlier removal beyond the bias iterations.
const EXTRA_OUTLIER_ROUNDS: usize = 10;

pub struct RefineInput<'a> {
    pub views: &'a [Vec<(Point3<f64>, Point2<f64>)>],
    pub initial_intrinsics: Intrinsics,
    pub initial_poses: &'a [Isometry3<f64>],
    pub options: &'a CalibrationOptions,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Refinement {
    pub intrinsics: Intrinsics,
    pub std_dev: Option<IntrinsicsStdDev>,
    pub camera_to_target: Vec<Isometry3<f64>>,
    /// Bias-corrected centres of every input dot.
    pub corrected: Vec<Vec<Point2<f64>>>,
    pub active: Vec<Vec<bool>>,
    /// `(view, dot index, residual px)` of dropped dots.
    pub outliers: Vec<(usize, usize, f64)>,
    pub bias_iterations: usize,
    /// RMS per residual component at the solution (px).
    pub sigma_px: f64,
    /// Target points of every input dot.
    pub targets: Vec<Vec<Point3<f64>>>,
}

impl Refinement {
    /// The corrected observations still in use for view `v`.
    pub fn used_observations(&self, v: usize) -> Vec<(Point3<f64>, Point2<f64>)> {
        self.targets[v]
            .iter()
            .zip(&self.corrected[v])
            .zip(&self.active[v])
            .filter(|(_, &a)| a)
            .map(|((t, p), _)| (*t, *p))
            .collect()
    }
}

/// Run the refinement.
pub fn refine(input: &RefineInput) -> Result<Refinement, CameraError> {
    let options = input.options;
    let block = match options.fixed_intrinsics {
        Some(i) => IntrinsicsBlock::Fixed(i),
        None => IntrinsicsBlock::Free {
            with_k3: options.estimate_k3,
        },
    };
    let views = input.views;
    let mut offsets: Vec<Vec<Vector2<f64>>> = views
        .iter()
        .map(|v| vec![Vector2::zeros(); v.len()])
        .collect();
    let mut active: Vec<Vec<bool>> = views.iter().map(|v| vec![true; v.len()]).collect();
    let mut outliers = Vec::new();
    let mut reference_weight = 0.0;
    let mut x: Option<DVector<f64>> = None;
    let lm = LmOptions {
        damping: Damping::Marquardt {
            mu0: START_DAMPING,
            lambda: DAMPING_FACTOR,
        },
        cost_tolerance: LM_COST_TOLERANCE,
        step_tolerance: LM_STEP_TOLERANCE,
        ..LmOptions::default()
    };
    let mut bias_iterations = 0;
    let max_rounds = options.max_bias_iterations.max(1) + EXTRA_OUTLIER_ROUNDS;
    let mut last: Option<(LmReport, Vec<Correspondences>)> = None;
    let boundary = DiscBoundary::new(BOUNDARY_SAMPLES);
    for _ in 0..max_rounds {
        let used: Vec<Vec<(Point3<f64>, Point2<f64>)>> = views
            .iter()
            .enumerate()
            .map(|(v, obs)| {
                obs.iter()
                    .enumerate()
                    .filter(|(i, _)| active[v][*i])
                    .map(|(i, (t, p))| (*t, p - offsets[v][i]))
                    .collect()
            })
            .collect();
        let refs = if reference_weight > 0.0 {
            options.reference_distances.as_slice()
        } else {
            &[]
        };
        let problem = JointProblem {
            views: &used,
            block,
            references: refs,
            reference_weight,
        };
        let x0 = x
            .take()
            .unwrap_or_else(|| problem.encode(&input.initial_intrinsics, input.initial_poses));
        let report = solve(&problem, x0, &lm)?;
        let intr = problem.intrinsics(&report.x);
        let poses: Vec<_> = (0..views.len())
            .map(|v| problem.pose(&report.x, v))
            .collect();
        // Robust sigma over the active dots' residual components.
        let n_img = report.residuals.len() - refs.len();
        let mut abs: Vec<f64> = report
            .residuals
            .rows(0, n_img)
            .iter()
            .map(|r| r.abs())
            .collect();
        let middle = abs.len() / 2;
        let (_, median, _) = abs.select_nth_unstable_by(middle, f64::total_cmp);
        let sigma = MAD_TO_SIGMA * *median;
        // Bias first: until the predicted offsets have settled, residuals
        // still hold the perspective bias (several sigma near the corners)
        // and must not be taken for outliers.
        let mut change: f64 = 0.0;
        if let Some(d) = options.dot_diameter_mm {
            bias_iterations += 1;
            for (v, obs) in views.iter().enumerate() {
                for (i, (t, _)) in obs.iter().enumerate() {
                    let off = boundary
                        .centre_bias(&intr, &poses[v], t, d / 2.0)
                        .ok_or_else(|| CameraError::DegenerateView {
                            view: v,
                            reason: "a dot boundary projects behind the camera".into(),
                        })?;
                    change = change.max((off - offsets[v][i]).norm());
                    offsets[v][i] = off;
                }
            }
        }
        let mut new_outliers = false;
        let bias_settled =
            change <= OUTLIER_BIAS_SETTLED_PX || bias_iterations >= options.max_bias_iterations;
        // One dot per view and round, the worst: a gross error drags its
        // view's pose and with it the neighbours' residuals.
        for (v, obs) in views.iter().enumerate() {
            let remaining = active[v].iter().filter(|&&a| a).count();
            if !bias_settled || remaining <= MIN_DOTS_PER_VIEW {
                continue;
            }
            let worst = obs
                .iter()
                .enumerate()
                .filter(|(i, _)| active[v][*i])
                .filter_map(|(i, (t, p))| {
                    Some((
                        i,
                        (p - offsets[v][i] - intr.project(&(poses[v] * t))?).norm(),
                    ))
                })
                .max_by(|a, b| a.1.total_cmp(&b.1));
            if let Some((i, r)) = worst.filter(|w| w.1 > options.outlier_sigmas * sigma) {
                active[v][i] = false;
                outliers.push((v, i, r));
                new_outliers = true;
            }
        }
        let refs_pending = !options.reference_distances.is_empty() && reference_weight == 0.0;
        if refs_pending {
            let min_sigma = options
                .reference_distances
                .iter()
                .map(|r| r.sigma_mm)
                .fold(f64::INFINITY, f64::min);
            reference_weight = sigma.max(f64::MIN_POSITIVE) / min_sigma;
        }
        x = Some(report.x.clone());
        let converged = !new_outliers && !refs_pending && change <= options.bias_tolerance_px;
        last = Some((report, used));
        if converged
            || bias_iterations >= options.max_bias_iterations
                && options.dot_diameter_mm.is_some()
                && !new_outliers
        {
            break;
        }
    }
    let (report, used) = last.expect("at least one round ran");
    let refs = if reference_weight > 0.0 {
        options.reference_distances.as_slice()
    } else {
        &[]
    };
    let problem = JointProblem {
        views: &used,
        block,
        references: refs,
        reference_weight,
    };
    let intrinsics = problem.intrinsics(&report.x);
    let camera_to_target: Vec<_> = (0..views.len())
        .map(|v| problem.pose(&report.x, v))
        .collect();
    let n_img = report.residuals.len() - refs.len();
    let sigma_px = (report.residuals.rows(0, n_img).norm_squared() / n_img as f64).sqrt();
    let std_dev = match block {
        IntrinsicsBlock::Fixed(_) => None,
        IntrinsicsBlock::Free { .. } => {
            intrinsics_std_dev(&problem, &report, block.len(), &intrinsics)
        }
    };
    let corrected = views
        .iter()
        .enumerate()
        .map(|(v, obs)| {
            obs.iter()
                .enumerate()
                .map(|(i, (_, p))| p - offsets[v][i])
                .collect()
        })
        .collect();
    Ok(Refinement {
        intrinsics,
        std_dev,
        camera_to_target,
        corrected,
        active,
        outliers,
        bias_iterations,
        sigma_px,
        targets: views
            .iter()
            .map(|v| v.iter().map(|(t, _)| *t).collect())
            .collect(),
    })
}

fn intrinsics_std_dev(
    problem: &JointProblem,
    report: &LmReport,
    n_intr: usize,
    intr: &Intrinsics,
) -> Option<IntrinsicsStdDev> {
    let inv = problem.intrinsics_inverse_normal(&report.normal_matrix)?;
    let n = n_intr.min(inv.nrows());
    let covariance = inv.view((0, 0), (n, n)) * report.residual_variance();
    Some(IntrinsicsStdDev::from_covariance(&covariance, intr))
}
