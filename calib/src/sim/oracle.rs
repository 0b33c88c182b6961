//! The oracle floor of a simulated campaign (issue 5): the same
//! identification given the **true** camera poses plus noise at the level
//! the camera step really achieves, i.e. drawn from each pose's marginal
//! covariance of the camera bundle ([`camera_step_precision`]) for the
//! campaign's dot noise. A method that reaches the oracle loses nothing
//! between the images and the kinematics.

use nalgebra::{Cholesky, DVector, Matrix6, Point3, SVector, Vector6};
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
/// Spreads the correlated oracle's draws apart (the golden-ratio constant).
const DRAW_STRIDE: u64 = 0x9e37_79b9_7f4a_7c15;

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

/// [`oracle_measurements`] with the camera step's errors drawn jointly, as
/// one bundle makes them: a single intrinsics error (covariance
/// `intrinsics`) moves every pose by its gain, plus each pose's own error
/// with the intrinsics known (`known`). The marginals are `covariances`
/// (which the measurements carry), but the poses are correlated.
fn correlated_measurements(
    poses: &[&SimPose],
    precision: &super::camera_step::CameraStepPrecision,
    rng: &mut StdRng,
) -> Vec<Measurement> {
    let l_c = Cholesky::new(precision.intrinsics.clone())
        .map(|c| c.l())
        .unwrap_or_else(|| nalgebra::DMatrix::zeros(8, 8));
    let z_c = DVector::from_fn(8, |_, _| StandardNormal.sample(rng));
    let shared = SVector::<f64, 8>::from_column_slice((l_c * z_c).as_slice());
    poses
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let l = Cholesky::new(precision.poses_known_intrinsics[k])
                .map(|c| c.l())
                .unwrap_or_default();
            let z = Vector6::from_fn(|_, _| StandardNormal.sample(rng));
            let error = precision.pose_intrinsics_gain[k] * shared + l * z;
            Measurement {
                joints_rad: p.joints_rad.clone(),
                observed: Observed::Pose {
                    world_to_tool: perturb_left(&p.target_to_camera, &error),
                    covariance: Some(precision.poses[k]),
                },
            }
        })
        .collect()
}

/// Validation accuracy (against the true camera positions) of the oracle
/// identification of `campaign`, whose calibration images show the board
/// points `board_points` with dot noise `sigma_px`. The poses' errors are
/// drawn independently from their marginals: this ignores that the camera
/// step's one intrinsics error is shared by every pose, and is optimistic
/// (see [`oracle_accuracy_correlated`]).
pub fn oracle_accuracy(
    spec: &CampaignSpec,
    campaign: &Campaign,
    board_points: &[Point3<f64>],
    sigma_px: f64,
) -> Result<AccuracyStats, ExperimentError> {
    oracle_with(spec, campaign, board_points, sigma_px, None)
}

/// [`oracle_accuracy`] with the camera step's errors drawn jointly (one
/// intrinsics error shared by all poses, as a real camera step has).
/// One intrinsics draw per call varies a lot between campaigns: `draw`
/// selects an independent draw, to average several.
pub fn oracle_accuracy_correlated(
    spec: &CampaignSpec,
    campaign: &Campaign,
    board_points: &[Point3<f64>],
    sigma_px: f64,
    draw: u64,
) -> Result<AccuracyStats, ExperimentError> {
    oracle_with(spec, campaign, board_points, sigma_px, Some(draw))
}

fn oracle_with(
    spec: &CampaignSpec,
    campaign: &Campaign,
    board_points: &[Point3<f64>],
    sigma_px: f64,
    correlated_draw: Option<u64>,
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
    let data = match correlated_draw {
        Some(draw) => {
            let seed = spec.seed ^ ORACLE_SEED ^ (draw + 1).wrapping_mul(DRAW_STRIDE);
            correlated_measurements(&cal, &precision, &mut StdRng::seed_from_u64(seed))
        }
        None => oracle_measurements(
            &cal,
            &precision.poses,
            &mut StdRng::seed_from_u64(spec.seed ^ ORACLE_SEED),
        ),
    };
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
