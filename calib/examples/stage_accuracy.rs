//! The stage test's figures (issue 18, BENCHMARKS.md "Stage accuracy"):
//! the paper's campaign rendered and detected for a few seeds, calibrated
//! with the stage's translations in the bundle; per sequence the true 3-D
//! position error of every image's camera position (with the stage
//! bundle's intrinsics, and with those of the free calibration that starts
//! it, i.e. without the stage), the paper's Table 1 by the average-rotation
//! method and the travelled-distance error; and the CPU time of the
//! calibration.
//!
//! `cargo run --release -p robocal-calib --example stage_accuracy -- [seeds] [camera]`
//! (default 3 seeds, camera `irb2400`; `puma560` is the paper's 752x582).

use std::time::Instant;

use nalgebra::Vector3;
use robocal_calib::camera::calibrate::CalibrationOptions;
use robocal_calib::camera::pose::estimate_pose;
use robocal_calib::sim::render::RenderOptions;
use robocal_calib::sim::stage_campaign::{simulate_stage, StageSpec};
use robocal_calib::stage::{calibrate_stage, StageView};

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let seeds: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(3);
    let camera = args.get(2).map_or("irb2400", String::as_str);
    println!("seed seq distance_mm | true 3-D mean: stage / free | paper's method |mean|,|median|,|std| vs true | travel mean max | fx-fx_true stage free");
    for seed in 0..seeds {
        let spec = StageSpec::paper_with_camera(camera, 100 + seed);
        let campaign = simulate_stage(&spec).expect("campaign");
        let render = RenderOptions::default();
        let views: Vec<StageView> = (0..campaign.poses.len())
            .map(|i| campaign.rendered_view(i, &render).expect("rendered"))
            .collect();
        let options = CalibrationOptions {
            dot_diameter_mm: Some(spec.target.dot_diameter_mm),
            ..CalibrationOptions::default()
        };
        let started = Instant::now();
        let fit = calibrate_stage(&views, &options).expect("calibration");
        let seconds = started.elapsed().as_secs_f64();
        for acc in &fit.accuracy {
            let (mut stage, mut free) = (Vec::new(), Vec::new());
            let mut truth_errors = Vec::new();
            for (k, pose) in campaign.poses.iter().enumerate() {
                if pose.sequence != acc.sequence {
                    continue;
                }
                let truth = pose.target_to_camera.translation.vector;
                let e = fit.views[k].pose.target_to_camera.translation.vector - truth;
                stage.push(e.norm());
                truth_errors.push(e);
                let used: Vec<_> = views[k]
                    .observations
                    .dots
                    .iter()
                    .zip(&fit.start.views[k].corrected_pixels)
                    .map(|(d, px)| (d.target_mm, *px))
                    .collect();
                let p = estimate_pose(&fit.start.intrinsics, &used, None).expect("pose");
                free.push((p.target_to_camera.translation.vector - truth).norm());
            }
            let t = robocal_calib::stage::assessment::AxisTable::from_errors(&truth_errors);
            let n = |v: [f64; 3]| Vector3::from(v).norm();
            println!(
                "{seed} {} {:.0} | {:.4} / {:.4} | {:.4},{:.4},{:.4} vs {:.4},{:.4},{:.4} | {:.4} {:.4} | {:+.3} {:+.3}",
                acc.sequence,
                acc.distance_mm,
                mean(&stage),
                mean(&free),
                n(acc.mean_mm),
                n(acc.median_mm),
                n(acc.std_mm),
                n(t.mean_mm),
                n(t.median_mm),
                n(t.std_mm),
                acc.travelled_distance_error_mm.mean_mm,
                acc.travelled_distance_error_mm.max_mm,
                fit.intrinsics.fx - spec.intrinsics.fx,
                fit.start.intrinsics.fx - spec.intrinsics.fx,
            );
        }
        println!(
            "seed {seed}: calibrate_stage {seconds:.2} s wall ({} images)",
            views.len()
        );
    }
}
