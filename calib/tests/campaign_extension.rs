//! Issue 30, "tell the user what to shoot next", on simulated cells: a
//! weak campaign (six shoulder/elbow configurations of four poses each,
//! only the wrist moving inside a group, `sim::grouped_campaign`) is
//! extended by a plan seeded with its poses; the poses the plan proposes
//! are shot by the same true robot and added, and the validation error at
//! the campaign's spread validation poses falls by the gain the plan
//! predicted, within 1.5x (mean over cells and noise draws: one draw's
//! error scatters by half its mean). Both campaigns are identified as a
//! job does it (`sim::planned::calibrate_images`).

use robocal_calib::plan::plan_campaign;
use robocal_calib::plan::PlanPurpose;
use robocal_calib::sim::campaign::CampaignSpec;
use robocal_calib::sim::campaign_io::PoseSet;
use robocal_calib::sim::grouped_campaign::{simulate_grouped_campaign, Grouping};
use robocal_calib::sim::planned::{calibrate_images, expected_error, plan_request, shoot_with};

/// Cells averaged.
const CELLS: u64 = 3;
/// Noise draws shot per cell. A weak campaign's error lies mostly along
/// its one or two worst directions, so one draw's error scatters by up to
/// three quarters of its mean: 16 draws per cell bring the measured gain's
/// scatter to about a tenth.
const DRAWS: u64 = 16;
/// Poses the extension proposes.
const ADDED_POSES: usize = 12;
/// Spread validation poses of each cell.
const VAL_POSES: usize = 12;
/// Measured gain / predicted gain must lie in this band.
const GAIN_RATIO_RANGE: (f64, f64) = (1.0 / 1.5, 1.5);

#[test]
fn extension_of_a_grouped_campaign_meets_its_predicted_gain() {
    let (mut predicted_gain, mut measured_gain) = (0.0, 0.0);
    for seed in 1..=CELLS {
        let mut spec = CampaignSpec::standard("irb2400", seed).unwrap();
        spec.val_poses = VAL_POSES;
        let campaign = simulate_grouped_campaign(&spec, Grouping::SIX_BY_FOUR).unwrap();
        let existing: Vec<Vec<f64>> = campaign
            .poses
            .iter()
            .filter(|p| p.set == PoseSet::Cal)
            .map(|p| p.joints_rad.clone())
            .collect();
        let mut request = plan_request(&spec, &campaign, ADDED_POSES).unwrap();
        request.purpose = PlanPurpose::Calibration;
        request.existing_joints_rad = existing.clone();
        let plan = plan_campaign(&request).unwrap();
        assert_eq!(plan.poses.len(), ADDED_POSES);
        let before_predicted = plan
            .existing
            .as_ref()
            .and_then(|e| e.validation_error_mean_mm())
            .expect("the grouped campaign determines every parameter");
        let after_predicted = plan.prediction.validation_error_mean_mm;
        let added: Vec<Vec<f64>> = plan.poses.iter().map(|p| p.joints_rad.clone()).collect();
        let all: Vec<Vec<f64>> = existing.iter().chain(&added).cloned().collect();
        let truth = campaign.truth.model().unwrap();
        let (mut before, mut after) = (0.0, 0.0);
        for draw in 0..DRAWS {
            // One draw for both: the existing poses' images are the same.
            let images = shoot_with(&spec, &truth, &all, draw).unwrap();
            before += calibrate_images(&spec, &campaign, &images[..existing.len()])
                .unwrap()
                .norm
                .mean_mm;
            after += calibrate_images(&spec, &campaign, &images)
                .unwrap()
                .norm
                .mean_mm;
        }
        let (before, after) = (before / DRAWS as f64, after / DRAWS as f64);
        // The plan predicts at its own random poses in the request's
        // ranges; at the cell's validation poses for comparison.
        let at_val = (
            expected_error(&request, &campaign, &existing).unwrap(),
            expected_error(&request, &campaign, &all).unwrap(),
        );
        println!(
            "cell {seed}: predicted {before_predicted:.4} -> {after_predicted:.4} mm (at the val poses {:.4} -> {:.4}), measured {before:.4} -> {after:.4} mm over {DRAWS} draws",
            at_val.0, at_val.1
        );
        predicted_gain += before_predicted - after_predicted;
        measured_gain += before - after;
    }
    let ratio = measured_gain / predicted_gain;
    println!("gain: predicted {predicted_gain:.4}, measured {measured_gain:.4}, ratio {ratio:.3}");
    assert!(
        (GAIN_RATIO_RANGE.0..=GAIN_RATIO_RANGE.1).contains(&ratio),
        "measured / predicted gain = {ratio}"
    );
}
