use nalgebra::{Point2, Point3};
use robocal_calib::camera::pose::{estimate_pose, reprojection_residuals};
use robocal_calib::camera::{
    calibrate, CalibrationOptions, DotObservation, ImageSize, ViewObservations,
};
use robocal_calib::vision::{decode_image, detect, DecodeLimits, TargetSpec};
fn main() {
    let t = TargetSpec {
        rows: 10,
        cols: 10,
        pitch_mm: 25.4,
        dot_diameter_mm: 12.7,
        origin_marker_diameter_mm: Some(25.4),
    };
    let mut views = Vec::new();
    for k in 0..15 {
        let bytes = std::fs::read(format!(
            "calib/tests/data/rct_wrist_circles_10x10/images/{k}.png"
        ))
        .unwrap();
        let img = decode_image(&bytes, &DecodeLimits::default()).unwrap();
        let det = detect(&img, &t).unwrap();
        views.push(ViewObservations {
            image_size: ImageSize {
                width: 640,
                height: 480,
            },
            dots: det
                .dots
                .iter()
                .map(|d| DotObservation {
                    row: d.row as u32,
                    col: d.col as u32,
                    target_mm: Point3::from(t.dot_centre_mm(d.row, d.col)),
                    pixel: Point2::new(d.x, d.y),
                })
                .collect(),
        });
    }
    let set: Vec<usize> = (0..15).filter(|k| *k != 2).collect();
    let obs: Vec<ViewObservations> = set.iter().map(|&k| views[k].clone()).collect();
    let c = calibrate(&obs, &CalibrationOptions::default()).unwrap();
    let pairs: Vec<(Point3<f64>, Point2<f64>)> = views[2]
        .dots
        .iter()
        .map(|d| (d.target_mm, d.pixel))
        .collect();
    let pose = estimate_pose(&c.intrinsics, &pairs, None).unwrap();
    let mut r = vec![0.0; 2 * pairs.len()];
    reprojection_residuals(
        &c.intrinsics,
        &pose.target_to_camera.inverse(),
        &pairs,
        &mut r,
    )
    .unwrap();
    for (i, d) in views[2].dots.iter().enumerate() {
        let e = r[2 * i].hypot(r[2 * i + 1]);
        if e > 0.4 {
            println!(
                "({},{}) at {:.1},{:.1}: residual {:.2} px",
                d.row, d.col, d.pixel.x, d.pixel.y, e
            );
        }
    }
}
