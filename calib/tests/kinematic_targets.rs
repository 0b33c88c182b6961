//! Issue 5 targets on simulated IRB-2400 and PUMA-560 campaigns (60 cal +
//! 30 val poses), see `sim::experiment`: validation error of the joint
//! refinement against the oracle floor and the two-step pipeline, the
//! before/after improvement, compensation, and every parameter within
//! 3 sigma of the truth. Means over a few campaigns keep one unlucky draw
//! from deciding; the Monte-Carlo figures come from the
//! `kinematics_bench` example (BENCHMARKS.md "Kinematics").

use robocal_calib::sim::campaign::CampaignSpec;
use robocal_calib::sim::experiment::{run_experiment, ExperimentResult};

/// Campaigns averaged per preset in CI.
const CAMPAIGNS: u64 = 4;
const ORACLE_FACTOR: f64 = 1.1;
const MIN_IMPROVEMENT: f64 = 12.0;
/// The two-step pipeline must be worse than the joint refinement by this.
const TWO_STEP_MARGIN: f64 = 1.3;
/// The calibrated model reaches its own targets within this (mm).
const IK_SELF_TOL_MM: f64 = 0.01;
/// Compensated stations vs after-calibration validation error: the same
/// model error, evaluated at slightly different joints.
const COMPENSATION_FACTOR: f64 = 1.05;

fn mean(results: &[ExperimentResult], f: impl Fn(&ExperimentResult) -> f64) -> f64 {
    results.iter().map(f).sum::<f64>() / results.len() as f64
}

fn targets(preset: &str) {
    let results: Vec<ExperimentResult> = (1..=CAMPAIGNS)
        .map(|seed| run_experiment(&CampaignSpec::standard(preset, seed).unwrap()).unwrap())
        .collect();
    let before = mean(&results, |r| r.before.norm.mean_mm);
    let oracle = mean(&results, |r| r.oracle.norm.mean_mm);
    let two_step = mean(&results, |r| r.two_step_plain.norm.mean_mm);
    let weighted = mean(&results, |r| r.two_step_weighted.norm.mean_mm);
    let paper = mean(&results, |r| r.paper.norm.mean_mm);
    let joint = mean(&results, |r| r.joint.norm.mean_mm);
    let comp = mean(&results, |r| r.compensated.norm.mean_mm);
    println!(
        "{preset}: before {before:.4} oracle {oracle:.4} two-step {two_step:.4} (weighted {weighted:.4}) paper {paper:.4} joint {joint:.4} compensated {comp:.4} mm"
    );
    assert!(
        joint <= ORACLE_FACTOR * oracle,
        "joint {joint} vs oracle {oracle}"
    );
    assert!(
        joint * TWO_STEP_MARGIN <= two_step,
        "joint {joint} vs two-step {two_step}"
    );
    assert!(
        joint * TWO_STEP_MARGIN <= weighted,
        "joint {joint} vs weighted {weighted}"
    );
    assert!(
        before >= MIN_IMPROVEMENT * joint,
        "before {before} after {joint}"
    );
    assert!(
        comp <= COMPENSATION_FACTOR * joint,
        "compensated {comp} vs {joint}"
    );
    for r in &results {
        assert!(r.max_ik_residual_mm < IK_SELF_TOL_MM);
        assert_eq!(
            r.fixed,
            ["dtheta_1", "d_1", "dtheta_6", "a_6", "d_6", "alpha_6"]
        );
        assert_eq!(r.free_count, 30);
    }
}

#[test]
fn irb2400_campaign_meets_accuracy_targets() {
    targets("irb2400");
}

#[test]
fn puma560_campaign_meets_accuracy_targets() {
    targets("puma560");
}

/// Relative tolerance on the estimated joint noise (one campaign's
/// variance component has a few tens of percent of scatter).
const JOINT_NOISE_REL_TOL: f64 = 0.4;
/// Largest joint noise estimated when the campaign has none (deg).
const NO_JOINT_NOISE_DEG: f64 = 6e-5;

/// With the campaign's encoder noise (1e-4 deg) estimated from the data by
/// the joint refinement's variance components, every identified parameter
/// lies within 3 standard deviations of the truth expressed in the
/// identified parameterisation; without encoder noise too.
#[test]
fn identified_parameters_lie_within_three_sigma_of_truth() {
    for preset in ["irb2400", "puma560"] {
        for encoder_sigma_deg in [1e-4, 0.0] {
            let mut spec = CampaignSpec::standard(preset, 1).unwrap();
            spec.encoder_sigma_deg = encoder_sigma_deg;
            let r = run_experiment(&spec).unwrap();
            let estimated_deg = r.estimated_joint_sigma_rad.to_degrees();
            println!(
                "{preset} encoder {encoder_sigma_deg:e} deg: estimated {estimated_deg:.3e} deg, worst {:.2} sigma ({})",
                r.worst_sigma_ratio.0, r.worst_sigma_ratio.1
            );
            assert!(
                r.worst_sigma_ratio.0 <= 3.0,
                "{preset}: {:?}",
                r.worst_sigma_ratio
            );
            if encoder_sigma_deg > 0.0 {
                let rel = (estimated_deg / encoder_sigma_deg - 1.0).abs();
                assert!(rel < JOINT_NOISE_REL_TOL, "{preset}: {estimated_deg:e} deg");
            } else {
                // Below ~5e-5 deg these campaigns cannot tell joint noise
                // from none (20-campaign mean 2e-5 deg, BENCHMARKS.md).
                assert!(estimated_deg < NO_JOINT_NOISE_DEG, "{estimated_deg:e}");
            }
        }
    }
}
