//! The chessboard detector on real photographs
//! (calib/tests/data/aubo_i10_hkclr): 24 photos 2400x1800 of an 11x8
//! inner-corner board from a flange camera, cross-checked against OpenCV 5
//! findChessboardCorners + cornerSubPix (derived_opencv5/).

use std::collections::HashMap;

use super::*;
use crate::vision::image::{decode_image, DecodeLimits};

const AUBO_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/aubo_i10_hkclr");
/// Both are sub-pixel saddle estimates on sharp, high-contrast corners:
/// their median distance must be small, any single one below a pixel (a
/// wrong order would be a whole square, ~60 px, off).
const MAX_MEDIAN_DIFF_PX: f64 = 0.1;
const MAX_DIFF_PX: f64 = 0.5;

pub fn aubo_board() -> ChessboardSpec {
    ChessboardSpec {
        inner_corners: [11, 8],
        square_mm: 10.0,
    }
}

fn opencv_corners() -> HashMap<String, Vec<(f64, f64)>> {
    let csv = std::fs::read_to_string(format!(
        "{AUBO_DIR}/derived_opencv5/corners_findChessboardCorners.csv"
    ))
    .unwrap();
    let mut out: HashMap<String, Vec<(f64, f64)>> = HashMap::new();
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        out.entry(f[0].to_string())
            .or_default()
            .push((f[2].parse().unwrap(), f[3].parse().unwrap()));
    }
    out
}

/// Every image file, `groupN/name.png`, sorted.
pub fn aubo_images() -> Vec<String> {
    let mut names = Vec::new();
    for g in 1..=6 {
        let dir = format!("{AUBO_DIR}/images/group{g}");
        for e in std::fs::read_dir(&dir).unwrap() {
            let name = e.unwrap().file_name().into_string().unwrap();
            names.push(format!("group{g}/{name}"));
        }
    }
    names.sort();
    names
}

#[test]
fn every_aubo_photo_gives_the_board_in_opencv_order() {
    let spec = aubo_board();
    let reference = opencv_corners();
    let names = aubo_images();
    assert_eq!(names.len(), 24);
    let mut all = Vec::new();
    for name in &names {
        let bytes = std::fs::read(format!("{AUBO_DIR}/images/{name}")).unwrap();
        let img = decode_image(&bytes, &DecodeLimits::default()).unwrap();
        let det = detect_chessboard(&img, &spec).unwrap();
        assert!(det.ordering_unique, "11x8 is not half-turn symmetric");
        assert_eq!(det.points.len(), 88, "{name}");
        let cv = &reference[name];
        let mut d: Vec<f64> = det
            .points
            .iter()
            .map(|p| {
                let (x, y) = cv[p.row * spec.cols() + p.col];
                (p.x_px - x).hypot(p.y_px - y)
            })
            .collect();
        d.sort_by(f64::total_cmp);
        let (median, worst) = (d[d.len() / 2], d[d.len() - 1]);
        eprintln!("{name}: median {median:.3} px, worst {worst:.3} px from OpenCV");
        assert!(worst < MAX_DIFF_PX, "{name}: worst {worst}");
        all.extend(d);
    }
    all.sort_by(f64::total_cmp);
    let median = all[all.len() / 2];
    eprintln!("all 24: median {median:.3} px from OpenCV");
    assert!(median < MAX_MEDIAN_DIFF_PX, "median {median}");
}
