//! Are the joint refinement's standard deviations right? Per campaign the
//! RMS over the free parameters of `(estimate - truth) / sigma` (truth: the
//! true model refitted exactly in the identified parameterisation, its fit
//! cost printed), and per parameter over all campaigns. Only the weighted
//! identification and the joint refinement run, so hundreds of campaigns
//! take a minute: 20 campaigns pin z rms only to about +-0.05.
//! `RUNS=400 PRESET=puma560 ENCODER_DEG=1e-4 [PIXEL=0.1] [KNOWN=1] [SEED_START=0]
//! cargo run --release -p robocal-calib --example sigma_calibration`
//! (`KNOWN=1`: the joint refinement is told the true joint noise.)
use nalgebra::DVector;
use robocal_calib::kinematics::identify::{
    fit_parameters, identify, IdentifyMode, IdentifyOptions, JointNoise, Measurement, Observed,
};
use robocal_calib::kinematics::joint_refine::{joint_refine, ImageNoise};
use robocal_calib::kinematics::Instrument;
use robocal_calib::sim::campaign::CampaignSpec;
use robocal_calib::sim::experiment::{prepare, start_model};

fn env(k: &str) -> Option<f64> {
    std::env::var(k).ok().and_then(|v| v.parse().ok())
}

fn main() {
    let runs = env("RUNS").unwrap_or(5.0) as u64;
    let first = env("SEED_START").unwrap_or(0.0) as u64;
    let preset = std::env::var("PRESET").unwrap_or("puma560".into());
    let mut sum_z2: Vec<f64> = vec![];
    let mut names = vec![];
    let mut n = 0.0;
    for seed in first..first + runs {
        let mut spec = CampaignSpec::standard(&preset, seed + 1).unwrap();
        if let Some(v) = env("ENCODER_DEG") {
            spec.encoder_sigma_deg = v;
        }
        if let Some(v) = env("PIXEL") {
            spec.pixel_sigma_px = v;
        }
        let p = prepare(&spec).unwrap();
        let opts = IdentifyOptions {
            mode: IdentifyMode::Weighted,
            joint_noise: JointNoise::default(),
        };
        let wid = identify(
            &start_model(&spec, &p.weighted).unwrap(),
            Instrument::Camera,
            &p.weighted,
            opts,
        )
        .unwrap();
        let free = wid.identifiability.free.clone();
        let jn = if env("KNOWN").is_some() {
            JointNoise::Known {
                sigma_rad: spec.encoder_sigma_deg.to_radians(),
            }
        } else {
            JointNoise::Estimate
        };
        let noise = ImageNoise {
            sigma_px: spec.pixel_sigma_px,
            joint: jn,
        };
        let joint =
            joint_refine(&wid.model, &p.camera_step, &p.images, &free, noise, false).unwrap();
        let tm = p.campaign.truth.model().unwrap();
        let exact: Vec<Measurement> = p
            .campaign
            .poses
            .iter()
            .map(|q| Measurement {
                joints_rad: q.joints_rad.clone(),
                observed: Observed::Pose {
                    world_to_tool: tm.world_to_tool(&q.joints_rad).unwrap(),
                    covariance: None,
                },
            })
            .collect();
        let (eq, rep) = fit_parameters(
            &wid.before,
            Instrument::Camera,
            &exact,
            &free,
            IdentifyMode::Weighted.into(),
        )
        .unwrap();
        let diff: DVector<f64> = joint.layout.difference(&joint.model, &eq);
        let z: Vec<f64> = free.iter().map(|&i| diff[i] / joint.std_devs[i]).collect();
        if sum_z2.is_empty() {
            sum_z2 = vec![0.0; z.len()];
            names = free
                .iter()
                .map(|&i| joint.layout.params[i].name.clone())
                .collect();
        }
        if z.len() == sum_z2.len() {
            for (s, v) in sum_z2.iter_mut().zip(&z) {
                *s += v * v;
            }
            n += 1.0;
        }
        let zr = (z.iter().map(|v| v * v).sum::<f64>() / z.len() as f64).sqrt();
        println!(
            "seed {} zrms {:.3} eqfit cost {:.3e} it {} sigma_px {:.4} sigma_q {:.3e} deg free {}",
            seed + 1,
            zr,
            rep.cost,
            rep.iterations,
            joint.sigma_px,
            joint.joint_sigma_rad.to_degrees(),
            free.len()
        );
    }
    let tot: f64 = sum_z2.iter().sum::<f64>() / (n * sum_z2.len() as f64);
    println!("TOTAL z rms {:.3} over {} campaigns", tot.sqrt(), n);
    for (nm, s) in names.iter().zip(&sum_z2) {
        print!("{nm}:{:.2} ", (s / n).sqrt());
    }
    println!();
}
