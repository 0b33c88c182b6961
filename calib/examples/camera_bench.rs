//! Benchmark (issue 4): time to calibrate 60 images' points, beside OpenCV's
//! `calibrateCamera` on the same points in the same run.
//!
//! `cargo run --release -p robocal-calib --example camera_bench -- [repeats]`
//! (runs `python3 bench/opencv_calibrate.py`; needs opencv-python-headless):
//! the default campaigns of both issue-4 cameras; `-- [repeats] legacy`: the
//! first design's campaign (9x9 board placed at random, 1280x1024).

use std::io::Write;
use std::time::Instant;

use robocal_calib::camera::{calibrate, CalibrationOptions, CameraCalibration, ViewObservations};
use robocal_calib::sim::point_views::{simulate_views, Board, ViewCampaignSpec, ViewLayout};

const SCRIPT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../bench/opencv_calibrate.py");

/// Process CPU seconds (user + system) from /proc/self/stat (Linux, 100 Hz
/// ticks): on the shared, loaded box wall time mostly measures the others.
fn cpu_seconds() -> f64 {
    const TICKS_PER_SECOND: f64 = 100.0;
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let fields: Vec<&str> = stat
        .rsplit(')')
        .next()
        .unwrap_or("")
        .split_whitespace()
        .collect();
    let tick = |i: usize| {
        fields
            .get(i)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    (tick(11) + tick(12)) / TICKS_PER_SECOND
}

/// Median wall time and mean CPU time per calibration.
fn median_seconds(
    repeats: usize,
    views: &[ViewObservations],
    options: &CalibrationOptions,
) -> (f64, f64, CameraCalibration) {
    let mut times = Vec::new();
    let mut last = None;
    let cpu0 = cpu_seconds();
    for _ in 0..repeats {
        let start = Instant::now();
        last = Some(calibrate(views, options).expect("calibration"));
        times.push(start.elapsed().as_secs_f64());
    }
    let cpu = (cpu_seconds() - cpu0) / repeats as f64;
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], cpu, last.expect("repeats >= 1"))
}

/// Writes the campaign's points for the OpenCV script; returns the path.
fn write_points(views: &[ViewObservations], tag: &str) -> std::path::PathBuf {
    let path = std::env::temp_dir().join(format!(
        "robocal_camera_bench_{}_{tag}.csv",
        std::process::id()
    ));
    let mut file = std::fs::File::create(&path).expect("temp file");
    writeln!(file, "view,row,col,x_mm,y_mm,z_mm,u_px,v_px").unwrap();
    for (v, view) in views.iter().enumerate() {
        for d in &view.dots {
            let (t, p) = (d.target_mm, d.pixel);
            writeln!(
                file,
                "{v},{},{},{},{},{},{:.10},{:.10}",
                d.row, d.col, t.x, t.y, t.z, p.x, p.y
            )
            .unwrap();
        }
    }
    path
}

/// OpenCV's CPU seconds per call for `key` (a model) in the script's JSON.
fn opencv_cpu(json: &str, key: &str) -> Option<f64> {
    let v: serde_json::Value = serde_json::from_str(json).ok()?;
    v.get(key)?.get("cpu_seconds_mean")?.as_f64()
}

fn bench(spec: &ViewCampaignSpec, repeats: usize) {
    let sims = simulate_views(spec).expect("simulation");
    let views: Vec<ViewObservations> = sims.iter().map(|s| s.observations.clone()).collect();
    let size = spec.image_size;
    let path = write_points(&views, &format!("{}x{}", size.width, size.height));
    let points: usize = views.iter().map(|v| v.dots.len()).sum();
    let b = spec.board;
    println!(
        "== campaign: {} views, {points} points ({}x{} board), {}x{}, noise {} px",
        views.len(),
        b.rows,
        b.cols,
        size.width,
        size.height,
        spec.noise_px
    );
    let mut ours = Vec::new();
    for (label, key, options) in [
        (
            "robocal refined (k1,k2,p1,p2), no bias correction",
            Some("k1k2p1p2"),
            CalibrationOptions::default(),
        ),
        (
            "robocal refined (k1,k2,p1,p2) + bias correction",
            None,
            CalibrationOptions {
                dot_diameter_mm: Some(spec.board.dot_diameter_mm),
                ..Default::default()
            },
        ),
        (
            "robocal refined (k1,k2,p1,p2,k3)",
            Some("k1k2p1p2k3"),
            CalibrationOptions {
                estimate_k3: true,
                ..Default::default()
            },
        ),
    ] {
        let (secs, cpu, cal) = median_seconds(repeats, &views, &options);
        let i = cal.intrinsics;
        println!(
            "{label:52} wall median {secs:.3} s  cpu mean {cpu:.3} s  rms {:.5} px  fx {:.3} fy {:.3} cx {:.3} cy {:.3}",
            cal.rms_px, i.fx, i.fy, i.cx, i.cy
        );
        if let Some(key) = key {
            ours.push((key, cpu));
        }
    }
    let output = std::process::Command::new("python3")
        .args([
            SCRIPT,
            path.to_str().unwrap(),
            &size.width.to_string(),
            &size.height.to_string(),
            &repeats.to_string(),
        ])
        .output();
    match output {
        Ok(o) if o.status.success() => {
            let json = String::from_utf8_lossy(&o.stdout);
            println!("opencv: {}", json.trim());
            for (key, cpu) in ours {
                if let Some(theirs) = opencv_cpu(&json, key) {
                    println!("{key}: OpenCV cpu / robocal cpu = {:.2}", theirs / cpu);
                }
            }
        }
        Ok(o) => println!(
            "opencv script failed: {}",
            String::from_utf8_lossy(&o.stderr)
        ),
        Err(e) => println!("could not run python3: {e}"),
    }
    let _ = std::fs::remove_file(&path);
    let t = spec.intrinsics;
    println!("truth: fx {} fy {} cx {} cy {}", t.fx, t.fy, t.cx, t.cy);
}

fn main() {
    let repeats: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(5)
        .max(1);
    if std::env::args().nth(2).as_deref() == Some("legacy") {
        // The first campaign design: the 9x9 board placed at random.
        bench(
            &ViewCampaignSpec {
                board: Board::standard(),
                layout: ViewLayout::Random,
                ..ViewCampaignSpec::modern_1280x1024(2024)
            },
            repeats,
        );
        return;
    }
    bench(&ViewCampaignSpec::modern_1280x1024(2024), repeats);
    bench(&ViewCampaignSpec::paper_752x582(2024), repeats);
}
