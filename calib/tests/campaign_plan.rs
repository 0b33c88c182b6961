//! Issue 16 on simulated cells: a 30-pose plan identifies the robot at
//! least as well as 60 random poses of the same cell, and the plan's
//! predicted validation error is within 0.67x–1.5x of what the campaign
//! then achieves (means over a few cells, so that one noise draw does not
//! decide). The campaign is identified as a job does it
//! (`sim::planned::calibrate_images`).

use robocal_calib::plan::plan_campaign;
use robocal_calib::sim::campaign::{simulate_campaign, CampaignSpec};
use robocal_calib::sim::campaign_io::PoseSet;
use robocal_calib::sim::planned::{calibrate_images, plan_request, shoot};

/// Cells averaged per preset.
const CELLS: u64 = 3;
const PLANNED_POSES: usize = 30;
/// Candidates per plan (the issue asks for thousands).
const CANDIDATES: usize = 2000;
const RATIO_RANGE: (f64, f64) = (0.67, 1.5);

fn check(preset: &str) {
    let (mut planned, mut random, mut predicted) = (0.0, 0.0, 0.0);
    for seed in 1..=CELLS {
        let spec = CampaignSpec::standard(preset, seed).unwrap();
        let campaign = simulate_campaign(&spec).unwrap();
        let mut request = plan_request(&spec, &campaign, PLANNED_POSES).unwrap();
        request.candidates = CANDIDATES;
        let plan = plan_campaign(&request).unwrap();
        assert_eq!(plan.poses.len(), PLANNED_POSES);
        let joints: Vec<Vec<f64>> = plan.poses.iter().map(|p| p.joints_rad.clone()).collect();
        let images = shoot(&spec, &campaign, &joints).unwrap();
        let plan_error = calibrate_images(&spec, &campaign, &images)
            .unwrap()
            .norm
            .mean_mm;
        let random_joints: Vec<Vec<f64>> = campaign
            .poses
            .iter()
            .filter(|p| p.set == PoseSet::Cal)
            .map(|p| p.joints_rad.clone())
            .collect();
        let images = shoot(&spec, &campaign, &random_joints).unwrap();
        let random_error = calibrate_images(&spec, &campaign, &images)
            .unwrap()
            .norm
            .mean_mm;
        println!(
            "{preset} cell {seed}: planned {plan_error:.4} mm (predicted {:.4}), 60 random {random_error:.4} mm, cond {:.1}",
            plan.prediction.validation_error_mean_mm, plan.prediction.condition_number
        );
        planned += plan_error;
        random += random_error;
        predicted += plan.prediction.validation_error_mean_mm;
    }
    assert!(planned <= random, "planned {planned} vs random {random}");
    let ratio = predicted / planned;
    assert!(
        (RATIO_RANGE.0..=RATIO_RANGE.1).contains(&ratio),
        "predicted / achieved = {ratio}"
    );
}

#[test]
fn irb2400_plan_beats_random_and_predicts_its_error() {
    check("irb2400");
}

#[test]
fn puma560_plan_beats_random_and_predicts_its_error() {
    check("puma560");
}
