//! Monte-Carlo of simulated camera-calibration campaigns (issue 4): refined
//! and paper mode against the truth, figures for BENCHMARKS.md ("Camera").
//!
//! `cargo run --release -p robocal-calib --example camera_campaign -- [seeds] [noise_px]`

use std::time::Instant;

use robocal_calib::camera::{calibrate, CalibrationMode, CalibrationOptions, CameraCalibration};
use robocal_calib::sim::point_views::{simulate_views, SimulatedView, ViewCampaignSpec};

/// One campaign's errors against the truth.
struct Errors {
    fx_pct: f64,
    fy_pct: f64,
    cx_px: f64,
    cy_px: f64,
    rms_over_noise: f64,
    position_rms_ratio: f64,
    position_worst_ratio: f64,
    corrected_centre_px: f64,
    seconds: f64,
}

fn errors(
    spec: &ViewCampaignSpec,
    sims: &[SimulatedView],
    cal: &CameraCalibration,
    seconds: f64,
) -> Errors {
    let (t, c) = (&spec.intrinsics, &cal.intrinsics);
    let (mut pos_sq, mut dist, mut worst, mut centre_sq, mut n) = (0.0, 0.0, 0.0f64, 0.0, 0.0);
    for (s, v) in sims.iter().zip(&cal.views) {
        let truth = s.camera_to_target.inverse().translation.vector;
        let err = (v.pose.target_to_camera.translation.vector - truth).norm();
        pos_sq += err * err;
        dist += truth.norm();
        worst = worst.max(err / truth.norm());
        for (((p, q), o), centroid) in v
            .corrected_pixels
            .iter()
            .zip(&s.true_centre_images)
            .zip(&s.observations.dots)
            .zip(&s.true_centroids)
        {
            centre_sq += (p - (o.pixel - centroid) - q).norm_squared();
            n += 1.0;
        }
    }
    let k = sims.len() as f64;
    Errors {
        fx_pct: 100.0 * (c.fx - t.fx) / t.fx,
        fy_pct: 100.0 * (c.fy - t.fy) / t.fy,
        cx_px: c.cx - t.cx,
        cy_px: c.cy - t.cy,
        rms_over_noise: cal.rms_px / std::f64::consts::SQRT_2 / spec.noise_px,
        position_rms_ratio: (dist / k) / (pos_sq / k).sqrt(),
        position_worst_ratio: 1.0 / worst,
        corrected_centre_px: (centre_sq / n).sqrt(),
        seconds,
    }
}

fn summarise(label: &str, runs: &[Errors]) {
    let n = runs.len() as f64;
    let rms =
        |f: &dyn Fn(&Errors) -> f64| (runs.iter().map(|e| f(e).powi(2)).sum::<f64>() / n).sqrt();
    let max = |f: &dyn Fn(&Errors) -> f64| runs.iter().map(|e| f(e).abs()).fold(0.0, f64::max);
    let frac =
        |f: &dyn Fn(&Errors) -> bool| 100.0 * runs.iter().filter(|e| f(e)).count() as f64 / n;
    println!("{label} ({} campaigns)", runs.len());
    println!(
        "  fx err %  rms {:.5} max {:.5} | fy err % rms {:.5} max {:.5} | within 0.01%: {:.0}%",
        rms(&|e| e.fx_pct),
        max(&|e| e.fx_pct),
        rms(&|e| e.fy_pct),
        max(&|e| e.fy_pct),
        frac(&|e| e.fx_pct.abs() < 0.01 && e.fy_pct.abs() < 0.01)
    );
    println!("  cx err px rms {:.4} max {:.4} | cy err px rms {:.4} max {:.4} | both within 0.1 px: {:.0}%", rms(&|e| e.cx_px), max(&|e| e.cx_px), rms(&|e| e.cy_px), max(&|e| e.cy_px), frac(&|e| e.cx_px.abs() < 0.1 && e.cy_px.abs() < 0.1));
    println!(
        "  per-axis reprojection rms / noise: mean {:.3} max dev {:.3}",
        runs.iter().map(|e| e.rms_over_noise).sum::<f64>() / n,
        max(&|e| e.rms_over_noise - 1.0)
    );
    println!("  camera position: rms error 1:{:.0} (worst campaign 1:{:.0}), worst single view 1:{:.0} | rms within 1:15000: {:.0}%",
        runs.iter().map(|e| e.position_rms_ratio).sum::<f64>() / n,
        runs.iter().map(|e| e.position_rms_ratio).fold(f64::INFINITY, f64::min),
        runs.iter().map(|e| e.position_worst_ratio).fold(f64::INFINITY, f64::min),
        frac(&|e| e.position_rms_ratio > 15000.0));
    println!(
        "  bias-corrected centres vs true centre images: rms {:.2e} px (max campaign {:.2e})",
        rms(&|e| e.corrected_centre_px),
        max(&|e| e.corrected_centre_px)
    );
    println!(
        "  time per calibration: mean {:.3} s",
        runs.iter().map(|e| e.seconds).sum::<f64>() / n
    );
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let seeds: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(10);
    let noise: Option<f64> = args.get(2).and_then(|s| s.parse().ok());
    for (label, make) in [
        (
            "1280x1024, fy/fx = 1",
            ViewCampaignSpec::modern_1280x1024 as fn(u64) -> ViewCampaignSpec,
        ),
        ("752x582, fy/fx = 0.9825", ViewCampaignSpec::paper_752x582),
    ] {
        let (mut refined, mut paper) = (Vec::new(), Vec::new());
        for seed in 0..seeds {
            let mut spec = make(1000 + seed);
            if let Some(sigma) = noise {
                spec.noise_px = sigma;
            }
            let sims = simulate_views(&spec).expect("simulation");
            let views: Vec<_> = sims.iter().map(|s| s.observations.clone()).collect();
            for (mode, out) in [
                (CalibrationMode::Refined, &mut refined),
                (CalibrationMode::Paper, &mut paper),
            ] {
                let options = CalibrationOptions {
                    mode,
                    dot_diameter_mm: Some(spec.board.dot_diameter_mm),
                    ..Default::default()
                };
                let start = Instant::now();
                let cal = calibrate(&views, &options).expect("calibration");
                out.push(errors(&spec, &sims, &cal, start.elapsed().as_secs_f64()));
            }
        }
        let spec = make(0);
        println!(
            "== {label}: 60 views, {} px noise, fx {}",
            noise.unwrap_or(spec.noise_px),
            spec.intrinsics.fx
        );
        summarise("refined", &refined);
        summarise("paper", &paper);
    }
}
