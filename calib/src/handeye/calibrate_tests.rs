//! The flange bundle against the simulator's truth: the clean fit, and the
//! honesty of its standard deviations by Monte Carlo (issue 14).

use nalgebra::Vector6;

use super::test_campaign::FlangeCampaign;
use super::*;
use crate::geometry::pose_error;

/// Monte-Carlo noise draws for the sigma check.
const MC_RUNS: u64 = 30;
/// Bounds on RMS(error / sigma) the issue asks for.
const Z_RMS_RANGE: (f64, f64) = (0.5, 2.0);

fn errors(fit: &FlangeCalibration, sim: &FlangeCampaign) -> (Vector6<f64>, Vector6<f64>) {
    (
        pose_error(&fit.flange_to_camera, &sim.flange_to_camera),
        pose_error(&fit.target_to_base, &sim.target_to_base),
    )
}

fn sigmas(s: &PoseSigma) -> Vector6<f64> {
    let r = s.rotation_deg.map(f64::to_radians);
    Vector6::new(
        s.translation_mm[0],
        s.translation_mm[1],
        s.translation_mm[2],
        r[0],
        r[1],
        r[2],
    )
}

#[test]
fn clean_campaign_recovers_the_truth_within_its_sigmas() {
    let sim = FlangeCampaign::new(11);
    let fit = calibrate_flange(&sim.views(None), &sim.options()).unwrap();
    assert!(
        fit.per_pose.iter().all(|p| !p.outlier),
        "{:?}",
        fit.per_pose
    );
    let sigma_px = sim.campaign.truth.pixel_sigma_px;
    assert!(
        (fit.sigma_px / sigma_px - 1.0).abs() < 0.1,
        "sigma {}",
        fit.sigma_px
    );
    let (ex, et) = errors(&fit, &sim);
    let (sx, st) = (
        sigmas(&fit.flange_to_camera_sigma),
        sigmas(&fit.target_to_base_sigma),
    );
    for k in 0..6 {
        assert!(
            ex[k].abs() < 4.0 * sx[k],
            "hand-eye {k}: {} vs sigma {}",
            ex[k],
            sx[k]
        );
        assert!(
            et[k].abs() < 4.0 * st[k],
            "board {k}: {} vs sigma {}",
            et[k],
            st[k]
        );
    }
    let truth = sim.intrinsics();
    assert!((fit.intrinsics.fx - truth.fx).abs() < 4.0 * fit.intrinsics_sigma.fx);
    assert!((fit.intrinsics.k1 - truth.k1).abs() < 4.0 * fit.intrinsics_sigma.k1);
    // The figures are small in absolute terms too (0.1 px noise).
    assert!(
        ex.fixed_rows::<3>(0).norm() < 0.5,
        "hand-eye translation {ex}"
    );
    assert!(ex.fixed_rows::<3>(3).norm() < 1e-3);
}

#[test]
fn sigmas_are_honest_by_monte_carlo() {
    let sim = FlangeCampaign::new(12);
    let options = sim.options();
    let mut sum_sq = [0.0; 12];
    let mut jack_sq = [0.0; 12];
    for run in 0..MC_RUNS {
        let fit = calibrate_flange(&sim.views(Some(1000 + run)), &options).unwrap();
        assert!(fit.per_pose.iter().all(|p| !p.outlier));
        let (ex, et) = errors(&fit, &sim);
        let (sx, st) = (
            sigmas(&fit.flange_to_camera_sigma),
            sigmas(&fit.target_to_base_sigma),
        );
        for k in 0..6 {
            sum_sq[k] += (ex[k] / sx[k]).powi(2);
            sum_sq[6 + k] += (et[k] / st[k]).powi(2);
        }
        let jack = fit.jackknife.unwrap();
        let (jx, jt) = (sigmas(&jack.flange_to_camera), sigmas(&jack.target_to_base));
        for k in 0..6 {
            jack_sq[k] += (ex[k] / jx[k]).powi(2);
            jack_sq[6 + k] += (et[k] / jt[k]).powi(2);
        }
    }
    let z_rms: Vec<f64> = sum_sq.iter().map(|s| (s / MC_RUNS as f64).sqrt()).collect();
    let z_jack: Vec<f64> = jack_sq
        .iter()
        .map(|s| (s / MC_RUNS as f64).sqrt())
        .collect();
    eprintln!("RMS(error/sigma), hand-eye [t r], board [t r]: {z_rms:.2?}");
    eprintln!("RMS(error/jackknife sigma), same order: {z_jack:.2?}");
    for (k, z) in z_rms.iter().chain(&z_jack).enumerate() {
        assert!(
            (Z_RMS_RANGE.0..=Z_RMS_RANGE.1).contains(z),
            "component {k}: RMS(error/sigma) = {z:.2}"
        );
    }
}

#[test]
fn too_few_poses_is_an_error_not_a_panic() {
    let sim = FlangeCampaign::new(13);
    let views = sim.views(None);
    assert!(matches!(
        calibrate_flange(&views[..2], &sim.options()),
        Err(HandEyeError::TooFewPoses { .. })
    ));
    let mut poisoned = views.clone();
    poisoned[4].base_to_flange.translation.vector.x = f64::NAN;
    let fit = calibrate_flange(&poisoned, &sim.options()).unwrap();
    assert!(fit.per_pose[4].outlier);
    assert!(fit.per_pose[4]
        .reason
        .as_deref()
        .unwrap()
        .contains("not finite"));
    assert_eq!(fit.per_pose.iter().filter(|p| p.outlier).count(), 1);
    let mut empty = views.clone();
    for v in empty.iter_mut().skip(2) {
        v.points.truncate(3);
    }
    assert!(calibrate_flange(&empty, &sim.options()).is_err());
}

/// Flange-pose noise of a controller that is not exact (mm, deg).
const FLANGE_NOISE_MM: f64 = 0.3;
const FLANGE_NOISE_DEG: f64 = 0.03;

/// With noisy flange poses the formal sigmas (white pixel noise) are too
/// small; the jackknife's stay honest.
#[test]
fn jackknife_sigmas_are_honest_with_noisy_flange_poses() {
    use rand::{rngs::StdRng, SeedableRng};
    use rand_distr::{Distribution, Normal};
    let sim = FlangeCampaign::new(14);
    let options = sim.options();
    let mut formal_sq = [0.0; 6];
    let mut jack_sq = [0.0; 6];
    for run in 0..MC_RUNS {
        let mut rng = StdRng::seed_from_u64(5000 + run);
        let (t, r) = (
            Normal::new(0.0, FLANGE_NOISE_MM).unwrap(),
            Normal::new(0.0, FLANGE_NOISE_DEG.to_radians()).unwrap(),
        );
        let mut views = sim.views(Some(3000 + run));
        for v in views.iter_mut() {
            let d = Vector6::from_fn(|i, _| {
                if i < 3 {
                    t.sample(&mut rng)
                } else {
                    r.sample(&mut rng)
                }
            });
            v.base_to_flange = crate::geometry::perturb_left(&v.base_to_flange, &d);
        }
        let fit = calibrate_flange(&views, &options).unwrap();
        assert!(fit.per_pose.iter().all(|p| !p.outlier));
        let ex = pose_error(&fit.flange_to_camera, &sim.flange_to_camera);
        let formal = sigmas(&fit.flange_to_camera_sigma);
        let jack = sigmas(&fit.jackknife.unwrap().flange_to_camera);
        for k in 0..6 {
            formal_sq[k] += (ex[k] / formal[k]).powi(2);
            jack_sq[k] += (ex[k] / jack[k]).powi(2);
        }
    }
    let z = |s: &[f64; 6]| s.map(|v| (v / MC_RUNS as f64).sqrt());
    eprintln!(
        "noisy flange poses, hand-eye RMS(error/sigma): formal {:.2?}, jackknife {:.2?}",
        z(&formal_sq),
        z(&jack_sq)
    );
    for (k, v) in z(&jack_sq).iter().enumerate() {
        assert!(
            (Z_RMS_RANGE.0..=Z_RMS_RANGE.1).contains(v),
            "component {k}: {v:.2}"
        );
    }
}

/// Noise draws of the errors-in-variables check (each runs the noise
/// estimation and a jackknife: kept small).
const EIV_RUNS: u64 = 8;

/// Flange noise estimated from the data: its size is found, and the formal
/// sigmas (which then include it) are honest.
#[test]
fn estimated_flange_noise_makes_formal_sigmas_honest() {
    use rand::{rngs::StdRng, SeedableRng};
    use rand_distr::{Distribution, Normal};
    let sim = FlangeCampaign::new(15);
    let options = FlangeOptions {
        estimate_flange_noise: true,
        ..sim.options()
    };
    let mut z_sq = [0.0; 6];
    let mut noise_t = Vec::new();
    let mut noise_r = Vec::new();
    for run in 0..EIV_RUNS {
        let mut rng = StdRng::seed_from_u64(7000 + run);
        let (t, r) = (
            Normal::new(0.0, FLANGE_NOISE_MM).unwrap(),
            Normal::new(0.0, FLANGE_NOISE_DEG.to_radians()).unwrap(),
        );
        let mut views = sim.views(Some(6000 + run));
        for v in views.iter_mut() {
            let d = Vector6::from_fn(|i, _| {
                if i < 3 {
                    t.sample(&mut rng)
                } else {
                    r.sample(&mut rng)
                }
            });
            v.base_to_flange = crate::geometry::perturb_left(&v.base_to_flange, &d);
        }
        let fit = calibrate_flange(&views, &options).unwrap();
        let noise = fit.flange_noise.unwrap();
        noise_t.push(noise.translation_mm);
        noise_r.push(noise.rotation_rad.to_degrees());
        let ex = pose_error(&fit.flange_to_camera, &sim.flange_to_camera);
        let s = sigmas(&fit.flange_to_camera_sigma);
        for k in 0..6 {
            z_sq[k] += (ex[k] / s[k]).powi(2);
        }
    }
    let z = z_sq.map(|v| (v / EIV_RUNS as f64).sqrt());
    eprintln!(
        "estimated flange noise: t {noise_t:.3?} mm, r {noise_r:.4?} deg (true {FLANGE_NOISE_MM}, {FLANGE_NOISE_DEG}); hand-eye RMS(error/formal sigma) {z:.2?}"
    );
    let median = |v: &[f64]| super::robust::median(v);
    assert!((median(&noise_t) / FLANGE_NOISE_MM).ln().abs() < 2f64.ln());
    assert!((median(&noise_r) / FLANGE_NOISE_DEG).ln().abs() < 2f64.ln());
    for (k, v) in z.iter().enumerate() {
        assert!(
            (Z_RMS_RANGE.0..=Z_RMS_RANGE.1).contains(v),
            "component {k}: {v:.2}"
        );
    }
}
