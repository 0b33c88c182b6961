//! Times the Rust identification (60 poses) and joint refinement on a
//! simulated IRB-2400 campaign, and writes the pose-level problem (start
//! model, free parameters, measurements, whitening) as JSON for
//! `bench/kinematics_scipy.py`, which times scipy on the same data.
//! `cargo run -p robocal-calib --example kinematics_export -- out.json [preset] [repeats]`

use std::time::Instant;

use nalgebra::DMatrix;
use robocal_calib::geometry::pose_to_matrix_rows;
use robocal_calib::kinematics::identify::{
    fit_parameters, identify, validate, IdentifyMode, JointNoise, Observed,
};
use robocal_calib::kinematics::joint_refine::{joint_refine, ImageNoise};
use robocal_calib::kinematics::Instrument;
use robocal_calib::sim::campaign::CampaignSpec;
use robocal_calib::sim::experiment::{prepare, start_model};
use serde_json::json;

fn main() {
    let mut args = std::env::args().skip(1);
    let out = args
        .next()
        .unwrap_or_else(|| "kinematics_problem.json".into());
    let preset = args.next().unwrap_or_else(|| "irb2400".into());
    let repeats: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(5);
    let spec = CampaignSpec::standard(&preset, 1).expect("preset");
    let p = prepare(&spec).expect("campaign");
    let start = start_model(&spec, &p.weighted).expect("start");
    let best = |f: &mut dyn FnMut()| -> f64 {
        (0..repeats)
            .map(|_| {
                let t = Instant::now();
                f();
                t.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min)
    };
    let mut id = None;
    let t_identify = best(&mut || {
        id = Some(
            identify(
                &start,
                Instrument::Camera,
                &p.weighted,
                IdentifyMode::Weighted.into(),
            )
            .unwrap(),
        )
    });
    let id = id.expect("ran");
    let free = id.identifiability.free.clone();
    let mut fit_cost = 0.0;
    let t_fit = best(&mut || {
        let (_, r) = fit_parameters(
            &id.before,
            Instrument::Camera,
            &p.weighted,
            &free,
            IdentifyMode::Weighted.into(),
        )
        .unwrap();
        fit_cost = r.cost;
    });
    let mut joint = None;
    let t_joint = best(&mut || {
        joint = Some(
            joint_refine(
                &id.model,
                &p.camera_step,
                &p.images,
                &free,
                ImageNoise {
                    sigma_px: spec.pixel_sigma_px,
                    joint: JointNoise::Estimate,
                },
                false,
            )
            .unwrap(),
        )
    });
    let joint = joint.expect("ran");
    let val_after = validate(&id.model, &p.val).unwrap().0.norm.mean_mm;
    let val_joint = validate(&joint.model, &p.val).unwrap().0.norm.mean_mm;
    println!(
        "rust {preset}: {} cal poses, {} free parameters; identify (frames + identifiability + LM + covariance) {:.4} s; pose-level LM alone {:.4} s (cost {:.6}); joint refinement ({} dots, {} parameters) {:.4} s; val mean {:.4} mm (pose-level) {:.4} mm (joint)",
        p.weighted.len(),
        free.len(),
        t_identify,
        t_fit,
        fit_cost,
        p.images.iter().map(|i| i.observations.len()).sum::<usize>(),
        free.len() + 8,
        t_joint,
        val_after,
        val_joint
    );
    let measurements: Vec<_> = p
        .weighted
        .iter()
        .map(|m| {
            let Observed::Pose {
                world_to_tool,
                covariance,
            } = &m.observed
            else {
                unreachable!("camera poses")
            };
            let cov = DMatrix::from_column_slice(6, 6, covariance.expect("weighted").as_slice());
            let w = cov
                .cholesky()
                .expect("pd")
                .l()
                .try_inverse()
                .expect("invertible");
            let rows: Vec<Vec<f64>> = (0..6).map(|r| w.row(r).iter().copied().collect()).collect();
            json!({"q": m.joints_rad, "pose": pose_to_matrix_rows(world_to_tool), "w": rows})
        })
        .collect();
    let doc = json!({
        "joints": id.before.robot.joints,
        "world_to_base": pose_to_matrix_rows(&id.before.world_to_base),
        "flange_to_tool": pose_to_matrix_rows(&id.before.flange_to_tool),
        "free": free,
        "measurements": measurements,
        "rust": {"identify_s": t_identify, "fit_s": t_fit, "fit_cost": fit_cost, "joint_refine_s": t_joint},
    });
    std::fs::write(&out, serde_json::to_string(&doc).unwrap()).expect("write");
}
