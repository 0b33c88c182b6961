//! K-fold cross-validation of a selected term set (issue 19, method.md §7):
//! the set stays only if it lowers the whitened error on held-out poses
//! against the geometric fit. On real campaigns the residual is not white
//! (model misfit), so a Wald test alone keeps terms that fit the
//! calibration poses and nothing else.

use nalgebra::{DMatrix, DVector};

use super::identify::IdentifyError;
use super::measurement::Measurement;
use super::nongeometric::NonGeometric;
use super::params::{CalibratedModel, ParamLayout};
use super::term_fit::TermFit;
use crate::solver::{solve, LmOptions};

/// Folds of the cross-validation (every k-th pose held out).
pub const FOLDS: usize = 5;

/// Held-out sums of squared whitened residuals `(geometric, with terms)`.
#[allow(clippy::too_many_arguments)]
pub(super) fn held_out_costs(
    layout: &ParamLayout,
    reference: &CalibratedModel,
    free: &[usize],
    terms: &NonGeometric,
    active: &[usize],
    x0: &DVector<f64>,
    data: &[Measurement],
    whitening: &[DMatrix<f64>],
) -> Result<(f64, f64), IdentifyError> {
    let lm = LmOptions::default();
    let mut costs = (0.0, 0.0);
    for fold in 0..FOLDS {
        let (train, test): (Vec<usize>, Vec<usize>) =
            (0..data.len()).partition(|i| i % FOLDS != fold);
        let pick = |idx: &[usize]| -> (Vec<Measurement>, Vec<DMatrix<f64>>) {
            (
                idx.iter().map(|&i| data[i].clone()).collect(),
                idx.iter().map(|&i| whitening[i].clone()).collect(),
            )
        };
        let (d_train, w_train) = pick(&train);
        let (d_test, w_test) = pick(&test);
        for (with_terms, cost) in [(false, &mut costs.0), (true, &mut costs.1)] {
            let free_terms: &[usize] = if with_terms { active } else { &[] };
            let unknowns = free.len() + free_terms.len();
            let fit = TermFit {
                layout,
                reference,
                free,
                terms,
                free_terms,
                data: &d_train,
                whitening: &w_train,
            };
            let sol = solve(&fit, x0.rows(0, unknowns).into_owned(), &lm)?;
            let held = TermFit {
                data: &d_test,
                whitening: &w_test,
                ..fit
            };
            let (r, _) = held.evaluate(&sol.x, false).ok_or(IdentifyError::NoPoses)?;
            *cost += r.norm_squared();
        }
    }
    Ok(costs)
}
