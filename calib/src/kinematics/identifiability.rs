//! Identifiability analysis (method.md §5): which parameters a campaign can
//! determine, by the SVD and a pivoted Gram–Schmidt of the column-scaled
//! identification Jacobian.
//!
//! Structural redundancies (a parameter that is a combination of others for
//! every pose, e.g. `dtheta_1` against the base yaw, `d_1` against the base
//! height, the joint-6 terms against the hand–eye) are found on a rich,
//! deterministic set of reference poses and fixed at their reference value;
//! the campaign is then checked: a parameter that is structurally free but
//! not determined by the campaign's poses (too few, too similar) is an error
//! naming it (a few such weak parameters, up to [`MAX_WEAK_FIXED`], are
//! held fixed and reported instead).

use nalgebra::{DMatrix, DVector};
use rand::{rngs::StdRng, Rng, SeedableRng};
use serde::{Deserialize, Serialize};

use super::jacobian::tool_pose_jacobian;
use super::model::KinematicsError;
use super::params::{CalibratedModel, ParamKind, ParamLayout};

/// Rotation rows are multiplied by this length (mm per rad) when no weights
/// are given, so that 1 mrad counts like 1 mm at one metre.
pub const ROTATION_ROW_SCALE_MM: f64 = 1000.0;
/// A column whose part not explained by the columns kept before it is below
/// this fraction of its norm is structurally redundant.
pub const STRUCTURAL_TOL: f64 = 1e-7;
/// A structurally free column whose unexplained part, on the campaign's
/// poses, is below this fraction is not identifiable from the campaign.
pub const CAMPAIGN_TOL: f64 = 1e-4;
/// At most this many structurally free parameters may be left undetermined
/// by a campaign; they are then held fixed and reported in
/// [`IdentifiabilityReport::weak`]. More is an error: the campaign cannot
/// identify the model.
pub const MAX_WEAK_FIXED: usize = 3;
/// An identified parameter whose excitation (the part of its unit-scaled
/// Jacobian column no other identified column explains) is below this is
/// reported as poorly determined: its σ is more than `1 / WEAK_EXCITATION`
/// times what the same poses would give it alone. Random poses spread over
/// the joint ranges give every parameter 0.18-0.77 (Aubo i10 model, 24
/// poses); the real Aubo campaign, joints 1-3 fixed in groups of four,
/// gives its link 1-3 terms 0.011-0.11.
pub const WEAK_EXCITATION: f64 = 0.05;
/// Random poses used to find the structural redundancies.
const REFERENCE_POSES: usize = 40;
const REFERENCE_SEED: u64 = 0x5eed_cafe;

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum IdentifiabilityError {
    #[error("{poses} poses give {rows} equations for {needed} free parameters: add poses")]
    TooFewPoses {
        poses: usize,
        rows: usize,
        needed: usize,
    },
    #[error("the campaign's poses do not determine {parameters:?}: vary the joints they belong to (more distinct poses)")]
    Unidentifiable { parameters: Vec<String> },
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
}

/// The outcome of the analysis, reported with every identification.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IdentifiabilityReport {
    /// Numerical rank of the column-scaled Jacobian of all parameters.
    pub rank: usize,
    /// Names of the parameters held fixed: structurally redundant ones and
    /// the campaign's weak ones.
    pub fixed: Vec<String>,
    /// The subset of `fixed` that this campaign's poses did not determine
    /// (structurally identifiable): vary the poses to identify them.
    pub weak: Vec<String>,
    /// Identified parameters the campaign determines poorly: excitation
    /// below [`WEAK_EXCITATION`] (e.g. links whose joints take only a few
    /// distinct values). Identified, but with a large σ. `analyse` judges
    /// the Jacobian it is given; `identify` replaces this with
    /// [`poorly_determined`] on the poses' geometry.
    pub poorly_determined: Vec<String>,
    /// Indices (into the layout) of the parameters that are identified.
    pub free: Vec<usize>,
    /// Per identified parameter (as `free`), the part of its unit-scaled
    /// Jacobian column that no other identified column explains: 1 for a
    /// parameter the poses see alone, near 0 for one they barely tell from
    /// a combination of others (its σ grows as 1 / excitation).
    pub excitation: Vec<f64>,
    /// `s_max / s_min` of the column-scaled Jacobian of the free parameters.
    pub condition_number: f64,
    /// Borm and Menq's O1: `(s_1 ... s_n)^(1/n) / sqrt(m)`, free parameters,
    /// column-scaled; larger is better.
    pub observability_index: f64,
    /// Singular values of the column-scaled free Jacobian, descending.
    pub singular_values: Vec<f64>,
}

/// Order in which columns are offered to the pivoted Gram–Schmidt: base and
/// tool first, so the joint terms that trade against them are the ones
/// fixed (the model keeps their nominal values, api.md "compensate").
fn offer_order(layout: &ParamLayout) -> Vec<usize> {
    let (mut first, mut rest): (Vec<usize>, Vec<usize>) = (0..layout.len()).partition(|&i| {
        matches!(
            layout.params[i].kind,
            ParamKind::Base(_) | ParamKind::Tool(_)
        )
    });
    first.append(&mut rest);
    first
}

/// Columns normalised to unit length (zero columns stay zero).
fn scale_columns(jac: &DMatrix<f64>) -> DMatrix<f64> {
    let mut s = jac.clone();
    for mut c in s.column_iter_mut() {
        let n = c.norm();
        if n > 0.0 {
            c /= n;
        }
    }
    s
}

/// Pivoted Gram–Schmidt in `order`: indices kept, indices redundant at `tol`.
fn select(scaled: &DMatrix<f64>, order: &[usize], tol: f64) -> (Vec<usize>, Vec<usize>) {
    let mut basis: Vec<DVector<f64>> = Vec::new();
    let (mut kept, mut dropped) = (Vec::new(), Vec::new());
    for &j in order {
        let mut v = scaled.column(j).into_owned();
        let norm = v.norm();
        // Twice is enough (Kahan–Parlett) for a stable projection.
        for _ in 0..2 {
            for b in &basis {
                let c = b.dot(&v);
                v.axpy(-c, b, 1.0);
            }
        }
        if norm > 0.0 && v.norm() > tol * norm {
            basis.push(v.normalize());
            kept.push(j);
        } else {
            dropped.push(j);
        }
    }
    kept.sort_unstable();
    (kept, dropped)
}

/// Unweighted stacked Jacobian (rotation rows scaled by
/// [`ROTATION_ROW_SCALE_MM`]) of `model` at the given joint vectors.
pub fn stacked_jacobian(
    layout: &ParamLayout,
    model: &CalibratedModel,
    joints_rad: &[Vec<f64>],
) -> Result<DMatrix<f64>, KinematicsError> {
    let rows = layout.instrument.rows();
    let mut jac = DMatrix::zeros(rows * joints_rad.len(), layout.len());
    for (k, q) in joints_rad.iter().enumerate() {
        let (_, j) = tool_pose_jacobian(layout, model, q)?;
        let mut block = j.rows(0, rows).into_owned();
        if rows == 6 {
            block.rows_mut(3, 3).scale_mut(ROTATION_ROW_SCALE_MM);
        }
        jac.rows_mut(k * rows, rows).copy_from(&block);
    }
    Ok(jac)
}

/// Parameters redundant for this robot and instrument whatever the poses.
pub fn structural_redundancies(
    layout: &ParamLayout,
    model: &CalibratedModel,
) -> Result<Vec<usize>, KinematicsError> {
    let all: Vec<usize> = (0..layout.len()).collect();
    structural_redundancies_among(layout, model, &all)
}

/// The structural redundancies when only `columns` are estimated and every
/// other parameter is known: a re-check with the hand–eye known determines
/// the last joint's zero, which in a full calibration trades against the
/// hand–eye's rotation. Returns a subset of `columns`.
pub fn structural_redundancies_among(
    layout: &ParamLayout,
    model: &CalibratedModel,
    columns: &[usize],
) -> Result<Vec<usize>, KinematicsError> {
    let mut rng = StdRng::seed_from_u64(REFERENCE_SEED);
    let poses: Vec<Vec<f64>> = (0..REFERENCE_POSES)
        .map(|_| {
            model
                .robot
                .joints
                .iter()
                .map(|j| rng.random_range(j.min_rad..=j.max_rad))
                .collect()
        })
        .collect();
    let jac = stacked_jacobian(layout, model, &poses)?;
    let order: Vec<usize> = offer_order(layout)
        .into_iter()
        .filter(|i| columns.contains(i))
        .collect();
    Ok(select(&scale_columns(&jac), &order, STRUCTURAL_TOL).1)
}

/// Per column of `cols` (unit columns), its distance from the span of the
/// other columns: `1 / sqrt(((CᵀC)⁻¹)_ii)`, from the SVD `C = U S Vᵀ` as
/// `((CᵀC)⁻¹)_ii = Σ_k V_ik² / s_k²`. Independent of the column order,
/// unlike the pivoted Gram–Schmidt that chose the columns.
fn excitation(cols: &DMatrix<f64>) -> Vec<f64> {
    let svd = cols.clone().svd(false, true);
    let Some(v_t) = svd.v_t else {
        return vec![0.0; cols.ncols()];
    };
    (0..cols.ncols())
        .map(|i| {
            let inv: f64 = svd
                .singular_values
                .iter()
                .enumerate()
                .map(|(k, s)| v_t[(k, i)].powi(2) / (s * s).max(f64::MIN_POSITIVE))
                .sum();
            1.0 / inv.sqrt()
        })
        .collect()
}

/// The identified parameters (`free`) that the campaign's poses determine
/// poorly: excitation below [`WEAK_EXCITATION`] on the *unweighted*
/// stacked Jacobian at `joints_rad`, i.e. on the poses' geometry alone.
/// The identification's whitened Jacobian also carries the measurement's
/// noise model (a camera measures depth far worse than the image plane),
/// which lowers nearly every column's excitation on a one-camera campaign
/// and would hide which joints the campaign failed to move.
pub fn poorly_determined(
    layout: &ParamLayout,
    model: &CalibratedModel,
    joints_rad: &[Vec<f64>],
    free: &[usize],
) -> Result<Vec<String>, KinematicsError> {
    let scaled = scale_columns(&stacked_jacobian(layout, model, joints_rad)?);
    let cols = DMatrix::from_fn(scaled.nrows(), free.len(), |r, c| scaled[(r, free[c])]);
    Ok(free
        .iter()
        .zip(excitation(&cols))
        .filter(|(_, e)| *e < WEAK_EXCITATION)
        .map(|(&i, _)| layout.params[i].name.clone())
        .collect())
}

/// Analyse a campaign's (weighted) Jacobian `jac` (all layout columns):
/// fix the structural redundancies, check that the campaign determines the
/// rest, and report rank, condition number and observability index.
pub fn analyse(
    layout: &ParamLayout,
    model: &CalibratedModel,
    jac: &DMatrix<f64>,
) -> Result<IdentifiabilityReport, IdentifiabilityError> {
    let structural = structural_redundancies(layout, model)?;
    let candidates: Vec<usize> = offer_order(layout)
        .into_iter()
        .filter(|i| !structural.contains(i))
        .collect();
    let poses = jac.nrows() / layout.instrument.rows();
    if jac.nrows() < candidates.len() {
        return Err(IdentifiabilityError::TooFewPoses {
            poses,
            rows: jac.nrows(),
            needed: candidates.len(),
        });
    }
    let scaled = scale_columns(jac);
    let (free, weak) = select(&scaled, &candidates, CAMPAIGN_TOL);
    if weak.len() > MAX_WEAK_FIXED {
        return Err(IdentifiabilityError::Unidentifiable {
            parameters: weak
                .iter()
                .map(|&i| layout.params[i].name.clone())
                .collect(),
        });
    }
    let full_sv = scaled.clone().svd(false, false).singular_values;
    let s_max = full_sv.max();
    let rank = full_sv
        .iter()
        .filter(|&&s| s > STRUCTURAL_TOL * s_max)
        .count();
    let free_cols = DMatrix::from_fn(jac.nrows(), free.len(), |r, c| scaled[(r, free[c])]);
    let excitation = excitation(&free_cols);
    let mut sv: Vec<f64> = free_cols
        .svd(false, false)
        .singular_values
        .iter()
        .copied()
        .collect();
    sv.sort_by(|a, b| b.total_cmp(a));
    let n = sv.len() as f64;
    let log_mean = sv
        .iter()
        .map(|s| s.max(f64::MIN_POSITIVE).ln())
        .sum::<f64>()
        / n;
    let mut fixed: Vec<usize> = structural.into_iter().chain(weak.iter().copied()).collect();
    fixed.sort_unstable();
    Ok(IdentifiabilityReport {
        rank,
        fixed: fixed
            .iter()
            .map(|&i| layout.params[i].name.clone())
            .collect(),
        weak: weak
            .iter()
            .map(|&i| layout.params[i].name.clone())
            .collect(),
        poorly_determined: free
            .iter()
            .zip(&excitation)
            .filter(|(_, &e)| e < WEAK_EXCITATION)
            .map(|(&i, _)| layout.params[i].name.clone())
            .collect(),
        free,
        excitation,
        condition_number: sv[0] / sv[sv.len() - 1],
        observability_index: log_mean.exp() / (jac.nrows() as f64).sqrt(),
        singular_values: sv,
    })
}

#[cfg(test)]
#[path = "identifiability_tests.rs"]
mod tests;
