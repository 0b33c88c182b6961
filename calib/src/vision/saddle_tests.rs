//! The saddle/point-symmetry refiner on rendered chessboards (truth known).

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

use super::*;
use crate::sim::render::RenderOptions;
use crate::sim::render_chessboard::render_chessboard;
use crate::sim::views::reference_camera;
use crate::vision::chessboard::ChessboardSpec;
use crate::vision::image::GrayImage;

/// RMS and worst error of corners refined from guesses up to `offset_px`
/// away from the truth.
fn refine_errors(
    opts: &RenderOptions,
    tilt_deg: f64,
    offset_px: f64,
    half: f64,
) -> (f64, f64, usize) {
    let spec = ChessboardSpec {
        inner_corners: [9, 6],
        square_mm: 30.0,
    };
    let iso = Isometry3::from_parts(
        Translation3::new(0.0, 0.0, 650.0),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.3)
            * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), tilt_deg.to_radians()),
    ) * Translation3::new(-120.0, -75.0, 0.0);
    let mut rng = StdRng::seed_from_u64(11);
    let view =
        render_chessboard(&reference_camera(), &iso, &spec, 1280, 1024, opts, &mut rng).unwrap();
    let (mut sum2, mut worst, mut n) = (0.0, 0.0f64, 0usize);
    for t in &view.truth {
        let guess = [
            t.x + rng.random_range(-offset_px..offset_px),
            t.y + rng.random_range(-offset_px..offset_px),
        ];
        let Some([x, y]) = refine_saddle(&view.image, guess, half) else {
            continue;
        };
        let e = (x - t.x).hypot(y - t.y);
        sum2 += e * e;
        worst = worst.max(e);
        n += 1;
    }
    ((sum2 / n.max(1) as f64).sqrt(), worst, n)
}

#[test]
fn refined_corners_match_the_truth_from_rough_guesses() {
    let sharp = RenderOptions::default();
    let blurred = RenderOptions {
        blur_sigma_px: 2.0,
        noise_sigma_grey: 3.0,
        ..sharp
    };
    let dark = RenderOptions {
        vignetting: 0.65,
        ..sharp
    };
    for (name, opts, tilt, bound) in [
        ("sharp", sharp, 10.0, 0.03),
        ("steep", sharp, 55.0, 0.04),
        ("blurred", blurred, 30.0, 0.06),
        ("uneven", dark, 30.0, 0.04),
    ] {
        let (rms, worst, n) = refine_errors(&opts, tilt, 1.5, 8.0);
        eprintln!("{name}: {n}/54 refined, RMS {rms:.4} px, worst {worst:.3} px");
        assert_eq!(n, 54, "{name}");
        assert!(rms < bound, "{name}: RMS {rms}");
    }
}

#[test]
fn no_corner_means_none() {
    let flat = GrayImage::new(64, 64, vec![100.0; 64 * 64]).unwrap();
    assert_eq!(refine_saddle(&flat, [32.0, 32.0], 6.0), None);
    // A window too small or not a number.
    assert_eq!(refine_saddle(&flat, [32.0, 32.0], 0.5), None);
    assert_eq!(refine_saddle(&flat, [32.0, 32.0], f64::NAN), None);
    // At the image border.
    assert_eq!(refine_saddle(&flat, [1.0, 1.0], 6.0), None);
}
