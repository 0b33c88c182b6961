//! Predicted uncertainty of a pose through a model with non-geometric
//! terms, the terms' covariance with the geometry included (issue 19,
//! method.md §6 "beyond"). A term `t` deflects joint `j_t` by
//! `v_t f_t(q)`, so its column in the pose Jacobian is that joint's `dθ`
//! column times `f_t(q)`; with `J_ext = [J, J_t(q)]` over the geometry and
//! the term values, `Σ_pose = J_ext Σ_full J_ext^T` where `Σ_full` is the
//! joint covariance of geometry and terms the image-level refinement found
//! (`super::refined_terms`). Taking the two as independent instead
//! (`TermModel::term_variance` beside the geometric covariance) ignores
//! that a term and the joint offset it shares a column with trade against
//! each other.

use nalgebra::DMatrix;

use super::params::{ParamLayout, PARAMS_PER_JOINT};
use super::term_model::{TermCovariance, TermModel};
use super::uncertainty::{
    check_covariance, frame_jacobian, psd_factor, std_of_spread, PoseFrame, PoseStd,
    UncertaintyError,
};

/// The joint covariance of geometry and terms, factored once (as
/// [`super::uncertainty::CovarianceFactor`]).
#[derive(Debug, Clone)]
pub struct TermCovarianceFactor {
    layout: ParamLayout,
    /// `L`, (layout + terms) x rank.
    factor: DMatrix<f64>,
}

impl TermCovarianceFactor {
    /// From the layout-sized `geometric` covariance (marginal over the
    /// terms) and the terms' covariance `with` it.
    pub fn new(
        layout: &ParamLayout,
        geometric: &DMatrix<f64>,
        with: &TermCovariance,
    ) -> Result<Self, UncertaintyError> {
        check_covariance(layout, geometric)?;
        let (n, nt) = (layout.len(), with.terms.nrows());
        if with.terms.ncols() != nt || with.cross.nrows() != n || with.cross.ncols() != nt {
            return Err(UncertaintyError::Shape {
                rows: with.cross.nrows(),
                cols: with.cross.ncols(),
                expected: n,
            });
        }
        if with
            .cross
            .iter()
            .chain(with.terms.iter())
            .any(|v| !v.is_finite())
        {
            return Err(UncertaintyError::NotFinite);
        }
        let mut full = DMatrix::zeros(n + nt, n + nt);
        full.view_mut((0, 0), (n, n)).copy_from(geometric);
        full.view_mut((0, n), (n, nt)).copy_from(&with.cross);
        full.view_mut((n, 0), (nt, n))
            .copy_from(&with.cross.transpose());
        full.view_mut((n, n), (nt, nt)).copy_from(&with.terms);
        Ok(Self {
            layout: layout.clone(),
            factor: psd_factor(&full),
        })
    }

    /// The σ of `frame` at commanded joints `q_rad` through `model` (its
    /// terms in the order of the covariance).
    pub fn pose_std(
        &self,
        model: &TermModel,
        q_rad: &[f64],
        frame: PoseFrame,
    ) -> Result<PoseStd, UncertaintyError> {
        let n = self.layout.len();
        let nt = self.factor.nrows() - n;
        if model.terms.terms.len() != nt {
            return Err(UncertaintyError::Shape {
                rows: model.terms.terms.len(),
                cols: nt,
                expected: nt,
            });
        }
        let bent = model.deflected(q_rad)?;
        let jac = frame_jacobian(&self.layout, &model.model, &bent, frame)?;
        let basis = model.terms.basis(q_rad)?;
        let mut extended = DMatrix::zeros(6, n + nt);
        extended.columns_mut(0, n).copy_from(&jac);
        for (t, (term, f)) in model.terms.terms.iter().zip(&basis).enumerate() {
            let column = jac.column(term.joint() * PARAMS_PER_JOINT) * *f;
            extended.set_column(n + t, &column);
        }
        Ok(std_of_spread(&(extended * &self.factor)))
    }
}

#[cfg(test)]
#[path = "term_uncertainty_tests.rs"]
mod tests;
