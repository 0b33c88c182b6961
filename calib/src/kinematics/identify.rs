//! Kinematic identification by Levenberg–Marquardt (method.md §6) and the
//! before/after accuracy at validation poses (method.md §7).
//!
//! Stages: (1) "before": nominal kinematics, only the world-to-base and
//! flange-to-tool transforms fitted; (2) identifiability analysis at that
//! model (structural redundancies fixed, the campaign checked);
//! (3) every free parameter fitted. Residuals are measured minus predicted
//! tool poses (6 rows: mm and small-angle rad) or positions (3 rows).
//! [`IdentifyMode::Paper`] is the paper's eq. 18 with Marquardt's schedule on
//! the plain residual; [`IdentifyMode::Weighted`] (the default, **beyond**)
//! whitens each pose's residual with its covariance from the camera step and
//! uses column scaling with gain-ratio damping.

use nalgebra::{DMatrix, DVector, Vector3};

use super::identifiability::{
    analyse, poorly_determined, IdentifiabilityError, IdentifiabilityReport,
};
pub use super::identify_error::IdentifyError;
pub use super::identify_options::{IdentifyMode, IdentifyOptions, JointNoise};
pub use super::measurement::{
    Measurement, Observed, DEFAULT_POSITION_SIGMA_MM, DEFAULT_ROTATION_SIGMA_RAD,
};
use super::params::{CalibratedModel, Instrument, ParamKind, ParamLayout};
use super::pose_fit::{full_vector, unweighted_residuals, PoseFit};
use super::weights::{estimate_joint_sigma, PoseCovariances};
use crate::solver::{solve, LeastSquaresProblem, LmOptions, Termination};
use crate::stats::AccuracyStats;

/// Iteration cap of the default fit: ill-conditioned tracker campaigns
/// (the UR5 grid, condition number ~6e4) creep for ~300 iterations before
/// the cost settles; each costs milliseconds.
const MAX_ITERATIONS: usize = 1000;

/// Rounds of (fit, re-estimate the joint noise) with [`JointNoise::Estimate`].
const JOINT_NOISE_ROUNDS: usize = 2;

/// The identified model with its uncertainty.
#[derive(Debug, Clone)]
pub struct Identification {
    /// Nominal kinematics with only world-to-base and tool fitted.
    pub before: CalibratedModel,
    pub model: CalibratedModel,
    pub layout: ParamLayout,
    /// `model = layout.apply(before, correction)`; zero at fixed parameters.
    pub correction: DVector<f64>,
    /// Standard deviation of every parameter (zero where fixed).
    pub std_devs: DVector<f64>,
    /// Full parameter covariance (layout order, internal units; zero rows
    /// and columns where fixed): what predicted uncertainties propagate
    /// (method.md §6, [`super::uncertainty`]).
    pub covariance: DMatrix<f64>,
    pub identifiability: IdentifiabilityReport,
    /// RMS of the (weighted) calibration residual.
    pub residual_rms: f64,
    /// Joint noise used in the weights (rad): given or estimated.
    pub joint_sigma_rad: f64,
    pub iterations: usize,
    pub termination: Termination,
}

pub(super) fn options(mode: IdentifyMode) -> LmOptions {
    match mode {
        IdentifyMode::Paper => LmOptions::paper(),
        IdentifyMode::Weighted => LmOptions {
            max_iterations: MAX_ITERATIONS,
            ..LmOptions::default()
        },
    }
}

/// Fit only the parameters selected by `which` (layout indices) of
/// `reference` to `data` (joint noise as given, never estimated); returns
/// the fitted model and the solver's report.
pub fn fit_parameters(
    reference: &CalibratedModel,
    instrument: Instrument,
    data: &[Measurement],
    which: &[usize],
    options: IdentifyOptions,
) -> Result<(CalibratedModel, crate::solver::LmReport), IdentifyError> {
    if data.is_empty() {
        return Err(IdentifyError::NoPoses);
    }
    let layout = ParamLayout::new(&reference.robot, instrument);
    let w = PoseCovariances::new(&layout, reference, data)?
        .whitening(options.initial_joint_sigma_rad(), options.mode)?;
    let problem = PoseFit {
        layout: &layout,
        reference,
        free: which,
        data,
        whitening: &w,
        prior: None,
    };
    let report = solve(
        &problem,
        DVector::zeros(which.len()),
        &self::options(options.mode),
    )?;
    let model = layout.apply(reference, &problem.full(&report.x));
    Ok((model, report))
}

/// Indices of the world-to-base (and, with `tool`, flange-to-tool) values.
pub fn frame_indices(layout: &ParamLayout, tool: bool) -> Vec<usize> {
    (0..layout.len())
        .filter(|&i| match layout.params[i].kind {
            ParamKind::Base(_) => true,
            ParamKind::Tool(_) => tool,
            _ => false,
        })
        .collect()
}

/// Identify kinematics, base and tool from `reference` (nominal kinematics
/// with a rough world-to-base and tool, see [`super::initial::initial_world_to_base`]).
pub fn identify(
    reference: &CalibratedModel,
    instrument: Instrument,
    cal: &[Measurement],
    options: IdentifyOptions,
) -> Result<Identification, IdentifyError> {
    let layout = ParamLayout::new(&reference.robot, instrument);
    let mut joint_sigma_rad = options.initial_joint_sigma_rad();
    let (before, _) = fit_parameters(
        reference,
        instrument,
        cal,
        &frame_indices(&layout, true),
        IdentifyOptions {
            mode: IdentifyMode::Weighted,
            joint_noise: JointNoise::Known {
                sigma_rad: joint_sigma_rad,
            },
        },
    )?;
    let covariances = PoseCovariances::new(&layout, &before, cal)?;
    let mut w = covariances.whitening(joint_sigma_rad, options.mode)?;
    let all: Vec<usize> = (0..layout.len()).collect();
    let probe = PoseFit {
        layout: &layout,
        reference: &before,
        free: &all,
        data: cal,
        whitening: &w,
        prior: None,
    };
    let (_, jac_all) = probe
        .evaluate(&before, true)
        .ok_or(IdentifyError::NoPoses)?;
    let mut identifiability = analyse(&layout, &before, &jac_all)?;
    let joints: Vec<Vec<f64>> = cal.iter().map(|m| m.joints_rad.clone()).collect();
    identifiability.poorly_determined =
        poorly_determined(&layout, &before, &joints, &identifiability.free)
            .map_err(IdentifiabilityError::from)?;
    let free = identifiability.free.clone();
    let fit = |w: &[DMatrix<f64>], x0: DVector<f64>| {
        let problem = PoseFit {
            layout: &layout,
            reference: &before,
            free: &free,
            data: cal,
            whitening: w,
            prior: None,
        };
        solve(&problem, x0, &self::options(options.mode))
    };
    let mut report = fit(&w, DVector::zeros(free.len()))?;
    let estimate =
        options.joint_noise == JointNoise::Estimate && options.mode != IdentifyMode::Paper;
    for _ in 0..if estimate { JOINT_NOISE_ROUNDS } else { 0 } {
        let model = layout.apply(&before, &full_vector(&layout, &free, &report.x));
        let residuals = unweighted_residuals(&layout, &model, cal)?;
        let dof = residuals.len() * instrument.rows() - free.len();
        joint_sigma_rad =
            estimate_joint_sigma(&covariances, &residuals, dof).ok_or(IdentifyError::NoPoses)?;
        w = covariances.whitening(joint_sigma_rad, options.mode)?;
        report = fit(&w, report.x.clone())?;
    }
    let correction = full_vector(&layout, &free, &report.x);
    let model = layout.apply(&before, &correction);
    // Covariance from the Jacobian at the solution itself (x = 0 around it).
    let at_solution = PoseFit {
        layout: &layout,
        reference: &model,
        free: &free,
        data: cal,
        whitening: &w,
        prior: None,
    };
    let jac = at_solution
        .jacobian(&DVector::zeros(free.len()))
        .ok_or(IdentifyError::NoPoses)?;
    let dof = (report.residuals.len() - free.len()).max(1) as f64;
    let cov = crate::solver::covariance_from_jacobian(&jac, report.cost / dof);
    let covariance = super::uncertainty::embed_covariance(layout.len(), &free, &cov);
    let std_devs = covariance.diagonal().map(|v| v.max(0.0).sqrt());
    Ok(Identification {
        before,
        model,
        correction,
        std_devs,
        covariance,
        identifiability,
        residual_rms: (report.cost / report.residuals.len() as f64).sqrt(),
        joint_sigma_rad,
        iterations: report.iterations,
        termination: report.termination,
        layout,
    })
}

/// Position errors (measured minus predicted tool position, world frame)
/// of `model` at `data`, and their statistics (method.md §7).
pub fn validate(
    model: &CalibratedModel,
    data: &[Measurement],
) -> Result<(AccuracyStats, Vec<Vector3<f64>>), IdentifyError> {
    let errors = data
        .iter()
        .enumerate()
        .map(|(pose, m)| {
            let pred = model
                .world_to_tool(&m.joints_rad)
                .map_err(|source| IdentifyError::Pose { pose, source })?;
            Ok(m.observed.position_mm() - pred.translation.vector)
        })
        .collect::<Result<Vec<_>, IdentifyError>>()?;
    Ok((AccuracyStats::from_errors(&errors), errors))
}

/// Deterministic hold-out split when a campaign has no `val` poses: every
/// k-th pose (k = round(1 / fraction)) goes to validation.
pub fn holdout_split(count: usize, fraction: f64) -> (Vec<usize>, Vec<usize>) {
    if !(fraction > 0.0 && fraction < 1.0) {
        return ((0..count).collect(), Vec::new());
    }
    let every = (1.0 / fraction).round().max(2.0) as usize;
    (0..count).partition(|i| (i + 1) % every != 0)
}

#[cfg(test)]
#[path = "identify_tests.rs"]
mod tests;
