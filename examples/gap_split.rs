//! Splits the pipeline-vs-oracle gap of `pipeline_accuracy` into its
//! sources: the joint refinement (`kinematics::joint_refine`, the pipeline's
//! last stage) rerun from the pipeline's identified model on
//!
//! * (a) the TRUE images of the dots the pipeline used plus Gaussian noise
//!   of the dot noise the camera stage measured (intrinsics refined, as the
//!   pipeline does); (a') the same with the true intrinsics held;
//! * (b) the detected (bias-corrected) points with the true intrinsics held;
//! * (c) the detected points as the pipeline does (intrinsics refined).
//!
//! If (a) reaches the oracle and (c) does not, the detected points carry a
//! systematic error; if (a) is already far off, the identification is.
//! Errors: mean 3-D validation error against the true camera positions.
//!
//! ```text
//! cargo run --release --example gap_split -- [--robots irb2400 --seeds 1]
//! ```

use clap::Parser;
use nalgebra::Point3;
use rand::{rngs::StdRng, Rng, SeedableRng};
use robocal::cli::campaign::{run_local, simulate, simulated_target};
use robocal::domain::ParameterSet;
use robocal_calib::camera::Intrinsics;
use robocal_calib::kinematics::identify::{validate, JointNoise};
use robocal_calib::kinematics::joint_refine::{joint_refine, ImageNoise, ImagePose};
use robocal_calib::kinematics::{CalibratedModel, Instrument, ParamLayout};
use robocal_calib::sim::campaign::Campaign;
use robocal_calib::sim::campaign_io::PoseSet;
use robocal_calib::sim::oracle::{oracle_accuracy, truth_measurements};

/// Seeds the synthetic dot noise of run (a) apart from the campaign's.
const SYNTH_SEED: u64 = 0x005e_ed0a;

#[derive(Parser)]
struct Args {
    #[arg(long, default_value = "irb2400")]
    robots: String,
    /// Comma-separated campaign seeds.
    #[arg(long, default_value = "1")]
    seeds: String,
    #[arg(long, default_value_t = 60)]
    cal: usize,
    #[arg(long, default_value_t = 30)]
    val: usize,
    /// Noise draws of run (a) averaged (its spread is the estimator's).
    #[arg(long, default_value_t = 3)]
    draws: u64,
}

/// Mean validation error (mm) of a joint refinement from `start`.
#[allow(clippy::too_many_arguments)]
fn refine_error(
    start: &CalibratedModel,
    intrinsics: &Intrinsics,
    images: &[ImagePose],
    free: &[usize],
    sigma_px: f64,
    hold: bool,
    campaign: &Campaign,
) -> Result<(f64, f64, f64, Intrinsics), String> {
    let r = joint_refine(
        start,
        intrinsics,
        images,
        free,
        ImageNoise {
            sigma_px,
            joint: JointNoise::Estimate,
        },
        hold,
    )
    .map_err(|e| e.to_string())?;
    let val = truth_measurements(campaign, PoseSet::Val);
    let err = validate(&r.model, &val).map_err(|e| e.to_string())?.0;
    Ok((
        err.norm.mean_mm,
        r.sigma_px,
        r.joint_sigma_rad.to_degrees(),
        r.intrinsics,
    ))
}

/// A standard normal draw (Box–Muller).
fn gaussian(rng: &mut StdRng) -> f64 {
    let u: f64 = 1.0 - rng.random::<f64>();
    let v: f64 = rng.random::<f64>();
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

fn main() -> Result<(), String> {
    let args = Args::parse();
    let target = simulated_target();
    for preset in args.robots.split(',') {
        for seed in args.seeds.split(',').map(|s| s.parse::<u64>().unwrap()) {
            let dir = tempfile::tempdir().map_err(|e| e.to_string())?;
            let (spec, campaign) = simulate(preset, dir.path(), args.cal, args.val, seed)?;
            let output = run_local(dir.path(), "GAP")?;
            let set = output.parameter_set.ok_or("no parameter set")?;
            let typed: ParameterSet = set
                .parameters
                .into_kinematic()
                .ok_or("not a kinematic set")?;
            let model = typed.model()?;
            let intr_pipe: Intrinsics = typed.camera.ok_or("no camera intrinsics")?;
            let fixed = typed.fixed;
            let layout = ParamLayout::new(&model.robot, Instrument::Camera);
            let free: Vec<usize> = (0..layout.len())
                .filter(|&i| !fixed.contains(&layout.params[i].name))
                .collect();
            let truth = campaign.truth.intrinsics;
            let sigma_px = set.report["camera"]["reprojection_rms_px"]
                .as_f64()
                .ok_or("no rms")?
                / std::f64::consts::SQRT_2;
            let (mut detected, mut synthetic) = (Vec::new(), Vec::new());
            let (mut bias_sum, mut bias_n) = (nalgebra::Vector2::zeros(), 0usize);
            let mut err2 = 0.0;
            for (i, pose) in campaign.poses.iter().enumerate() {
                if pose.set != PoseSet::Cal {
                    continue;
                }
                let id = format!("p{:03}", i + 1);
                let Some(doc) = output.detections.iter().find(|d| d.pose_id == id) else {
                    continue;
                };
                let camera_to_target = pose.target_to_camera.inverse();
                let model_camera_to_target = model
                    .world_to_tool(&pose.joints_rad)
                    .map_err(|e| e.to_string())?
                    .inverse();
                let (mut det, mut syn) = (Vec::new(), Vec::new());
                for p in &doc.detection.points {
                    let Some(residual) = p.residual_px.filter(|_| !p.outlier) else {
                        continue;
                    };
                    let m = target.dot_centre_mm(p.row as usize, p.col as usize);
                    let point = Point3::new(m[0], m[1], m[2]);
                    // The fits use the bias-corrected centres = prediction +
                    // stored residual.
                    let predicted = intr_pipe
                        .project(&(model_camera_to_target * point))
                        .ok_or("behind")?;
                    let observed = predicted + nalgebra::Vector2::new(residual[0], residual[1]);
                    let ideal = truth.project(&(camera_to_target * point)).ok_or("behind")?;
                    let e = observed - ideal;
                    bias_sum += e;
                    bias_n += 1;
                    err2 += e.norm_squared();
                    det.push((point, observed));
                    syn.push((point, ideal));
                }
                if det.is_empty() {
                    continue;
                }
                detected.push(ImagePose {
                    joints_rad: pose.joints_rad.clone(),
                    observations: det,
                });
                synthetic.push(ImagePose {
                    joints_rad: pose.joints_rad.clone(),
                    observations: syn,
                });
            }
            let val = truth_measurements(&campaign, PoseSet::Val);
            let pipeline = validate(&model, &val)
                .map_err(|e| e.to_string())?
                .0
                .norm
                .mean_mm;
            let points: Vec<_> = (0..target.rows)
                .flat_map(|r| (0..target.cols).map(move |c| (r, c)))
                .map(|(r, c)| Point3::from(target.dot_centre_mm(r, c)))
                .collect();
            let oracle = oracle_accuracy(&spec, &campaign, &points, sigma_px)
                .map_err(|e| e.to_string())?
                .norm
                .mean_mm;
            println!(
                "{preset} seed {seed}: pipeline {pipeline:.4} mm | oracle {oracle:.4} mm | ratio {:.3} | dot noise {sigma_px:.4} px/axis | detected-vs-true rms {:.4} px/axis, mean ({:+.4},{:+.4}) px",
                pipeline / oracle,
                (err2 / (2.0 * bias_n as f64)).sqrt(),
                bias_sum.x / bias_n as f64,
                bias_sum.y / bias_n as f64,
            );
            let mut runs: Vec<(String, Vec<ImagePose>, Intrinsics, bool)> = Vec::new();
            for draw in 0..args.draws {
                let mut rng = StdRng::seed_from_u64(seed ^ SYNTH_SEED ^ (draw << 32));
                let noisy: Vec<ImagePose> = synthetic
                    .iter()
                    .map(|p| ImagePose {
                        joints_rad: p.joints_rad.clone(),
                        observations: p
                            .observations
                            .iter()
                            .map(|(x, ideal)| {
                                let noise = nalgebra::Vector2::from_fn(|_, _| {
                                    sigma_px * gaussian(&mut rng)
                                });
                                (*x, ideal + noise)
                            })
                            .collect(),
                    })
                    .collect();
                runs.push((
                    format!("(a)  true pts + noise #{draw}, intr refined"),
                    noisy.clone(),
                    intr_pipe,
                    false,
                ));
                runs.push((
                    format!("(a') true pts + noise #{draw}, true intr held"),
                    noisy,
                    truth,
                    true,
                ));
            }
            runs.push((
                "(b)  detected, true intr held".into(),
                detected.clone(),
                truth,
                true,
            ));
            runs.push((
                "(c)  detected, intr refined (pipeline)".into(),
                detected,
                intr_pipe,
                false,
            ));
            for (name, images, intr, hold) in &runs {
                let (e, s_px, s_q, fitted) =
                    refine_error(&model, intr, images, &free, sigma_px, *hold, &campaign)?;
                println!(
                    "  {name}: {e:.4} mm ({:.3}x oracle) | sigma_px {s_px:.4} | sigma_q {s_q:.5} deg | fx {:+.3} cx {:+.3} cy {:+.3} k1 {:+.5} vs truth",
                    e / oracle,
                    fitted.fx - truth.fx,
                    fitted.cx - truth.cx,
                    fitted.cy - truth.cy,
                    fitted.k1 - truth.k1,
                );
            }
        }
    }
    Ok(())
}
