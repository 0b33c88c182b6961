//! Campaign planning for BENCHMARKS.md (issue 16): the CPU time to plan 30
//! poses from >= 2,000 feasible candidates (split into candidate
//! generation, the per-pose information and the rest: selection,
//! prediction, path), predicted vs achieved validation error over
//! simulated cells of both presets, and planned (D- and I-optimal) vs
//! random poses at 10, 20, 30 and 60 poses, achieved and expected.
//! `cargo run --release -p robocal-calib --example plan_bench -- [cells per preset]`
//! (0 cells: the plan time only).

use std::time::Instant;

use robocal_calib::plan::candidates::{generate, limited_model};
use robocal_calib::plan::information::{pose_factor, Columns};
use robocal_calib::plan::{plan_campaign, PlanCriterion, PlanPurpose};
use robocal_calib::sim::campaign::{simulate_campaign, Campaign, CampaignSpec};
use robocal_calib::sim::campaign_io::PoseSet;
use robocal_calib::sim::planned::{calibrate_images, expected_error, plan_request, shoot};

const PLANNED: usize = 30;
const COUNTS: [usize; 4] = [10, 20, 30, 60];
const PRESETS: [&str; 2] = ["irb2400", "puma560"];
/// Feasible candidates the plans choose from (the floor; the
/// planner generates stations until this many are feasible).
const MIN_FEASIBLE: usize = 2000;

/// The achieved validation error (mm) of a campaign shot at `joints`, or
/// why it failed (a board point left the image, an identification failed).
fn achieved(spec: &CampaignSpec, campaign: &Campaign, joints: &[Vec<f64>]) -> Result<f64, String> {
    let images = shoot(spec, campaign, joints).map_err(|e| e.to_string())?;
    calibrate_images(spec, campaign, &images)
        .map(|s| s.norm.mean_mm)
        .map_err(|e| e.to_string())
}

/// CPU time of the calling thread (s), from `/proc/thread-self/schedstat`
/// (Linux; NaN elsewhere).
fn cpu_s() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |ns| ns * 1e-9)
}

/// Sum and count of the figures that exist.
#[derive(Clone, Copy, Default)]
struct Mean(f64, usize);

impl Mean {
    fn add(&mut self, v: Option<f64>) {
        if let Some(v) = v.filter(|v| v.is_finite()) {
            self.0 += v;
            self.1 += 1;
        }
    }
    fn get(self) -> f64 {
        self.0 / self.1.max(1) as f64
    }
}

fn main() {
    let cells: u64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(5);
    // Plan time, one core (the planner is single-threaded): CPU time of
    // this thread, so that other processes on a shared machine do not
    // count; wall time alongside.
    for preset in PRESETS {
        let spec = CampaignSpec::standard(preset, 1).expect("preset");
        let campaign = simulate_campaign(&spec).expect("campaign");
        let mut request = plan_request(&spec, &campaign, PLANNED).expect("request");
        request.candidates = MIN_FEASIBLE;
        let t0 = cpu_s();
        let set = generate(&request).expect("candidates");
        let t1 = cpu_s();
        let model = limited_model(&request).expect("model");
        let columns = Columns::of(&request, &model).expect("columns");
        let feasible = set
            .candidates
            .iter()
            .filter_map(|c| pose_factor(&request, &model, &columns, &c.joints_rad))
            .count();
        let t2 = cpu_s();
        let (generated, parameters) = (set.filters[0].survivors, columns.len());
        let (candidates_s, information_s) = (t1 - t0, t2 - t1);
        let (cpu, wall) = (cpu_s(), Instant::now());
        let plan = plan_campaign(&request).expect("plan");
        let (cpu, wall) = (cpu_s() - cpu, wall.elapsed().as_secs_f64());
        println!(
            "{preset}: {generated} stations generated, {feasible} feasible, {parameters} parameters; plan_campaign of {PLANNED} (criterion {:?}) {cpu:.2} s CPU ({wall:.2} s wall): candidates {candidates_s:.2} s, information {information_s:.2} s, selection + prediction + path {:.2} s; path {:.0} deg",
            PlanCriterion::for_purpose(request.purpose),
            cpu - candidates_s - information_s,
            plan.path_length_rad.to_degrees()
        );
    }
    if cells == 0 {
        return;
    }
    // Predicted vs achieved, planned (both criteria) vs random.
    let criteria = [("D", PlanCriterion::D), ("I", PlanCriterion::I)];
    let mut ratios = [Vec::new(), Vec::new()];
    for preset in PRESETS {
        // Per count: achieved and predicted per criterion, random achieved
        // and its expectation.
        let mut achieved_sum = [[Mean::default(); 2]; COUNTS.len()];
        let mut predicted_sum = [[Mean::default(); 2]; COUNTS.len()];
        // The same prediction at the campaign's own `val` poses, for the
        // plans and the random poses alike.
        let mut expected_sum = [[Mean::default(); 2]; COUNTS.len()];
        let mut random_sum = [Mean::default(); COUNTS.len()];
        let mut random_expected = [Mean::default(); COUNTS.len()];
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
                for (c, (name, criterion)) in criteria.iter().enumerate() {
                    request.criterion = Some(*criterion);
                    let plan = plan_campaign(&request).expect("plan");
                    let joints: Vec<Vec<f64>> =
                        plan.poses.iter().map(|p| p.joints_rad.clone()).collect();
                    let predicted = plan.prediction.validation_error_mean_mm;
                    predicted_sum[k][c].add(Some(predicted));
                    expected_sum[k][c].add(expected_error(&request, &campaign, &joints).ok());
                    match achieved(&spec, &campaign, &joints) {
                        Ok(mm) => {
                            achieved_sum[k][c].add(Some(mm));
                            if n == PLANNED {
                                ratios[c].push(mm / predicted);
                                println!(
                                    "{preset} cell {seed}: {n} planned ({name}) achieved {mm:.4} mm, predicted {predicted:.4} mm (achieved/predicted {:.2}), cond {:.0}",
                                    mm / predicted,
                                    plan.prediction.condition_number
                                );
                            }
                        }
                        Err(e) => {
                            println!("{preset} cell {seed}: {n} planned ({name}) failed: {e}")
                        }
                    }
                }
                match achieved(&spec, &campaign, &random[..n]) {
                    Ok(mm) => random_sum[k].add(Some(mm)),
                    Err(e) => println!("{preset} cell {seed}: {n} random failed: {e}"),
                }
                random_expected[k].add(expected_error(&request, &campaign, &random[..n]).ok());
            }
        }
        for (k, &n) in COUNTS.iter().enumerate() {
            println!(
                "{preset}: {n} poses, achieved (expected at the val poses): planned D {:.4} ({:.4}), planned I {:.4} ({:.4}), random {:.4} ({:.4}); planner's prediction D {:.4}, I {:.4}; cells D {} I {} random {}",
                achieved_sum[k][0].get(),
                expected_sum[k][0].get(),
                achieved_sum[k][1].get(),
                expected_sum[k][1].get(),
                random_sum[k].get(),
                random_expected[k].get(),
                predicted_sum[k][0].get(),
                predicted_sum[k][1].get(),
                achieved_sum[k][0].1,
                achieved_sum[k][1].1,
                random_sum[k].1
            );
        }
    }
    for ((name, _), ratios) in criteria.iter().zip(&ratios) {
        let mean = ratios.iter().sum::<f64>() / ratios.len().max(1) as f64;
        let (lo, hi) = ratios
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, h), r| (l.min(*r), h.max(*r)));
        println!(
            "{name}: achieved/predicted at {PLANNED} poses over {} cells: mean {mean:.2}, min {lo:.2}, max {hi:.2}",
            ratios.len()
        );
    }
}
