//! The bound against a Monte Carlo of a small problem: 8 calibration
//! poses of a PUMA 560 class arm, the frames, the identifiable joint zeros
//! and the 8 intrinsics unknown; [`REPETITIONS`] campaigns with fresh dot
//! and encoder noise, each identified by the maximum-likelihood joint
//! refinement (noise known, started at the truth). Its empirical
//! covariance must match the bound, and the bound computed with a wrong
//! noise level must not.

use nalgebra::{DMatrix, DVector, Point2, Vector2};
use rand::{rngs::StdRng, SeedableRng};
use rand_distr::{Distribution, Normal};

use super::cramer_rao::{cramer_rao, BoundInput, CramerRao};
use super::identifiable;
use crate::kinematics::identify_options::JointNoise;
use crate::kinematics::image_information::InformationInput;
use crate::kinematics::joint_refine::{joint_refine, ImageNoise, ImagePose};
use crate::kinematics::{CalibratedModel, Instrument, ParamKind, ParamLayout};
use crate::sim::campaign::{simulate_campaign, CampaignSpec};
use crate::sim::campaign_io::PoseSet;

/// Noisy campaigns identified.
const REPETITIONS: usize = 200;
/// Encoder noise (deg): large enough that marginalising it matters (at
/// ~0.8 m it moves every dot of an image by ~0.2 px together, against
/// 0.1 px of independent dot noise).
const ENCODER_DEG: f64 = 0.003;
/// Allowed distance of a Monte Carlo statistic from its expectation, in
/// its own standard errors.
const STANDARD_ERRORS: f64 = 4.0;

struct Problem {
    truth: CalibratedModel,
    spec: CampaignSpec,
    cal_joints: Vec<Vec<f64>>,
    val_joints: Vec<Vec<f64>>,
    free: Vec<usize>,
}

fn problem() -> Problem {
    let mut spec = CampaignSpec::standard("puma560", 11).unwrap();
    spec.cal_poses = 8;
    spec.val_poses = 6;
    spec.encoder_sigma_deg = ENCODER_DEG;
    let campaign = simulate_campaign(&spec).unwrap();
    let truth = campaign.truth.model().unwrap();
    let layout = ParamLayout::new(&truth.robot, Instrument::Camera);
    let free = identifiable(&truth)
        .unwrap()
        .into_iter()
        .filter(|&i| {
            matches!(
                layout.params[i].kind,
                ParamKind::Base(_) | ParamKind::Tool(_) | ParamKind::JointOffset
            )
        })
        .collect();
    let joints = |set| {
        campaign
            .poses
            .iter()
            .filter(|p| p.set == set)
            .map(|p| p.joints_rad.clone())
            .collect()
    };
    Problem {
        cal_joints: joints(PoseSet::Cal),
        val_joints: joints(PoseSet::Val),
        truth,
        spec,
        free,
    }
}

/// The bound of `p` with the given noise.
fn bound(p: &Problem, images: &[ImagePose], sigma_px: f64, encoder_rad: f64) -> CramerRao {
    cramer_rao(&BoundInput {
        information: InformationInput {
            model: &p.truth,
            intrinsics: &p.spec.intrinsics,
            terms: None,
            poses: images,
            free: &p.free,
            sigma_px,
            joint_sigma_rad: encoder_rad,
            hold_intrinsics: false,
        },
        val_joints: &p.val_joints,
    })
    .unwrap()
}

/// One repetition: its estimation error (bound's order) and the mean
/// squared validation error (mm²) against the true camera.
fn repetition(p: &Problem, rng: &mut StdRng) -> (DVector<f64>, f64) {
    let sigma_q = p.spec.encoder_sigma_deg.to_radians();
    let encoder = Normal::new(0.0, sigma_q).unwrap();
    let pixel = Normal::new(0.0, p.spec.pixel_sigma_px).unwrap();
    let mut off = |q: &[f64]| -> Vec<f64> { q.iter().map(|v| v + encoder.sample(rng)).collect() };
    let true_joints: Vec<Vec<f64>> = p.cal_joints.iter().map(|q| off(q)).collect();
    let val_truth: Vec<_> = p
        .val_joints
        .iter()
        .map(|q| p.truth.world_to_tool(&off(q)).unwrap().translation.vector)
        .collect();
    let images: Vec<ImagePose> = p
        .cal_joints
        .iter()
        .zip(&true_joints)
        .map(|(q, q_true)| {
            let inv = p.truth.world_to_tool(q_true).unwrap().inverse();
            ImagePose {
                joints_rad: q.clone(),
                observations: p
                    .spec
                    .board
                    .points()
                    .into_iter()
                    .map(|x| {
                        let uv = p.spec.intrinsics.project(&(inv * x)).unwrap();
                        let e = Vector2::new(pixel.sample(rng), pixel.sample(rng));
                        (x, Point2::from(uv.coords + e))
                    })
                    .collect(),
            }
        })
        .collect();
    let noise = ImageNoise {
        sigma_px: p.spec.pixel_sigma_px,
        joint: JointNoise::Known { sigma_rad: sigma_q },
    };
    let fit = joint_refine(&p.truth, &p.spec.intrinsics, &images, &p.free, noise, false).unwrap();
    let layout = ParamLayout::new(&p.truth.robot, Instrument::Camera);
    let dx = layout.difference(&fit.model, &p.truth);
    let (a, b) = (fit.intrinsics, p.spec.intrinsics);
    let di = [
        a.fx - b.fx,
        a.fy - b.fy,
        a.cx - b.cx,
        a.cy - b.cy,
        a.k1 - b.k1,
        a.k2 - b.k2,
        a.p1 - b.p1,
        a.p2 - b.p2,
    ];
    let error = DVector::from_iterator(
        p.free.len() + di.len(),
        p.free.iter().map(|&i| dx[i]).chain(di),
    );
    let val_ms = p
        .val_joints
        .iter()
        .zip(&val_truth)
        .map(|(q, t)| (fit.model.world_to_tool(q).unwrap().translation.vector - t).norm_squared())
        .sum::<f64>()
        / p.val_joints.len() as f64;
    (error, val_ms)
}

/// `mean(dᵀ Σ⁻¹ d) / n` over the repetitions: 1 when the errors' covariance
/// is `Σ`, with standard error `sqrt(2 / (N n))` for Gaussian errors.
fn whitened_mean(errors: &[DVector<f64>], covariance: &DMatrix<f64>) -> f64 {
    let n = covariance.nrows();
    let inverse = covariance.clone().cholesky().unwrap().inverse();
    errors
        .iter()
        .map(|d| (d.transpose() * &inverse * d)[(0, 0)])
        .sum::<f64>()
        / (errors.len() * n) as f64
}

#[test]
fn the_bound_matches_a_monte_carlo_of_a_small_problem() {
    let p = problem();
    let mut rng = StdRng::seed_from_u64(0x003c_ab1e);
    let runs: Vec<(DVector<f64>, f64)> =
        (0..REPETITIONS).map(|_| repetition(&p, &mut rng)).collect();
    let errors: Vec<DVector<f64>> = runs.iter().map(|r| r.0.clone()).collect();
    // The bound needs only which points each image sees.
    let images: Vec<ImagePose> = p
        .cal_joints
        .iter()
        .map(|q| ImagePose {
            joints_rad: q.clone(),
            observations: p
                .spec
                .board
                .points()
                .into_iter()
                .map(|x| (x, Point2::origin()))
                .collect(),
        })
        .collect();
    let sigma_q = p.spec.encoder_sigma_deg.to_radians();
    let right = bound(&p, &images, p.spec.pixel_sigma_px, sigma_q);
    assert_eq!(right.undetermined, 0);
    let n = right.covariance.nrows();
    let tolerance = STANDARD_ERRORS * (2.0 / (REPETITIONS * n) as f64).sqrt();
    let t = whitened_mean(&errors, &right.covariance);
    // The worst direction too: the whitened sample covariance's extreme
    // eigenvalues, against the Marchenko–Pastur edges (1 ± sqrt(n/N))² of
    // white noise, with a margin for their own fluctuation.
    let inverse_root = right
        .covariance
        .clone()
        .cholesky()
        .unwrap()
        .l()
        .try_inverse()
        .unwrap();
    let mut sample = DMatrix::zeros(n, n);
    for d in &errors {
        let z = &inverse_root * d;
        sample += &z * z.transpose() / REPETITIONS as f64;
    }
    let eigen = sample.symmetric_eigenvalues();
    let ratio = (n as f64 / REPETITIONS as f64).sqrt();
    let (edge_lo, edge_hi) = ((1.0 - ratio).powi(2), (1.0 + ratio).powi(2));
    // Validation: the mean squared 3-D error against the bound's, within
    // the Monte Carlo's own standard error.
    let val: Vec<f64> = runs.iter().map(|r| r.1).collect();
    let val_mean = val.iter().sum::<f64>() / val.len() as f64;
    let val_se = (val.iter().map(|v| (v - val_mean).powi(2)).sum::<f64>()
        / (val.len() * (val.len() - 1)) as f64)
        .sqrt();
    let predicted = right.validation.rms_mm.powi(2);
    // The same statistics with a wrong noise model.
    let wrong_pixel = bound(&p, &images, 1.5 * p.spec.pixel_sigma_px, sigma_q);
    let no_encoder = bound(&p, &images, p.spec.pixel_sigma_px, 0.0);
    let t_pixel = whitened_mean(&errors, &wrong_pixel.covariance);
    let t_encoder = whitened_mean(&errors, &no_encoder.covariance);
    eprintln!(
        "{n} unknowns, {REPETITIONS} runs: whitened {t:.3} (±{tolerance:.3}); eigenvalues {:.3}..{:.3} (edges {edge_lo:.3}..{edge_hi:.3}); validation {:.5} ± {:.5} mm² against {predicted:.5} (parameters {:.4} mm, encoder {:.4} mm); wrong pixel noise {t_pixel:.3}, encoder ignored {t_encoder:.3} (validation {:.5})",
        eigen.min(),
        eigen.max(),
        val_mean,
        val_se,
        right.validation.parameters_rms_mm,
        right.validation.encoder_rms_mm,
        no_encoder.validation.rms_mm.powi(2),
    );
    assert!((t - 1.0).abs() < tolerance, "whitened {t}");
    assert!(
        eigen.min() > 0.75 * edge_lo && eigen.max() < 1.25 * edge_hi,
        "{eigen:?}"
    );
    assert!(
        (val_mean - predicted).abs() < STANDARD_ERRORS * val_se,
        "validation {val_mean} ± {val_se} against {predicted}"
    );
    // Either wrong noise model fails the same test.
    assert!(
        (t_pixel - 1.0).abs() > tolerance,
        "wrong pixel noise passes: {t_pixel}"
    );
    assert!(
        (t_encoder - 1.0).abs() > tolerance,
        "ignored encoder passes: {t_encoder}"
    );
}
