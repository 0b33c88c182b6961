//! The detector on real photographs (calib/tests/data/circles/cmu_datta_10x7):
//! 20 images of a 10x7 symmetric grid without marker, strong barrel
//! distortion; cross-checked against OpenCV 5 findCirclesGrid centres.

use std::collections::HashMap;

use super::*;

const CMU_DIR: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/circles/cmu_datta_10x7"
);
/// Largest accepted median distance to OpenCV's blob centroids, px (both are
/// uncorrected centres of ~45 px dots; OpenCV's are coarser).
const MAX_MEDIAN_DIFF_PX: f64 = 0.15;
const MAX_DIFF_PX: f64 = 1.0;

/// The CMU board: 7 rows x 10 cols, 23 mm pitch, no marker; the dot diameter
/// is not published, ~15 mm from the images (only the bias size uses it).
pub fn cmu_target() -> TargetSpec {
    TargetSpec {
        rows: 7,
        cols: 10,
        pitch_mm: 23.0,
        dot_diameter_mm: 15.0,
        origin_marker_diameter_mm: None,
    }
}

fn opencv_centres() -> HashMap<String, Vec<(f64, f64)>> {
    let csv = std::fs::read_to_string(format!(
        "{CMU_DIR}/derived_opencv5/centers_findCirclesGrid.csv"
    ))
    .unwrap();
    let mut out: HashMap<String, Vec<(f64, f64)>> = HashMap::new();
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        out.entry(f[0].to_string())
            .or_default()
            .push((f[4].parse().unwrap(), f[5].parse().unwrap()));
    }
    out
}

#[test]
fn all_cmu_photographs_are_detected_and_agree_with_opencv() {
    let reference = opencv_centres();
    let mut diffs = Vec::new();
    let mut names: Vec<&String> = reference.keys().collect();
    names.sort();
    assert_eq!(names.len(), 20);
    for name in names {
        let bytes = std::fs::read(format!("{CMU_DIR}/{name}")).unwrap();
        let img = decode_image(&bytes, &DecodeLimits::default()).unwrap();
        let det = detect(&img, &cmu_target()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(!det.ordering_unique);
        assert_eq!(det.dots.len(), 70);
        // Our origin is the top-left-most corner, row-major with +x along
        // the 10-dot rows: OpenCV's index 0 is the top-left dot too.
        let cv = &reference[name];
        for (d, c) in det.dots.iter().zip(cv) {
            diffs.push((d.ellipse.cx - c.0).hypot(d.ellipse.cy - c.1));
        }
    }
    diffs.sort_by(f64::total_cmp);
    let median = diffs[diffs.len() / 2];
    let max = diffs[diffs.len() - 1];
    assert!(
        median < MAX_MEDIAN_DIFF_PX && max < MAX_DIFF_PX,
        "median {median:.3} max {max:.3}"
    );
}
