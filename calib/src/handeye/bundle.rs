//! The flange-pose bundle (method.md §4 **beyond**, §6): every board point
//! of every image predicted through
//! `target_to_camera_k = target_to_base * base_to_flange_k * flange_to_camera`
//! with the flange poses held as given (or corrected under a prior), and
//! the unknowns of [`super::bundle_model`].
//!
//! Both transforms move by [`crate::geometry::perturb_left`] (translation
//! added, rotation `exp(dr) R` in the outer frame), the same convention as
//! the kinematic identification, so their covariance is in
//! `geometry::pose_error`'s coordinates. The board scale multiplies the
//! nominal board coordinates: a printed pitch that differs from the
//! configured one is observable because the flange translations are in
//! millimetres. The problem ([`super::bundle_problem`]) assembles its
//! normal equations point by point, so memory does not grow with the
//! number of points.

use nalgebra::{DMatrix, DVector, Matrix6, Vector6};

use super::bundle_model::POSE_PARAMS;
pub use super::bundle_model::{
    BundleFreedom, BundleModel, Pairs, BUNDLE_INTRINSICS, PINHOLE_INTRINSICS,
};
use super::bundle_problem::Bundle;
use super::redundancy::components;
pub use super::redundancy::VarianceComponents;
use crate::covariance::covariance_from_normal;
use crate::geometry::Pose;
use crate::normal_matrix::NormalMatrix;
use crate::solver::{solve, LeastSquaresProblem, LmOptions, LmReport, SolverError};

/// A converged bundle with its covariance.
#[derive(Debug, Clone)]
pub struct BundleFit {
    pub model: BundleModel,
    pub freedom: BundleFreedom,
    /// Covariance of `[free intrinsics; target_to_base (6); flange_to_camera
    /// (6); board scale?]` at the solution, transforms in the
    /// `pose_error` coordinates (mm, rad), scaled by the residual variance.
    pub covariance: DMatrix<f64>,
    /// Point residual standard deviation per image axis (px).
    pub sigma_px: f64,
    /// RMS reprojection over all used points (px, per point).
    pub rms_px: f64,
    pub points: usize,
    pub iterations: usize,
    /// The fitted flange corrections (zero without `flange_weights`).
    pub flange_corrections: Vec<Vector6<f64>>,
    /// Present with `flange_weights`.
    pub components: Option<VarianceComponents>,
}

impl BundleFit {
    /// Offset of `target_to_base` in [`Self::covariance`].
    pub fn target_to_base_offset(&self) -> usize {
        self.freedom.intrinsics.len()
    }

    /// Offset of `flange_to_camera` in [`Self::covariance`].
    pub fn flange_to_camera_offset(&self) -> usize {
        self.target_to_base_offset() + POSE_PARAMS
    }

    /// Standard deviation of the board scale, if it was refined.
    pub fn board_scale_sigma(&self) -> Option<f64> {
        let i = self.flange_to_camera_offset() + POSE_PARAMS;
        self.freedom
            .board_scale
            .then(|| self.covariance[(i, i)].max(0.0).sqrt())
    }

    /// The 6x6 covariance block starting at `offset`.
    pub fn block6(&self, offset: usize) -> Matrix6<f64> {
        Matrix6::from_fn(|i, j| self.covariance[(offset + i, offset + j)])
    }
}

/// Fit the bundle to `views` (flange pose, point pairs) from `start`.
pub fn fit_bundle(
    views: &[(Pose, &Pairs)],
    start: &BundleModel,
    freedom: &BundleFreedom,
) -> Result<BundleFit, SolverError> {
    if freedom.intrinsics.iter().any(|&i| i >= BUNDLE_INTRINSICS) {
        return Err(SolverError::Empty);
    }
    let problem = Bundle {
        views,
        reference: *start,
        freedom,
    };
    let n = problem.params();
    let report: LmReport = solve(&problem, DVector::zeros(n), &LmOptions::default())?;
    let model = problem.unpack(&report.x);
    let head = problem.head();
    let flange_corrections: Vec<Vector6<f64>> = (0..problem.corrections() / POSE_PARAMS)
        .map(|k| Bundle::delta(&report.x, head + POSE_PARAMS * k))
        .collect();
    // Re-linearise about the solution (corrected flange poses, zero
    // corrections) so that the covariance is in the transforms' own
    // left-perturbation coordinates.
    let corrected: Vec<(Pose, &Pairs)> = views
        .iter()
        .enumerate()
        .map(|(k, (_, p))| (problem.flange(&report.x, k), *p))
        .collect();
    let at_solution = Bundle {
        views: &corrected,
        reference: model,
        freedom,
    };
    let (normal, _) = at_solution
        .normal_equations(&DVector::zeros(n), &report.residuals)
        .ok_or(SolverError::NonFinite)?;
    let variance = report.residual_variance();
    let pixel_rows = problem.pixel_rows();
    let pixel_ss = report.residuals.rows(0, pixel_rows).norm_squared();
    let (head_inverse, components) = match (&normal, freedom.flange_weights) {
        (NormalMatrix::Arrow(a), Some(w)) => match a.invert() {
            Some(inverse) => {
                let c = components(&report.residuals, pixel_rows, &w, &inverse.tail_diagonal, n);
                (inverse.head, Some(c))
            }
            // Singular: the head's pseudo-inverse, and no variance
            // components (their redundancies need the regular inverse).
            None => (a.pseudo_invert().head, None),
        },
        _ => (covariance_from_normal(&normal.to_dense(), 1.0), None),
    };
    Ok(BundleFit {
        model,
        freedom: freedom.clone(),
        covariance: head_inverse.view((0, 0), (head, head)).into_owned() * variance,
        sigma_px: variance.sqrt(),
        rms_px: (pixel_ss / (pixel_rows / 2) as f64).sqrt(),
        points: pixel_rows / 2,
        iterations: report.iterations,
        flange_corrections,
        components,
    })
}

#[cfg(test)]
#[path = "bundle_tests.rs"]
mod tests;
