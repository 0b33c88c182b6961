//! A camera job's default identification, run from calib on simulated
//! images: the calib functions the service's pipeline calls
//! (`src/pipeline/identify_stage.rs`, `model_selection.rs`) with its
//! default options, in its order (method.md §6.1–§6.8):
//!
//! 1. per-image PnP, each pose with its covariance;
//! 2. the weighted pose-level identification (which parameters the
//!    campaign determines);
//! 3. the joint refinement on the image points, dot and joint noise
//!    estimated;
//! 4. the model ladder on held-out configuration groups, the kept rung
//!    refitted on the calibration images (noise estimated);
//!
//! or, with the job's `non_geometric` option, the term selection at pose
//! level and again on the image points (no ladder, as in the pipeline).
//!
//! What differs from a job: the images are dot centres with Gaussian
//! noise (no rendering or detection), the camera step is replaced by the
//! true intrinsics as the start (the joint refinement refines them from
//! the same images), and no pose is screened out.

use super::campaign::{true_terms, Campaign, CampaignSpec};
use super::campaign_io::PoseSet;
use super::experiment_error::ExperimentError;
use super::start_model::start_model;
use crate::camera::model::Intrinsics;
use crate::camera::pose::estimate_pose;
use crate::kinematics::config_groups::configuration_groups;
use crate::kinematics::identifiability::structural_redundancies;
use crate::kinematics::identify::{
    identify, IdentifyMode, IdentifyOptions, JointNoise, Measurement, Observed,
};
use crate::kinematics::image_term_selection::select_terms_on_images;
use crate::kinematics::joint_refine::{joint_refine, ImageNoise, ImagePose, JointRefinement};
use crate::kinematics::model_ladder::{climb, fit_rung, LadderInput, Rung};
use crate::kinematics::nongeometric::{CandidateOptions, NonGeometric};
use crate::kinematics::prior::KinematicPrior;
use crate::kinematics::term_selection::identify_with_terms;
use crate::kinematics::{CalibratedModel, Instrument, ParamLayout};

/// What the job kept.
#[derive(Debug, Clone)]
pub struct JobFit {
    pub refinement: JointRefinement,
    /// The kept non-geometric terms (none by default).
    pub terms: NonGeometric,
    /// The ladder's rung (`None`: no ladder ran, the full model is kept).
    pub rung: Option<Rung>,
}

impl JobFit {
    pub fn model(&self) -> &CalibratedModel {
        &self.refinement.model
    }

    /// The fit judged at `campaign`'s validation poses (see
    /// [`JobValidation`]).
    pub fn validation(
        &self,
        spec: &CampaignSpec,
        campaign: &Campaign,
    ) -> Result<JobValidation, ExperimentError> {
        let truth = campaign.truth.model()?;
        let true_terms = true_terms(spec, &truth);
        let (mut total, mut parameters) = (Vec::new(), Vec::new());
        for p in campaign.poses.iter().filter(|p| p.set == PoseSet::Val) {
            let predicted = self
                .terms
                .world_to_tool(self.model(), &p.joints_rad)?
                .translation
                .vector;
            let exact = true_terms
                .world_to_tool(&truth, &p.joints_rad)?
                .translation
                .vector;
            total.push((predicted - p.target_to_camera.translation.vector).norm());
            parameters.push((predicted - exact).norm());
        }
        let rms = |e: &[f64]| (e.iter().map(|v| v * v).sum::<f64>() / e.len().max(1) as f64).sqrt();
        Ok(JobValidation {
            rms_mm: rms(&total),
            mean_mm: total.iter().sum::<f64>() / total.len().max(1) as f64,
            parameters_rms_mm: rms(&parameters),
        })
    }
}

/// A fit's 3-D camera position errors at the validation poses (mm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JobValidation {
    /// Against the true camera (the recorded joints were off by the
    /// encoder noise): what a user measures.
    pub rms_mm: f64,
    pub mean_mm: f64,
    /// Against the true robot at the recorded joints: the fit's own part.
    pub parameters_rms_mm: f64,
}

/// Dot noise the job starts the joint refinement with (px): the camera
/// step's RMS in the pipeline; here the spec's noise (it is re-estimated).
fn start_noise(spec: &CampaignSpec) -> ImageNoise {
    ImageNoise {
        sigma_px: spec.pixel_sigma_px.max(1e-3),
        joint: JointNoise::Estimate,
    }
}

/// The job's identification of the calibration images `cal` (module doc);
/// `non_geometric` is the job option of that name.
pub fn default_job_fit(
    spec: &CampaignSpec,
    cal: &[ImagePose],
    non_geometric: bool,
) -> Result<JobFit, ExperimentError> {
    let intrinsics: Intrinsics = spec.intrinsics;
    let measurements = cal
        .iter()
        .map(|im| {
            let estimate = estimate_pose(&intrinsics, &im.observations, None)?;
            Ok(Measurement {
                joints_rad: im.joints_rad.clone(),
                observed: Observed::Pose {
                    world_to_tool: estimate.target_to_camera,
                    covariance: Some(estimate.covariance_6x6),
                },
            })
        })
        .collect::<Result<Vec<_>, ExperimentError>>()?;
    let options = IdentifyOptions {
        mode: IdentifyMode::Weighted,
        joint_noise: JointNoise::default(),
    };
    let start = start_model(spec, &measurements)?;
    let noise = start_noise(spec);
    if non_geometric {
        let candidates = CandidateOptions::for_robot(&start.robot);
        let pose_level = identify_with_terms(
            &start,
            Instrument::Camera,
            &measurements,
            options,
            &candidates,
        )?;
        let on_images = select_terms_on_images(&pose_level, &intrinsics, cal, noise, false)?;
        return Ok(JobFit {
            terms: on_images.selection.terms.clone(),
            refinement: on_images.refinement,
            rung: None,
        });
    }
    let id = identify(&start, Instrument::Camera, &measurements, options)?;
    let campaign_free = id.identifiability.free.clone();
    let full = joint_refine(&id.model, &intrinsics, cal, &campaign_free, noise, false)?;
    let (refinement, rung) = ladder(spec, cal, full, &campaign_free)?;
    Ok(JobFit {
        terms: NonGeometric::none(&refinement.model),
        refinement,
        rung,
    })
}

/// The model ladder as the pipeline runs it (`model_selection::select`):
/// nominal kinematics with the full fit's frames, the full fit's intrinsics
/// and noise, the default prior; the kept rung refitted unless it is the
/// full model itself. Validation poses are separate configurations in the
/// simulator, so the calibration poses alone are grouped.
fn ladder(
    spec: &CampaignSpec,
    cal: &[ImagePose],
    full: JointRefinement,
    campaign_free: &[usize],
) -> Result<(JointRefinement, Option<Rung>), ExperimentError> {
    let joints: Vec<Vec<f64>> = cal.iter().map(|p| p.joints_rad.clone()).collect();
    let groups = configuration_groups(&joints, &[]);
    let nominal = CalibratedModel {
        robot: spec.nominal.clone(),
        ..full.model.clone()
    };
    let layout = ParamLayout::new(&spec.nominal, Instrument::Camera);
    let structural = structural_redundancies(&layout, &nominal)?;
    let identifiable: Vec<usize> = (0..layout.len())
        .filter(|i| !structural.contains(i))
        .collect();
    let prior = KinematicPrior::default();
    let input = LadderInput {
        nominal: &nominal,
        intrinsics: &full.intrinsics,
        poses: cal,
        groups: &groups,
        measured: &[],
        campaign_free,
        identifiable: &identifiable,
        prior: &prior,
        noise: ImageNoise {
            sigma_px: full.sigma_px,
            joint: JointNoise::Known {
                sigma_rad: full.joint_sigma_rad,
            },
        },
        hold_intrinsics: false,
        // The geometric rungs: a job with terms on runs term selection
        // instead (below), as it did before the ladder had a terms rung.
        candidates: None,
    };
    let Some(chosen) = climb(&input, &Rung::ALL) else {
        return Ok((full, None));
    };
    if chosen.chosen == Rung::Full {
        return Ok((full, Some(Rung::Full)));
    }
    let estimate = ImageNoise {
        sigma_px: full.sigma_px,
        joint: JointNoise::Estimate,
    };
    let (refit, _) = fit_rung(chosen.chosen, &input, cal, estimate)?;
    Ok((refit, Some(chosen.chosen)))
}
