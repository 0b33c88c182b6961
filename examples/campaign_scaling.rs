//! Issue 12 benchmark: time and peak memory of the calibration pipeline
//! (`calibrate-local`: detect, camera, identify, report) against the number
//! of poses. One rendered campaign of the largest size is written once
//! (cached under `--dir`); each size calibrates its first poses (the same
//! cal/val proportion) in a child process of its own, so each peak RSS
//! (`VmHWM` of `/proc/self/status`) is that run's alone.
//!
//! ```text
//! cargo run --example campaign_scaling -- [--sizes 30,60,120,240,500,1000]
//! ```
//! (the dev profile builds deps and `robocal-calib` at opt-level 2; add
//! `--release` for the numbers of a release build). Rendering 1,000 poses
//! takes about 20 minutes on two busy cores, once.
//! Expected: time about linear in the pose count, memory flat (a job holds
//! the detected points, never the images).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use clap::Parser;
use robocal_calib::sim::campaign_io::{PoseEntry, PoseSet};

#[derive(Parser)]
struct Args {
    #[arg(long, default_value = "puma560")]
    robot: String,
    /// Pose counts to calibrate (the campaign is rendered for the largest).
    #[arg(long, value_delimiter = ',', default_value = "30,60,120,240,500,1000")]
    sizes: Vec<usize>,
    /// Where the rendered campaign is kept between runs.
    #[arg(long, default_value = "target/campaign-scaling")]
    dir: PathBuf,
    /// Internal: calibrate this campaign directory and print the figures.
    #[arg(long, hide = true)]
    one: Option<PathBuf>,
}

/// Share of calibration poses, as in the standard campaigns (45 + 15).
const CAL_SHARE: f64 = 0.75;
const SEED: u64 = 12;

fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("VmHWM:"))
                .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn split(n: usize) -> (usize, usize) {
    let cal = (n as f64 * CAL_SHARE).round() as usize;
    (cal, n - cal)
}

/// A campaign directory of the first `cal` + `val` poses of `full`.
fn subset(full: &Path, n: usize) -> PathBuf {
    let (cal, val) = split(n);
    let entries: Vec<PoseEntry> =
        serde_json::from_str(&std::fs::read_to_string(full.join("poses.json")).unwrap()).unwrap();
    let pick = |set: PoseSet, count: usize| {
        entries
            .iter()
            .filter(move |e| e.set == set)
            .take(count)
            .map(|e| PoseEntry {
                image: format!("../full/{}", e.image),
                ..e.clone()
            })
    };
    let chosen: Vec<PoseEntry> = pick(PoseSet::Cal, cal)
        .chain(pick(PoseSet::Val, val))
        .collect();
    assert_eq!(chosen.len(), n, "the rendered campaign is too small");
    let dir = full.parent().unwrap().join(format!("n{n}"));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(full.join("campaign.json"), dir.join("campaign.json")).unwrap();
    std::fs::write(
        dir.join("poses.json"),
        serde_json::to_string(&chosen).unwrap(),
    )
    .unwrap();
    dir
}

fn main() {
    let args = Args::parse();
    if let Some(dir) = args.one {
        let start = Instant::now();
        let report = robocal::cli::campaign::calibrate_local(&dir, "bench").unwrap();
        let secs = start.elapsed().as_secs_f64();
        println!(
            "{secs:.2} {:.1} {:.3}",
            peak_rss_mb(),
            report.after.norm.mean_mm
        );
        return;
    }
    let largest = *args.sizes.iter().max().expect("at least one size");
    let full = args.dir.join("full");
    let rendered: usize = std::fs::read_to_string(full.join("poses.json"))
        .ok()
        .and_then(|t| serde_json::from_str::<Vec<PoseEntry>>(&t).ok())
        .map_or(0, |e| e.len());
    if rendered < largest {
        let (cal, val) = split(largest);
        eprintln!("rendering {largest} poses into {} ...", full.display());
        let start = Instant::now();
        robocal::cli::campaign::simulate(&args.robot, &full, cal, val, SEED).unwrap();
        eprintln!("rendered in {:.0} s", start.elapsed().as_secs_f64());
    }
    let exe = std::env::current_exe().unwrap();
    println!("| poses | time (s) | s per pose (ms) | peak RSS (MB) | after mean (mm) |");
    println!("|------:|---------:|----------------:|--------------:|----------------:|");
    for &n in &args.sizes {
        let dir = subset(&full, n);
        let out = Command::new(&exe).arg("--one").arg(&dir).output().unwrap();
        assert!(
            out.status.success(),
            "{n} poses: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8_lossy(&out.stdout);
        let figures: Vec<f64> = text
            .split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect();
        println!(
            "| {n} | {:.2} | {:.1} | {:.0} | {:.3} |",
            figures[0],
            1000.0 * figures[0] / n as f64,
            figures[1],
            figures[2]
        );
    }
}
