//! The pose-level identification problem (method.md §6): each pose's
//! measured-minus-predicted tool pose (6 rows: mm and small-angle rad) or
//! position (3 rows), whitened by its weights ([`super::weights`]), over the
//! free entries of the parameter vector; with a prior (method.md §6.7), one
//! pseudo-observation per free parameter after the poses' rows.

use nalgebra::{DMatrix, DVector};

use super::identify_error::IdentifyError;
use super::jacobian::tool_pose_jacobian;
use super::measurement::{Measurement, Observed};
use super::params::{CalibratedModel, ParamLayout};
use super::prior::PriorRows;
use crate::geometry::pose_error;
use crate::solver::LeastSquaresProblem;

/// Whitened residuals `W (measured - predicted)` over the free parameters.
pub(super) struct PoseFit<'a> {
    pub(super) layout: &'a ParamLayout,
    pub(super) reference: &'a CalibratedModel,
    pub(super) free: &'a [usize],
    pub(super) data: &'a [Measurement],
    pub(super) whitening: &'a [DMatrix<f64>],
    /// The kinematic prior over `free` (`None`: maximum likelihood).
    pub(super) prior: Option<&'a PriorRows>,
}

impl PoseFit<'_> {
    pub(super) fn full(&self, x: &DVector<f64>) -> DVector<f64> {
        full_vector(self.layout, self.free, x)
    }

    fn rows(&self) -> usize {
        self.layout.instrument.rows()
    }

    /// Residual and full-column Jacobian at model `m` (x = 0 around it).
    pub(super) fn evaluate(
        &self,
        m: &CalibratedModel,
        with_jac: bool,
    ) -> Option<(DVector<f64>, DMatrix<f64>)> {
        let rows = self.rows();
        let cols = if with_jac { self.layout.len() } else { 0 };
        let mut r = DVector::zeros(rows * self.data.len());
        let mut jac = DMatrix::zeros(rows * self.data.len(), cols);
        for (k, (meas, w)) in self.data.iter().zip(self.whitening).enumerate() {
            let (pred, j) = if with_jac {
                tool_pose_jacobian(self.layout, m, &meas.joints_rad).ok()?
            } else {
                (
                    m.world_to_tool(&meas.joints_rad).ok()?,
                    DMatrix::zeros(0, 0),
                )
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
                jac.rows_mut(k * rows, rows)
                    .copy_from(&(-(w * j.rows(0, rows))));
            }
        }
        Some((r, jac))
    }
}

impl LeastSquaresProblem for PoseFit<'_> {
    fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
        let m = self.layout.apply(self.reference, &self.full(x));
        let r = self.evaluate(&m, false)?.0;
        let Some(p) = self.prior else {
            return Some(r);
        };
        let data_rows = r.len();
        let mut out = DVector::zeros(data_rows + p.len());
        out.rows_mut(0, data_rows).copy_from(&r);
        for k in 0..p.len() {
            out[data_rows + k] = p.residual(k, x[k]);
        }
        Some(out)
    }

    fn jacobian(&self, x: &DVector<f64>) -> Option<DMatrix<f64>> {
        let m = self.layout.apply(self.reference, &self.full(x));
        let (_, jac) = self.evaluate(&m, true)?;
        let prior_rows = self.prior.map_or(0, PriorRows::len);
        let data_rows = jac.nrows();
        Some(DMatrix::from_fn(
            data_rows + prior_rows,
            self.free.len(),
            |r, c| match (r < data_rows, self.prior) {
                (true, _) => jac[(r, self.free[c])],
                (false, Some(p)) if r - data_rows == c => p.weight[c],
                _ => 0.0,
            },
        ))
    }
}

/// The layout-length vector with `x` at the `free` indices, zero elsewhere.
pub(super) fn full_vector(layout: &ParamLayout, free: &[usize], x: &DVector<f64>) -> DVector<f64> {
    let mut full = DVector::zeros(layout.len());
    for (k, &i) in free.iter().enumerate() {
        full[i] = x[k];
    }
    full
}

/// Measured minus predicted tool pose (or position) of `model` at every
/// pose, unweighted, as `rows x 1` columns.
pub(super) fn unweighted_residuals(
    layout: &ParamLayout,
    model: &CalibratedModel,
    data: &[Measurement],
) -> Result<Vec<DMatrix<f64>>, IdentifyError> {
    let rows = layout.instrument.rows();
    let identity = vec![DMatrix::identity(rows, rows); data.len()];
    let probe = PoseFit {
        layout,
        reference: model,
        free: &[],
        data,
        whitening: &identity,
        prior: None,
    };
    let (r, _) = probe.evaluate(model, false).ok_or(IdentifyError::NoPoses)?;
    Ok((0..data.len())
        .map(|k| DMatrix::from_column_slice(rows, 1, r.rows(k * rows, rows).as_slice()))
        .collect())
}
