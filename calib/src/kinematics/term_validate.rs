//! Accuracy of a model with non-geometric terms at validation poses
//! (method.md §7, issue 19), and the world-to-base refit of a validation
//! series measured from another instrument station.

use nalgebra::{DVector, Vector3};

use super::identify::{frame_indices, IdentifyError, IdentifyOptions};
use super::measurement::Measurement;
use super::nongeometric::NonGeometric;
use super::params::{CalibratedModel, Instrument, ParamLayout};
use super::term_fit::TermFit;
use super::weights::PoseCovariances;
use crate::solver::{solve, LmOptions};
use crate::stats::AccuracyStats;

/// Position errors (measured minus predicted) of `model` with `terms`.
pub fn validate_with_terms(
    model: &CalibratedModel,
    terms: &NonGeometric,
    data: &[Measurement],
) -> Result<(AccuracyStats, Vec<Vector3<f64>>), IdentifyError> {
    let errors = data
        .iter()
        .enumerate()
        .map(|(pose, m)| {
            let pred = terms
                .world_to_tool(model, &m.joints_rad)
                .map_err(|source| IdentifyError::Pose { pose, source })?;
            Ok(m.observed.position_mm() - pred.translation.vector)
        })
        .collect::<Result<Vec<_>, IdentifyError>>()?;
    Ok((AccuracyStats::from_errors(&errors), errors))
}

/// Refit only the world-to-base transform of `model` (terms held) to `data`.
pub fn refit_base_with_terms(
    model: &CalibratedModel,
    terms: &NonGeometric,
    instrument: Instrument,
    data: &[Measurement],
    options: IdentifyOptions,
) -> Result<CalibratedModel, IdentifyError> {
    if data.is_empty() {
        return Err(IdentifyError::NoPoses);
    }
    let layout = ParamLayout::new(&model.robot, instrument);
    let free = frame_indices(&layout, false);
    let w = PoseCovariances::new(&layout, model, data)?
        .whitening(options.initial_joint_sigma_rad(), options.mode)?;
    let fit = TermFit {
        layout: &layout,
        reference: model,
        free: &free,
        terms,
        free_terms: &[],
        data,
        whitening: &w,
    };
    let sol = solve(&fit, DVector::zeros(free.len()), &LmOptions::default())?;
    Ok(fit.split(&sol.x).0)
}
