//! The plan's prediction: parameter covariance `sigma_px^2 (J^T J)^-1` of
//! the image-level identification on the chosen poses (no prior: a job has
//! none), and its propagation to the camera position at random validation
//! poses in the same ranges. A job's validation error is the mean 3-D
//! distance between predicted and measured camera positions at the `val`
//! poses (`kinematics::identify::validate`); its model part is what is
//! predicted here (the simulator measures it against the true positions).

use nalgebra::{DMatrix, Matrix3, Vector3};
use rand::{rngs::StdRng, SeedableRng};
use rand_distr::{Distribution, StandardNormal};

use super::error::PlanError;
use super::information::Columns;
use crate::kinematics::jacobian::tool_pose_jacobian;
use crate::kinematics::CalibratedModel;

/// Draws of the position error per validation pose for its mean norm.
const NORM_DRAWS: usize = 400;
const NORM_SEED: u64 = 0x0e_7707;
/// Relative eigenvalue of the column-scaled information below which a
/// direction of the parameters is not determined by the chosen poses.
pub const UNDETERMINED_TOL: f64 = 1e-14;
/// Parameters named when some direction is undetermined.
const NAMED_PARAMETERS: usize = 3;

/// What the plan predicts.
#[derive(Debug, Clone, PartialEq)]
pub struct Prediction {
    /// Mean over the validation poses of the expected 3-D camera position
    /// error (mm).
    pub validation_error_mean_mm: f64,
    /// `(name, standard deviation)` of every identified parameter (mm, rad,
    /// px or unitless as the layout and the intrinsics name them).
    pub parameter_std_devs: Vec<(String, f64)>,
    /// `s_max / s_min` of the column-scaled image-level Jacobian.
    pub condition_number: f64,
}

/// Predict from the chosen poses' factors (whitened: `J^T J = sum G^T G`
/// already divided by `sigma_px^2`); `validation_joints_rad` are the poses
/// the error is averaged over.
pub fn predict(
    model: &CalibratedModel,
    columns: &Columns,
    factors: &[&DMatrix<f64>],
    validation_joints_rad: &[Vec<f64>],
) -> Result<Prediction, PlanError> {
    let p = columns.len();
    let mut info = DMatrix::<f64>::zeros(p, p);
    for g in factors {
        info += g.transpose() * *g;
    }
    let d = DMatrix::from_fn(p, p, |r, c| {
        if r == c {
            1.0 / info[(r, r)].max(f64::MIN_POSITIVE).sqrt()
        } else {
            0.0
        }
    });
    let scaled = &d * &info * &d;
    let eig = scaled.clone().symmetric_eigen();
    let (mut lo, mut hi, mut lo_k) = (f64::INFINITY, 0.0f64, 0);
    for (k, &v) in eig.eigenvalues.iter().enumerate() {
        if v < lo {
            lo = v;
            lo_k = k;
        }
        hi = hi.max(v);
    }
    if lo.is_nan() || lo <= UNDETERMINED_TOL * hi {
        let v = eig.eigenvectors.column(lo_k);
        let mut idx: Vec<usize> = (0..p).collect();
        idx.sort_by(|&a, &b| v[b].abs().total_cmp(&v[a].abs()));
        return Err(PlanError::Unidentifiable {
            parameters: idx[..NAMED_PARAMETERS.min(p)]
                .iter()
                .map(|&i| columns.names[i].clone())
                .collect(),
        });
    }
    let cov_scaled =
        &d * scaled.try_inverse().ok_or(PlanError::Unidentifiable {
            parameters: columns.names.clone(),
        })? * &d;
    let parameter_std_devs = (0..p)
        .map(|i| {
            (
                columns.names[i].clone(),
                cov_scaled[(i, i)].max(0.0).sqrt() * columns.scale[i],
            )
        })
        .collect();
    let nf = columns.free.len();
    let cov_kin = cov_scaled.view((0, 0), (nf, nf)).into_owned();
    let mut rng = StdRng::seed_from_u64(NORM_SEED);
    let draws: Vec<Vector3<f64>> = (0..NORM_DRAWS)
        .map(|_| Vector3::from_fn(|_, _| StandardNormal.sample(&mut rng)))
        .collect();
    let mut total = 0.0;
    for q in validation_joints_rad {
        let (_, jt) = tool_pose_jacobian(&columns.layout, model, q)
            .map_err(|e| PlanError::Model(e.to_string()))?;
        let a = DMatrix::from_fn(3, nf, |r, c| jt[(r, columns.free[c])] * columns.scale[c]);
        let pos = &a * &cov_kin * a.transpose();
        let pos = Matrix3::from_fn(|r, c| pos[(r, c)]);
        total += mean_norm(&pos, &draws);
    }
    Ok(Prediction {
        validation_error_mean_mm: total / validation_joints_rad.len().max(1) as f64,
        parameter_std_devs,
        condition_number: (hi / lo).sqrt(),
    })
}

/// `sum A_v^T A_v` over `validation_joints_rad`, with `A_v` the camera
/// position's Jacobian in the scaled columns (zero for the intrinsics):
/// `tr(W Cov)` is the summed position variance at those poses, what the
/// selection's I criterion minimises.
pub fn position_weight(
    model: &CalibratedModel,
    columns: &Columns,
    validation_joints_rad: &[Vec<f64>],
) -> Result<DMatrix<f64>, PlanError> {
    let p = columns.len();
    let nf = columns.free.len();
    let mut w = DMatrix::zeros(p, p);
    for q in validation_joints_rad {
        let (_, jt) = tool_pose_jacobian(&columns.layout, model, q)
            .map_err(|e| PlanError::Model(e.to_string()))?;
        let a = DMatrix::from_fn(3, p, |r, c| {
            if c < nf {
                jt[(r, columns.free[c])] * columns.scale[c]
            } else {
                0.0
            }
        });
        w += a.transpose() * a;
    }
    Ok(w)
}

/// `E|e|` for `e ~ N(0, cov)`, over the fixed standard-normal `draws`.
fn mean_norm(cov: &Matrix3<f64>, draws: &[Vector3<f64>]) -> f64 {
    let eig = cov.symmetric_eigen();
    let root =
        eig.eigenvectors * Matrix3::from_diagonal(&eig.eigenvalues.map(|v| v.max(0.0).sqrt()));
    draws.iter().map(|z| (root * z).norm()).sum::<f64>() / draws.len().max(1) as f64
}
