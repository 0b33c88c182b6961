//! Issue 16 on simulated cells: a 30-pose plan identifies the robot at
//! least as well as 60 random poses of the same cell (in expectation at
//! the cell's validation poses: one noise draw's error scatters by half
//! its mean, more than the two differ), and the plan's predicted
//! validation error is within 0.67x–1.5x of what the campaign then
//! achieves (mean over cells and noise draws), for both presets and for a
//! robot sent as a plain DH table with a 5 MP camera. The campaign is identified as a job does it
//! (`sim::planned::calibrate_images`).

use robocal_calib::plan::plan_campaign;
use robocal_calib::plan::request::DEFAULT_CANDIDATES;
use robocal_calib::sim::campaign::{simulate_campaign, CampaignSpec};
use robocal_calib::sim::campaign_io::PoseSet;
use robocal_calib::sim::campaign_kinds::{
    kr16_dh_robot as dh_table_robot, FIVE_MP_INTRINSICS, FIVE_MP_SIZE_PX,
};
use robocal_calib::sim::planned::{calibrate_images, expected_error, plan_request, shoot_with};

/// Cells averaged per preset.
const CELLS: u64 = 3;
/// Noise draws shot per cell. One draw's validation error scatters by
/// about half its mean, with a heavy tail (DH table + 5 MP, 10 draws per
/// cell: 0.009–0.078 mm around a mean of 0.024; BENCHMARKS.md, "Campaign
/// planner"): over 3 x 6 draws the mean's scatter is ~13 %, a third of the
/// issue's 0.67x–1.5x band (with 3 x 3 draws the DH cell measured 1.51x
/// by chance; 10 draws per cell give 0.97x).
const DRAWS: u64 = 6;
const PLANNED_POSES: usize = 30;
const RATIO_RANGE: (f64, f64) = (0.67, 1.5);

/// The simulator's cell for the DH-table robot (a KR 16 class arm as a
/// plain DH table, `sim::campaign_kinds::kr16_dh_robot`) and the 5 MP camera (the
/// standard spec otherwise: errors, noise, ranges, board).
fn dh_table_spec(seed: u64) -> CampaignSpec {
    let mut spec = CampaignSpec::standard("irb2400", seed).unwrap();
    spec.nominal = dh_table_robot();
    spec.intrinsics = FIVE_MP_INTRINSICS;
    spec.image_size = FIVE_MP_SIZE_PX;
    spec
}

fn preset_spec(preset: &'static str) -> impl Fn(u64) -> CampaignSpec {
    move |seed| CampaignSpec::standard(preset, seed).unwrap()
}

fn check(preset: &str, spec_of: impl Fn(u64) -> CampaignSpec) {
    let (mut achieved, mut predicted) = (0.0, 0.0);
    let (mut expected_plan, mut expected_random) = (0.0, 0.0);
    for seed in 1..=CELLS {
        let spec = spec_of(seed);
        let campaign = simulate_campaign(&spec).unwrap();
        // The planner's default: 2,000 feasible candidates (the issue's
        // "thousands"; with 2,000 *generated* stations the PUMA 560 kept
        // ~460 and its plan fell behind 60 random poses).
        let request = plan_request(&spec, &campaign, PLANNED_POSES).unwrap();
        let plan = plan_campaign(&request).unwrap();
        assert_eq!(plan.poses.len(), PLANNED_POSES);
        let feasible = plan.filters.last().unwrap().survivors;
        assert!(feasible >= DEFAULT_CANDIDATES, "{feasible} feasible");
        let joints: Vec<Vec<f64>> = plan.poses.iter().map(|p| p.joints_rad.clone()).collect();
        let random_joints: Vec<Vec<f64>> = campaign
            .poses
            .iter()
            .filter(|p| p.set == PoseSet::Cal)
            .map(|p| p.joints_rad.clone())
            .collect();
        let truth = campaign.truth.model().unwrap();
        let mut cell = 0.0;
        for draw in 0..DRAWS {
            let images = shoot_with(&spec, &truth, &joints, draw).unwrap();
            cell += calibrate_images(&spec, &campaign, &images)
                .unwrap()
                .norm
                .mean_mm;
        }
        let plan_expected = expected_error(&request, &campaign, &joints).unwrap();
        let random_expected = expected_error(&request, &campaign, &random_joints).unwrap();
        println!(
            "{preset} cell {seed}: planned {:.4} mm over {DRAWS} draws (predicted {:.4}, expected at the val poses {plan_expected:.4}), 60 random expected {random_expected:.4}, cond {:.1}",
            cell / DRAWS as f64,
            plan.prediction.validation_error_mean_mm,
            plan.prediction.condition_number
        );
        achieved += cell / DRAWS as f64;
        predicted += plan.prediction.validation_error_mean_mm;
        expected_plan += plan_expected;
        expected_random += random_expected;
    }
    println!(
        "{preset}: planned {:.4} mm, predicted {:.4}; expected planned {:.4}, 60 random {:.4}",
        achieved / CELLS as f64,
        predicted / CELLS as f64,
        expected_plan / CELLS as f64,
        expected_random / CELLS as f64
    );
    // No worse than 60 random poses, compared where one noise draw does
    // not decide: the expected error of both pose sets at the same
    // validation poses.
    assert!(
        expected_plan <= expected_random,
        "expected: planned {expected_plan} vs random {expected_random}"
    );
    let ratio = predicted / achieved;
    assert!(
        (RATIO_RANGE.0..=RATIO_RANGE.1).contains(&ratio),
        "predicted / achieved = {ratio}"
    );
}

#[test]
fn irb2400_plan_beats_random_and_predicts_its_error() {
    check("irb2400", preset_spec("irb2400"));
}

#[test]
fn puma560_plan_beats_random_and_predicts_its_error() {
    check("puma560", preset_spec("puma560"));
}

#[test]
fn dh_table_robot_with_5mp_camera_plan_beats_random_and_predicts_its_error() {
    check("dh-table/5MP", dh_table_spec);
}
