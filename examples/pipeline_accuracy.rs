//! Issue 5's accuracy targets through the service's own pipeline (issue 6):
//! rendered campaigns (images, detection, camera step, pose measurement,
//! identification, joint refinement — exactly what a calibration job runs)
//! against the oracle floor of the same campaign (`sim::oracle`: true
//! camera poses plus the camera step's noise at the dot noise the pipeline
//! really measured). Validation error = predicted vs **true** camera
//! position at the validation poses.
//!
//! ```text
//! cargo run --release --example pipeline_accuracy -- [--campaigns 5 --cal 60 --val 30]
//! ```

use clap::Parser;
use robocal::campaign::{rendered_spec, run_local, simulate, simulated_target};
use robocal::evaluate::model_of;
use robocal_calib::kinematics::identify::validate;
use robocal_calib::sim::campaign::simulate_campaign;
use robocal_calib::sim::campaign_io::PoseSet;
use robocal_calib::sim::oracle::{oracle_accuracy, truth_measurements};

#[derive(Parser)]
struct Args {
    #[arg(long, default_value_t = 5)]
    campaigns: u64,
    #[arg(long, default_value_t = 60)]
    cal: usize,
    #[arg(long, default_value_t = 30)]
    val: usize,
    #[arg(long, default_value = "irb2400,puma560")]
    robots: String,
}

fn main() -> Result<(), String> {
    let args = Args::parse();
    for preset in args.robots.split(',') {
        let (mut sum_joint, mut sum_oracle, mut sum_before) = (0.0, 0.0, 0.0);
        for seed in 1..=args.campaigns {
            let dir = tempfile::tempdir().map_err(|e| e.to_string())?;
            simulate(preset, dir.path(), args.cal, args.val, seed)?;
            let output = run_local(dir.path(), "ACCURACY")?;
            let set = output.parameter_set.ok_or("no parameter set")?;
            let model = model_of(&set.parameters)?;
            let spec = rendered_spec(preset, args.cal, args.val, seed)?;
            let campaign = simulate_campaign(&spec).map_err(|e| e.to_string())?;
            let val = truth_measurements(&campaign, PoseSet::Val);
            let joint = validate(&model, &val).map_err(|e| e.to_string())?.0;
            let report = &set.report;
            // The camera step's RMS is per dot (2-D residual length); the
            // oracle's noise is per image axis.
            let sigma_px = report["camera"]["reprojection_rms_px"]
                .as_f64()
                .ok_or("report without reprojection RMS")?
                / std::f64::consts::SQRT_2;
            let target = simulated_target();
            let points: Vec<_> = (0..target.rows)
                .flat_map(|r| (0..target.cols).map(move |c| (r, c)))
                .map(|(r, c)| nalgebra::Point3::from(target.dot_centre_mm(r, c)))
                .collect();
            let oracle =
                oracle_accuracy(&spec, &campaign, &points, sigma_px).map_err(|e| e.to_string())?;
            let parsed: robocal::report::Report =
                serde_json::from_value(report.clone()).map_err(|e| e.to_string())?;
            let before = parsed.before.norm.mean_mm;
            println!(
                "{preset} seed {seed}: before {before:.4} mm (measured) | pipeline {:.4} mm | oracle {:.4} mm | pipeline/oracle {:.3} | dot noise {sigma_px:.4} px/axis",
                joint.norm.mean_mm,
                oracle.norm.mean_mm,
                joint.norm.mean_mm / oracle.norm.mean_mm
            );
            sum_joint += joint.norm.mean_mm;
            sum_oracle += oracle.norm.mean_mm;
            sum_before += before;
        }
        let n = args.campaigns as f64;
        println!(
            "SUMMARY {preset} ({} campaigns, {}+{} poses, mean 3-D val error vs truth): before {:.4} mm | pipeline {:.4} mm | oracle {:.4} mm | pipeline/oracle {:.3} | improvement {:.1}x",
            args.campaigns,
            args.cal,
            args.val,
            sum_before / n,
            sum_joint / n,
            sum_oracle / n,
            sum_joint / sum_oracle,
            sum_before / sum_joint
        );
    }
    Ok(())
}
