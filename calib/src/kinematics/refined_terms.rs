//! Non-geometric terms as the image-level joint refinement found them
//! (issue 19, method.md §6 "beyond"): the values, and the covariance of
//! terms and geometry together, read from the refinement's own inverse
//! normal matrix (joint corrections eliminated, intrinsics and further
//! boards marginalised). The geometric block is marginal over the terms,
//! so a set that keeps them states the geometry no more precisely than the
//! data with the terms free allow.

use nalgebra::DMatrix;

use super::nongeometric::NonGeometric;
use super::term_model::TermCovariance;
use super::uncertainty::embed_covariance;

/// The refined terms and their covariance with the geometry.
#[derive(Debug, Clone, PartialEq)]
pub struct RefinedTerms {
    /// The terms with their refined values (order as given).
    pub terms: NonGeometric,
    /// σ of each term value (its unit).
    pub std_devs: Vec<f64>,
    /// Layout-sized covariance of the geometry (internal units, zero where
    /// fixed), marginal over the terms and the intrinsics.
    pub geometric_covariance: DMatrix<f64>,
    /// The terms' covariance with the geometry and among themselves.
    pub covariance: TermCovariance,
}

impl RefinedTerms {
    /// From the head covariance `head_cov` (already scaled by the residual
    /// variance) of a refinement whose free layout values are `free`
    /// (head positions `0..free.len()`) and whose term values sit at head
    /// positions `term_start..term_start + terms.len()`.
    pub(super) fn from_head(
        terms: NonGeometric,
        head_cov: &DMatrix<f64>,
        layout_len: usize,
        free: &[usize],
        term_start: usize,
    ) -> Self {
        let nt = terms.terms.len();
        let nf = free.len();
        let geometric = head_cov.view((0, 0), (nf, nf)).into_owned();
        let mut cross_covariance = DMatrix::zeros(layout_len, nt);
        for (a, &i) in free.iter().enumerate() {
            for t in 0..nt {
                cross_covariance[(i, t)] = head_cov[(a, term_start + t)];
            }
        }
        let term_covariance = head_cov
            .view((term_start, term_start), (nt, nt))
            .into_owned();
        Self {
            std_devs: (0..nt)
                .map(|t| term_covariance[(t, t)].max(0.0).sqrt())
                .collect(),
            geometric_covariance: embed_covariance(layout_len, free, &geometric),
            covariance: TermCovariance {
                cross: cross_covariance,
                terms: term_covariance,
            },
            terms,
        }
    }
}
