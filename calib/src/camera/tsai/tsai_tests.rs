//! Tsai stages on exact synthetic data (method.md §3).

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};

use super::*;

/// A tilted board seen by a pinhole with Tsai-form distortion `k` (px^-2,
/// distorted -> undistorted, radius in y pixels).
fn synthetic(fx: f64, m: f64, k: f64) -> (Vec<CentredPoint>, Isometry3<f64>) {
    let pose = Isometry3::from_parts(
        Translation3::new(-90.0, -70.0, 800.0),
        UnitQuaternion::from_scaled_axis(Vector3::new(0.45, -0.25, 0.3)),
    );
    let mut points = Vec::new();
    for r in 0..9 {
        for c in 0..9 {
            let w = Point3::new(c as f64 * 25.0, r as f64 * 25.0, 0.0);
            let p = pose * w;
            let (xu, yu) = (fx * p.x / p.z, m * fx * p.y / p.z);
            // Invert Xu = Xd (1 + k r^2) by fixed-point iteration.
            let (mut xd, mut yd) = (xu, yu);
            for _ in 0..100 {
                let s = 1.0 + k * ((m * xd).powi(2) + yd * yd);
                (xd, yd) = (xu / s, yu / s);
            }
            points.push(CentredPoint {
                world: w.xy().coords,
                image: nalgebra::Vector2::new(xd, yd),
            });
        }
    }
    (points, pose)
}

#[test]
fn both_stage2_forms_recover_an_exact_pinhole() {
    for m in [1.0, 0.9825] {
        let (points, pose) = synthetic(1000.0, m, 0.0);
        assert!(alignment_residual_rms(&points, m).unwrap() < 1e-9);
        for form in [Stage2Form::BothAxes, Stage2Form::YOnly] {
            let v = calibrate_view(0, &points, m, form).unwrap();
            assert!((v.fx - 1000.0).abs() < 1e-6, "{form:?} fx {}", v.fx);
            assert!(v.k.abs() < 1e-12);
            assert!(
                (v.camera_to_target.translation.vector - pose.translation.vector).norm() < 1e-6
            );
            assert!(v.camera_to_target.rotation.angle_to(&pose.rotation) < 1e-9);
            let tilt = pose.rotation.to_rotation_matrix().matrix()[(2, 2)]
                .acos()
                .to_degrees();
            assert!((v.board_angle_deg - tilt).abs() < 1e-6);
        }
    }
}

#[test]
fn stage2_estimates_tsai_distortion() {
    let k = 8e-8; // the paper's order of magnitude (method.md §2)
    let (points, _) = synthetic(1000.0, 1.0, k);
    let v = calibrate_view(0, &points, 1.0, Stage2Form::BothAxes).unwrap();
    // Eq. 32 linearises 1/(1 - k r^2): small bias, right sign and size.
    assert!((v.k / k - 1.0).abs() < 0.1, "k {}", v.k);
    assert!((v.fx / 1000.0 - 1.0).abs() < 2e-3, "fx {}", v.fx);
}

#[test]
fn stage1_refuses_too_few_points() {
    let (points, _) = synthetic(1000.0, 1.0, 0.0);
    assert!(stage1(&points[..4], 1.0).is_none());
    assert!(calibrate_view(3, &points[..4], 1.0, Stage2Form::BothAxes).is_err());
}
