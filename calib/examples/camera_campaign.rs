//! Simulated camera-calibration campaigns (issue 4): refined and paper mode
//! against the truth. `cargo run --release -p robocal-calib --example camera_campaign [seeds]`

use std::time::Instant;

use robocal_calib::camera::{calibrate, CalibrationMode, CalibrationOptions, CameraCalibration};
use robocal_calib::sim::views::{simulate_views, SimulatedView, ViewCampaignSpec};

fn report(
    name: &str,
    spec: &ViewCampaignSpec,
    sims: &[SimulatedView],
    cal: &CameraCalibration,
    seconds: f64,
) {
    let t = &spec.intrinsics;
    let c = &cal.intrinsics;
    let mut worst_pos: f64 = 0.0;
    let mut sum_sq_centre = 0.0;
    let mut n = 0.0;
    for (s, v) in sims.iter().zip(&cal.views) {
        let truth = s.camera_to_target.inverse().translation.vector;
        let est = v.pose.target_to_camera.translation.vector;
        worst_pos = worst_pos.max((truth - est).norm() / truth.norm());
        if std::env::var("ROBOCAL_DEBUG").is_ok() {
            let cov = v.pose.covariance_6x6;
            eprintln!(
                "pos err {:?} sd {:.4} {:.4} {:.4} angle {:.1} rms {:.4}",
                (est - truth).as_slice(),
                cov[(0, 0)].sqrt(),
                cov[(1, 1)].sqrt(),
                cov[(2, 2)].sqrt(),
                v.board_angle_deg,
                v.rms_px
            );
        }
        // Corrected centre minus the injected noise vs the true centre image:
        // the error of the predicted bias.
        for (((p, q), o), c) in v
            .corrected_pixels
            .iter()
            .zip(&s.true_centre_images)
            .zip(&s.observations.dots)
            .zip(&s.true_centroids)
        {
            let noise = o.pixel - c;
            sum_sq_centre += (p - noise - q).norm_squared();
            n += 1.0;
        }
    }
    println!(
        "{name:28} fx {:+.5}% fy {:+.5}% cx {:+.4} cy {:+.4} px  rms {:.5} px (noise {:.4}, rms/expected {:.3})  worst position 1:{:.0}  centres {:.5} px rms  {:.2} s  bias_it {} outliers {}",
        100.0 * (c.fx - t.fx) / t.fx,
        100.0 * (c.fy - t.fy) / t.fy,
        c.cx - t.cx,
        c.cy - t.cy,
        cal.rms_px,
        spec.noise_px,
        cal.rms_px / (spec.noise_px * 2f64.sqrt()),
        1.0 / worst_pos,
        (sum_sq_centre / n).sqrt(),
        seconds,
        cal.bias_iterations,
        cal.outliers.len(),
    );
    if let Some(sd) = cal.std_dev {
        println!(
            "    std: fx {:.4} fy {:.4} cx {:.4} cy {:.4} k1 {:.2e}",
            sd.fx, sd.fy, sd.cx, sd.cy, sd.k1
        );
    }
    println!("    est {:?}\n    true {:?}", c, t);
}

fn main() {
    let seeds: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    for seed in 0..seeds {
        for (label, spec) in [
            (
                "1280x1024 fy/fx=1",
                ViewCampaignSpec::modern_1280x1024(seed),
            ),
            (
                "752x582 fy/fx=0.9825",
                ViewCampaignSpec::paper_752x582(seed),
            ),
        ] {
            let mut spec = spec;
            if let Some(f) = std::env::var("FX_SCALE")
                .ok()
                .and_then(|v| v.parse::<f64>().ok())
            {
                spec.intrinsics.fx *= f;
                spec.intrinsics.fy *= f;
            }
            if let Some(t) = std::env::var("TILT_MAX")
                .ok()
                .and_then(|v| v.parse::<f64>().ok())
            {
                spec.tilt_deg.1 = t;
            }
            let sims = simulate_views(&spec).expect("simulation");
            let views: Vec<_> = sims.iter().map(|s| s.observations.clone()).collect();
            for mode in [CalibrationMode::Refined, CalibrationMode::Paper] {
                let options = CalibrationOptions {
                    mode,
                    dot_diameter_mm: Some(spec.board.dot_diameter_mm),
                    ..Default::default()
                };
                let start = Instant::now();
                let cal = calibrate(&views, &options).expect("calibration");
                let secs = start.elapsed().as_secs_f64();
                report(
                    &format!("seed {seed} {label} {mode:?}"),
                    &spec,
                    &sims,
                    &cal,
                    secs,
                );
            }
        }
    }
}
