//! A quick re-check of a calibrated set (issue 17): a few measured poses
//! judged against what the set predicts, with the set's own uncertainty.
//!
//! The test (method.md §7 residuals, §6 covariance): stack every pose's
//! residual `r` (measured minus predicted tool pose, 6 rows, or position,
//! 3 rows). If nothing changed, `r` is zero-mean with covariance
//! `C = J Σ Jᵀ + R`: `J` the identification Jacobian at the check's joints
//! (every pose at once, so the parameter error is shared across poses),
//! `Σ` the set's parameter covariance, `R` block-diagonal, each pose's
//! measurement covariance plus its joint noise ([`PoseCovariances`]). Then
//! `T = rᵀ C⁻¹ r` is chi-square with `n·rows` degrees of freedom, and the
//! check **passes** when its upper-tail p-value is at least
//! [`SIGNIFICANCE`] (a false alarm in 1 % of checks of an unchanged robot).
//!
//! With non-geometric terms kept (issue 19) the check's joints are
//! deflected by them before the chain (the terms held at their values),
//! and each term adds a column `T_k` shared by every pose (the `dθ_i`
//! column of its joint times its basis `f_k(q)`): `J Σ Jᵀ` becomes
//! `[J T] Σ_full [J T]ᵀ`, with the terms' covariance with the geometry when
//! the set stores it (image-level sets), else each term independent with
//! its σ. The terms are suspects too: a gear or a joint's stiffness that
//! changed is named like a parameter.
//!
//! Otherwise the world-to-base transform alone is re-fitted (the board,
//! or the tracker, or the robot's base moved), and every identified
//! kinematic parameter is ranked by how much of the whitened residual it
//! explains beyond the base (the chi-square drop of adding it alone,
//! linearised). The verdict is **base moved** when the re-fitted residual
//! passes the same test with `n·rows − 6` degrees of freedom and no single
//! parameter explains significantly more (its drop, chi-square with 1
//! degree of freedom, under `SIGNIFICANCE / parameters tried`); else it is
//! **drift**, naming the first-ranked parameters as the suspects.

use nalgebra::{DMatrix, DVector};

use super::identify::{
    fit_parameters, IdentifyError, IdentifyMode, IdentifyOptions, JointNoise, Measurement,
};
use super::jacobian::tool_pose_jacobian;
use super::nongeometric::TermKind;
use super::params::{CalibratedModel, Instrument, ParamKind, ParamLayout, PARAMS_PER_JOINT};
use super::pose_fit::unweighted_residuals;
use super::term_model::TermModel;
use super::weights::PoseCovariances;
use crate::chi_square::chi_square_p_value;

/// The test's level: a re-check of an unchanged robot fails this often.
pub const SIGNIFICANCE: f64 = 0.01;
/// Fewest poses a re-check takes (the base re-fit needs more rows than 6).
pub const MIN_CHECK_POSES: usize = 3;
/// Suspects named at most.
pub const MAX_SUSPECTS: usize = 3;
/// World-to-base components re-fitted for "base moved".
const BASE_DOF: usize = 6;

#[derive(Debug, thiserror::Error)]
pub enum RecheckError {
    #[error("a re-check needs at least {MIN_CHECK_POSES} measured poses, got {0}")]
    TooFewPoses(usize),
    #[error("the set's covariance is {got}x{got}, its layout has {expected} parameters")]
    CovarianceShape { expected: usize, got: usize },
    #[error("the predicted covariance of the residuals is not positive definite")]
    NotPositiveDefinite,
    #[error(transparent)]
    Identify(#[from] IdentifyError),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    Pass,
    Drift,
    BaseMoved,
}

/// What a suspect is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SuspectKind {
    /// A parameter of the layout.
    Parameter(ParamKind),
    /// A kept non-geometric term (its value in the term's unit).
    Term(TermKind),
}

/// A parameter or kept term that may have changed.
#[derive(Debug, Clone, PartialEq)]
pub struct Suspect {
    /// Its name in the layout (`dtheta_2`, `a_3`, ...) or the term's
    /// (`periodic_4.cos2`, ...).
    pub name: String,
    pub kind: SuspectKind,
    /// The change that explains the residual best (mm or rad, or the
    /// term's unit).
    pub change: f64,
    /// `change` over the set's standard deviation of the parameter.
    pub change_sigmas: f64,
    /// How much of the chi-square statistic it explains beyond the base.
    pub chi2_drop: f64,
}

/// What the re-check found.
#[derive(Debug, Clone, PartialEq)]
pub struct Recheck {
    pub verdict: Verdict,
    /// Mean length of the position residuals (mm).
    pub mean_mm: f64,
    /// What the set predicts for it: the mean over poses of the RMS length
    /// of the position residual, `sqrt(trace)` of its 3x3 block of `C`.
    pub expected_mean_mm: f64,
    /// `rᵀ C⁻¹ r` and its degrees of freedom.
    pub chi2: f64,
    pub dof: usize,
    pub p_value: f64,
    /// The same after re-fitting the world-to-base transform alone.
    pub base_p_value: f64,
    /// The re-fitted world-to-base transform (the model's otherwise).
    pub refitted_world_to_base: crate::geometry::Pose,
    /// Most likely changed parameters, most likely first (drift only).
    pub suspects: Vec<Suspect>,
}

/// What is checked: the set's model (with its kept terms) and covariance,
/// the joint noise, and the check's measurements (commanded joints).
pub struct RecheckInput<'a> {
    pub model: &'a TermModel,
    pub instrument: Instrument,
    /// The set's parameter covariance (layout order, internal units).
    pub covariance: &'a DMatrix<f64>,
    pub joint_sigma_rad: f64,
    pub data: &'a [Measurement],
}

/// The stacked residual, its prediction covariance's Cholesky factor and
/// the Jacobian at `model`.
struct Whitened {
    /// `L⁻¹ r`.
    residual: DVector<f64>,
    /// `L⁻¹ J` (every layout column).
    jacobian: DMatrix<f64>,
    /// `L⁻¹ T` (every kept term's column).
    term_jacobian: DMatrix<f64>,
    /// Mean position residual length, and its prediction.
    mean_mm: f64,
    expected_mean_mm: f64,
}

/// The check's measurements as the geometric chain sees them, and each
/// pose's term bases `f_k(q)` at its commanded joints.
struct Deflected {
    data: Vec<Measurement>,
    bases: Vec<Vec<f64>>,
}

impl Deflected {
    fn new(model: &TermModel, data: &[Measurement]) -> Result<Self, RecheckError> {
        let mut out = Self {
            data: Vec::with_capacity(data.len()),
            bases: Vec::with_capacity(data.len()),
        };
        for (pose, m) in data.iter().enumerate() {
            let at = |source| IdentifyError::Pose { pose, source };
            out.data.push(Measurement {
                joints_rad: model.deflected(&m.joints_rad).map_err(at)?,
                observed: m.observed.clone(),
            });
            out.bases
                .push(model.terms.basis(&m.joints_rad).map_err(at)?);
        }
        Ok(out)
    }
}

/// `T`: each kept term's column, its joint's `dθ` column of the stacked
/// Jacobian `jac` times its basis at each pose (module doc).
fn term_columns(terms: &TermModel, d: &Deflected, jac: &DMatrix<f64>, rows: usize) -> DMatrix<f64> {
    let mut t_cols = DMatrix::zeros(jac.nrows(), terms.terms.terms.len());
    for (t, term) in terms.terms.terms.iter().enumerate() {
        let column = jac.column(term.joint() * PARAMS_PER_JOINT);
        for (k, basis) in d.bases.iter().enumerate() {
            t_cols
                .view_mut((k * rows, t), (rows, 1))
                .copy_from(&(column.rows(k * rows, rows) * basis[t]));
        }
    }
    t_cols
}

/// `[J T] Σ_full [J T]ᵀ` (module doc): the set's covariance `geometric`
/// and the terms' (stored with the geometry, or independent with their σ).
fn predicted_covariance(
    terms: &TermModel,
    geometric: &DMatrix<f64>,
    jac: &DMatrix<f64>,
    t_cols: &DMatrix<f64>,
) -> DMatrix<f64> {
    let mut c = jac * geometric * jac.transpose();
    match &terms.covariance {
        Some(tc) => {
            let cross = jac * &tc.cross * t_cols.transpose();
            c += &cross + cross.transpose() + t_cols * &tc.terms * t_cols.transpose();
        }
        None => {
            for (t, sd) in terms.term_std_devs.iter().enumerate() {
                let v = t_cols.column(t) * *sd;
                c += &v * v.transpose();
            }
        }
    }
    c
}

fn whiten(
    input: &RecheckInput,
    model: &CalibratedModel,
    d: &Deflected,
) -> Result<Whitened, RecheckError> {
    let layout = ParamLayout::new(&model.robot, input.instrument);
    let rows = input.instrument.rows();
    let data = &d.data;
    let n = data.len();
    let residuals = unweighted_residuals(&layout, model, data)?;
    let covariances = PoseCovariances::new(&layout, model, data)?;
    let mut r = DVector::zeros(n * rows);
    let mut jac = DMatrix::zeros(n * rows, layout.len());
    let mut c = DMatrix::zeros(n * rows, n * rows);
    for (k, m) in data.iter().enumerate() {
        r.rows_mut(k * rows, rows).copy_from(&residuals[k]);
        let (_, j) = tool_pose_jacobian(&layout, model, &m.joints_rad)
            .map_err(|source| IdentifyError::Pose { pose: k, source })?;
        jac.rows_mut(k * rows, rows).copy_from(&j.rows(0, rows));
        c.view_mut((k * rows, k * rows), (rows, rows))
            .copy_from(&covariances.covariance(k, input.joint_sigma_rad));
    }
    let t_cols = term_columns(input.model, d, &jac, rows);
    c += predicted_covariance(input.model, input.covariance, &jac, &t_cols);
    let mean_mm = residuals.iter().map(|e| e.rows(0, 3).norm()).sum::<f64>() / n as f64;
    let expected_mean_mm = (0..n)
        .map(|k| {
            let block = c.view((k * rows, k * rows), (3, 3));
            block.trace().max(0.0).sqrt()
        })
        .sum::<f64>()
        / n as f64;
    let l = c.cholesky().ok_or(RecheckError::NotPositiveDefinite)?.l();
    let residual = l
        .solve_lower_triangular(&r)
        .ok_or(RecheckError::NotPositiveDefinite)?;
    let jacobian = l
        .solve_lower_triangular(&jac)
        .ok_or(RecheckError::NotPositiveDefinite)?;
    let term_jacobian = l
        .solve_lower_triangular(&t_cols)
        .ok_or(RecheckError::NotPositiveDefinite)?;
    Ok(Whitened {
        residual,
        jacobian,
        term_jacobian,
        mean_mm,
        expected_mean_mm,
    })
}

/// Layout indices of the world-to-base components.
fn base_indices(layout: &ParamLayout) -> Vec<usize> {
    (0..layout.len())
        .filter(|&i| matches!(layout.params[i].kind, ParamKind::Base(_)))
        .collect()
}

/// `v` with its projection on the columns of `b` removed (least squares).
fn project_out(b: &DMatrix<f64>, v: &DVector<f64>) -> DVector<f64> {
    let normal = b.transpose() * b;
    match normal.cholesky() {
        Some(chol) => v - b * chol.solve(&(b.transpose() * v)),
        None => v.clone(),
    }
}

/// Kinematic parameters and kept terms ranked by the chi-square drop each
/// explains beyond the base, at the base-refitted model's whitened
/// residual, and how many were tried.
fn rank_suspects(
    layout: &ParamLayout,
    w: &Whitened,
    covariance: &DMatrix<f64>,
    terms: &TermModel,
) -> (Vec<Suspect>, usize) {
    let base = base_indices(layout);
    let b = DMatrix::from_fn(w.jacobian.nrows(), base.len(), |r, c| {
        w.jacobian[(r, base[c])]
    });
    let residual = project_out(&b, &w.residual);
    // The residual is measured minus predicted; the prediction moves by
    // a·δ along the whitened column a, so δ = a·w / a·a.
    let candidate = |name: String, kind: SuspectKind, column: DVector<f64>, sd: f64| {
        let a = project_out(&b, &column);
        let aa = a.dot(&a);
        (aa > 0.0).then(|| {
            let aw = a.dot(&residual);
            let change = aw / aa;
            Suspect {
                name,
                kind,
                change,
                change_sigmas: change / sd,
                chi2_drop: aw * aw / aa,
            }
        })
    };
    let parameters = (0..layout.len())
        .filter(|&i| layout.params[i].joint.is_some() && covariance[(i, i)] > 0.0)
        .filter_map(|i| {
            let p = &layout.params[i];
            let column = w.jacobian.column(i).into_owned();
            candidate(
                p.name.clone(),
                SuspectKind::Parameter(p.kind),
                column,
                covariance[(i, i)].sqrt(),
            )
        });
    let kept_terms = terms
        .terms
        .terms
        .iter()
        .zip(&terms.term_std_devs)
        .enumerate()
        .filter(|(_, (_, sd))| **sd > 0.0)
        .filter_map(|(t, (term, sd))| {
            let column = w.term_jacobian.column(t).into_owned();
            candidate(term.name(), SuspectKind::Term(*term), column, *sd)
        });
    let mut suspects: Vec<Suspect> = parameters.chain(kept_terms).collect();
    let tried = suspects.len();
    suspects.sort_by(|x, y| y.chi2_drop.total_cmp(&x.chi2_drop));
    suspects.truncate(MAX_SUSPECTS);
    (suspects, tried)
}

/// Judges the check's measurements against the set (see the module doc).
pub fn recheck(input: &RecheckInput) -> Result<Recheck, RecheckError> {
    let n = input.data.len();
    if n < MIN_CHECK_POSES {
        return Err(RecheckError::TooFewPoses(n));
    }
    let layout = ParamLayout::new(&input.model.model.robot, input.instrument);
    let size = input.covariance.nrows();
    if size != layout.len() || input.covariance.ncols() != size {
        return Err(RecheckError::CovarianceShape {
            expected: layout.len(),
            got: size,
        });
    }
    let dof = n * input.instrument.rows();
    let deflected = Deflected::new(input.model, input.data)?;
    let at_set = whiten(input, &input.model.model, &deflected)?;
    let chi2 = at_set.residual.norm_squared();
    let p_value = chi_square_p_value(chi2, dof).ok_or(RecheckError::NotPositiveDefinite)?;
    let options = IdentifyOptions {
        mode: IdentifyMode::Weighted,
        joint_noise: JointNoise::Known {
            sigma_rad: input.joint_sigma_rad,
        },
    };
    let (refitted, _) = fit_parameters(
        &input.model.model,
        input.instrument,
        &deflected.data,
        &base_indices(&layout),
        options,
    )?;
    let at_base = whiten(input, &refitted, &deflected)?;
    let base_p_value = chi_square_p_value(at_base.residual.norm_squared(), dof - BASE_DOF)
        .ok_or(RecheckError::NotPositiveDefinite)?;
    let (suspects, tried) = rank_suspects(&layout, &at_base, input.covariance, input.model);
    // Nested models: does one kinematic parameter on top of the base
    // explain significantly more (a 1-dof chi-square drop, at the level
    // shared among the parameters tried, Bonferroni)?
    let kinematic = suspects.first().is_some_and(|s| {
        chi_square_p_value(s.chi2_drop, 1).is_some_and(|p| p < SIGNIFICANCE / tried.max(1) as f64)
    });
    let verdict = if p_value >= SIGNIFICANCE {
        Verdict::Pass
    } else if base_p_value >= SIGNIFICANCE && !kinematic {
        Verdict::BaseMoved
    } else {
        Verdict::Drift
    };
    let suspects = match verdict {
        Verdict::Drift => suspects,
        _ => Vec::new(),
    };
    Ok(Recheck {
        verdict,
        mean_mm: at_set.mean_mm,
        expected_mean_mm: at_set.expected_mean_mm,
        chi2,
        dof,
        p_value,
        base_p_value,
        refitted_world_to_base: refitted.world_to_base,
        suspects,
    })
}

#[cfg(test)]
#[path = "recheck_tests.rs"]
mod tests;
