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
    }
    let z_rms: Vec<f64> = sum_sq.iter().map(|s| (s / MC_RUNS as f64).sqrt()).collect();
    eprintln!("RMS(error/sigma), hand-eye [t r], board [t r]: {z_rms:.2?}");
    for (k, z) in z_rms.iter().enumerate() {
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
    let mut empty = views.clone();
    for v in empty.iter_mut().skip(2) {
        v.points.truncate(3);
    }
    assert!(calibrate_flange(&empty, &sim.options()).is_err());
}
