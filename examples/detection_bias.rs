//! Diagnostic of the detector's systematic error on a rendered campaign: the
//! raw ellipse centres, corrected for the perspective/distortion bias with
//! the TRUE camera (`camera::bias::centre_bias`), against the true images of
//! the dot centres. Per-pose mean errors and the radial slope (error along
//! the radius per pixel of radius) show what the noise model does not: a
//! pose-correlated bias (vignetting gave +1e-5 px/px before the detector
//! divided the illumination gradient out).
//!
//! ```text
//! cargo run --release --example detection_bias -- [preset seed vignetting blur_px noise_grey poses]
//! cargo run --release --example detection_bias -- irb2400 1 0.25 0.7 2.0 10
//! ```
use nalgebra::{Point2, Point3};
use rand::{rngs::StdRng, SeedableRng};
use robocal::cli::campaign::{rendered_spec, simulated_target};
use robocal_calib::camera::bias::centre_bias;
use robocal_calib::sim::campaign::simulate_campaign;
use robocal_calib::sim::campaign_io::PoseSet;
use robocal_calib::sim::render::RenderOptions;
use robocal_calib::sim::render_circles::render_target;
use robocal_calib::vision::{self, DetectOptions};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let preset = args.get(1).map_or("irb2400", |s| s.as_str());
    let seed: u64 = args.get(2).map_or(1, |s| s.parse().unwrap());
    let vign: f64 = args.get(3).map_or(0.25, |s| s.parse().unwrap());
    let blur: f64 = args.get(4).map_or(0.7, |s| s.parse().unwrap());
    let noise: f64 = args.get(5).map_or(2.0, |s| s.parse().unwrap());
    let npose: usize = args.get(6).map_or(10, |s| s.parse().unwrap());
    let spec = rendered_spec(preset, 60, 30, seed).unwrap();
    let campaign = simulate_campaign(&spec).unwrap();
    let target = simulated_target();
    let intr = campaign.truth.intrinsics;
    let (w, h) = spec.image_size;
    let opts = RenderOptions {
        vignetting: vign,
        blur_sigma_px: blur,
        noise_sigma_grey: noise,
        ..RenderOptions::default()
    };
    let (mut s2, mut n, mut mean_sum) = (0.0, 0usize, nalgebra::Vector2::zeros());
    let mut radial = (0.0, 0.0); // sum r*e_r, sum r^2
    for (i, pose) in campaign
        .poses
        .iter()
        .filter(|p| p.set == PoseSet::Cal)
        .take(npose)
        .enumerate()
    {
        let mut rng = StdRng::seed_from_u64(seed * 1000 + i as u64);
        let c2t = pose.target_to_camera.inverse();
        let view = render_target(
            &intr, &c2t, &target, w as usize, h as usize, &opts, &mut rng,
        )
        .unwrap();
        let det = vision::detect_with(
            &view.image,
            &target,
            &DetectOptions {
                correct_perspective_bias: false,
                ..DetectOptions::default()
            },
        )
        .unwrap();
        let (mut ps2, mut pn, mut pmean) = (0.0, 0usize, nalgebra::Vector2::zeros());
        let mut diam = 0.0;
        for d in &det.dots {
            if d.row == 0 && d.col == 0 {
                continue;
            }
            let m = target.dot_centre_mm(d.row, d.col);
            let p = Point3::new(m[0], m[1], m[2]);
            let r = 0.5 * target.dot_diameter_at_mm(d.row, d.col);
            let b = centre_bias(&intr, &c2t, &p, r).unwrap();
            let truth = intr.project(&(c2t * p)).unwrap();
            let corrected = Point2::new(d.ellipse.cx, d.ellipse.cy) - b;
            let e = corrected - truth;
            ps2 += e.norm_squared();
            pn += 1;
            pmean += e;
            let rv = truth - Point2::new(intr.cx, intr.cy);
            radial.0 += rv.dot(&e);
            radial.1 += rv.norm_squared();
            diam += 2.0 * d.ellipse.semi_major_px;
        }
        println!(
            "pose {i}: rms {:.4} px | mean err ({:+.4},{:+.4}) px | dot size ~{:.1} px",
            (ps2 / pn as f64).sqrt(),
            pmean.x / pn as f64,
            pmean.y / pn as f64,
            diam / pn as f64
        );
        s2 += ps2;
        n += pn;
        mean_sum += pmean;
    }
    println!(
        "ALL: rms {:.4} px per dot (2-D), mean ({:+.4},{:+.4}), radial slope {:+.3e} px/px",
        (s2 / n as f64).sqrt(),
        mean_sum.x / n as f64,
        mean_sum.y / n as f64,
        radial.0 / radial.1
    );
}
