//! Campaign planning for BENCHMARKS.md (issue 16): the time to plan 30
//! poses from >= 2,000 candidates (split into candidate generation, the
//! per-pose information and the D-optimal selection), predicted vs
//! achieved validation error over simulated cells of both presets, and
//! planned vs random poses at 10, 20, 30 and 60 poses.
//! `cargo run -p robocal-calib --example plan_bench -- [cells per preset]`

use std::time::Instant;

use robocal_calib::plan::candidates::{generate, limited_model};
use robocal_calib::plan::information::{pose_factor, Columns};
use robocal_calib::plan::select::d_optimal;
use robocal_calib::plan::{plan_campaign, PlanPurpose};
use robocal_calib::sim::campaign::{simulate_campaign, CampaignSpec};
use robocal_calib::sim::campaign_io::PoseSet;
use robocal_calib::sim::planned::{calibrate_images, plan_request, shoot};

const PLANNED: usize = 30;
const COUNTS: [usize; 4] = [10, 20, 30, 60];
const PRESETS: [&str; 2] = ["irb2400", "puma560"];

fn main() {
    let cells: u64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(5);
    // Plan time, one core (the planner is single-threaded).
    for preset in PRESETS {
        let spec = CampaignSpec::standard(preset, 1).expect("preset");
        let campaign = simulate_campaign(&spec).expect("campaign");
        let request = plan_request(&spec, &campaign, PLANNED).expect("request");
        let t0 = Instant::now();
        let set = generate(&request).expect("candidates");
        let t1 = Instant::now();
        let model = limited_model(&request).expect("model");
        let columns = Columns::of(&request, &model).expect("columns");
        let factors: Vec<_> = set
            .candidates
            .iter()
            .filter_map(|c| pose_factor(&request, &model, &columns, &c.joints_rad))
            .collect();
        let t2 = Instant::now();
        let chosen = d_optimal(&factors, columns.len(), PLANNED);
        let t3 = Instant::now();
        let total = Instant::now();
        let plan = plan_campaign(&request).expect("plan");
        let total = total.elapsed().as_secs_f64();
        println!(
            "{preset}: {} generated, {} feasible, {} parameters; candidates {:.2} s, information {:.2} s, selection of {} {:.2} s; plan_campaign {total:.2} s, path {:.0} deg",
            request.candidates,
            factors.len(),
            columns.len(),
            (t1 - t0).as_secs_f64(),
            (t2 - t1).as_secs_f64(),
            chosen.len(),
            (t3 - t2).as_secs_f64(),
            plan.path_length_rad.to_degrees()
        );
    }
    // Predicted vs achieved, planned vs random.
    let mut ratios = Vec::new();
    for preset in PRESETS {
        let mut planned_sum = [0.0; COUNTS.len()];
        let mut random_sum = [0.0; COUNTS.len()];
        for seed in 1..=cells {
            let spec = CampaignSpec::standard(preset, seed).expect("preset");
            let campaign = simulate_campaign(&spec).expect("campaign");
            let random: Vec<Vec<f64>> = campaign
                .poses
                .iter()
                .filter(|p| p.set == PoseSet::Cal)
                .map(|p| p.joints_rad.clone())
                .collect();
            for (k, &n) in COUNTS.iter().enumerate() {
                let mut request = plan_request(&spec, &campaign, n).expect("request");
                request.purpose = PlanPurpose::Calibration;
                let plan = plan_campaign(&request).expect("plan");
                let joints: Vec<Vec<f64>> =
                    plan.poses.iter().map(|p| p.joints_rad.clone()).collect();
                let achieved = calibrate_images(
                    &spec,
                    &campaign,
                    &shoot(&spec, &campaign, &joints).expect("shoot"),
                )
                .expect("calibrate")
                .norm
                .mean_mm;
                let baseline = calibrate_images(
                    &spec,
                    &campaign,
                    &shoot(&spec, &campaign, &random[..n]).expect("shoot"),
                )
                .map_or(f64::NAN, |s| s.norm.mean_mm);
                planned_sum[k] += achieved;
                random_sum[k] += baseline;
                if n == PLANNED {
                    let predicted = plan.prediction.validation_error_mean_mm;
                    ratios.push(achieved / predicted);
                    println!(
                        "{preset} cell {seed}: {n} planned achieved {achieved:.4} mm, predicted {predicted:.4} mm (achieved/predicted {:.2}), cond {:.0}",
                        achieved / predicted,
                        plan.prediction.condition_number
                    );
                }
            }
        }
        for (k, &n) in COUNTS.iter().enumerate() {
            println!(
                "{preset}: {n} poses: planned {:.4} mm, random {:.4} mm (mean over {cells} cells)",
                planned_sum[k] / cells as f64,
                random_sum[k] / cells as f64
            );
        }
    }
    let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
    let (lo, hi) = ratios
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(l, h), r| (l.min(*r), h.max(*r)));
    println!(
        "achieved/predicted over {} cells: mean {mean:.2}, min {lo:.2}, max {hi:.2}",
        ratios.len()
    );
}
