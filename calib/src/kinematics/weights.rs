//! Measurement weights for the identification (method.md §6 **beyond**).
//!
//! Each pose's residual is whitened by its covariance: the camera step's
//! pose covariance (or the tracker's), **plus** what the noise of the
//! recorded joint angles adds. A joint that is really at `q + e` moves the
//! tool exactly as a joint offset `dtheta = e` would, so that term is
//! `J_q Sigma_q J_q^T` with `J_q` the `dtheta` columns of the identification
//! Jacobian ([`tool_pose_jacobian`]). Leaving it out makes the weights too
//! optimistic wherever the camera is more precise than the encoders (its
//! orientation, mostly), and the reported standard deviations too small.
//!
//! When the joint noise is not known, [`estimate_joint_sigma`] estimates
//! it from the residuals: the scalar variance component for which the
//! weighted residual sum equals its degrees of freedom (Helmert / Förstner
//! variance-component estimation, one component).

use nalgebra::DMatrix;

use super::identify_error::IdentifyError;
use super::identify_options::IdentifyMode;
use super::jacobian::tool_pose_jacobian;
use super::measurement::{
    Measurement, Observed, DEFAULT_POSITION_SIGMA_MM, DEFAULT_ROTATION_SIGMA_RAD,
};
use super::params::{CalibratedModel, Instrument, ParamLayout};

/// Bisection steps for the variance component (relative width 2^-60).
const VARIANCE_BISECTION_STEPS: usize = 60;
/// Largest joint noise the estimate considers (rad, about 6 degrees).
const MAX_JOINT_SIGMA_RAD: f64 = 0.1;

/// Each pose's measurement covariance and joint Jacobian at `model`.
pub struct PoseCovariances {
    /// Measurement covariance without joint noise (`rows x rows`).
    measurement: Vec<DMatrix<f64>>,
    /// `J_q` (`rows x joints`): the tool's motion per radian of each joint.
    joint_jacobian: Vec<DMatrix<f64>>,
}

impl PoseCovariances {
    /// Check the measurements against `layout` and collect their
    /// covariances (a default where none was given) and joint Jacobians.
    pub fn new(
        layout: &ParamLayout,
        model: &CalibratedModel,
        data: &[Measurement],
    ) -> Result<Self, IdentifyError> {
        let instrument = layout.instrument;
        let rows = instrument.rows();
        let offsets = layout.joint_offset_indices();
        let mut measurement = Vec::with_capacity(data.len());
        let mut joint_jacobian = Vec::with_capacity(data.len());
        for (pose, m) in data.iter().enumerate() {
            let (_, jac) = tool_pose_jacobian(layout, model, &m.joints_rad)
                .map_err(|source| IdentifyError::Pose { pose, source })?;
            joint_jacobian.push(DMatrix::from_fn(rows, offsets.len(), |r, c| {
                jac[(r, offsets[c])]
            }));
            measurement.push(match (&m.observed, instrument) {
                (Observed::Pose { covariance, .. }, Instrument::Camera) => match covariance {
                    Some(c) => DMatrix::from_column_slice(6, 6, c.as_slice()),
                    None => default_covariance(6),
                },
                (Observed::Pose { .. }, Instrument::Tracker) => default_covariance(3),
                (Observed::Position { covariance, .. }, Instrument::Tracker) => match covariance {
                    Some(c) => DMatrix::from_column_slice(3, 3, c.as_slice()),
                    None => default_covariance(3),
                },
                (Observed::Position { .. }, Instrument::Camera) => {
                    return Err(IdentifyError::WrongMeasurement {
                        pose,
                        instrument,
                        expected: "full-pose",
                    })
                }
            });
        }
        Ok(Self {
            measurement,
            joint_jacobian,
        })
    }

    /// Covariance of pose `k` with joint noise `sigma_rad` on every joint.
    pub fn covariance(&self, k: usize, joint_sigma_rad: f64) -> DMatrix<f64> {
        let jq = &self.joint_jacobian[k];
        &self.measurement[k] + jq * jq.transpose() * joint_sigma_rad.powi(2)
    }

    /// Whitening `W` (`W^T W = Sigma^-1`) of every pose; identity in paper
    /// mode (eq. 18 weighs every residual alike).
    pub fn whitening(
        &self,
        joint_sigma_rad: f64,
        mode: IdentifyMode,
    ) -> Result<Vec<DMatrix<f64>>, IdentifyError> {
        (0..self.measurement.len())
            .map(|pose| {
                let cov = self.covariance(pose, joint_sigma_rad);
                if mode == IdentifyMode::Paper {
                    return Ok(DMatrix::identity(cov.nrows(), cov.nrows()));
                }
                cov.cholesky()
                    .and_then(|c| c.l().try_inverse())
                    .ok_or(IdentifyError::BadCovariance { pose })
            })
            .collect()
    }

    /// `sum_k r_k^T Sigma_k(sigma)^-1 r_k` for unweighted residuals `r_k`.
    fn weighted_sum(&self, residuals: &[DMatrix<f64>], joint_sigma_rad: f64) -> Option<f64> {
        residuals
            .iter()
            .enumerate()
            .map(|(k, r)| {
                let chol = self.covariance(k, joint_sigma_rad).cholesky()?;
                Some((r.transpose() * chol.solve(r))[(0, 0)])
            })
            .sum()
    }
}

/// The joint noise (rad) that makes the weighted residual sum of the
/// unweighted per-pose residuals `residuals` (each `rows x 1`) equal to
/// `dof`: zero when the measurement covariances alone already explain the
/// scatter. `None` for inconsistent input.
pub fn estimate_joint_sigma(
    covariances: &PoseCovariances,
    residuals: &[DMatrix<f64>],
    dof: usize,
) -> Option<f64> {
    let target = dof as f64;
    if residuals.len() != covariances.measurement.len() || target <= 0.0 {
        return None;
    }
    if covariances.weighted_sum(residuals, 0.0)? <= target {
        return Some(0.0);
    }
    if covariances.weighted_sum(residuals, MAX_JOINT_SIGMA_RAD)? > target {
        return Some(MAX_JOINT_SIGMA_RAD);
    }
    // The weighted sum falls monotonically as the covariance grows.
    let (mut lo, mut hi) = (0.0, MAX_JOINT_SIGMA_RAD);
    for _ in 0..VARIANCE_BISECTION_STEPS {
        let mid = 0.5 * (lo + hi);
        if covariances.weighted_sum(residuals, mid)? > target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

/// The covariance assumed for a measurement given without one.
pub fn default_covariance(rows: usize) -> DMatrix<f64> {
    DMatrix::from_fn(rows, rows, |i, j| match (i == j, i < 3) {
        (false, _) => 0.0,
        (true, true) => DEFAULT_POSITION_SIGMA_MM.powi(2),
        (true, false) => DEFAULT_ROTATION_SIGMA_RAD.powi(2),
    })
}
