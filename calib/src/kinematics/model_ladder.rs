//! The model ladder (method.md §6.8 "Model selection by held-out groups"): a
//! campaign decides how much of the kinematics it can carry by how each
//! candidate model predicts arm configurations it was not fitted to. Every
//! rung is fitted on the image points of all configuration groups but one
//! (or a fold of groups) and predicts the held-out group's image points
//! through its kinematics, hand–eye, board pose and intrinsics; the rung
//! with the smallest pooled held-out reprojection error is kept.
//!
//! A residual on the fitted poses cannot tell a model that learned the arm
//! from one that bent weakly determined links to the noise of a few
//! configurations: only held-out configurations can (the real campaign of
//! six shoulder/elbow configurations that motivated this predicted unseen
//! configurations worse than the nominal model).

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::identify::{validate, Measurement};
use super::identify_error::IdentifyError;
use super::image_pose::{ImageNoise, ImagePose};
use super::joint_refine::{joint_refine, joint_refine_with_prior, JointRefinement};
use super::ladder_terms::fit_on;
pub use super::ladder_terms::fit_terms_rung;
use super::nongeometric::CandidateOptions;
use super::params::{CalibratedModel, ParamKind, ParamLayout};
use super::prior::{KinematicPrior, PriorRows};
use super::term_validate::validate_with_terms;
use crate::camera::model::Intrinsics;

/// At most this many folds: with more groups (a well-spread campaign, every
/// pose its own configuration) whole groups are dealt into this many folds.
pub const MAX_FOLDS: usize = 6;
/// Fewest groups for a held-out comparison: with fewer, every fold would
/// leave too little to fit, and the ladder keeps today's full model.
pub const MIN_GROUPS: usize = 3;
/// A richer rung is kept only when it predicts the held-out points better
/// than the simpler one by more than this fraction: a tie goes to the
/// model with fewer free directions.
pub const RICHER_MARGIN: f64 = 0.01;

/// One candidate model, from the simplest up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Rung {
    /// Nominal kinematics; only the board (`target_to_base`), the hand–eye
    /// and the intrinsics fitted.
    HandEye,
    /// + the joint zeros the campaign determines.
    JointOffsets,
    /// + every joint zero, held towards nominal by the prior.
    JointOffsetsPrior,
    /// + every parameter the campaign determines (maximum likelihood).
    Full,
    /// + every structurally identifiable parameter, held towards nominal
    ///   by the prior (maximum a posteriori).
    FullPrior,
    /// `Full` + the non-geometric terms (compliance, gear harmonics) the
    /// term selection keeps on the fitted poses (method.md §6.6).
    FullTerms,
}

impl Rung {
    pub const ALL: [Rung; 5] = [
        Rung::HandEye,
        Rung::JointOffsets,
        Rung::JointOffsetsPrior,
        Rung::Full,
        Rung::FullPrior,
    ];

    /// The geometric rungs, then the non-geometric terms on the richest.
    pub const WITH_TERMS: [Rung; 6] = [
        Rung::HandEye,
        Rung::JointOffsets,
        Rung::JointOffsetsPrior,
        Rung::Full,
        Rung::FullPrior,
        Rung::FullTerms,
    ];

    pub fn as_str(self) -> &'static str {
        match self {
            Rung::HandEye => "hand_eye",
            Rung::JointOffsets => "joint_offsets",
            Rung::JointOffsetsPrior => "joint_offsets_prior",
            Rung::Full => "full",
            Rung::FullPrior => "full_prior",
            Rung::FullTerms => "full_terms",
        }
    }

    /// Whether the rung's kinematic parameters carry the prior.
    pub fn has_prior(self) -> bool {
        matches!(self, Rung::JointOffsetsPrior | Rung::FullPrior)
    }

    /// A short description for reports.
    pub fn describe(self) -> &'static str {
        match self {
            Rung::HandEye => "nominal kinematics; board, hand–eye and camera fitted",
            Rung::JointOffsets => "+ the joint zeros the campaign determines",
            Rung::JointOffsetsPrior => "+ every joint zero, with its prior",
            Rung::Full => "+ every parameter the campaign determines",
            Rung::FullPrior => "+ every identifiable parameter, with priors",
            Rung::FullTerms => "full + the non-geometric terms the selection keeps",
        }
    }
}

/// What the ladder needs of a campaign.
#[derive(Debug, Clone, Copy)]
pub struct LadderInput<'a> {
    /// Nominal kinematics with the board and hand–eye of a first fit: every
    /// rung starts here and the prior is centred on its kinematics.
    pub nominal: &'a CalibratedModel,
    pub intrinsics: &'a Intrinsics,
    pub poses: &'a [ImagePose],
    /// Configuration group of every pose ([`super::config_groups`]).
    pub groups: &'a [usize],
    /// Each pose's measured camera pose (for errors in mm), where known.
    pub measured: &'a [Option<Measurement>],
    /// Layout indices the campaign determines (the identifiability's).
    pub campaign_free: &'a [usize],
    /// Layout indices that are not structurally redundant.
    pub identifiable: &'a [usize],
    pub prior: &'a KinematicPrior,
    /// Noise, with the joint noise known (estimated once beforehand).
    pub noise: ImageNoise,
    pub hold_intrinsics: bool,
    /// Term candidates of the `full_terms` rung (`None`: no terms rung);
    /// the rung selects them from the training poses' `measured` poses.
    pub candidates: Option<&'a CandidateOptions>,
}

/// A rung's held-out prediction.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RungScore {
    pub rung: Rung,
    /// Free parameters of the rung (kinematic, board and hand–eye).
    pub parameters: usize,
    /// RMS of every held-out image point's reprojection error (px).
    pub heldout_rms_px: f64,
    /// Held-out camera position errors (pose index, mm), where the pose's
    /// camera was measured.
    pub heldout_errors_mm: Vec<(usize, [f64; 3])>,
    /// Why the rung could not be scored (a fold failed), if it could not.
    pub failed: Option<String>,
}

/// The ladder's outcome.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Ladder {
    pub groups: usize,
    pub folds: usize,
    pub scores: Vec<RungScore>,
    pub chosen: Rung,
    /// Why `chosen` was kept, in a sentence.
    pub reason: String,
}

impl Ladder {
    pub fn score(&self, rung: Rung) -> Option<&RungScore> {
        self.scores.iter().find(|s| s.rung == rung)
    }
}

fn is_frame(layout: &ParamLayout, i: usize) -> bool {
    matches!(
        layout.params[i].kind,
        ParamKind::Base(_) | ParamKind::Tool(_)
    )
}

/// The layout indices a rung frees (sorted).
pub fn rung_free(
    rung: Rung,
    layout: &ParamLayout,
    campaign_free: &[usize],
    identifiable: &[usize],
) -> Vec<usize> {
    let offset = |i: usize| layout.params[i].kind == ParamKind::JointOffset;
    let mut free: Vec<usize> = match rung {
        Rung::HandEye => identifiable
            .iter()
            .copied()
            .filter(|&i| is_frame(layout, i))
            .collect(),
        Rung::JointOffsets => identifiable
            .iter()
            .copied()
            .filter(|&i| is_frame(layout, i) || (offset(i) && campaign_free.contains(&i)))
            .collect(),
        Rung::JointOffsetsPrior => identifiable
            .iter()
            .copied()
            .filter(|&i| is_frame(layout, i) || offset(i))
            .collect(),
        Rung::Full | Rung::FullTerms => campaign_free.to_vec(),
        Rung::FullPrior => identifiable.to_vec(),
    };
    free.sort_unstable();
    free.dedup();
    free
}

/// Fit one rung on `poses` from `nominal` (the prior centred there).
pub fn fit_rung(
    rung: Rung,
    input: &LadderInput,
    poses: &[ImagePose],
    noise: ImageNoise,
) -> Result<(JointRefinement, Vec<usize>), IdentifyError> {
    let layout = ParamLayout::new(&input.nominal.robot, super::Instrument::Camera);
    let free = rung_free(rung, &layout, input.campaign_free, input.identifiable);
    if rung == Rung::FullTerms {
        // Selected from the poses' measurements ([`fit_terms_rung`]).
        return Err(IdentifyError::NoPoses);
    }
    let fit = if rung.has_prior() {
        let rows = PriorRows::new(input.prior, &layout, &free, input.nominal, input.nominal);
        joint_refine_with_prior(
            input.nominal,
            input.intrinsics,
            poses,
            &free,
            &rows,
            noise,
            input.hold_intrinsics,
        )?
    } else {
        joint_refine(
            input.nominal,
            input.intrinsics,
            poses,
            &free,
            noise,
            input.hold_intrinsics,
        )?
    };
    Ok((fit, free))
}

/// The folds: each a list of pose indices held out together (whole groups,
/// one group per fold up to [`MAX_FOLDS`] groups, else dealt in turn).
pub fn folds(groups: &[usize]) -> Vec<Vec<usize>> {
    let count = super::config_groups::group_count(groups);
    let k = count.min(MAX_FOLDS);
    let mut out = vec![Vec::new(); k];
    for (pose, &g) in groups.iter().enumerate() {
        out[g % k.max(1)].push(pose);
    }
    out.retain(|f| !f.is_empty());
    out
}

/// Reprojection residuals (px) of `poses` predicted by `fit`.
fn squared_residuals(fit: &JointRefinement, pose: &ImagePose) -> Option<(f64, usize)> {
    let camera = match &fit.terms {
        Some(t) => t.terms.world_to_tool(&fit.model, &pose.joints_rad),
        None => fit.model.world_to_tool(&pose.joints_rad),
    };
    let inv = camera.ok()?.inverse();
    let mut sum = 0.0;
    for (p, uv) in &pose.observations {
        let pred = fit.intrinsics.project(&(inv * p))?;
        sum += (pred.coords - uv.coords).norm_squared();
    }
    Some((sum, pose.observations.len()))
}

/// Score one rung by held-out prediction over `folds`.
fn score(rung: Rung, input: &LadderInput, folds: &[Vec<usize>]) -> RungScore {
    let mut sum = 0.0;
    let mut points = 0usize;
    let mut errors = Vec::new();
    let mut parameters = 0;
    let mut failed = None;
    for fold in folds {
        let train: Vec<usize> = (0..input.poses.len())
            .filter(|i| !fold.contains(i))
            .collect();
        let fit = match fit_on(rung, input, &train) {
            Ok((fit, count)) => {
                parameters = count;
                fit
            }
            Err(e) => {
                failed = Some(e.to_string());
                break;
            }
        };
        for &i in fold {
            match squared_residuals(&fit, &input.poses[i]) {
                Some((s, n)) => {
                    sum += s;
                    points += n;
                }
                None => failed = Some(format!("pose {i} could not be predicted")),
            }
            if let Some(Some(m)) = input.measured.get(i) {
                let one = std::slice::from_ref(m);
                let predicted = match &fit.terms {
                    Some(t) => validate_with_terms(&fit.model, &t.terms, one),
                    None => validate(&fit.model, one),
                };
                if let Ok((_, e)) = predicted {
                    errors.push((i, [e[0].x, e[0].y, e[0].z]));
                }
            }
        }
    }
    let heldout_rms_px = if points > 0 && failed.is_none() {
        (sum / points as f64).sqrt()
    } else {
        f64::INFINITY
    };
    RungScore {
        rung,
        parameters,
        heldout_rms_px,
        heldout_errors_mm: errors,
        failed,
    }
}

/// One rung's held-out prediction over `input`'s groups ([`folds`]).
pub fn heldout_score(rung: Rung, input: &LadderInput) -> RungScore {
    score(rung, input, &folds(input.groups))
}

/// Score every rung of `rungs` by held-out prediction and keep the best
/// (a richer rung must beat the best simpler one by [`RICHER_MARGIN`]).
/// `None` when the campaign has fewer than [`MIN_GROUPS`] groups.
pub fn climb(input: &LadderInput, rungs: &[Rung]) -> Option<Ladder> {
    let groups = super::config_groups::group_count(input.groups);
    if groups < MIN_GROUPS || rungs.is_empty() {
        return None;
    }
    let folds = folds(input.groups);
    let scores: Vec<RungScore> = rungs
        .iter()
        .filter(|&&r| r != Rung::FullTerms || input.candidates.is_some())
        .map(|&r| score(r, input, &folds))
        .collect();
    let errors: Vec<f64> = scores.iter().map(|s| s.heldout_rms_px).collect();
    let best = &scores[keep_best(&errors)?];
    let hand_eye = scores.iter().find(|s| s.rung == Rung::HandEye);
    let reason = match hand_eye {
        Some(h) if best.rung != Rung::HandEye => format!(
            "{} predicts the held-out configurations best: {:.3} px against {:.3} px for nominal kinematics ({} groups, {} folds)",
            best.rung.as_str(),
            best.heldout_rms_px,
            h.heldout_rms_px,
            groups,
            folds.len()
        ),
        _ => format!(
            "no identified kinematics predicts the held-out configurations better than the nominal model ({:.3} px; {} groups, {} folds): the kinematics stay nominal",
            best.heldout_rms_px,
            groups,
            folds.len()
        ),
    };
    Some(Ladder {
        groups,
        folds: folds.len(),
        chosen: best.rung,
        reason,
        scores,
    })
}

/// Which of a ladder's rungs to keep, given each rung's held-out error in
/// ladder order (simplest first; not finite: not scored): a richer rung
/// must beat the best simpler one by more than [`RICHER_MARGIN`].
pub fn keep_best(heldout_errors: &[f64]) -> Option<usize> {
    let mut best: Option<usize> = None;
    for (k, &e) in heldout_errors.iter().enumerate() {
        if !e.is_finite() {
            continue;
        }
        match best {
            Some(b) if e >= heldout_errors[b] * (1.0 - RICHER_MARGIN) => {}
            _ => best = Some(k),
        }
    }
    best
}

/// The held-out camera position errors of `score` as vectors, in pose order.
pub fn errors_mm(score: &RungScore) -> Vec<Vector3<f64>> {
    let mut e = score.heldout_errors_mm.clone();
    e.sort_by_key(|(i, _)| *i);
    e.iter().map(|(_, v)| Vector3::from(*v)).collect()
}

#[cfg(test)]
#[path = "model_ladder_tests.rs"]
mod tests;
