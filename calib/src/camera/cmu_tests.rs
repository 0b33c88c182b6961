//! Real dot-grid photographs (calib/tests/data/circles/cmu_datta_10x7): calibrate
//! from OpenCV's detected centres and compare with OpenCV's own
//! `calibrateCamera` on the same points (derived_opencv5/README).

use std::collections::BTreeMap;

use nalgebra::{Point2, Point3};

use super::*;
use crate::camera::observations::DotObservation;

const CENTRES: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/circles/cmu_datta_10x7/derived_opencv5/centers_findCirclesGrid.csv"
);
/// Dot spacing (dataset README).
const PITCH_MM: f64 = 23.0;
const IMAGE_SIZE: ImageSize = ImageSize {
    width: 1024,
    height: 768,
};
/// OpenCV 5 `calibrateCamera` RMS on these points (README).
const OPENCV_RMS_5_PARAM: f64 = 0.0785;
const OPENCV_FX_5_PARAM: f64 = 844.05;
const OPENCV_CX_5_PARAM: f64 = 506.21;
const OPENCV_CY_5_PARAM: f64 = 365.64;

/// Views in file order, each dot at `(col p, row p, 0)`.
pub fn cmu_views() -> Vec<ViewObservations> {
    let text = std::fs::read_to_string(CENTRES).unwrap();
    let mut views: BTreeMap<String, Vec<DotObservation>> = BTreeMap::new();
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let (row, col): (u32, u32) = (f[2].parse().unwrap(), f[3].parse().unwrap());
        views
            .entry(f[0].to_string())
            .or_default()
            .push(DotObservation {
                row,
                col,
                target_mm: Point3::new(col as f64 * PITCH_MM, row as f64 * PITCH_MM, 0.0),
                pixel: Point2::new(f[4].parse().unwrap(), f[5].parse().unwrap()),
            });
    }
    views
        .into_values()
        .map(|dots| ViewObservations {
            image_size: IMAGE_SIZE,
            dots,
        })
        .collect()
}

#[test]
fn cmu_dot_photos_calibrate_as_well_as_opencv() {
    let views = cmu_views();
    assert_eq!(views.len(), 20);
    // Same points, same model as OpenCV's default (k1, k2, p1, p2, k3), no
    // outlier removal, no bias correction (the dot diameter is not given).
    let all_points = CalibrationOptions {
        estimate_k3: true,
        outlier_sigmas: f64::MAX,
        ..Default::default()
    };
    let cal = calibrate(&views, &all_points).unwrap();
    let i = cal.intrinsics;
    println!(
        "5-param: rms {:.4} px (OpenCV {OPENCV_RMS_5_PARAM}) {i:?}",
        cal.rms_px
    );
    assert!(
        cal.rms_px <= OPENCV_RMS_5_PARAM + 5e-4,
        "same minimum as OpenCV or better"
    );
    assert!((i.fx - OPENCV_FX_5_PARAM).abs() < 1.0);
    assert!((i.cx - OPENCV_CX_5_PARAM).abs() < 0.5 && (i.cy - OPENCV_CY_5_PARAM).abs() < 0.5);
    // The default model (k1, k2, p1, p2) with outlier rejection.
    let default = calibrate(&views, &CalibrationOptions::default()).unwrap();
    println!(
        "4-param default: rms {:.4} px, {} outliers, {:?}",
        default.rms_px,
        default.outliers.len(),
        default.intrinsics
    );
    assert!(default.rms_px < 2.0 * OPENCV_RMS_5_PARAM);
    // The paper's method on the same points.
    let paper = calibrate(
        &views,
        &CalibrationOptions {
            mode: CalibrationMode::Paper,
            ..Default::default()
        },
    )
    .unwrap();
    println!("paper: rms {:.4} px {:?}", paper.rms_px, paper.intrinsics);
    assert!(paper.paper_mode);
}
