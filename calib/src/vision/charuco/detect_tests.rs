//! ChArUco detection on rendered views with known truth (issue 14).

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rand::rngs::StdRng;
use rand::SeedableRng;

use super::*;
use crate::sim::render::RenderOptions;
use crate::sim::render_charuco::{render_charuco, TruthCorner};
use crate::sim::views::reference_camera;
use crate::vision::image::GrayImage;

const W: usize = 1280;
const H: usize = 1024;

fn board() -> CharucoSpec {
    CharucoSpec {
        squares: [9, 7],
        square_mm: 30.0,
        marker_mm: 22.0,
        dictionary: "DICT_5X5_100".into(),
        legacy_layout: false,
    }
}

/// Camera `distance_mm` from the board centre, tilted about the board's x
/// axis, rolled, with the board shifted by `shift_mm` in its own plane.
fn pose(distance_mm: f64, tilt_deg: f64, roll_deg: f64, shift_mm: [f64; 2]) -> Isometry3<f64> {
    let spec = board();
    let centre = Vector3::new(
        0.5 * spec.cols() as f64 * spec.square_mm + shift_mm[0],
        0.5 * spec.rows() as f64 * spec.square_mm + shift_mm[1],
        0.0,
    );
    let rot = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), roll_deg.to_radians())
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), tilt_deg.to_radians());
    Isometry3::from_parts(Translation3::new(0.0, 0.0, distance_mm), rot)
        * Translation3::from(-centre)
}

/// (found, visible, RMS px, worst px) of a detection against the truth.
fn score(
    spec: &CharucoSpec,
    iso: &Isometry3<f64>,
    opts: &RenderOptions,
    seed: u64,
) -> (usize, usize, f64, f64) {
    let mut rng = StdRng::seed_from_u64(seed);
    let view = render_charuco(&reference_camera(), iso, spec, W, H, opts, &mut rng).unwrap();
    let det = detect_charuco(&view.image, spec).unwrap();
    assert!(det.ordering_unique);
    let nx = spec.cols() - 1;
    let (mut sum2, mut worst) = (0.0, 0.0f64);
    for p in &det.points {
        let t = view.truth[p.row * nx + p.col];
        let e = (p.x_px - t.x).hypot(p.y_px - t.y);
        sum2 += e * e;
        worst = worst.max(e);
    }
    let visible = view.truth.iter().filter(|t| t.visible).count();
    let n = det.points.len();
    (n, visible, (sum2 / n.max(1) as f64).sqrt(), worst)
}

/// RMS distance, px, of a detection's corners from their truth.
fn rms_px(spec: &CharucoSpec, det: &BoardDetection, truth: &[TruthCorner]) -> f64 {
    let nx = spec.cols() - 1;
    let s: f64 = det
        .points
        .iter()
        .map(|p| {
            let t = truth[p.row * nx + p.col];
            (p.x_px - t.x).powi(2) + (p.y_px - t.y).powi(2)
        })
        .sum();
    (s / det.points.len().max(1) as f64).sqrt()
}

#[test]
fn rendered_views_give_every_visible_corner_with_its_identity() {
    let spec = board();
    let sharp = RenderOptions {
        supersampling: 8,
        board_margin_mm: 15.0,
        ..RenderOptions::default()
    };
    let blurred = RenderOptions {
        blur_sigma_px: 2.0,
        ..sharp
    };
    // (name, pose, options, least fraction of visible corners found, RMS bound px)
    let cases = [
        (
            "fronto",
            pose(600.0, 0.0, 10.0, [0.0, 0.0]),
            sharp,
            1.0,
            0.05,
        ),
        (
            "steep",
            pose(650.0, 55.0, 30.0, [0.0, 0.0]),
            sharp,
            1.0,
            0.05,
        ),
        (
            "partial",
            pose(500.0, 20.0, 0.0, [90.0, 40.0]),
            sharp,
            0.9,
            0.08,
        ),
        (
            "blurred",
            pose(700.0, 35.0, -20.0, [0.0, 0.0]),
            blurred,
            1.0,
            0.06,
        ),
    ];
    for (k, (name, iso, opts, min_rate, max_rms)) in cases.iter().enumerate() {
        let (found, visible, rms, worst) = score(&spec, iso, opts, k as u64);
        eprintln!("{name}: {found}/{visible} corners, RMS {rms:.3} px, worst {worst:.3} px");
        assert!(
            found as f64 >= min_rate * visible as f64 && found > 0,
            "{name}: {found}/{visible}"
        );
        assert!(rms <= *max_rms, "{name}: RMS {rms}");
        // A wrong identity would be a whole square (~60 px) off.
        assert!(worst < 0.2, "{name}: worst {worst}");
    }
}

#[test]
fn an_image_without_the_board_is_no_board_and_bad_specs_are_refused() {
    let img = GrayImage::new(200, 150, vec![128.0; 200 * 150]).unwrap();
    assert!(matches!(
        detect_charuco(&img, &board()),
        Err(DetectError::NoBoard(_))
    ));
    let mut bad = board();
    bad.marker_mm = 40.0;
    assert!(matches!(
        detect_charuco(&img, &bad),
        Err(DetectError::InvalidTarget(_))
    ));
}

#[test]
fn refinement_beats_the_homography_prediction_several_fold() {
    let spec = board();
    let opts = RenderOptions {
        supersampling: 8,
        board_margin_mm: 15.0,
        ..RenderOptions::default()
    };
    let mut rng = StdRng::seed_from_u64(7);
    let iso = pose(620.0, 40.0, 25.0, [0.0, 0.0]);
    let view = render_charuco(&reference_camera(), &iso, &spec, W, H, &opts, &mut rng).unwrap();
    let rms = |det: &BoardDetection| rms_px(&spec, det, &view.truth);
    let predicted = rms(&detect_charuco_with(&view.image, &spec, None).unwrap());
    let refined = rms(&detect_charuco(&view.image, &spec).unwrap());
    eprintln!("predicted RMS {predicted:.3} px, refined {refined:.3} px");
    assert!(refined * 3.0 < predicted, "{refined} vs {predicted}");
}

/// A legacy board (even rows) is found with `legacy_layout: true`; read
/// with the current layout its markers disagree about the squares (odd
/// cols) and the spec is refused naming the field, never wrong corners.
#[test]
fn legacy_boards_need_the_legacy_flag_and_never_give_wrong_corners_without_it() {
    // Odd and even column counts: with even cols every row of markers
    // shifts by one square, alternately left and right.
    for squares in [[9, 6], [8, 6]] {
        let legacy = CharucoSpec {
            squares,
            legacy_layout: true,
            ..board()
        };
        let opts = RenderOptions {
            supersampling: 8,
            board_margin_mm: 15.0,
            ..RenderOptions::default()
        };
        let iso = pose(600.0, 30.0, 15.0, [0.0, 0.0]);
        let (found, visible, rms, worst) = score(&legacy, &iso, &opts, 11);
        assert_eq!(
            found, visible,
            "{squares:?} legacy board with the legacy flag"
        );
        assert!(rms < 0.05 && worst < 0.2, "RMS {rms}, worst {worst}");
        let mut rng = StdRng::seed_from_u64(11);
        let view =
            render_charuco(&reference_camera(), &iso, &legacy, W, H, &opts, &mut rng).unwrap();
        let current = CharucoSpec {
            legacy_layout: false,
            ..legacy.clone()
        };
        match detect_charuco(&view.image, &current) {
            Err(DetectError::GridMismatch(m)) => assert!(m.starts_with("legacy_layout"), "{m}"),
            other => panic!("{squares:?} current layout on a legacy board: {other:?}"),
        }
    }
}

/// Far, steep, blurred and noisy views (the bench's blurred kind, markers
/// ~35 px whose thresholded corners the blur rounds): every visible corner
/// from the 8-bit image as a decoder gives it, within 0.05 px RMS of the
/// truth, and the same corners as from the f32 render to rounding.
#[test]
fn far_steep_blurred_views_give_every_corner_from_the_eight_bit_image() {
    let spec = board();
    let opts = RenderOptions {
        supersampling: 8,
        board_margin_mm: 15.0,
        blur_sigma_px: 2.0,
        noise_sigma_grey: 3.0,
        ..RenderOptions::default()
    };
    for (k, roll_deg) in [0.0, 57.0, 123.0, 211.0, 300.0].into_iter().enumerate() {
        let iso = pose(800.0, 45.0, roll_deg, [20.0, -20.0]);
        let mut rng = StdRng::seed_from_u64(90 + k as u64);
        let view = render_charuco(&reference_camera(), &iso, &spec, W, H, &opts, &mut rng).unwrap();
        let bytes = view.image.to_luma8();
        let det = detect_charuco(&bytes, &spec).unwrap();
        let visible = view.truth.iter().filter(|t| t.visible).count();
        assert_eq!(det.points.len(), visible, "roll {roll_deg}");
        let rms = rms_px(&spec, &det, &view.truth);
        assert!(rms < 0.05, "roll {roll_deg}: RMS {rms}");
        let float = detect_charuco(&GrayImage::from_dynamic(&bytes.clone().into()), &spec).unwrap();
        assert_eq!(float.points.len(), det.points.len());
        for (a, b) in det.points.iter().zip(&float.points) {
            assert_eq!((a.row, a.col), (b.row, b.col));
            assert!((a.x_px - b.x_px).hypot(a.y_px - b.y_px) < 1e-3);
        }
    }
}
