//! Are the predicted pose σ honest (issue "Deploy the result")? Per
//! simulated campaign: the weighted identification and the joint
//! refinement (as the service runs them, synthetic dot noise instead of
//! rendered images), the refinement's full covariance, and over the
//! validation poses RMS(|true error| / predicted σ) of the camera position
//! and orientation in the target frame; the Mahalanobis check of the
//! parameter estimate `d^T Σ^+ d / rank` against the true model refitted in
//! the identified parameterisation. Pooled over all campaigns at the end.
//! `RUNS=40 PRESET=irb2400 CAL=24 VAL=16 [PIXEL=0.1] [SEED_START=0] [RENDERED_CAMERA=1] [ENCODER_DEG=1e-4]
//! cargo run --release -p robocal-calib --example sigma_honesty`
use robocal_calib::geometry::pose_error;
use robocal_calib::kinematics::identify::{identify, IdentifyMode, IdentifyOptions, JointNoise};
use robocal_calib::kinematics::joint_covariance::joint_refine_covariance;
use robocal_calib::kinematics::joint_refine::{joint_refine, ImageNoise};
use robocal_calib::kinematics::uncertainty::{pose_std, PoseFrame};
use robocal_calib::kinematics::Instrument;
use robocal_calib::sim::campaign::CampaignSpec;
use robocal_calib::sim::campaign_io::PoseSet;
use robocal_calib::sim::experiment::{prepare, start_model};
use robocal_calib::sim::oracle::equivalent_truth;
use robocal_calib::sim::rendered_camera::rendered_camera;

fn env(k: &str) -> Option<f64> {
    std::env::var(k).ok().and_then(|v| v.parse().ok())
}

fn main() {
    let runs = env("RUNS").unwrap_or(5.0) as u64;
    let first = env("SEED_START").unwrap_or(0.0) as u64;
    let preset = std::env::var("PRESET").unwrap_or("irb2400".into());
    let (mut all_p, mut all_r, mut all_n, mut all_m, mut all_k) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let mut low = 0;
    for seed in first..first + runs {
        let mut spec = CampaignSpec::standard(&preset, seed + 1).unwrap();
        spec.cal_poses = env("CAL").unwrap_or(24.0) as usize;
        spec.val_poses = env("VAL").unwrap_or(16.0) as usize;
        if std::env::var("RENDERED_CAMERA").is_ok() {
            let (intrinsics, size, _) = rendered_camera(&preset);
            spec.intrinsics = intrinsics;
            spec.image_size = size;
        }
        if let Some(v) = env("ENCODER_DEG") {
            spec.encoder_sigma_deg = v;
        }
        if let Some(v) = env("PIXEL") {
            spec.pixel_sigma_px = v;
        }
        let Ok(p) = prepare(&spec) else {
            println!("seed {}: campaign failed", seed + 1);
            continue;
        };
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
        let noise = ImageNoise {
            sigma_px: spec.pixel_sigma_px,
            joint: JointNoise::Estimate,
        };
        let joint =
            joint_refine(&wid.model, &p.camera_step, &p.images, &free, noise, false).unwrap();
        let cov = joint_refine_covariance(&joint, &p.images, &free, false).unwrap();
        let truth = p.campaign.truth.model().unwrap();
        // Mahalanobis distance of the parameter error (the correlations
        // matter for the propagation, not only the diagonal).
        let eq = equivalent_truth(&p.campaign, &wid.before, &free).unwrap();
        let diff = joint.layout.difference(&joint.model, &eq);
        let d = nalgebra::DVector::from_iterator(free.len(), free.iter().map(|&i| diff[i]));
        let c = nalgebra::DMatrix::from_fn(free.len(), free.len(), |a, b| cov[(free[a], free[b])]);
        let svd = c.clone().svd(true, true);
        let rank = svd.rank(1e-12 * svd.singular_values.max());
        let pinv = svd.pseudo_inverse(1e-12 * c.max()).unwrap();
        let maha = (d.transpose() * &pinv * &d)[(0, 0)];
        let (mut sp, mut sr, mut n) = (0.0, 0.0, 0.0);
        let (mut ep, mut er, mut gp, mut gr) = (0.0, 0.0, 0.0, 0.0);
        for pose in p.campaign.poses.iter().filter(|q| q.set == PoseSet::Val) {
            let q = &pose.joints_rad;
            let e = pose_error(
                &truth.world_to_tool(q).unwrap(),
                &joint.model.world_to_tool(q).unwrap(),
            );
            let s = pose_std(&joint.layout, &joint.model, &cov, q, PoseFrame::ToolInWorld).unwrap();
            let (a, b) = (e.rows(0, 3).norm(), e.rows(3, 3).norm());
            sp += (a / s.position_mm).powi(2);
            sr += (b / s.rotation_rad).powi(2);
            ep += a * a;
            er += b * b;
            gp += s.position_mm.powi(2);
            gr += s.rotation_rad.powi(2);
            n += 1.0;
        }
        let (rp, rr) = ((sp / n).sqrt(), (sr / n).sqrt());
        if rp < 0.5 || rr < 0.5 {
            low += 1;
        }
        println!(
            "seed {:3}: RMS(err/σ) pos {rp:.3} rot {rr:.3} | err {:.4} mm σ {:.4} mm | \
             err {:.2e} σ {:.2e} rad | maha/rank {:.3} ({rank}) | σpx {:.4} σq {:.2e} deg",
            seed + 1,
            (ep / n).sqrt(),
            (gp / n).sqrt(),
            (er / n).sqrt(),
            (gr / n).sqrt(),
            maha / rank as f64,
            joint.sigma_px,
            joint.joint_sigma_rad.to_degrees(),
        );
        all_p += sp;
        all_r += sr;
        all_n += n;
        all_m += maha;
        all_k += rank as f64;
    }
    println!(
        "ALL {preset}: RMS(err/σ) pos {:.3} rot {:.3} over {all_n} val poses; maha/rank {:.3}; \
         campaigns with a ratio < 0.5: {low} of {runs}",
        (all_p / all_n).sqrt(),
        (all_r / all_n).sqrt(),
        all_m / all_k
    );
}
