//! The pose-level identification with non-geometric terms (issue 19,
//! method.md §6): the free geometric entries of the parameter vector and
//! the free term values fitted jointly, residuals whitened as in
//! [`super::pose_fit`].
//!
//! Term `k` deflects joint `i` by `p_k f_k(q)`, so its Jacobian column is
//! the `dtheta_i` column at the deflected joints times `f_k(q)`.

use nalgebra::{DMatrix, DVector};

use super::jacobian::tool_pose_jacobian;
use super::measurement::{Measurement, Observed};
use super::nongeometric::NonGeometric;
use super::params::{CalibratedModel, ParamLayout, PARAMS_PER_JOINT};
use crate::geometry::pose_error;
use crate::solver::LeastSquaresProblem;

/// Whitened residuals over `x = [free geometric entries; free term values]`.
pub(super) struct TermFit<'a> {
    pub(super) layout: &'a ParamLayout,
    pub(super) reference: &'a CalibratedModel,
    /// Geometric layout indices fitted.
    pub(super) free: &'a [usize],
    /// Terms and their starting values (`x` adds to these).
    pub(super) terms: &'a NonGeometric,
    /// Term indices fitted; the others keep their values.
    pub(super) free_terms: &'a [usize],
    pub(super) data: &'a [Measurement],
    pub(super) whitening: &'a [DMatrix<f64>],
}

impl TermFit<'_> {
    pub(super) fn unknowns(&self) -> usize {
        self.free.len() + self.free_terms.len()
    }

    /// The geometric model and the terms at `x`.
    pub(super) fn split(&self, x: &DVector<f64>) -> (CalibratedModel, NonGeometric) {
        let mut full = DVector::zeros(self.layout.len());
        for (k, &i) in self.free.iter().enumerate() {
            full[i] = x[k];
        }
        let mut terms = self.terms.clone();
        for (k, &t) in self.free_terms.iter().enumerate() {
            terms.values[t] += x[self.free.len() + k];
        }
        (self.layout.apply(self.reference, &full), terms)
    }

    /// Whitened residual and (optionally) the Jacobian over `x`.
    pub(super) fn evaluate(
        &self,
        x: &DVector<f64>,
        with_jac: bool,
    ) -> Option<(DVector<f64>, DMatrix<f64>)> {
        let (model, terms) = self.split(x);
        let rows = self.layout.instrument.rows();
        let n = self.data.len();
        let cols = if with_jac { self.unknowns() } else { 0 };
        let mut r = DVector::zeros(rows * n);
        let mut jac = DMatrix::zeros(rows * n, cols);
        for (k, (meas, w)) in self.data.iter().zip(self.whitening).enumerate() {
            let q = terms.deflected(&meas.joints_rad).ok()?;
            let (pred, j) = if with_jac {
                tool_pose_jacobian(self.layout, &model, &q).ok()?
            } else {
                (model.world_to_tool(&q).ok()?, DMatrix::zeros(0, 0))
            };
            let e = match &meas.observed {
                Observed::Pose { world_to_tool, .. } => pose_error(world_to_tool, &pred),
                Observed::Position { position_mm, .. } => {
                    let d = position_mm - pred.translation.vector;
                    nalgebra::Vector6::new(d.x, d.y, d.z, 0.0, 0.0, 0.0)
                }
            };
            r.rows_mut(k * rows, rows).copy_from(&(w * e.rows(0, rows)));
            if with_jac {
                let wj = -(w * j.rows(0, rows));
                for (c, &i) in self.free.iter().enumerate() {
                    jac.view_mut((k * rows, c), (rows, 1))
                        .copy_from(&wj.column(i));
                }
                let basis = terms.basis(&meas.joints_rad).ok()?;
                for (c, &t) in self.free_terms.iter().enumerate() {
                    let joint_col = terms.terms[t].joint() * PARAMS_PER_JOINT;
                    jac.view_mut((k * rows, self.free.len() + c), (rows, 1))
                        .copy_from(&(wj.column(joint_col) * basis[t]));
                }
            }
        }
        Some((r, jac))
    }
}

impl LeastSquaresProblem for TermFit<'_> {
    fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
        Some(self.evaluate(x, false)?.0)
    }

    fn jacobian(&self, x: &DVector<f64>) -> Option<DMatrix<f64>> {
        Some(self.evaluate(x, true)?.1)
    }
}
