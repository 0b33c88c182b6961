//! Issue 5's accuracy targets through the service's own pipeline (issue 6):
//! rendered campaigns (images, detection, camera step, pose measurement,
//! identification, joint refinement — exactly what a calibration job runs)
//! judged against the simulator's truth (`robocal::testkit::accuracy`):
//!
//! * validation error = predicted vs **true** camera position at the
//!   validation poses, for the default job, the two-step job
//!   (`joint_refinement: false`: per-image poses, then the pose-level fit)
//!   and paper mode (`refine_intrinsics: false`);
//! * the oracle floors of the same campaign (`calib::sim::oracle`) at the
//!   dot noise the pipeline measured;
//! * every identified parameter against the truth in its reported sigmas.
//!
//! ```text
//! cargo run --release --example pipeline_accuracy -- [--campaigns 5 --cal 60 --val 30 --draws 5]
//! ```

use clap::Parser;
use robocal::cli::campaign::{run_local_with, simulate};
use robocal::domain::ParameterSet;
use robocal::schema::job::CalibrationOptions;
use robocal::testkit::accuracy::{compare_with_truth, dot_noise_px, oracle_floors};

/// A parameter further than this many sigmas from the truth is a miss.
const SIGMA_BOUND: f64 = 3.0;

#[derive(Parser)]
struct Args {
    #[arg(long, default_value_t = 5)]
    campaigns: u64,
    /// First campaign seed.
    #[arg(long, default_value_t = 1)]
    first_seed: u64,
    #[arg(long, default_value_t = 60)]
    cal: usize,
    #[arg(long, default_value_t = 30)]
    val: usize,
    /// Noise draws averaged for the correlated and image-level floors.
    #[arg(long, default_value_t = 5)]
    draws: u64,
    #[arg(long, default_value = "irb2400,puma560")]
    robots: String,
}

/// Sums over the campaigns of one preset.
#[derive(Default)]
struct Totals {
    before: f64,
    pipeline: f64,
    two_step: f64,
    paper: f64,
    independent: f64,
    correlated: f64,
    image: f64,
    z_squares: f64,
    z_count: usize,
    all_within: usize,
}

fn main() -> Result<(), String> {
    let args = Args::parse();
    for preset in args.robots.split(',') {
        let mut t = Totals::default();
        for seed in args.first_seed..args.first_seed + args.campaigns {
            let dir = tempfile::tempdir().map_err(|e| e.to_string())?;
            let (spec, campaign) = simulate(preset, dir.path(), args.cal, args.val, seed)?;
            let run = |options: CalibrationOptions| {
                run_local_with(dir.path(), "ACCURACY", options)?
                    .parameter_set
                    .ok_or_else(|| "no parameter set".to_string())
            };
            let set = run(CalibrationOptions::default())?;
            let two_step = run(CalibrationOptions {
                joint_refinement: false,
                ..CalibrationOptions::default()
            })?;
            let paper = run(CalibrationOptions {
                refine_intrinsics: false,
                ..CalibrationOptions::default()
            })?;
            let typed = |v: &robocal::domain::CalibratedSet| -> Result<ParameterSet, String> {
                v.kinematic()
                    .cloned()
                    .ok_or_else(|| "not a kinematic set".into())
            };
            let pipeline = compare_with_truth(&typed(&set.parameters)?, &campaign)?;
            let two_step = compare_with_truth(&typed(&two_step.parameters)?, &campaign)?;
            let paper = compare_with_truth(&typed(&paper.parameters)?, &campaign)?;
            let parsed: robocal::report::Report =
                serde_json::from_value(set.report.clone()).map_err(|e| e.to_string())?;
            let sigma_px = dot_noise_px(&parsed)?;
            let floors = oracle_floors(&spec, &campaign, sigma_px, &pipeline.free, args.draws)?;
            let before = parsed.before.norm.mean_mm;
            let (worst_name, worst_z) = pipeline.worst().cloned().unwrap_or_default();
            let within = worst_z.abs() <= SIGMA_BOUND;
            let mm = pipeline.validation.norm.mean_mm;
            println!(
                "{preset} seed {seed}: before {before:.4} mm (measured) | pipeline {mm:.4} | two-step {:.4} | paper {:.4} | floors: image {:.4}, pose correlated {:.4}, pose independent {:.4} | pipeline/image floor {:.3} | z rms {:.3}, worst {worst_name} {worst_z:+.2} | dot noise {sigma_px:.4} px/axis",
                two_step.validation.norm.mean_mm,
                paper.validation.norm.mean_mm,
                floors.image_mm,
                floors.pose_correlated_mm,
                floors.pose_independent_mm,
                mm / floors.image_mm,
                pipeline.z_rms(),
            );
            t.before += before;
            t.pipeline += mm;
            t.two_step += two_step.validation.norm.mean_mm;
            t.paper += paper.validation.norm.mean_mm;
            t.independent += floors.pose_independent_mm;
            t.correlated += floors.pose_correlated_mm;
            t.image += floors.image_mm;
            t.z_squares += pipeline.z.iter().map(|(_, z)| z * z).sum::<f64>();
            t.z_count += pipeline.z.len();
            t.all_within += usize::from(within);
        }
        let n = args.campaigns as f64;
        println!(
            "SUMMARY {preset} ({} campaigns, {}+{} poses, mean 3-D val error vs truth, mm): before {:.4} | pipeline {:.4} | two-step {:.4} ({:.2}x pipeline) | paper {:.4} | image floor {:.4} | pose floor correlated {:.4} | pose floor independent {:.4} | pipeline / image floor {:.3} | pipeline / pose correlated {:.3} | pipeline / pose independent {:.3} | improvement {:.1}x | all params within {SIGMA_BOUND} sigma {}/{} | z rms {:.3}",
            args.campaigns,
            args.cal,
            args.val,
            t.before / n,
            t.pipeline / n,
            t.two_step / n,
            t.two_step / t.pipeline,
            t.paper / n,
            t.image / n,
            t.correlated / n,
            t.independent / n,
            t.pipeline / t.image,
            t.pipeline / t.correlated,
            t.pipeline / t.independent,
            t.before / t.pipeline,
            t.all_within,
            args.campaigns,
            (t.z_squares / t.z_count.max(1) as f64).sqrt(),
        );
    }
    Ok(())
}
