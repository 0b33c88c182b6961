//! Are `forward`'s predicted σ honest through the service's own pipeline
//! (issue "Deploy the result")? Rendered campaigns (images, detection,
//! camera step, identification, joint refinement, the stored covariance),
//! as `tests/it/uncertainty.rs` runs them, for many seeds: per campaign and
//! pooled, RMS over the validation poses of |true error| / predicted σ of
//! the camera pose in the target frame (true error: the served camera pose
//! against the true robot's at the recorded joints).
//!
//! ```text
//! cargo run --example sigma_pipeline -- [--campaigns 10 --first-seed 1 --cal 24 --val 16 --robots irb2400,puma560]
//! ```

use clap::Parser;
use robocal::cli::campaign::{run_local, simulate};
use robocal::domain::ParameterSet;
use robocal::service::uncertainty::Uncertainty;
use robocal_calib::geometry::pose_error;
use robocal_calib::sim::campaign::compliance;
use robocal_calib::sim::campaign_io::PoseSet;

#[derive(Parser)]
struct Args {
    #[arg(long, default_value_t = 10)]
    campaigns: u64,
    #[arg(long, default_value_t = 1)]
    first_seed: u64,
    #[arg(long, default_value_t = 24)]
    cal: usize,
    #[arg(long, default_value_t = 16)]
    val: usize,
    #[arg(long, default_value = "irb2400,puma560")]
    robots: String,
}

fn main() -> Result<(), String> {
    let args = Args::parse();
    for preset in args.robots.split(',') {
        let (mut all_p, mut all_r, mut all_n) = (0.0, 0.0, 0.0);
        for seed in args.first_seed..args.first_seed + args.campaigns {
            let dir = tempfile::tempdir().map_err(|e| e.to_string())?;
            let (_, campaign) = simulate(preset, dir.path(), args.cal, args.val, seed)?;
            let set = run_local(dir.path(), "SIGMA")?
                .parameter_set
                .ok_or("no parameter set")?;
            let notes: Vec<String> = set.report["notes"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(|n| n.as_str())
                .filter(|n| n.contains("noise"))
                .map(str::to_string)
                .collect();
            let report: robocal::report::Report =
                serde_json::from_value(set.report.clone()).map_err(|e| e.to_string())?;
            let dot_px = robocal::testkit::accuracy::dot_noise_px(&report)?;
            let set: ParameterSet = set
                .parameters
                .into_kinematic()
                .ok_or("not a kinematic set")?;
            // The set with its kept terms (none unless the job selected some).
            let model = set.term_model()?;
            let u = Uncertainty::of(&set, &model).ok_or("no covariance")??;
            let truth = campaign.truth.model().map_err(|e| e.to_string())?;
            let (mut sp, mut sr, mut n) = (0.0, 0.0, 0.0);
            let (mut ep, mut gp) = (0.0, 0.0);
            for pose in campaign.poses.iter().filter(|p| p.set == PoseSet::Val) {
                let q = &pose.joints_rad;
                let bent = compliance(&truth.robot, q, campaign.truth.compliance_rad_per_m);
                let e = pose_error(
                    &truth.world_to_tool(&bent).map_err(|e| e.to_string())?,
                    &model.world_to_tool(q).map_err(|e| e.to_string())?,
                );
                let s = u.at(&model, q, None)?;
                sp += (e.rows(0, 3).norm() / s.position_std_mm).powi(2);
                ep += e.rows(0, 3).norm_squared();
                gp += s.position_std_mm.powi(2);
                sr += (e.rows(3, 3).norm() / s.rotation_std_deg.to_radians()).powi(2);
                n += 1.0;
            }
            println!(
                "{preset} seed {seed}: RMS(error/σ) position {:.3}, rotation {:.3}; RMS error {:.4} mm, RMS σ {:.4} mm; dot noise {dot_px:.4} px; {notes:?}",
                (sp / n).sqrt(),
                (sr / n).sqrt(),
                (ep / n).sqrt(),
                (gp / n).sqrt(),
            );
            all_p += sp;
            all_r += sr;
            all_n += n;
        }
        println!(
            "SUMMARY {preset}: {} campaigns, {all_n} validation poses: RMS(error/σ) position {:.3}, rotation {:.3}",
            args.campaigns,
            (all_p / all_n).sqrt(),
            (all_r / all_n).sqrt()
        );
    }
    Ok(())
}
