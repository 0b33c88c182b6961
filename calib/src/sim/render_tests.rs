//! The renderer against its own truth.

use super::*;
use crate::sim::render_circles::render_target;
use crate::vision::target::TargetSpec;
use nalgebra::{Translation3, UnitQuaternion};
use rand::{rngs::StdRng, SeedableRng};

/// Fronto-parallel pinhole view, no blur/noise/vignetting: the dark-mass
/// centroid of every dot is the projection of its centre.
#[test]
fn dark_mass_centroids_match_truth_in_a_fronto_parallel_view() {
    let cam = Intrinsics::pinhole(2000.0, 2000.0, 319.5, 239.5);
    let target = TargetSpec {
        rows: 3,
        cols: 4,
        pitch_mm: 25.0,
        dot_diameter_mm: 8.0,
        origin_marker_diameter_mm: Some(12.0),
    };
    let pose = Isometry3::from_parts(
        Translation3::new(-37.3, -24.1, 800.0),
        UnitQuaternion::identity(),
    );
    let opts = RenderOptions {
        blur_sigma_px: 0.0,
        noise_sigma_grey: 0.0,
        vignetting: 0.0,
        ..Default::default()
    };
    let mut rng = StdRng::seed_from_u64(0);
    let view = render_target(&cam, &pose, &target, 640, 480, &opts, &mut rng).unwrap();
    let img = &view.image;
    for t in &view.truth {
        assert!(t.visible);
        let (mut m, mut mx, mut my) = (0.0, 0.0, 0.0);
        let r = 25i64;
        for y in (t.y.round() as i64 - r)..=(t.y.round() as i64 + r) {
            for x in (t.x.round() as i64 - r)..=(t.x.round() as i64 + r) {
                let w = opts.board_grey - img.at(x as usize, y as usize) as f64;
                m += w;
                mx += w * x as f64;
                my += w * y as f64;
            }
        }
        let (cx, cy) = (mx / m, my / m);
        assert!(
            (cx - t.x).abs() < 0.01 && (cy - t.y).abs() < 0.01,
            "dot {t:?}: centroid ({cx}, {cy})"
        );
    }
}

#[test]
fn invalid_settings_are_errors() {
    let cam = Intrinsics::pinhole(2000.0, 2000.0, 319.5, 239.5);
    let target = TargetSpec::robocal_9x9();
    let pose = Isometry3::translation(0.0, 0.0, 800.0);
    let mut rng = StdRng::seed_from_u64(0);
    for (w, h, opts) in [
        (0, 480, RenderOptions::default()),
        (
            640,
            480,
            RenderOptions {
                supersampling: 0,
                ..Default::default()
            },
        ),
        (
            640,
            480,
            RenderOptions {
                noise_sigma_grey: f64::NAN,
                ..Default::default()
            },
        ),
        (
            640,
            480,
            RenderOptions {
                vignetting: 1.0,
                ..Default::default()
            },
        ),
    ] {
        assert!(render_target(&cam, &pose, &target, w, h, &opts, &mut rng).is_err());
    }
}
