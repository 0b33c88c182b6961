//! The oracle floors of a simulated campaign (issue 5): the same
//! identification given the **true** camera poses plus noise at the level
//! the camera step really achieves, i.e. drawn from each pose's marginal
//! covariance of the camera bundle ([`camera_step_precision`]) for the
//! campaign's dot noise. A method that reaches the oracle loses nothing
//! between the images and the kinematics.
//!
//! Three floors, from the most optimistic:
//! * [`oracle_accuracy`]: every pose's error drawn independently from its
//!   marginal. A camera step shares one intrinsics error across all poses,
//!   so no estimator from the images reaches this floor when that shared
//!   error dominates (few dots per image, views near the image centre);
//! * [`oracle_accuracy_correlated`]: the same marginals with the shared
//!   intrinsics error drawn once per campaign, as a bundle makes it;
//! * [`image_oracle_accuracy`]: the efficient estimator on the images
//!   themselves, i.e. the joint refinement (maximum likelihood, method.md §6
//!   **beyond**) on the true image of every dot plus the measured dot noise,
//!   started from the truth with the true joint noise known. Its mean over
//!   noise draws is the Cramér–Rao floor of the campaign: what a perfect
//!   detector and camera step would let the service reach.

use nalgebra::{Cholesky, DVector, Matrix6, Point3, SVector, Vector6};
use rand::{rngs::StdRng, SeedableRng};
use rand_distr::{Distribution, StandardNormal};

use super::camera_step::camera_step_precision;
use super::campaign::{Campaign, CampaignSpec, SimPose};
use super::campaign_io::PoseSet;
use super::experiment_error::ExperimentError;
use super::start_model::start_model;
use crate::geometry::perturb_left;
use crate::kinematics::identify::{
    fit_parameters, identify, validate, IdentifyMode, IdentifyOptions, JointNoise, Measurement,
    Observed,
};
use crate::kinematics::joint_refine::{joint_refine, ImageNoise, ImagePose};
use crate::kinematics::{CalibratedModel, Instrument};
use crate::stats::AccuracyStats;

/// Seeds the oracle's noise apart from the campaign's own.
const ORACLE_SEED: u64 = 0x0a_c1e;
/// Spreads the correlated oracle's draws apart (the golden-ratio constant).
const DRAW_STRIDE: u64 = 0x9e37_79b9_7f4a_7c15;
/// Seeds the image-level oracle's dot noise apart from the others.
const IMAGE_ORACLE_SEED: u64 = 0x1a_6e0a;

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

/// The true robot in the parameterisation an identification with free
/// layout indices `free` reports: the redundant (fixed) terms of the true
/// robot folded into base and hand–eye by an exact fit to the true camera
/// poses at every recorded joint vector, from `reference` (whose fixed
/// terms, the nominal ones, stay). Estimates are compared with this.
pub fn equivalent_truth(
    campaign: &Campaign,
    reference: &CalibratedModel,
    free: &[usize],
) -> Result<CalibratedModel, ExperimentError> {
    let true_model = campaign.truth.model()?;
    let exact: Vec<Measurement> = campaign
        .poses
        .iter()
        .map(|p| {
            Ok(Measurement {
                joints_rad: p.joints_rad.clone(),
                observed: Observed::Pose {
                    world_to_tool: true_model.world_to_tool(&p.joints_rad)?,
                    covariance: None,
                },
            })
        })
        .collect::<Result<_, crate::kinematics::KinematicsError>>()?;
    let options = IdentifyMode::Weighted.into();
    Ok(fit_parameters(reference, Instrument::Camera, &exact, free, options)?.0)
}

/// The image-level oracle (see the module doc): validation accuracy of the
/// joint refinement on the true image of every board point of every
/// calibration pose plus Gaussian noise of `sigma_px` per axis, one entry
/// per noise draw (`draws` of them). It starts from the truth
/// ([`equivalent_truth`] and the true intrinsics, which it refines) and
/// identifies the layout indices `free`, as the pipeline does.
pub fn image_oracle_accuracy(
    spec: &CampaignSpec,
    campaign: &Campaign,
    sigma_px: f64,
    free: &[usize],
    draws: u64,
) -> Result<Vec<AccuracyStats>, ExperimentError> {
    let cal: Vec<&SimPose> = campaign
        .poses
        .iter()
        .filter(|p| p.set == PoseSet::Cal)
        .collect();
    let truth_cal = truth_measurements(campaign, PoseSet::Cal);
    let start = equivalent_truth(campaign, &start_model(spec, &truth_cal)?, free)?;
    let points = spec.board.points();
    let noise = ImageNoise {
        sigma_px,
        joint: JointNoise::Known {
            sigma_rad: spec.encoder_sigma_deg.to_radians(),
        },
    };
    let val = truth_measurements(campaign, PoseSet::Val);
    (0..draws)
        .map(|draw| {
            let seed = spec.seed ^ IMAGE_ORACLE_SEED ^ (draw + 1).wrapping_mul(DRAW_STRIDE);
            let mut rng = StdRng::seed_from_u64(seed);
            let images: Vec<ImagePose> = cal
                .iter()
                .map(|p| ImagePose {
                    joints_rad: p.joints_rad.clone(),
                    observations: points
                        .iter()
                        .zip(&p.ideal_px)
                        .map(|(x, ideal)| {
                            let e = nalgebra::Vector2::from_fn(|_, _| {
                                let z: f64 = StandardNormal.sample(&mut rng);
                                sigma_px * z
                            });
                            (*x, ideal + e)
                        })
                        .collect(),
                })
                .collect();
            let fit = joint_refine(
                &start,
                &campaign.truth.intrinsics,
                &images,
                free,
                noise,
                false,
            )?;
            Ok(validate(&fit.model, &val)?.0)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::campaign::simulate_campaign;

    /// Free layout indices of a pose-level identification of `campaign`.
    fn identified_free(spec: &CampaignSpec, campaign: &Campaign) -> Vec<usize> {
        let cal = truth_measurements(campaign, PoseSet::Cal);
        let start = start_model(spec, &cal).unwrap();
        identify(&start, Instrument::Camera, &cal, IdentifyOptions::default())
            .unwrap()
            .identifiability
            .free
    }

    /// A small campaign without encoder noise: the truth is exactly
    /// recoverable from noise-free data.
    fn quiet_campaign(seed: u64) -> (CampaignSpec, Campaign) {
        let mut spec = CampaignSpec::standard("puma560", seed).unwrap();
        spec.cal_poses = 24;
        spec.val_poses = 8;
        spec.encoder_sigma_deg = 0.0;
        let campaign = simulate_campaign(&spec).unwrap();
        (spec, campaign)
    }

    /// The equivalent truth differs from the true robot in its fixed terms
    /// but predicts every true camera pose.
    #[test]
    fn equivalent_truth_predicts_the_true_camera_poses() {
        let (spec, campaign) = quiet_campaign(3);
        let free = identified_free(&spec, &campaign);
        assert!(free.len() < 36, "nothing fixed: {}", free.len());
        let cal = truth_measurements(&campaign, PoseSet::Cal);
        let equivalent =
            equivalent_truth(&campaign, &start_model(&spec, &cal).unwrap(), &free).unwrap();
        let val = truth_measurements(&campaign, PoseSet::Val);
        let error = validate(&equivalent, &val).unwrap().0;
        assert!(error.norm.max_mm < 1e-6, "{:?}", error.norm);
    }

    /// The image-level floor scales with the dot noise and vanishes with it.
    #[test]
    fn image_oracle_recovers_the_truth_as_the_noise_vanishes() {
        let (spec, campaign) = quiet_campaign(4);
        let free = identified_free(&spec, &campaign);
        let at = |sigma_px: f64| {
            let draws = image_oracle_accuracy(&spec, &campaign, sigma_px, &free, 2).unwrap();
            assert_eq!(draws.len(), 2);
            draws.iter().map(|s| s.norm.mean_mm).sum::<f64>() / 2.0
        };
        let (coarse, fine) = (at(0.1), at(1e-4));
        assert!(fine < 1e-4, "{fine} mm at 1e-4 px");
        // Linear in the noise: 1000x less noise, ~1000x less error.
        let ratio = coarse / fine;
        assert!(
            (500.0..2000.0).contains(&ratio),
            "{coarse} / {fine} = {ratio}"
        );
    }
}
