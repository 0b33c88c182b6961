//! One simulated calibration experiment end to end (method.md §6–8), shared
//! by the target tests and the `kinematics_bench` example: simulate a
//! campaign; identify from (a) the oracle — true camera poses plus
//! independent noise drawn from each pose's covariance at the camera step's
//! level (intrinsics calibrated from the same images: the marginal pose
//! covariance of that bundle, [`camera_step_precision`]), (b) the two-step pipeline —
//! per-image PnP then a pose-level fit, unweighted ("OpenCV-style") or
//! covariance-weighted, (c) paper mode, (d) the joint refinement on the
//! image points; compare predicted with true camera positions at the
//! validation poses; compensate the validation stations.

use std::time::Instant;

use nalgebra::{Cholesky, DVector, Vector6};
use rand::{rngs::StdRng, SeedableRng};
use rand_distr::{Distribution, StandardNormal};

use super::camera_step::camera_step_precision;
use super::campaign::{compliance, simulate_campaign, Campaign, CampaignSpec};
use super::campaign_io::PoseSet;
pub use super::experiment_error::ExperimentError;
use super::oracle::{equivalent_truth, oracle_measurements, truth_measurements};
pub use super::start_model::start_model;
use crate::camera::model::Intrinsics;
use crate::camera::pose::estimate_pose;
use crate::geometry::{perturb_left, Pose};
use crate::kinematics::identify::{
    identify, validate, IdentifyMode, IdentifyOptions, JointNoise, Measurement, Observed,
};
use crate::kinematics::ik::inverse_kinematics;
use crate::kinematics::joint_refine::{joint_refine, ImageNoise, ImagePose};
use crate::kinematics::{CalibratedModel, Instrument};
use crate::stats::AccuracyStats;

/// Validation statistics (3-D camera position vs truth) of every method.
#[derive(Debug, Clone)]
pub struct ExperimentResult {
    pub before: AccuracyStats,
    pub oracle: AccuracyStats,
    /// The stricter floor with known intrinsics (see [`Prepared`]).
    pub oracle_known_intrinsics: AccuracyStats,
    pub two_step_plain: AccuracyStats,
    pub two_step_weighted: AccuracyStats,
    pub paper: AccuracyStats,
    pub joint: AccuracyStats,
    /// Largest `|estimate - truth| / sigma` over the joint refinement's
    /// free parameters, and its name.
    pub worst_sigma_ratio: (f64, String),
    /// RMS over the free parameters of `(estimate - truth) / sigma`: 1 when
    /// the reported standard deviations are right.
    pub sigma_ratio_rms: f64,
    /// Joint noise the joint refinement estimated (rad).
    pub estimated_joint_sigma_rad: f64,
    pub fixed: Vec<String>,
    pub free_count: usize,
    pub condition_number: f64,
    pub observability_index: f64,
    /// Compensated stations on the true robot: position error (mm).
    pub compensated: AccuracyStats,
    /// Largest IK residual on the calibrated model (mm).
    pub max_ik_residual_mm: f64,
    pub reprojection_rms_px: f64,
    /// Joint refinement's iterations and termination.
    pub joint_iterations: (usize, String),
    pub identify_seconds: f64,
    pub joint_refine_seconds: f64,
}

/// Intrinsics as the camera step delivers them: the truth plus an error
/// drawn from the bundle's intrinsics covariance.
fn camera_step_intrinsics(
    truth: &Intrinsics,
    cov: &nalgebra::DMatrix<f64>,
    rng: &mut StdRng,
) -> Intrinsics {
    let l = Cholesky::new(cov.clone())
        .map(|c| c.l())
        .unwrap_or_else(|| cov.map(|_| 0.0));
    let z = DVector::from_fn(cov.nrows(), |_, _| StandardNormal.sample(rng));
    crate::kinematics::projection::apply_intrinsics(truth, (l * z).as_slice())
}

/// A simulated campaign turned into every method's input.
#[derive(Debug, Clone)]
pub struct Prepared {
    pub campaign: Campaign,
    /// Intrinsics as the camera step delivers them.
    pub camera_step: Intrinsics,
    /// True camera poses plus independent camera-step-level noise.
    pub oracle: Vec<Measurement>,
    /// True camera poses plus the noise of a PnP with the true intrinsics
    /// (a stricter floor no method without known intrinsics can reach).
    pub oracle_known_intrinsics: Vec<Measurement>,
    /// Per-image PnP with the camera step's intrinsics, no covariance.
    pub plain: Vec<Measurement>,
    /// The same poses with the camera step's marginal covariance.
    pub weighted: Vec<Measurement>,
    /// Raw image points for the joint refinement.
    pub images: Vec<ImagePose>,
    /// True camera poses at the validation poses.
    pub val: Vec<Measurement>,
}

/// Simulate `spec` and build every method's input (see the module doc).
pub fn prepare(spec: &CampaignSpec) -> Result<Prepared, ExperimentError> {
    let campaign = simulate_campaign(spec)?;
    let truth_cam = campaign.truth.intrinsics;
    let mut rng = StdRng::seed_from_u64(spec.seed ^ 0xa5a5);
    let sigma = spec.pixel_sigma_px;
    let board = campaign.truth.board;
    let cal_poses: Vec<_> = campaign
        .poses
        .iter()
        .filter(|p| p.set == PoseSet::Cal)
        .collect();
    let bundle: Vec<_> = cal_poses
        .iter()
        .map(|p| (p.target_to_camera, board.points()))
        .collect();
    let precision =
        camera_step_precision(&truth_cam, &bundle, sigma).ok_or(ExperimentError::Degenerate)?;
    let cam_step = camera_step_intrinsics(&truth_cam, &precision.intrinsics, &mut rng);
    let (mut plain, mut weighted, mut images) = (vec![], vec![], vec![]);
    let mut strict_rng = StdRng::seed_from_u64(spec.seed ^ 0x5a5a);
    let mut oracle_known_intrinsics = vec![];
    let oracle = oracle_measurements(&cal_poses, &precision.poses, &mut rng);
    for ((p, cov), strict) in cal_poses
        .iter()
        .zip(&precision.poses)
        .zip(&precision.poses_known_intrinsics)
    {
        let cov = *cov;
        let ls = Cholesky::new(*strict).map(|c| c.l()).unwrap_or_default();
        let zs = Vector6::from_fn(|_, _| StandardNormal.sample(&mut strict_rng));
        oracle_known_intrinsics.push(Measurement {
            joints_rad: p.joints_rad.clone(),
            observed: Observed::Pose {
                world_to_tool: perturb_left(&p.target_to_camera, &(ls * zs)),
                covariance: Some(*strict),
            },
        });
        let obs = p.observations(&board);
        let q = p.joints_rad.clone();
        // OpenCV-style PnP: homography start, LM on the reprojection error.
        let fit = estimate_pose(&cam_step, &obs, None)?;
        plain.push(Measurement {
            joints_rad: q.clone(),
            observed: Observed::Pose {
                world_to_tool: fit.target_to_camera,
                covariance: None,
            },
        });
        weighted.push(Measurement {
            joints_rad: q.clone(),
            observed: Observed::Pose {
                world_to_tool: fit.target_to_camera,
                covariance: Some(cov),
            },
        });
        images.push(ImagePose {
            joints_rad: q,
            observations: obs,
        });
    }
    let val = truth_measurements(&campaign, PoseSet::Val);
    Ok(Prepared {
        campaign,
        camera_step: cam_step,
        oracle,
        oracle_known_intrinsics,
        plain,
        weighted,
        images,
        val,
    })
}

pub fn run_experiment(spec: &CampaignSpec) -> Result<ExperimentResult, ExperimentError> {
    let Prepared {
        campaign,
        camera_step: cam_step,
        oracle,
        oracle_known_intrinsics,
        plain,
        weighted,
        images,
        val,
    } = prepare(spec)?;
    let sigma = spec.pixel_sigma_px;
    // Every method is told the encoder noise, except the one the service
    // runs (two-step weighted, then the joint refinement, which estimates
    // it; the pose-level fit takes the covariances as they are).
    let known = JointNoise::Known {
        sigma_rad: spec.encoder_sigma_deg.to_radians(),
    };
    let run_with = |data: &[Measurement], mode, joint_noise| {
        let options = IdentifyOptions { mode, joint_noise };
        identify(&start_model(spec, data)?, Instrument::Camera, data, options)
            .map_err(ExperimentError::from)
    };
    let run = |data: &[Measurement], mode| run_with(data, mode, known);
    let stats = |m: &CalibratedModel| -> Result<AccuracyStats, ExperimentError> {
        Ok(validate(m, &val)?.0)
    };
    let oracle_id = run(&oracle, IdentifyMode::Weighted)?;
    let strict_id = run(&oracle_known_intrinsics, IdentifyMode::Weighted)?;
    let plain_id = run(&plain, IdentifyMode::Weighted)?;
    let paper_id = run(&plain, IdentifyMode::Paper)?;
    let t0 = Instant::now();
    let weighted_id = run_with(&weighted, IdentifyMode::Weighted, JointNoise::default())?;
    let identify_seconds = t0.elapsed().as_secs_f64();
    let free = weighted_id.identifiability.free.clone();
    let t1 = Instant::now();
    let noise = ImageNoise {
        sigma_px: sigma,
        joint: JointNoise::Estimate,
    };
    let joint = joint_refine(&weighted_id.model, &cam_step, &images, &free, noise, false)?;
    let joint_refine_seconds = t1.elapsed().as_secs_f64();

    // Truth in the identified parameterisation (fixed terms folded into
    // base and hand–eye).
    let true_model = exact_model(&campaign);
    let equivalent = equivalent_truth(&campaign, &weighted_id.before, &free)?;
    let diff: DVector<f64> = joint.layout.difference(&joint.model, &equivalent);
    let ratios: Vec<f64> = free.iter().map(|&i| diff[i] / joint.std_devs[i]).collect();
    let sigma_ratio_rms =
        (ratios.iter().map(|z| z * z).sum::<f64>() / ratios.len().max(1) as f64).sqrt();
    let worst = free
        .iter()
        .map(|&i| {
            (
                (diff[i] / joint.std_devs[i]).abs(),
                joint.layout.params[i].name.clone(),
            )
        })
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .unwrap_or((0.0, String::new()));

    // Compensation: reach each validation station's true camera pose.
    let (mut comp, mut max_res) = (vec![], 0.0f64);
    for p in campaign.poses.iter().filter(|p| p.set == PoseSet::Val) {
        let target = p.target_to_camera;
        let sol = inverse_kinematics(&joint.model, &target, std::slice::from_ref(&p.joints_rad))?;
        max_res = max_res.max(sol.residual_mm);
        // The true robot, compliance included (encoder noise is random).
        let q_true = compliance(
            &campaign.truth.robot,
            &sol.joints_rad,
            spec.compliance_rad_per_m,
        );
        let reached = true_model.world_to_tool(&q_true).unwrap_or_default();
        comp.push(reached.translation.vector - target.translation.vector);
    }
    Ok(ExperimentResult {
        before: stats(&weighted_id.before)?,
        oracle: stats(&oracle_id.model)?,
        oracle_known_intrinsics: stats(&strict_id.model)?,
        two_step_plain: stats(&plain_id.model)?,
        two_step_weighted: stats(&weighted_id.model)?,
        paper: stats(&paper_id.model)?,
        joint: stats(&joint.model)?,
        worst_sigma_ratio: worst,
        estimated_joint_sigma_rad: joint.joint_sigma_rad,
        sigma_ratio_rms,
        fixed: weighted_id.identifiability.fixed.clone(),
        free_count: free.len(),
        condition_number: weighted_id.identifiability.condition_number,
        observability_index: weighted_id.identifiability.observability_index,
        compensated: AccuracyStats::from_errors(&comp),
        max_ik_residual_mm: max_res,
        reprojection_rms_px: joint.reprojection_rms_px,
        joint_iterations: (joint.iterations, format!("{:?}", joint.termination)),
        identify_seconds,
        joint_refine_seconds,
    })
}

fn exact_model(campaign: &Campaign) -> CalibratedModel {
    campaign.truth.model().unwrap_or_else(|_| CalibratedModel {
        robot: campaign.truth.robot.clone(),
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::identity(),
    })
}
