//! K-fold cross-validation of a selected term set (issue 19, method.md §7):
//! the set stays only if it lowers the whitened error on held-out poses
//! against the geometric fit. On real campaigns the residual is not white
//! (model misfit), so a Wald test alone keeps terms that fit the
//! calibration poses and nothing else.
//!
//! Two kinds of folds. [`interleaved_folds`] hold out every k-th pose:
//! the held-out poses share the campaign's coverage of joint space, so a
//! term that only fits the covered region passes them. [`region_folds`]
//! hold out a contiguous block of one joint's angles: the fit must predict
//! a region of that joint it has not seen, which is what a term must do
//! on another campaign (the UR10's Series C and D lie outside Series B's
//! joint-1 and joint-5 ranges; BENCHMARKS.md, "Non-geometric terms").

use nalgebra::{DMatrix, DVector};

use super::identify::IdentifyError;
use super::measurement::Measurement;
use super::nongeometric::NonGeometric;
use super::params::{CalibratedModel, ParamLayout};
use super::term_fit::TermFit;
use crate::solver::{solve, LmOptions};

/// Folds of the cross-validation (every k-th pose held out).
pub const FOLDS: usize = 5;

/// Fold of every pose: every [`FOLDS`]-th pose held out together.
pub(super) fn interleaved_folds(poses: usize) -> Vec<usize> {
    (0..poses).map(|i| i % FOLDS).collect()
}

/// Fold of every pose: [`FOLDS`] contiguous blocks of equal size along
/// `joint`'s angle (ties kept in pose order), so each fold holds out one
/// region of that joint's covered range.
pub(super) fn region_folds(data: &[Measurement], joint: usize) -> Vec<usize> {
    let mut order: Vec<usize> = (0..data.len()).collect();
    order.sort_by(|&a, &b| data[a].joints_rad[joint].total_cmp(&data[b].joints_rad[joint]));
    let mut folds = vec![0; data.len()];
    for (rank, &i) in order.iter().enumerate() {
        folds[i] = rank * FOLDS / data.len().max(1);
    }
    folds
}

/// Held-out sums of squared whitened residuals `(with terms `base`, with
/// terms `active`)` over the folds `folds` (one label in `0..FOLDS` per
/// pose); `base` empty is the geometric fit.
#[allow(clippy::too_many_arguments)]
pub(super) fn held_out_costs(
    layout: &ParamLayout,
    reference: &CalibratedModel,
    free: &[usize],
    terms: &NonGeometric,
    (base, active): (&[usize], &[usize]),
    x0: &DVector<f64>,
    data: &[Measurement],
    whitening: &[DMatrix<f64>],
    folds: &[usize],
) -> Result<(f64, f64), IdentifyError> {
    let lm = LmOptions::default();
    let mut costs = (0.0, 0.0);
    for fold in 0..FOLDS {
        let (train, test): (Vec<usize>, Vec<usize>) =
            (0..data.len()).partition(|&i| folds[i] != fold);
        if train.is_empty() || test.is_empty() {
            continue;
        }
        let pick = |idx: &[usize]| -> (Vec<Measurement>, Vec<DMatrix<f64>>) {
            (
                idx.iter().map(|&i| data[i].clone()).collect(),
                idx.iter().map(|&i| whitening[i].clone()).collect(),
            )
        };
        let (d_train, w_train) = pick(&train);
        let (d_test, w_test) = pick(&test);
        for (free_terms, cost) in [(base, &mut costs.0), (active, &mut costs.1)] {
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
            let start = DVector::from_fn(unknowns, |i, _| if i < free.len() { x0[i] } else { 0.0 });
            let sol = solve(&fit, start, &lm)?;
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
