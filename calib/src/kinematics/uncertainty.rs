//! Predicted uncertainty of a calibrated pose (issue "Deploy the result"):
//! the parameter covariance (method.md §6) propagated to the pose through
//! the identification Jacobian, `Σ_pose = J Σ_x J^T` (first order).
//!
//! The Jacobian ([`tool_pose_jacobian`]) differentiates the tool pose in the
//! world frame with respect to every layout parameter, including the
//! world-to-base transform (the board or tracker frame) and the hand–eye;
//! which groups a pose depends on is [`PoseFrame`]'s choice.

use nalgebra::{DMatrix, Matrix3};

use super::jacobian::tool_pose_jacobian;
use super::model::KinematicsError;
use super::params::{CalibratedModel, ParamKind, ParamLayout};
use crate::geometry::Pose;

/// Which pose's uncertainty is wanted, and so which parameters move it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PoseFrame {
    /// The flange in the robot's base frame: the link parameters only.
    FlangeInBase,
    /// The calibrated tool (camera, or tracker tool point) in the world
    /// frame: link parameters, world-to-base and hand–eye.
    ToolInWorld,
    /// A tool given exactly in the flange frame, in the world frame: link
    /// parameters and world-to-base (the hand–eye does not move it).
    GivenToolInWorld(Pose),
}

/// The 1σ size of a predicted pose's error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoseStd {
    /// `sqrt(trace Σ_position)` (mm): the RMS length of the 3-D position
    /// error, not a per-axis σ.
    pub position_mm: f64,
    /// `sqrt(trace Σ_rotation)` (rad) of the small-angle rotation error.
    pub rotation_rad: f64,
    /// The 3x3 position covariance (mm², world or base frame).
    pub position_covariance: Matrix3<f64>,
}

/// Why an uncertainty cannot be predicted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UncertaintyError {
    #[error("covariance is {rows}x{cols}, the parameter layout has {expected} entries")]
    Shape {
        rows: usize,
        cols: usize,
        expected: usize,
    },
    #[error("covariance has a non-finite entry")]
    NotFinite,
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
}

/// `cov_free` (the identified parameters `free`, in order) placed in a
/// layout-sized matrix with zero rows and columns at the fixed parameters.
pub fn embed_covariance(len: usize, free: &[usize], cov_free: &DMatrix<f64>) -> DMatrix<f64> {
    let mut full = DMatrix::zeros(len, len);
    for (a, &i) in free.iter().enumerate() {
        for (b, &j) in free.iter().enumerate() {
            full[(i, j)] = cov_free[(a, b)];
        }
    }
    full
}

/// Checks a layout-sized covariance once, before it is propagated to many
/// poses.
pub fn check_covariance(
    layout: &ParamLayout,
    covariance: &DMatrix<f64>,
) -> Result<(), UncertaintyError> {
    let n = layout.len();
    if covariance.nrows() != n || covariance.ncols() != n {
        return Err(UncertaintyError::Shape {
            rows: covariance.nrows(),
            cols: covariance.ncols(),
            expected: n,
        });
    }
    if covariance.iter().any(|v| !v.is_finite()) {
        return Err(UncertaintyError::NotFinite);
    }
    Ok(())
}

/// The predicted 1σ error of the pose `frame` at joints `q_rad`, from the
/// covariance of `model`'s parameters in `layout` order (internal units:
/// mm and rad).
pub fn pose_std(
    layout: &ParamLayout,
    model: &CalibratedModel,
    covariance: &DMatrix<f64>,
    q_rad: &[f64],
    frame: PoseFrame,
) -> Result<PoseStd, UncertaintyError> {
    check_covariance(layout, covariance)?;
    let jac = frame_jacobian(layout, model, q_rad, frame)?;
    let pose_cov = &jac * covariance * jac.transpose();
    let position_covariance: Matrix3<f64> = pose_cov.fixed_view::<3, 3>(0, 0).into_owned();
    let rotation_trace = pose_cov.fixed_view::<3, 3>(3, 3).trace();
    Ok(PoseStd {
        position_mm: position_covariance.trace().max(0.0).sqrt(),
        rotation_rad: rotation_trace.max(0.0).sqrt(),
        position_covariance,
    })
}

/// The identification Jacobian of the pose `frame` (6 x layout), with the
/// columns of the parameters that do not move that pose zeroed.
pub(super) fn frame_jacobian(
    layout: &ParamLayout,
    model: &CalibratedModel,
    q_rad: &[f64],
    frame: PoseFrame,
) -> Result<DMatrix<f64>, UncertaintyError> {
    let (at, keep_base, keep_tool) = match frame {
        PoseFrame::FlangeInBase => (
            CalibratedModel {
                robot: model.robot.clone(),
                world_to_base: Pose::identity(),
                flange_to_tool: Pose::identity(),
            },
            false,
            false,
        ),
        PoseFrame::ToolInWorld => (model.clone(), true, true),
        PoseFrame::GivenToolInWorld(tool) => (model.with_tool(tool), true, false),
    };
    let (_, mut jac) = tool_pose_jacobian(layout, &at, q_rad)?;
    for (i, p) in layout.params.iter().enumerate() {
        let keep = match p.kind {
            ParamKind::Base(_) => keep_base,
            ParamKind::Tool(_) => keep_tool,
            _ => true,
        };
        if !keep {
            jac.column_mut(i).fill(0.0);
        }
    }
    Ok(jac)
}

/// Relative size below which an eigenvalue of the covariance is dropped
/// from its factor (rounding of a positive semi-definite matrix).
const FACTOR_RANK_TOLERANCE: f64 = 1e-14;

/// A covariance ready to be propagated to many poses (a `forward` of
/// 10,000 rows): `Σ = L L^T` with `L` (layout x rank) from its symmetric
/// eigen-decomposition, computed once. Per pose `J L` (6 x rank) replaces
/// `J Σ J^T`, and the checks run once. A factor, not a Cholesky: a stored
/// covariance is singular (zero rows at fixed parameters, unidentifiable
/// combinations) and may carry rounding below zero.
#[derive(Debug, Clone)]
pub struct CovarianceFactor {
    layout: ParamLayout,
    /// `L`, layout x rank.
    factor: DMatrix<f64>,
}

impl CovarianceFactor {
    pub fn new(layout: &ParamLayout, covariance: &DMatrix<f64>) -> Result<Self, UncertaintyError> {
        check_covariance(layout, covariance)?;
        Ok(Self {
            layout: layout.clone(),
            factor: psd_factor(covariance),
        })
    }

    pub fn layout(&self) -> &ParamLayout {
        &self.layout
    }

    /// [`pose_std`] of `frame` at joints `q_rad` through the factor.
    pub fn pose_std(
        &self,
        model: &CalibratedModel,
        q_rad: &[f64],
        frame: PoseFrame,
    ) -> Result<PoseStd, UncertaintyError> {
        let jac = frame_jacobian(&self.layout, model, q_rad, frame)?;
        Ok(std_of_spread(&(jac * &self.factor)))
    }
}

/// `L` (n x rank) with `L L^T` the symmetric part of `covariance`, from its
/// eigen-decomposition (see [`CovarianceFactor`]).
pub(super) fn psd_factor(covariance: &DMatrix<f64>) -> DMatrix<f64> {
    let symmetric = (covariance + covariance.transpose()) * 0.5;
    let eigen = symmetric.symmetric_eigen();
    let largest = eigen.eigenvalues.iter().cloned().fold(0.0, f64::max);
    let kept: Vec<usize> = (0..eigen.eigenvalues.len())
        .filter(|&k| eigen.eigenvalues[k] > FACTOR_RANK_TOLERANCE * largest)
        .collect();
    DMatrix::from_fn(covariance.nrows(), kept.len(), |i, c| {
        let k = kept[c];
        eigen.eigenvectors[(i, k)] * eigen.eigenvalues[k].sqrt()
    })
}

/// The pose σ of `spread = J L` (6 x rank): `J Σ J^T = spread spread^T`.
pub(super) fn std_of_spread(spread: &DMatrix<f64>) -> PoseStd {
    let position = spread.rows(0, 3);
    let position_covariance: Matrix3<f64> =
        Matrix3::from_fn(|a, b| position.row(a).dot(&position.row(b)));
    let rotation_trace = spread.rows(3, 3).norm_squared();
    PoseStd {
        position_mm: position_covariance.trace().max(0.0).sqrt(),
        rotation_rad: rotation_trace.max(0.0).sqrt(),
        position_covariance,
    }
}

#[cfg(test)]
#[path = "uncertainty_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "uncertainty_honesty_tests.rs"]
mod honesty_tests;
