//! Issue 19 on a simulated camera campaign: the true robot with or without
//! the switch's terms, the pose-level selection, the image-level selection
//! (`kinematics::image_term_selection`) and the geometric image-level
//! refinement, each judged at the validation poses against the true camera
//! positions. Shared by calib's tests and `examples/camera_terms_bench`.

use std::time::Instant;

use super::campaign::CampaignSpec;
use super::experiment::prepare;
use super::experiment_error::ExperimentError;
use super::start_model::start_model;
use super::tracker_campaign::typical_terms;
use crate::kinematics::identify::{IdentifyMode, IdentifyOptions, JointNoise};
use crate::kinematics::image_term_selection::{select_terms_on_images, ImageTermSelection};
use crate::kinematics::joint_refine::{joint_refine, ImageNoise};
use crate::kinematics::nongeometric::{CandidateOptions, NonGeometric};
use crate::kinematics::term_selection::identify_with_terms;
use crate::kinematics::term_validate::validate_with_terms;
use crate::kinematics::{CalibratedModel, Instrument};

/// Calibration poses of the campaigns (the standard 60 + 20: the terms
/// need more than the geometry alone).
pub const CAL_POSES: usize = 80;

/// What one campaign gave.
pub struct CameraTermsOutcome {
    pub selected: ImageTermSelection,
    /// Validation mean error (mm, true camera positions) of the image-level
    /// selection's model with its terms.
    pub val_mm: f64,
    /// The same of the geometric image-level refinement.
    pub geometric_val_mm: f64,
    /// The same of the pose-level selection (its model and kept terms).
    pub pose_level_val_mm: f64,
    /// The true terms (none without the switch).
    pub truth: NonGeometric,
    /// Wall time (s) of the image-level selection and of one geometric
    /// joint refinement.
    pub selection_seconds: f64,
    pub refinement_seconds: f64,
}

/// The standard PUMA 560 campaign of `seed` with [`CAL_POSES`] poses,
/// the terms switched on or off, through every step (module doc).
pub fn run_camera_terms(seed: u64, switch: bool) -> Result<CameraTermsOutcome, ExperimentError> {
    let mut spec = CampaignSpec::standard("puma560", seed)?;
    spec.cal_poses = CAL_POSES;
    spec.non_geometric = switch;
    let p = prepare(&spec)?;
    let options = IdentifyOptions {
        mode: IdentifyMode::Weighted,
        joint_noise: JointNoise::default(),
    };
    let start = start_model(&spec, &p.weighted)?;
    let candidates = CandidateOptions::for_robot(&start.robot);
    let pose_level = identify_with_terms(
        &start,
        Instrument::Camera,
        &p.weighted,
        options,
        &candidates,
    )?;
    let noise = ImageNoise {
        sigma_px: spec.pixel_sigma_px,
        joint: JointNoise::Estimate,
    };
    let t0 = Instant::now();
    let selected = select_terms_on_images(&pose_level, &p.camera_step, &p.images, noise, false)?;
    let selection_seconds = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let geometric = joint_refine(
        &pose_level.geometric.model,
        &p.camera_step,
        &p.images,
        &pose_level.geometric.identifiability.free,
        noise,
        false,
    )?;
    let refinement_seconds = t1.elapsed().as_secs_f64();
    let mm = |model: &CalibratedModel, terms: &NonGeometric| {
        validate_with_terms(model, terms, &p.val).map(|(stats, _)| stats.norm.mean_mm)
    };
    let truth_model = p.campaign.truth.model()?;
    Ok(CameraTermsOutcome {
        val_mm: mm(&selected.refinement.model, &selected.selection.terms)?,
        geometric_val_mm: mm(&geometric.model, &NonGeometric::none(&geometric.model))?,
        pose_level_val_mm: mm(&pose_level.model, &pose_level.terms)?,
        truth: if switch {
            typical_terms(&truth_model)
        } else {
            NonGeometric::none(&truth_model)
        },
        selected,
        selection_seconds,
        refinement_seconds,
    })
}
