//! The pose-level fit (method.md §6) of chosen parameters with the
//! kinematic prior (method.md §6.7 "Priors"): the maximum a posteriori fit
//! a tracker campaign's model ladder fits its rungs with
//! ([`super::position_ladder`]). Without a prior it is the
//! maximum-likelihood fit of [`super::identify::fit_parameters`], with the
//! covariance as [`super::identify::identify`] states it.

use nalgebra::{DMatrix, DVector};

use super::identify::{options as lm_options, IdentifyError, IdentifyOptions};
use super::measurement::Measurement;
use super::params::{CalibratedModel, Instrument, ParamLayout};
use super::pose_fit::PoseFit;
use super::prior::{KinematicPrior, PriorRows};
use super::uncertainty::embed_covariance;
use super::weights::PoseCovariances;
use crate::solver::{covariance_from_jacobian, solve, LeastSquaresProblem};

/// A fit of `free` with its (posterior) covariance.
#[derive(Debug, Clone)]
pub struct PoseMapFit {
    pub model: CalibratedModel,
    /// Layout indices fitted (sorted as given).
    pub free: Vec<usize>,
    /// Layout-sized covariance (internal units; zero where fixed): the
    /// posterior when a prior was given.
    pub covariance: DMatrix<f64>,
    pub std_devs: DVector<f64>,
    /// RMS of the whitened pose residuals (prior rows excluded).
    pub residual_rms: f64,
}

/// Fit `free` (layout indices) of `reference` to `data`, with `prior`
/// centred on `nominal`'s kinematics (same structure) when given. The
/// joint noise is `options`' (never estimated here).
pub fn fit_with_prior(
    reference: &CalibratedModel,
    nominal: &CalibratedModel,
    instrument: Instrument,
    data: &[Measurement],
    free: &[usize],
    prior: Option<&KinematicPrior>,
    options: IdentifyOptions,
) -> Result<PoseMapFit, IdentifyError> {
    if data.is_empty() {
        return Err(IdentifyError::NoPoses);
    }
    let layout = ParamLayout::new(&reference.robot, instrument);
    let w = PoseCovariances::new(&layout, reference, data)?
        .whitening(options.initial_joint_sigma_rad(), options.mode)?;
    let rows = prior.map(|p| PriorRows::new(p, &layout, free, reference, nominal));
    let problem = PoseFit {
        layout: &layout,
        reference,
        free,
        data,
        whitening: &w,
        prior: rows.as_ref(),
    };
    let report = solve(
        &problem,
        DVector::zeros(free.len()),
        &lm_options(options.mode),
    )?;
    let model = layout.apply(reference, &problem.full(&report.x));
    // The covariance from the Jacobian at the solution (x = 0 around it);
    // the prior rows' Jacobian does not depend on where they are centred.
    let at_solution = PoseFit {
        reference: &model,
        ..problem
    };
    let jac = at_solution
        .jacobian(&DVector::zeros(free.len()))
        .ok_or(IdentifyError::NoPoses)?;
    let dof = report.residuals.len().saturating_sub(free.len()).max(1) as f64;
    let cov = covariance_from_jacobian(&jac, report.cost / dof);
    let covariance = embed_covariance(layout.len(), free, &cov);
    let std_devs = covariance.diagonal().map(|v| v.max(0.0).sqrt());
    let data_rows = data.len() * instrument.rows();
    let data_cost = report.residuals.rows(0, data_rows).norm_squared();
    Ok(PoseMapFit {
        model,
        free: free.to_vec(),
        covariance,
        std_devs,
        residual_rms: (data_cost / data_rows.max(1) as f64).sqrt(),
    })
}
