//! Redundancy of residual groups (method.md §6 **beyond**): how much of
//! each group's residual the fit could not absorb, the denominator of the
//! variance-component estimate in [`super::noise`].

use nalgebra::{DMatrix, DVector};

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
/// group of rows `G` is `|G| - tr((J^T J)^-1 J_G^T J_G)`.
pub(super) fn components(
    jac: &DMatrix<f64>,
    inverse: &DMatrix<f64>,
    residuals: &DVector<f64>,
    pixel_rows: usize,
    head: usize,
) -> VarianceComponents {
    let pixels = jac.rows(0, pixel_rows);
    let hat_pixels = (inverse * (pixels.transpose() * pixels)).trace();
    let mut prior = [(0.0, 0.0); 2];
    for i in 0..jac.ncols() - head {
        let (row, col) = (pixel_rows + i, head + i);
        let group = &mut prior[usize::from(i % POSE_PARAMS >= 3)];
        group.0 += residuals[row].powi(2);
        group.1 += 1.0 - jac[(row, col)].powi(2) * inverse[(col, col)];
    }
    VarianceComponents {
        pixel: (
            residuals.rows(0, pixel_rows).norm_squared(),
            pixel_rows as f64 - hat_pixels,
        ),
        translation: prior[0],
        rotation: prior[1],
    }
}
