//! Redundancy of residual groups (method.md §6 **beyond**): how much of
//! each group's residual the fit could not absorb, the denominator of the
//! variance-component estimate in [`super::noise`].

use nalgebra::{DVector, Vector6};

/// Unknowns of one flange correction (translation, rotation).
const POSE_PARAMS: usize = 6;

/// Sums of squared residuals (px^2) and redundancies of the residual
/// groups at the solution, for the variance-component estimate of
/// [`super::noise`]: dot pixels, flange translation and rotation priors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VarianceComponents {
    pub pixel: (f64, f64),
    pub translation: (f64, f64),
    pub rotation: (f64, f64),
}

/// Variance components (see [`VarianceComponents`]): the redundancy of a
/// group of rows `G` is `|G| - tr((J^T J)^-1 J_G^T J_G)`. A prior row
/// `w_i * correction_i` has `J_G^T J_G = w_i^2 e_i e_i^T`, so its share is
/// `w_i^2 (A^-1)_ii` (`tail_diagonal`: the diagonal of `A^-1` over the
/// corrections); the pixel rows take the rest of `tr(A^-1 A) = n` for the
/// regular normal matrix `A` of `n = unknowns`.
pub(super) fn components(
    residuals: &DVector<f64>,
    pixel_rows: usize,
    weights: &Vector6<f64>,
    tail_diagonal: &DVector<f64>,
    unknowns: usize,
) -> VarianceComponents {
    let corrections = tail_diagonal.len();
    let mut prior = [(0.0, 0.0); 2];
    let mut hat_prior = 0.0;
    for i in 0..corrections {
        let w = weights[i % POSE_PARAMS];
        let hat = w * w * tail_diagonal[i];
        let group = &mut prior[usize::from(i % POSE_PARAMS >= 3)];
        group.0 += residuals[pixel_rows + i].powi(2);
        group.1 += 1.0 - hat;
        hat_prior += hat;
    }
    VarianceComponents {
        pixel: (
            residuals.rows(0, pixel_rows).norm_squared(),
            pixel_rows as f64 - (unknowns as f64 - hat_prior),
        ),
        translation: prior[0],
        rotation: prior[1],
    }
}
