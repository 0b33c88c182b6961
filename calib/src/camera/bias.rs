//! Perspective and distortion bias of dot centres (method.md §4 **beyond**).
//!
//! A detector measures the centre of a dot's blob (grey-weighted centroid or
//! ellipse-fit centre), i.e. the area centroid of the image of the dot's
//! circular boundary, not the image of the dot's 3-D centre. The offset
//! between the two is predicted from the current camera model by projecting
//! the boundary (with distortion) and taking the polygon's area centroid;
//! calibration subtracts it from the observations and re-fits, iterating.

use nalgebra::{Isometry3, Point2, Point3, Vector2};

use super::model::Intrinsics;

/// Boundary points per dot for the bias prediction: the polygon's centroid
/// error is second order in the (already sub-pixel) perspective shift.
pub const BOUNDARY_SAMPLES: usize = 96;

/// Area centroid of the image of the circle of `radius_mm` around
/// `centre_target` in the board plane (z = 0), seen with `camera_to_target`
/// (`p_camera = camera_to_target * p_target`); `None` if any boundary point
/// is behind the camera or the polygon is degenerate.
pub fn projected_disc_centroid(
    intrinsics: &Intrinsics,
    camera_to_target: &Isometry3<f64>,
    centre_target: &Point3<f64>,
    radius_mm: f64,
    samples: usize,
) -> Option<Point2<f64>> {
    let boundary: Option<Vec<Point2<f64>>> = (0..samples)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / samples as f64;
            let p = centre_target
                + nalgebra::Vector3::new(radius_mm * a.cos(), radius_mm * a.sin(), 0.0);
            intrinsics.project(&(camera_to_target * p))
        })
        .collect();
    polygon_centroid(&boundary?)
}

/// Area centroid of a simple polygon (shoelace formula), computed relative
/// to the first vertex for precision.
pub fn polygon_centroid(vertices: &[Point2<f64>]) -> Option<Point2<f64>> {
    let origin = *vertices.first()?;
    let (mut area2, mut cx, mut cy) = (0.0, 0.0, 0.0);
    for i in 0..vertices.len() {
        let a = vertices[i] - origin;
        let b = vertices[(i + 1) % vertices.len()] - origin;
        let cross = a.x * b.y - b.x * a.y;
        area2 += cross;
        cx += (a.x + b.x) * cross;
        cy += (a.y + b.y) * cross;
    }
    if area2.abs() <= f64::EPSILON {
        return None;
    }
    Some(origin + Vector2::new(cx, cy) / (3.0 * area2))
}

/// Predicted offset `measured centre - image of the 3-D centre` of one dot.
pub fn centre_bias(
    intrinsics: &Intrinsics,
    camera_to_target: &Isometry3<f64>,
    centre_target: &Point3<f64>,
    radius_mm: f64,
) -> Option<Vector2<f64>> {
    let centroid = projected_disc_centroid(
        intrinsics,
        camera_to_target,
        centre_target,
        radius_mm,
        BOUNDARY_SAMPLES,
    )?;
    let centre = intrinsics.project(&(camera_to_target * centre_target))?;
    Some(centroid - centre)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix3, Translation3, UnitQuaternion, Vector3};

    /// Centre of the ellipse that a pinhole makes of the circle: map the
    /// circle's conic through the plane-to-image homography (independent of
    /// the polygon code).
    fn conic_centre(
        k: &Matrix3<f64>,
        pose: &Isometry3<f64>,
        c: &Point3<f64>,
        r: f64,
    ) -> Point2<f64> {
        let rot = pose.rotation.to_rotation_matrix();
        let t = pose.translation.vector;
        let h = k * Matrix3::from_columns(&[
            rot.matrix().column(0).into_owned(),
            rot.matrix().column(1).into_owned(),
            t,
        ]);
        let circle = Matrix3::new(
            1.0,
            0.0,
            -c.x,
            0.0,
            1.0,
            -c.y,
            -c.x,
            -c.y,
            c.x * c.x + c.y * c.y - r * r,
        );
        let h_inv = h.try_inverse().unwrap();
        let q = h_inv.transpose() * circle * h_inv;
        let a = nalgebra::Matrix2::new(q[(0, 0)], q[(0, 1)], q[(1, 0)], q[(1, 1)]);
        let b = Vector2::new(q[(0, 2)], q[(1, 2)]);
        Point2::from(-(a.try_inverse().unwrap() * b))
    }

    #[test]
    fn pinhole_bias_matches_the_conic_centre_of_the_projected_circle() {
        let cam = Intrinsics::pinhole(1500.0, 1500.0, 640.0, 512.0);
        let pose = Isometry3::from_parts(
            Translation3::new(-80.0, -60.0, 700.0),
            UnitQuaternion::from_scaled_axis(Vector3::new(0.5, -0.3, 0.2)),
        );
        let k = Matrix3::new(1500.0, 0.0, 640.0, 0.0, 1500.0, 512.0, 0.0, 0.0, 1.0);
        let c = Point3::new(150.0, 100.0, 0.0);
        let centroid = projected_disc_centroid(&cam, &pose, &c, 4.0, 720).unwrap();
        let expected = conic_centre(&k, &pose, &c, 4.0);
        assert!(
            (centroid - expected).norm() < 1e-5,
            "{centroid} vs {expected}"
        );
        // The bias is real (well above detector noise) and the default
        // sampling predicts it to far below 0.001 px.
        let bias = centre_bias(&cam, &pose, &c, 4.0).unwrap();
        let exact = expected - cam.project(&(pose * c)).unwrap();
        assert!(bias.norm() > 0.01, "bias {bias}");
        assert!((bias - exact).norm() < 1e-4, "{bias} vs {exact}");
    }

    #[test]
    fn fronto_parallel_undistorted_disc_has_no_bias() {
        let cam = Intrinsics::pinhole(1500.0, 1500.0, 640.0, 512.0);
        let pose = Isometry3::translation(-100.0, -100.0, 800.0);
        let bias = centre_bias(&cam, &pose, &Point3::new(75.0, 50.0, 0.0), 4.0).unwrap();
        assert!(bias.norm() < 1e-9);
    }
}
