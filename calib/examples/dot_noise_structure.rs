//! Is the rendered campaigns' dot detection error the i.i.d. noise the
//! identification assumes (issue "Deploy the result": served σ vs the
//! rendered pipeline's errors)? Per rendered view of a simulated campaign
//! (the renderer and detector the service runs, the CLI's per-pose noise
//! streams): the detected dot centre, with the perspective bias predicted
//! at the TRUE camera pose removed, against the image of the dot's centre.
//! Printed: the per-axis RMS of the dot error; how much of it is a
//! per-image component (the mean error of an image times √dots: 1 for
//! i.i.d. noise); and the pose a PnP with the true intrinsics gets from the
//! detected dots against the true pose, as `d^T C^-1 d / 6` with `C` the
//! PnP covariance at the measured per-dot noise (1 for i.i.d. noise). The
//! same PnP on the campaign's Gaussian dots (`observed_px`, noise `PIXEL`)
//! is the control.
//!
//! `PRESET=irb2400 SEEDS=3 POSES=12 [PIXEL=0.006] cargo run -p robocal-calib --example dot_noise_structure`
use nalgebra::{Point2, Point3, Vector6};
use rand::{rngs::StdRng, SeedableRng};
use robocal_calib::camera::bias::centre_bias;
use robocal_calib::camera::estimate_pose;
use robocal_calib::geometry::pose_error;
use robocal_calib::sim::campaign::{simulate_campaign, CampaignSpec};
use robocal_calib::sim::render::RenderOptions;
use robocal_calib::sim::render_circles::render_target;
use robocal_calib::sim::rendered_camera::rendered_camera;
use robocal_calib::vision::detect::detect;
use robocal_calib::vision::TargetSpec;

/// The CLI's per-pose noise-seed stride (`src/cli/campaign.rs`).
const NOISE_SEED_STRIDE: u64 = 0x9e37_79b9_7f4a_7c15;

fn env(k: &str) -> Option<f64> {
    std::env::var(k).ok().and_then(|v| v.parse().ok())
}

/// `d^T C^-1 d / 6` of the PnP pose from `obs` against `truth`, and the
/// per-axis RMS residual of that fit.
fn pnp_check(
    intr: &robocal_calib::camera::Intrinsics,
    obs: &[(Point3<f64>, Point2<f64>)],
    truth: &robocal_calib::geometry::Pose,
    sigma_px: f64,
) -> Option<(f64, Vector6<f64>)> {
    let est = estimate_pose(intr, obs, Some(&truth.inverse())).ok()?;
    let d = pose_error(truth, &est.target_to_camera);
    // The estimate's covariance is scaled by its own residual variance;
    // rescale to the common per-dot noise so views compare.
    let own = est.rms_px.powi(2) / 2.0;
    let c = est.covariance_6x6 * (sigma_px.powi(2) / own.max(1e-30));
    let ci = c.try_inverse()?;
    Some(((d.transpose() * ci * d)[(0, 0)] / 6.0, d))
}

fn main() {
    let preset = std::env::var("PRESET").unwrap_or("irb2400".into());
    let seeds = env("SEEDS").unwrap_or(3.0) as u64;
    let poses = env("POSES").unwrap_or(12.0) as usize;
    let target = TargetSpec::robocal_9x9();
    let (intr, (w, h), _) = rendered_camera(&preset);
    let (mut sq, mut n_dots) = (0.0, 0.0);
    let (mut mean_sq, mut n_img) = (0.0, 0.0);
    let (mut maha_r, mut maha_g, mut n_pnp) = (0.0, 0.0, 0.0);
    let mut per_dot: std::collections::HashMap<(usize, usize), (nalgebra::Vector2<f64>, f64)> =
        Default::default();
    let mut rendered_views = Vec::new();
    for seed in 1..=seeds {
        let mut spec = CampaignSpec::standard(&preset, seed).unwrap();
        spec.intrinsics = intr;
        spec.image_size = (w, h);
        if let Some(p) = env("PIXEL") {
            spec.pixel_sigma_px = p;
        }
        let campaign = simulate_campaign(&spec).unwrap();
        for (i, pose) in campaign.poses.iter().enumerate().take(poses) {
            let mut rng =
                StdRng::seed_from_u64(seed ^ (i as u64 + 1).wrapping_mul(NOISE_SEED_STRIDE));
            let camera_to_target = pose.target_to_camera.inverse();
            let Ok(view) = render_target(
                &campaign.truth.intrinsics,
                &camera_to_target,
                &target,
                w as usize,
                h as usize,
                &RenderOptions::default(),
                &mut rng,
            ) else {
                continue;
            };
            let Ok(det) = detect(&view.image, &target) else {
                continue;
            };
            let mut errs = Vec::new();
            let mut obs = Vec::new();
            for dot in &det.dots {
                let c = target.dot_centre_mm(dot.row, dot.col);
                let centre = Point3::new(c[0], c[1], c[2]);
                let radius = target.dot_diameter_at_mm(dot.row, dot.col) / 2.0;
                let Some(bias) = centre_bias(&intr, &camera_to_target, &centre, radius) else {
                    continue;
                };
                let measured = Point2::new(dot.ellipse.cx - bias.x, dot.ellipse.cy - bias.y);
                let ideal = pose.ideal_px[dot.row * target.cols + dot.col];
                let e = measured - ideal;
                errs.push(e);
                obs.push((centre, measured));
                let entry = per_dot.entry((dot.row, dot.col)).or_default();
                entry.0 += e;
                entry.1 += 1.0;
            }
            let k = errs.len() as f64;
            let mean = errs.iter().sum::<nalgebra::Vector2<f64>>() / k;
            sq += errs.iter().map(|e| e.norm_squared()).sum::<f64>();
            n_dots += k;
            mean_sq += mean.norm_squared() * k;
            n_img += 1.0;
            rendered_views.push((obs, pose.target_to_camera, pose.clone()));
        }
    }
    let sigma = (sq / (2.0 * n_dots)).sqrt();
    for (obs, truth, pose) in &rendered_views {
        let gauss: Vec<_> = obs
            .iter()
            .map(|(p, _)| {
                let (r, c) = (
                    (p.y / target.pitch_mm).round() as usize,
                    (p.x / target.pitch_mm).round() as usize,
                );
                (*p, pose.observed_px[r * target.cols + c])
            })
            .collect();
        let gs = env("PIXEL").unwrap_or(sigma);
        if let (Some((mr, _)), Some((mg, _))) = (
            pnp_check(&intr, obs, truth, sigma),
            pnp_check(&intr, &gauss, truth, gs),
        ) {
            maha_r += mr;
            maha_g += mg;
            n_pnp += 1.0;
        }
    }
    let fixed: f64 = per_dot
        .values()
        .map(|(s, k)| (s / *k).norm_squared() * *k)
        .sum::<f64>();
    println!(
        "{preset}: {n_img} views, {n_dots} dots: dot error per axis RMS {sigma:.5} px; \
         per-image mean component RMS*sqrt(dots)/sigma {:.3} (1 = i.i.d.); \
         per-dot mean over views RMS*sqrt(views)/sigma {:.3}; \
         PnP (true intrinsics) d'C^-1 d/6: rendered {:.3}, Gaussian control {:.3} ({n_pnp} views)",
        (mean_sq / (2.0 * n_img)).sqrt() / sigma,
        (fixed / (2.0 * per_dot.len() as f64)).sqrt() / sigma,
        maha_r / n_pnp,
        maha_g / n_pnp,
    );
}
