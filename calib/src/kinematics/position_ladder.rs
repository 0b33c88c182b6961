//! The model ladder on measured positions (method.md §6.8 "Model selection
//! by held-out groups"): a tracker campaign chooses how much of the
//! kinematics it can carry the way a camera campaign does
//! ([`super::model_ladder`]), by how each rung predicts the tool positions
//! of configuration groups it was not fitted to. The rungs are fitted at
//! pose level ([`super::pose_map`], with the prior where the rung has one);
//! the `full_terms` rung is the non-geometric term selection
//! ([`super::term_selection`]) run on the training groups alone, so a term
//! is kept only when it predicts unseen configurations.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::config_groups::group_count;
use super::identify::{validate, IdentifyError, IdentifyOptions};
use super::measurement::Measurement;
use super::model_ladder::{folds, keep_best, rung_free, Rung, MIN_GROUPS};
use super::nongeometric::CandidateOptions;
use super::params::{CalibratedModel, Instrument, ParamLayout};
use super::pose_map::{fit_with_prior, PoseMapFit};
use super::prior::KinematicPrior;
use super::term_selection::{identify_with_terms, TermIdentification};
use super::term_validate::validate_with_terms;

/// What the ladder needs of a tracker campaign.
#[derive(Debug, Clone, Copy)]
pub struct PositionLadderInput<'a> {
    /// Nominal kinematics with the frames of a first fit (the pose-level
    /// "before"): every rung starts here and the prior is centred on it.
    pub nominal: &'a CalibratedModel,
    pub instrument: Instrument,
    pub data: &'a [Measurement],
    /// Configuration group of every measurement ([`super::config_groups`]).
    pub groups: &'a [usize],
    /// Layout indices the campaign determines (the identifiability's).
    pub campaign_free: &'a [usize],
    /// Layout indices that are not structurally redundant.
    pub identifiable: &'a [usize],
    pub prior: &'a KinematicPrior,
    /// The weights of the pose-level fit (joint noise as the job's).
    pub options: IdentifyOptions,
    /// The term candidates of the `full_terms` rung (`None`: no terms).
    pub candidates: Option<&'a CandidateOptions>,
}

/// A rung fitted on some measurements.
#[derive(Debug, Clone)]
pub enum PositionFit {
    Geometric(Box<PoseMapFit>),
    Terms(Box<TermIdentification>),
}

impl PositionFit {
    /// Measured minus predicted tool position (mm) at `data`.
    pub fn errors_mm(&self, data: &[Measurement]) -> Result<Vec<Vector3<f64>>, IdentifyError> {
        Ok(match self {
            PositionFit::Geometric(f) => validate(&f.model, data)?.1,
            PositionFit::Terms(t) => validate_with_terms(&t.model, &t.terms, data)?.1,
        })
    }

    /// Free parameters (kinematic and frames; and kept terms).
    pub fn parameters(&self) -> usize {
        match self {
            PositionFit::Geometric(f) => f.free.len(),
            PositionFit::Terms(t) => t.geometric.identifiability.free.len() + t.terms.terms.len(),
        }
    }
}

/// A rung's held-out prediction.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PositionRungScore {
    pub rung: Rung,
    pub parameters: usize,
    /// RMS length of every held-out position error (mm).
    pub heldout_rms_mm: f64,
    /// Held-out position errors (measurement index, mm).
    pub heldout_errors_mm: Vec<(usize, [f64; 3])>,
    /// Why the rung could not be scored (a fold failed), if it could not.
    pub failed: Option<String>,
}

/// The ladder's outcome.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PositionLadder {
    pub groups: usize,
    pub folds: usize,
    pub scores: Vec<PositionRungScore>,
    pub chosen: Rung,
    /// Why `chosen` was kept, in a sentence.
    pub reason: String,
}

impl PositionLadder {
    pub fn score(&self, rung: Rung) -> Option<&PositionRungScore> {
        self.scores.iter().find(|s| s.rung == rung)
    }
}

/// Fit one rung on `data` from `input.nominal` (the prior centred there).
pub fn fit_position_rung(
    rung: Rung,
    input: &PositionLadderInput,
    data: &[Measurement],
) -> Result<PositionFit, IdentifyError> {
    if rung == Rung::FullTerms {
        let candidates = input.candidates.ok_or(IdentifyError::NoPoses)?;
        let t = identify_with_terms(
            input.nominal,
            input.instrument,
            data,
            input.options,
            candidates,
        )?;
        return Ok(PositionFit::Terms(Box::new(t)));
    }
    let layout = ParamLayout::new(&input.nominal.robot, input.instrument);
    let free = rung_free(rung, &layout, input.campaign_free, input.identifiable);
    let prior = rung.has_prior().then_some(input.prior);
    let fit = fit_with_prior(
        input.nominal,
        input.nominal,
        input.instrument,
        data,
        &free,
        prior,
        input.options,
    )?;
    Ok(PositionFit::Geometric(Box::new(fit)))
}

/// Score one rung by held-out prediction over `folds`.
fn score(rung: Rung, input: &PositionLadderInput, folds: &[Vec<usize>]) -> PositionRungScore {
    let (mut sum, mut count, mut parameters) = (0.0, 0usize, 0);
    let mut errors = Vec::new();
    let mut failed = None;
    for fold in folds {
        let train: Vec<Measurement> = (0..input.data.len())
            .filter(|i| !fold.contains(i))
            .map(|i| input.data[i].clone())
            .collect();
        let held: Vec<Measurement> = fold.iter().map(|&i| input.data[i].clone()).collect();
        let predicted = fit_position_rung(rung, input, &train).and_then(|fit| {
            parameters = fit.parameters();
            fit.errors_mm(&held)
        });
        match predicted {
            Ok(e) => {
                for (&i, e) in fold.iter().zip(&e) {
                    sum += e.norm_squared();
                    count += 1;
                    errors.push((i, [e.x, e.y, e.z]));
                }
            }
            Err(e) => {
                failed = Some(e.to_string());
                break;
            }
        }
    }
    let heldout_rms_mm = if count > 0 && failed.is_none() {
        (sum / count as f64).sqrt()
    } else {
        f64::INFINITY
    };
    PositionRungScore {
        rung,
        parameters,
        heldout_rms_mm,
        heldout_errors_mm: errors,
        failed,
    }
}

/// One rung's held-out prediction over `input`'s groups.
pub fn heldout_position_score(rung: Rung, input: &PositionLadderInput) -> PositionRungScore {
    score(rung, input, &folds(input.groups))
}

/// Score every rung of `rungs` by held-out prediction of the tool positions
/// and keep the best ([`keep_best`]). `None` when the campaign has fewer
/// than [`MIN_GROUPS`] groups.
pub fn climb_positions(input: &PositionLadderInput, rungs: &[Rung]) -> Option<PositionLadder> {
    let groups = group_count(input.groups);
    if groups < MIN_GROUPS || rungs.is_empty() {
        return None;
    }
    let folds = folds(input.groups);
    let rungs: Vec<Rung> = rungs
        .iter()
        .copied()
        .filter(|&r| r != Rung::FullTerms || input.candidates.is_some())
        .collect();
    let scores: Vec<PositionRungScore> = rungs.iter().map(|&r| score(r, input, &folds)).collect();
    let errors: Vec<f64> = scores.iter().map(|s| s.heldout_rms_mm).collect();
    let best = &scores[keep_best(&errors)?];
    let reason = match scores.iter().find(|s| s.rung == Rung::HandEye) {
        Some(h) if best.rung != Rung::HandEye => format!(
            "{} predicts the held-out configurations' positions best: {:.4} mm RMS against {:.4} mm for nominal kinematics ({} groups, {} folds)",
            best.rung.as_str(),
            best.heldout_rms_mm,
            h.heldout_rms_mm,
            groups,
            folds.len()
        ),
        _ => format!(
            "no identified kinematics predicts the held-out configurations' positions better than the nominal model ({:.4} mm RMS; {} groups, {} folds): the kinematics stay nominal",
            best.heldout_rms_mm,
            groups,
            folds.len()
        ),
    };
    Some(PositionLadder {
        groups,
        folds: folds.len(),
        chosen: best.rung,
        reason,
        scores,
    })
}

#[cfg(test)]
#[path = "position_ladder_tests.rs"]
mod tests;
