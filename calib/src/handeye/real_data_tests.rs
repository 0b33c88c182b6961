//! Real eye-in-hand data (issue 14): RCT's `test_set_10x10`, 15 webcam
//! images (640x480) of a 10x10 dot grid with a large origin dot, with the
//! controller's flange poses (`poses/N.yaml`: metres and a quaternion) and
//! no joints. Provenance and licence: `PROVENANCE.md` of the data folder.
//!
//! The fixtures live at `calib/tests/data/rct_wrist_circles_10x10` (copied
//! with their licence and provenance); `ROBOCAL_RCT_WRIST_DIR` may point at
//! another copy.

use std::path::PathBuf;

use nalgebra::{Point2, Point3, Quaternion, Translation3, UnitQuaternion};

use super::*;
use crate::camera::model::Intrinsics;
use crate::camera::{calibrate, CalibrationOptions, DotObservation, ImageSize, ViewObservations};
use crate::geometry::Pose;
use crate::vision::{decode_image, detect, BoardPoint, DecodeLimits, TargetSpec};

const IMAGES: usize = 15;
const IMAGE_SIZE: (u32, u32) = (640, 480);
/// The spacing `target.yaml` configures (m 0.0254).
const CONFIGURED_PITCH_MM: f64 = 25.4;
/// The spacing printed on the sheet ("20 mm between dots").
const PRINTED_PITCH_MM: f64 = 20.0;
/// The sheet: small dots half the pitch ("10 mm" at 20), the origin dot
/// ("20 mm" at 20) as large as the pitch; only the detector's size test
/// and the bias correction use them.
const DOT_PER_PITCH: f64 = 0.5;
const MARKER_PER_PITCH: f64 = 1.0;
/// RCT's rough camera guess (`camera_intr.yaml`).
const GUESS_F_PX: f64 = 550.0;
const GUESS_C_PX: (f64, f64) = (320.0, 240.0);
const M_TO_MM: f64 = 1000.0;
/// RCT's own intrinsic calibration of the set (`camera_intr_calibrated.yaml`).
const RCT_FX_PX: f64 = 542.324;
/// The camera stage on the images alone must reproduce RCT's focal this well.
const CAMERA_ONLY_FX_TOLERANCE: f64 = 0.005;
/// Largest reprojection RMS of the bundle with the pitch fitted (px).
const MAX_RMS_PX: f64 = 1.0;
/// The wrong pitch must fit at least this much worse than the fitted one.
const WRONG_PITCH_RMS_RATIO: f64 = 5.0;
/// The hand–eye rotation is -90 deg about the camera axis (RCT's guess)
/// within this much.
const HAND_EYE_ROTATION_TOLERANCE_DEG: f64 = 3.0;
const HAND_EYE_YAW_DEG: f64 = -90.0;
/// Every image is read (issue 14). Four are partial views: image 2 has the
/// origin dot clipped by the border (read from the three plain corners and
/// the board edges, `vision/order.rs`), and in images 6, 11 and 12 the
/// origin dot is seen but fails the sub-pixel outline tests, so it marks
/// the origin without being measured: 99 dots each.
const MIN_DETECTED: usize = IMAGES;

fn data_dir() -> Option<PathBuf> {
    let fixture =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/rct_wrist_circles_10x10");
    if fixture.is_dir() {
        return Some(fixture);
    }
    std::env::var_os("ROBOCAL_RCT_WRIST_DIR")
        .map(PathBuf::from)
        .filter(|p| p.is_dir())
}

fn target(pitch_mm: f64) -> TargetSpec {
    TargetSpec {
        rows: 10,
        cols: 10,
        pitch_mm,
        dot_diameter_mm: DOT_PER_PITCH * pitch_mm,
        origin_marker_diameter_mm: Some(MARKER_PER_PITCH * pitch_mm),
    }
}

/// `base_to_flange` from RCT's pose file (`x: …` lines, metres, quaternion).
fn read_pose(text: &str) -> Pose {
    let value = |key: &str| -> f64 {
        text.lines()
            .find_map(|l| l.strip_prefix(&format!("{key}:")))
            .unwrap_or_else(|| panic!("no {key}"))
            .trim()
            .parse()
            .unwrap()
    };
    let q = UnitQuaternion::from_quaternion(Quaternion::new(
        value("qw"),
        value("qx"),
        value("qy"),
        value("qz"),
    ));
    Pose::from_parts(
        Translation3::new(
            value("x") * M_TO_MM,
            value("y") * M_TO_MM,
            value("z") * M_TO_MM,
        ),
        q,
    )
}

/// The views whose board the detector finds (a view it refuses keeps its
/// flange pose and no points: the calibration reports it as unusable).
fn views(dir: &std::path::Path, pitch_mm: f64) -> Vec<FlangeView> {
    let spec = target(pitch_mm);
    (0..IMAGES)
        .map(|k| {
            let bytes = std::fs::read(dir.join(format!("images/{k}.png"))).unwrap();
            let img = decode_image(&bytes, &DecodeLimits::default()).unwrap();
            let pose = std::fs::read_to_string(dir.join(format!("poses/{k}.yaml"))).unwrap();
            let base_to_flange = read_pose(&pose);
            let det = match detect(&img, &spec) {
                Ok(det) => det,
                Err(e) => {
                    eprintln!("image {k}: {e}");
                    return FlangeView {
                        base_to_flange,
                        points: Vec::new(),
                    };
                }
            };
            assert!(
                det.ordering_unique,
                "image {k}: the origin dot was not found"
            );
            let points = det
                .dots
                .iter()
                .map(|d| BoardPoint {
                    row: d.row,
                    col: d.col,
                    target_mm: spec.dot_centre_mm(d.row, d.col),
                    x_px: d.x,
                    y_px: d.y,
                })
                .collect();
            FlangeView {
                base_to_flange,
                points,
            }
        })
        .collect()
}

/// The user's rough camera guess, everything refined.
fn options(fit_board_scale: bool) -> FlangeOptions {
    FlangeOptions {
        start_intrinsics: Intrinsics::pinhole(GUESS_F_PX, GUESS_F_PX, GUESS_C_PX.0, GUESS_C_PX.1),
        distortion: true,
        hold_intrinsics: false,
        fit_board_scale,
        estimate_flange_noise: false,
    }
}

fn summary(name: &str, fit: &FlangeCalibration) {
    let t = fit.flange_to_camera.translation.vector;
    let s = fit.flange_to_camera_sigma;
    let b = fit.base_to_target.translation.vector;
    let i = fit.intrinsics;
    eprintln!(
        "{name}: rms {:.3} px, fx {:.1} fy {:.1} cx {:.1} cy {:.1} k1 {:.3} k2 {:.3} p1 {:.4} p2 {:.4}; \
         flange_to_camera t [{:.1}, {:.1}, {:.1}] +- [{:.1}, {:.1}, {:.1}] mm, rot {:?} deg +- {:.2?}; \
         board origin in base [{:.1}, {:.1}, {:.1}] mm; scale {:.4} +- {:?}; outliers {:?}",
        fit.rms_px, i.fx, i.fy, i.cx, i.cy, i.k1, i.k2, i.p1, i.p2,
        t.x, t.y, t.z, s.translation_mm[0], s.translation_mm[1], s.translation_mm[2],
        crate::geometry::pose_to_xyz_rpy_deg(&fit.flange_to_camera).1.map(|v| (v * 100.0).round() / 100.0),
        s.rotation_deg,
        b.x, b.y, b.z, fit.board_scale, fit.board_scale_sigma,
        fit.per_pose.iter().enumerate().filter(|(_, p)| p.outlier).map(|(k, _)| k).collect::<Vec<_>>(),
    );
}

/// The camera stage alone (no robot data) on the detected views.
fn camera_only(views: &[FlangeView]) -> (Intrinsics, f64) {
    let obs: Vec<ViewObservations> = views
        .iter()
        .filter(|v| !v.points.is_empty())
        .map(|v| ViewObservations {
            image_size: ImageSize {
                width: IMAGE_SIZE.0,
                height: IMAGE_SIZE.1,
            },
            dots: v
                .points
                .iter()
                .map(|p| DotObservation {
                    row: p.row as u32,
                    col: p.col as u32,
                    target_mm: Point3::from(p.target_mm),
                    pixel: Point2::new(p.x_px, p.y_px),
                })
                .collect(),
        })
        .collect();
    let cal = calibrate(&obs, &CalibrationOptions::default()).unwrap();
    (cal.intrinsics, cal.rms_px)
}

/// Pitch (mm) and hand–eye translation (mm) of a fit, and their
/// jackknife standard deviations.
fn pitch_and_hand_eye(fit: &FlangeCalibration) -> ([f64; 4], [f64; 4]) {
    let t = fit.flange_to_camera.translation.vector;
    let j = fit.jackknife.unwrap();
    let s = j.flange_to_camera.translation_mm;
    (
        [CONFIGURED_PITCH_MM * fit.board_scale, t.x, t.y, t.z],
        [
            CONFIGURED_PITCH_MM * j.board_scale.unwrap(),
            s[0],
            s[1],
            s[2],
        ],
    )
}

#[test]
fn rct_wrist_circles_hand_eye_and_printed_pitch() {
    let dir =
        data_dir().expect("calib/tests/data/rct_wrist_circles_10x10 is part of the repository");
    let configured = views(&dir, CONFIGURED_PITCH_MM);
    let detected = configured.iter().filter(|v| v.points.len() >= 99).count();
    eprintln!("{detected} of {IMAGES} images detected");
    assert!(detected >= MIN_DETECTED);
    // The images alone reproduce RCT's intrinsics.
    // Image 2 is the one view of the image's lower-left corner: the
    // distortion model, fitted on the camera stage alone, is not determined
    // there, and the refined stage reports the focal undetermined (its dots
    // fit the other 14 views' intrinsics to 0.5 px RMS, 1.6 px worst, the
    // others to 0.16 px). The joint bundle below uses it.
    let corner_view = 2;
    let camera_views: Vec<FlangeView> = configured
        .iter()
        .enumerate()
        .filter(|(k, _)| *k != corner_view)
        .map(|(_, v)| v.clone())
        .collect();
    let (camera, camera_rms_px) = camera_only(&camera_views);
    eprintln!("camera stage alone: {camera:?}, rms {camera_rms_px:.3} px");
    assert!((camera.fx / RCT_FX_PX - 1.0).abs() < CAMERA_ONLY_FX_TOLERANCE);

    // One bundle from the rough guess: intrinsics, hand-eye, board, pitch.
    let scaled = calibrate_flange(&configured, &options(true)).unwrap();
    summary("joint, pitch fitted", &scaled);
    let per_pose: Vec<String> = scaled
        .per_pose
        .iter()
        .map(|p| format!("{:.2}", p.rms_px))
        .collect();
    eprintln!("joint, pitch fitted: per-pose RMS px {per_pose:?}");
    for (k, (v, p)) in configured.iter().zip(&scaled.per_pose).enumerate() {
        assert_eq!(p.outlier, v.points.is_empty(), "pose {k}: {p:?}");
    }
    assert!(scaled.rms_px < MAX_RMS_PX);
    let rpy = crate::geometry::pose_to_xyz_rpy_deg(&scaled.flange_to_camera).1;
    assert!(rpy[0].abs() < HAND_EYE_ROTATION_TOLERANCE_DEG);
    assert!(rpy[1].abs() < HAND_EYE_ROTATION_TOLERANCE_DEG);
    assert!((rpy[2] - HAND_EYE_YAW_DEG).abs() < HAND_EYE_ROTATION_TOLERANCE_DEG);
    let (figures, spread) = pitch_and_hand_eye(&scaled);
    eprintln!("joint: pitch and hand-eye t {figures:.3?} mm, jackknife sigma {spread:.3?} mm");

    // Intrinsics held at the images-only camera: the same pitch.
    let held_options = FlangeOptions {
        start_intrinsics: camera,
        hold_intrinsics: true,
        ..options(true)
    };
    let held = calibrate_flange(&configured, &held_options).unwrap();
    summary("intrinsics held, pitch fitted", &held);
    let (held_figures, held_spread) = pitch_and_hand_eye(&held);
    eprintln!(
        "held: pitch and hand-eye t {held_figures:.3?} mm, jackknife sigma {held_spread:.3?} mm"
    );

    // The flange poses let carry noise, estimated from the data.
    let noisy_options = FlangeOptions {
        estimate_flange_noise: true,
        ..options(true)
    };
    let noisy = calibrate_flange(&configured, &noisy_options).unwrap();
    summary("joint, pitch fitted, flange noise estimated", &noisy);
    let (noisy_figures, noisy_spread) = pitch_and_hand_eye(&noisy);
    eprintln!(
        "flange noise {:?}: pitch and hand-eye t {noisy_figures:.3?} mm, jackknife sigma {noisy_spread:.3?} mm",
        noisy.flange_noise
    );

    // The pitch the data say, against the configured and the printed one.
    let at_configured = calibrate_flange(&configured, &options(false)).unwrap();
    summary("joint, pitch 25.4 fixed", &at_configured);
    let at_printed = calibrate_flange(&views(&dir, PRINTED_PITCH_MM), &options(false)).unwrap();
    summary("joint, pitch 20 fixed", &at_printed);
    let pitch = figures[0];
    assert!((pitch - held_figures[0]).abs() < 3.0 * spread[0].max(held_spread[0]));
    assert!((pitch - CONFIGURED_PITCH_MM).abs() < (pitch - PRINTED_PITCH_MM).abs() / 5.0);
    assert!(at_printed.rms_px > WRONG_PITCH_RMS_RATIO * scaled.rms_px);
    assert!(at_configured.rms_px > scaled.rms_px);
    // Letting the flange poses carry noise weakens the scale (the flange
    // translations carry it) but still puts it nearer 25.4 than 20, and
    // gives the camera back its images-only focal length.
    let noisy_pitch = noisy_figures[0];
    assert!((noisy_pitch - CONFIGURED_PITCH_MM).abs() < (noisy_pitch - PRINTED_PITCH_MM).abs());
    assert!((noisy.intrinsics.fx / camera.fx - 1.0).abs() < CAMERA_ONLY_FX_TOLERANCE);
}
