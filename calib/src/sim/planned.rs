//! Planned campaigns in the simulator (issue 16): the plan request a user of
//! a simulated cell would send, the images the true robot takes at any
//! recorded joints, and a job's identification of them (per-image PnP, the
//! pose-level identification, then the joint refinement on the raw dots),
//! validated against the true camera positions at the campaign's `val`
//! poses. Shared by the planner's tests and the `plan_bench` example.

use nalgebra::{Point2, Vector2};
use rand::{rngs::StdRng, SeedableRng};
use rand_distr::{Distribution, Normal};

use super::campaign::{true_joints, true_terms, Campaign, CampaignSpec, SimError};
use super::campaign_io::PoseSet;
use super::experiment_error::ExperimentError;
use super::oracle::truth_measurements;
use super::start_model::start_model;
use crate::camera::pose::estimate_pose;
use crate::kinematics::identify::{
    identify, validate, IdentifyMode, IdentifyOptions, JointNoise, Measurement, Observed,
};
use crate::kinematics::joint_refine::{joint_refine, ImageNoise, ImagePose};
use crate::kinematics::{CalibratedModel, Instrument};
use crate::plan::information::{pose_factor, Columns};
use crate::plan::predict::predict;
use crate::plan::{PlanError, PlanRequest};
use crate::stats::AccuracyStats;

/// Seeds the dot and encoder noise of [`shoot`] apart from the campaign's.
const IMAGE_NOISE_SEED: u64 = 0xd07;
/// Separates the seeds of successive noise draws of [`shoot_with`].
const DRAW_STRIDE: u64 = 0x9e37_79b9_7f4a_7c15;

/// The plan request for `spec`'s cell: nominal robot, the hand–eye guess,
/// the board where the simulator placed it, the camera's true intrinsics
/// (a reused calibration; the job still refines them), the spec's ranges.
pub fn plan_request(
    spec: &CampaignSpec,
    campaign: &Campaign,
    poses: usize,
) -> Result<PlanRequest, ExperimentError> {
    let model = CalibratedModel {
        robot: spec.nominal.clone(),
        world_to_base: campaign.truth.model()?.world_to_base,
        flange_to_tool: spec.flange_to_camera_guess,
    };
    let mut r = PlanRequest::new(
        model,
        spec.intrinsics,
        spec.image_size,
        spec.board.points(),
        poses,
    );
    r.distance_mm = spec.distance_mm;
    r.view_angle_deg = spec.tilt_deg;
    r.sigma_px = spec.pixel_sigma_px;
    r.seed = spec.seed;
    Ok(r)
}

/// The images the true robot takes when its controller records `joints`
/// (encoder noise, compliance and dot noise as in the spec). A board point
/// leaving the image is an error: a plan must not put it there.
pub fn shoot(
    spec: &CampaignSpec,
    campaign: &Campaign,
    joints: &[Vec<f64>],
) -> Result<Vec<ImagePose>, ExperimentError> {
    shoot_with(spec, &campaign.truth.model()?, joints, 0)
}

/// [`shoot`] by the robot `truth` (e.g. the cell's true robot after a
/// drift of its joint zeros or base, for a quick check), with noise draw
/// number `draw` (one draw's validation error scatters by half its mean:
/// tests average several).
pub fn shoot_with(
    spec: &CampaignSpec,
    truth: &CalibratedModel,
    joints: &[Vec<f64>],
    draw: u64,
) -> Result<Vec<ImagePose>, ExperimentError> {
    let mut rng =
        StdRng::seed_from_u64(spec.seed ^ IMAGE_NOISE_SEED ^ draw.wrapping_mul(DRAW_STRIDE));
    let spec_error = |e: rand_distr::NormalError| SimError::Spec(e.to_string());
    let px = Normal::new(0.0, spec.pixel_sigma_px).map_err(spec_error)?;
    let enc = Normal::new(0.0, spec.encoder_sigma_deg.to_radians()).map_err(spec_error)?;
    let (w, h) = (f64::from(spec.image_size.0), f64::from(spec.image_size.1));
    let terms = true_terms(spec, truth);
    joints
        .iter()
        .enumerate()
        .map(|(k, q)| {
            let noisy: Vec<f64> = q.iter().map(|v| v + enc.sample(&mut rng)).collect();
            let true_q = true_joints(spec, &truth.robot, &terms, &noisy);
            let inv = truth.world_to_tool(&true_q)?.inverse();
            let observations = spec
                .board
                .points()
                .into_iter()
                .map(|p| {
                    let uv = spec
                        .intrinsics
                        .project(&(inv * p))
                        .filter(|uv| uv.x > 0.0 && uv.y > 0.0 && uv.x < w && uv.y < h)
                        .ok_or_else(|| {
                            SimError::Spec(format!("pose {k}: a board point leaves the image"))
                        })?;
                    let e = Vector2::new(px.sample(&mut rng), px.sample(&mut rng));
                    Ok((p, Point2::from(uv.coords + e)))
                })
                .collect::<Result<_, ExperimentError>>()?;
            Ok(ImagePose {
                joints_rad: q.clone(),
                observations,
            })
        })
        .collect()
}

/// A job's identification of `images` (see the module doc), validated at
/// the campaign's `val` poses against the true camera positions.
pub fn calibrate_images(
    spec: &CampaignSpec,
    campaign: &Campaign,
    images: &[ImagePose],
) -> Result<AccuracyStats, ExperimentError> {
    let cal = images
        .iter()
        .map(|im| {
            Ok(Measurement {
                joints_rad: im.joints_rad.clone(),
                observed: Observed::Pose {
                    world_to_tool: estimate_pose(&spec.intrinsics, &im.observations, None)?
                        .target_to_camera,
                    covariance: None,
                },
            })
        })
        .collect::<Result<Vec<_>, ExperimentError>>()?;
    let options = IdentifyOptions {
        mode: IdentifyMode::Weighted,
        joint_noise: JointNoise::default(),
    };
    let id = identify(&start_model(spec, &cal)?, Instrument::Camera, &cal, options)?;
    let noise = ImageNoise {
        sigma_px: spec.pixel_sigma_px,
        joint: JointNoise::Estimate,
    };
    let fit = joint_refine(
        &id.model,
        &spec.intrinsics,
        images,
        &id.identifiability.free,
        noise,
        false,
    )?;
    let val = truth_measurements(campaign, PoseSet::Val);
    Ok(validate(&fit.model, &val)?.0)
}

/// The planner's expected validation error (mm) of a campaign shot at
/// `joints` (any poses: planned or random), at the campaign's `val` poses:
/// the noise-free comparison of two pose sets on one cell.
pub fn expected_error(
    request: &PlanRequest,
    campaign: &Campaign,
    joints: &[Vec<f64>],
) -> Result<f64, PlanError> {
    let columns = Columns::of(request, &request.model)?;
    let factors: Vec<_> = joints
        .iter()
        .filter_map(|q| pose_factor(request, &request.model, &columns, q))
        .collect();
    let refs: Vec<_> = factors.iter().collect();
    let val: Vec<Vec<f64>> = campaign
        .poses
        .iter()
        .filter(|p| p.set == PoseSet::Val)
        .map(|p| p.joints_rad.clone())
        .collect();
    Ok(predict(&request.model, &columns, &refs, &val)?.validation_error_mean_mm)
}
