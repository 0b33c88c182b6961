//! Chessboard detection on rendered views with known truth (issue 14).

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rand::rngs::StdRng;
use rand::SeedableRng;

use super::*;
use crate::sim::render::RenderOptions;
use crate::sim::render_chessboard::render_chessboard;
use crate::sim::views::reference_camera;
use crate::vision::error::DetectError;
use crate::vision::image::GrayImage;

const W: usize = 1280;
const H: usize = 1024;

fn board(cols: usize, rows: usize) -> ChessboardSpec {
    ChessboardSpec {
        inner_corners: [cols, rows],
        square_mm: 30.0,
    }
}

/// Camera `distance_mm` from the board centre, tilted about the board's x
/// axis, rolled, with the board shifted by `shift_mm` in its own plane.
fn pose(spec: &ChessboardSpec, distance_mm: f64, tilt_deg: f64, roll_deg: f64) -> Isometry3<f64> {
    let centre = Vector3::new(
        0.5 * (spec.cols() - 1) as f64 * spec.square_mm,
        0.5 * (spec.rows() - 1) as f64 * spec.square_mm,
        0.0,
    );
    let rot = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), roll_deg.to_radians())
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), tilt_deg.to_radians());
    Isometry3::from_parts(Translation3::new(0.0, 0.0, distance_mm), rot)
        * Translation3::from(-centre)
}

/// (found, RMS px, worst px, ordering_unique) of a detection against the truth.
fn score(
    spec: &ChessboardSpec,
    iso: &Isometry3<f64>,
    opts: &RenderOptions,
    seed: u64,
) -> (usize, f64, f64, bool) {
    let mut rng = StdRng::seed_from_u64(seed);
    let view = render_chessboard(&reference_camera(), iso, spec, W, H, opts, &mut rng).unwrap();
    let det = detect_chessboard(&view.image, spec).unwrap();
    let (mut sum2, mut worst) = (0.0, 0.0f64);
    for p in &det.points {
        let t = view.truth[p.row * spec.cols() + p.col];
        let e = (p.x_px - t.x).hypot(p.y_px - t.y);
        sum2 += e * e;
        worst = worst.max(e);
    }
    let n = det.points.len();
    (
        n,
        (sum2 / n.max(1) as f64).sqrt(),
        worst,
        det.ordering_unique,
    )
}

#[test]
fn rendered_views_give_every_corner_in_opencv_order() {
    let spec = board(9, 6);
    let sharp = RenderOptions {
        supersampling: 8,
        board_margin_mm: 20.0,
        ..RenderOptions::default()
    };
    let blurred = RenderOptions {
        blur_sigma_px: 2.0,
        noise_sigma_grey: 3.0,
        ..sharp
    };
    let uneven = RenderOptions {
        vignetting: 0.65,
        ..sharp
    };
    // (name, pose, options, RMS bound px); rolls up to 160° check the order.
    let cases = [
        ("fronto", pose(&spec, 600.0, 0.0, 10.0), sharp, 0.03),
        ("upside down", pose(&spec, 600.0, 10.0, 170.0), sharp, 0.03),
        ("steep", pose(&spec, 650.0, 55.0, 30.0), sharp, 0.05),
        ("blurred", pose(&spec, 700.0, 35.0, -100.0), blurred, 0.06),
        ("uneven", pose(&spec, 600.0, 25.0, 60.0), uneven, 0.04),
    ];
    for (k, (name, iso, opts, max_rms)) in cases.iter().enumerate() {
        let (found, rms, worst, unique) = score(&spec, iso, opts, k as u64);
        eprintln!("{name}: {found}/54 corners, RMS {rms:.4} px, worst {worst:.3} px");
        assert!(unique, "9x6 is not half-turn symmetric");
        assert_eq!(found, spec.corner_count(), "{name}");
        assert!(rms <= *max_rms, "{name}: RMS {rms}");
        // A wrong order would be a whole square (> 20 px) off.
        assert!(worst < 0.2, "{name}: worst {worst}");
    }
}

#[test]
fn symmetric_boards_are_flagged_not_flipped_silently() {
    for (cols, rows) in [(8, 6), (7, 5)] {
        let spec = board(cols, rows);
        let opts = RenderOptions::default();
        for roll in [0.0, 180.0] {
            let iso = pose(&spec, 600.0, 15.0, roll + 5.0);
            let mut rng = StdRng::seed_from_u64(7);
            let view =
                render_chessboard(&reference_camera(), &iso, &spec, W, H, &opts, &mut rng).unwrap();
            let det = detect_chessboard(&view.image, &spec).unwrap();
            assert!(!det.ordering_unique, "{cols}x{rows} is ambiguous");
            assert_eq!(det.points.len(), spec.corner_count());
            // Either the truth or its half turn, never anything else.
            let n = spec.corner_count();
            let direct = det.points.iter().all(|p| {
                let t = view.truth[p.row * cols + p.col];
                (p.x_px - t.x).hypot(p.y_px - t.y) < 0.2
            });
            let turned = det.points.iter().all(|p| {
                let t = view.truth[n - 1 - (p.row * cols + p.col)];
                (p.x_px - t.x).hypot(p.y_px - t.y) < 0.2
            });
            assert!(direct != turned, "{cols}x{rows} roll {roll}");
            // The rule: rows run rightwards in the image.
            assert!(det.points[1].x_px > det.points[0].x_px);
        }
    }
}

#[test]
fn wrong_sizes_and_partial_views_are_refused() {
    let spec = board(9, 6);
    let opts = RenderOptions::default();
    let mut rng = StdRng::seed_from_u64(3);
    let iso = pose(&spec, 600.0, 10.0, 0.0);
    let view = render_chessboard(&reference_camera(), &iso, &spec, W, H, &opts, &mut rng).unwrap();
    // A smaller spec than the board: more than one window fits.
    let small = board(7, 5);
    match detect_chessboard(&view.image, &small) {
        Err(DetectError::GridMismatch(m)) => assert!(m.contains("inner_corners"), "{m}"),
        other => panic!("expected a mismatch, got {other:?}"),
    }
    // A larger spec than the board: a partial view, refused.
    let big = board(11, 8);
    assert!(matches!(
        detect_chessboard(&view.image, &big),
        Err(DetectError::NoBoard(_))
    ));
    // The board shifted half out of the image.
    let off = Isometry3::from_parts(
        Translation3::new(250.0, 0.0, 0.0),
        UnitQuaternion::identity(),
    ) * iso;
    let cut = render_chessboard(&reference_camera(), &off, &spec, W, H, &opts, &mut rng).unwrap();
    assert!(detect_chessboard(&cut.image, &spec).is_err());
    // An empty image.
    let blank = GrayImage::new(W, H, vec![128.0; W * H]).unwrap();
    assert!(detect_chessboard(&blank, &spec).is_err());
}

#[test]
fn invalid_specs_name_the_field() {
    let cases = [
        (
            ChessboardSpec {
                inner_corners: [1, 6],
                square_mm: 10.0,
            },
            "inner_corners",
        ),
        (
            ChessboardSpec {
                inner_corners: [7, 7],
                square_mm: 10.0,
            },
            "inner_corners",
        ),
        (
            ChessboardSpec {
                inner_corners: [9, 6],
                square_mm: 0.0,
            },
            "square_mm",
        ),
        (
            ChessboardSpec {
                inner_corners: [9, 6],
                square_mm: -3.0,
            },
            "square_mm",
        ),
        (
            ChessboardSpec {
                inner_corners: [9, 6],
                square_mm: f64::NAN,
            },
            "square_mm",
        ),
    ];
    for (spec, field) in cases {
        match spec.validate() {
            Err(DetectError::InvalidTarget(m)) => assert!(m.starts_with(field), "{m}"),
            other => panic!("{spec:?}: {other:?}"),
        }
    }
    assert!(
        board(8, 8).validate().is_ok(),
        "even square boards are only half-turn symmetric"
    );
}
