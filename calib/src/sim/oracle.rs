//! The oracle floor of a simulated campaign (issue 5): the same
//! identification given the **true** camera poses plus noise at the level
//! the camera step really achieves, i.e. drawn from each pose's marginal
//! covariance of the camera bundle ([`camera_step_precision`]) for the
//! campaign's dot noise. A method that reaches the oracle loses nothing
//! between the images and the kinematics.

use nalgebra::{Cholesky, Matrix6, Point3, Vector6};
use rand::{rngs::StdRng, SeedableRng};
use rand_distr::{Distribution, StandardNormal};

use super::camera_step::camera_step_precision;
use super::campaign::{Campaign, CampaignSpec, SimPose};
use super::campaign_io::PoseSet;
use super::experiment::{start_model, ExperimentError};
use crate::geometry::perturb_left;
use crate::kinematics::identify::{
    identify, validate, IdentifyMode, IdentifyOptions, JointNoise, Measurement, Observed,
};
use crate::kinematics::Instrument;
use crate::stats::AccuracyStats;

/// Seeds the oracle's noise apart from the campaign's own.
const ORACLE_SEED: u64 = 0x0a_c1e;

/// True camera poses at the campaign's poses of `set`, as measurements.
pub fn truth_measurements(campaign: &Campaign, set: PoseSet) -> Vec<Measurement> {
    campaign
        .poses
        .iter()
        .filter(|p| p.set == set)
        .map(|p| Measurement {
            joints_rad: p.joints_rad.clone(),
            observed: Observed::Pose {
                world_to_tool: p.target_to_camera,
                covariance: None,
            },
        })
        .collect()
}

/// The true camera pose of every pose in `poses` moved by a draw from its
/// covariance in `covariances`, carrying that covariance.
pub fn oracle_measurements(
    poses: &[&SimPose],
    covariances: &[Matrix6<f64>],
    rng: &mut StdRng,
) -> Vec<Measurement> {
    poses
        .iter()
        .zip(covariances)
        .map(|(p, cov)| {
            let l = Cholesky::new(*cov).map(|c| c.l()).unwrap_or_default();
            let z = Vector6::from_fn(|_, _| StandardNormal.sample(rng));
            Measurement {
                joints_rad: p.joints_rad.clone(),
                observed: Observed::Pose {
                    world_to_tool: perturb_left(&p.target_to_camera, &(l * z)),
                    covariance: Some(*cov),
                },
            }
        })
        .collect()
}

/// Validation accuracy (against the true camera positions) of the oracle
/// identification of `campaign`, whose calibration images show the board
/// points `board_points` with dot noise `sigma_px`.
pub fn oracle_accuracy(
    spec: &CampaignSpec,
    campaign: &Campaign,
    board_points: &[Point3<f64>],
    sigma_px: f64,
) -> Result<AccuracyStats, ExperimentError> {
    let cal: Vec<&SimPose> = campaign
        .poses
        .iter()
        .filter(|p| p.set == PoseSet::Cal)
        .collect();
    let bundle: Vec<_> = cal
        .iter()
        .map(|p| (p.target_to_camera, board_points.to_vec()))
        .collect();
    let precision = camera_step_precision(&campaign.truth.intrinsics, &bundle, sigma_px)
        .ok_or(ExperimentError::Degenerate)?;
    let mut rng = StdRng::seed_from_u64(spec.seed ^ ORACLE_SEED);
    let data = oracle_measurements(&cal, &precision.poses, &mut rng);
    let options = IdentifyOptions {
        mode: IdentifyMode::Weighted,
        joint_noise: JointNoise::Known {
            sigma_rad: spec.encoder_sigma_deg.to_radians(),
        },
    };
    let id = identify(
        &start_model(spec, &data)?,
        Instrument::Camera,
        &data,
        options,
    )?;
    let val = truth_measurements(campaign, PoseSet::Val);
    Ok(validate(&id.model, &val)?.0)
}
