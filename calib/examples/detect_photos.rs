//! The detector on the real photographs in shared/data/circles (issue 3):
//! detection rate, agreement with OpenCV 5 findCirclesGrid, and per-view
//! plane-fit reprojection RMS with OpenCV's published intrinsics for the CMU
//! set (same metric for our centres and OpenCV's).
//!
//! `cargo run --release -p robocal-calib --example detect_photos -- DIR`
//!
//! `DIR` holds `cmu_datta_10x7/` and `niftycal_laparoscope/` (the project's
//! data collection, `shared/data/circles`). Unlike the tests, which read the
//! copies in `calib/tests/data/`, it needs the NiftyCal sets, which are not
//! copied into the repository; no test depends on it.

use std::collections::HashMap;

use nalgebra::Vector2;
use robocal_calib::camera::model::Intrinsics;
use robocal_calib::vision::homography::Homography;
use robocal_calib::vision::{decode_image, detect, DecodeLimits, GrayImage, TargetSpec};

const CMU_PITCH_MM: f64 = 23.0;
/// Not published; ~15 mm from the images (sets only the bias correction size).
const CMU_DOT_MM: f64 = 15.0;

fn cmu_camera(data: &str) -> Intrinsics {
    let text = std::fs::read_to_string(format!(
        "{data}/cmu_datta_10x7/derived_opencv5/calibrateCamera_results.json"
    ))
    .unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let m = &v["k1k2p1p2k3 (OpenCV default 5-param)"];
    let d = |i: usize| m["dist"][i].as_f64().unwrap();
    Intrinsics {
        fx: m["fx"].as_f64().unwrap(),
        fy: m["fy"].as_f64().unwrap(),
        cx: m["cx"].as_f64().unwrap(),
        cy: m["cy"].as_f64().unwrap(),
        k1: d(0),
        k2: d(1),
        p1: d(2),
        p2: d(3),
        k3: d(4),
    }
}

/// Squared residuals of a per-view plane fit: undistort with the camera,
/// fit a board-to-normalised homography, re-project through the distortion.
fn plane_fit_sq(cam: &Intrinsics, board: &[Vector2<f64>], px: &[Vector2<f64>]) -> Vec<f64> {
    let rays: Vec<Vector2<f64>> = px
        .iter()
        .map(|p| cam.pixel_to_ray(&(*p).into()).unwrap())
        .collect();
    let h = Homography::fit(board, &rays).unwrap();
    board
        .iter()
        .zip(px)
        .map(|(b, p)| {
            let q = cam.normalized_to_pixel(&cam.distort(&h.apply(b).unwrap()));
            (q.coords - p).norm_squared()
        })
        .collect()
}

fn rms(v: &[f64]) -> f64 {
    (v.iter().sum::<f64>() / v.len().max(1) as f64).sqrt()
}

fn cmu(data: &str) {
    let target = TargetSpec {
        rows: 7,
        cols: 10,
        pitch_mm: CMU_PITCH_MM,
        dot_diameter_mm: CMU_DOT_MM,
        origin_marker_diameter_mm: None,
    };
    let cam = cmu_camera(data);
    let csv = std::fs::read_to_string(format!(
        "{data}/cmu_datta_10x7/derived_opencv5/centers_findCirclesGrid.csv"
    ))
    .unwrap();
    let mut cv: HashMap<String, Vec<Vector2<f64>>> = HashMap::new();
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        cv.entry(f[0].into())
            .or_default()
            .push(Vector2::new(f[4].parse().unwrap(), f[5].parse().unwrap()));
    }
    let mut names: Vec<String> = cv.keys().cloned().collect();
    names.sort();
    let (mut found, mut ours, mut raw, mut theirs, mut diff) = (0, vec![], vec![], vec![], vec![]);
    for name in &names {
        let img = decode_image(
            &std::fs::read(format!("{data}/cmu_datta_10x7/{name}")).unwrap(),
            &DecodeLimits::default(),
        )
        .unwrap();
        match detect(&img, &target) {
            Ok(det) => {
                found += 1;
                let board: Vec<Vector2<f64>> = det
                    .dots
                    .iter()
                    .map(|d| Vector2::new(d.col as f64 * CMU_PITCH_MM, d.row as f64 * CMU_PITCH_MM))
                    .collect();
                let px: Vec<Vector2<f64>> =
                    det.dots.iter().map(|d| Vector2::new(d.x, d.y)).collect();
                let px_raw: Vec<Vector2<f64>> = det
                    .dots
                    .iter()
                    .map(|d| Vector2::new(d.ellipse.cx, d.ellipse.cy))
                    .collect();
                ours.extend(plane_fit_sq(&cam, &board, &px));
                raw.extend(plane_fit_sq(&cam, &board, &px_raw));
                theirs.extend(plane_fit_sq(&cam, &board, &cv[name]));
                diff.extend(px_raw.iter().zip(&cv[name]).map(|(a, b)| (a - b).norm()));
            }
            Err(e) => println!("    {name}: {e}"),
        }
    }
    diff.sort_by(f64::total_cmp);
    println!(
        "cmu_datta_10x7 (1024x768, 10x7, no marker): detected {found}/{}",
        names.len()
    );
    println!(
        "  our raw centres vs OpenCV centres: median {:.3} px, max {:.3} px",
        diff[diff.len() / 2],
        diff[diff.len() - 1]
    );
    println!("  per-view plane-fit reprojection RMS with OpenCV's 5-parameter intrinsics:");
    println!("    ours (bias-corrected) {:.4} px, ours (raw ellipse centres) {:.4} px, OpenCV findCirclesGrid {:.4} px", rms(&ours), rms(&raw), rms(&theirs));
}

fn y_doubled(img: &GrayImage) -> GrayImage {
    let mut data = Vec::with_capacity(img.data.len() * 2);
    for row in img.data.chunks(img.width) {
        data.extend_from_slice(row);
        data.extend_from_slice(row);
    }
    GrayImage {
        width: img.width,
        height: img.height * 2,
        data,
    }
}

fn nifty(data: &str) {
    let files = [
        "tsai_coplanar_10x7/1479224185706804480_left.png",
        "tsai_coplanar_10x7/1479224185706804480_right.png",
        "tsai_noncoplanar_2plane_10x7/1479224227386188288_left.png",
        "tsai_noncoplanar_2plane_10x7/1479224227386188288_right.png",
    ];
    println!("niftycal_laparoscope (1920x540 interlaced; symmetric 10x7 grids, no marker):");
    for f in files {
        let img = decode_image(
            &std::fs::read(format!("{data}/niftycal_laparoscope/{f}")).unwrap(),
            &DecodeLimits::default(),
        )
        .unwrap();
        for (label, im) in [("native", img.clone()), ("y-doubled", y_doubled(&img))] {
            let outcome = [(7, 10), (10, 7)]
                .iter()
                .map(|&(rows, cols)| {
                    let t = TargetSpec {
                        rows,
                        cols,
                        pitch_mm: 4.0,
                        dot_diameter_mm: 2.0,
                        origin_marker_diameter_mm: None,
                    };
                    detect(&im, &t).map(|d| format!("found {} dots as {rows}x{cols}", d.dots.len()))
                })
                .collect::<Vec<_>>();
            let text = match outcome.iter().find(|r| r.is_ok()) {
                Some(Ok(s)) => s.clone(),
                _ => format!("error: {}", outcome[0].as_ref().unwrap_err()),
            };
            println!("  {f} {label}: {text}");
        }
    }
}

fn main() {
    let Some(data) = std::env::args().nth(1) else {
        eprintln!(
            "usage: detect_photos DIR  (DIR holds cmu_datta_10x7/ and niftycal_laparoscope/)"
        );
        std::process::exit(2);
    };
    cmu(&data);
    nifty(&data);
}
