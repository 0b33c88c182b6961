//! Projection of target points through a camera pose, with analytic
//! derivatives, shared by the per-image pose fit and the joint refinement
//! (method.md §6 **beyond**).
//!
//! The camera pose is `target_to_camera` (`T = (R, t)`), perturbed on the
//! left as in [`crate::geometry::perturb_left`]: `t + dt`, `exp(dr) R`. Then
//! `p_c = R^T (P - t)` moves by `-R^T dt + R^T [P - t]x dr`.

use nalgebra::{Matrix2x3, Matrix3, Point2, Point3, SMatrix, Vector2};

use crate::camera::model::{Intrinsics, MIN_DEPTH_MM};
use crate::geometry::Pose;

/// Intrinsics refined by the joint stage, in this order (k3 stays fixed).
pub const INTRINSIC_NAMES: [&str; 8] = ["fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2"];

/// Pixel of target point `p_target` and the derivatives of the pixel with
/// respect to the left perturbation of `target_to_camera` (2x6) and to the
/// intrinsics of [`INTRINSIC_NAMES`] (2x8). `None` behind the camera.
pub fn project_with_jacobians(
    cam: &Intrinsics,
    target_to_camera: &Pose,
    p_target: &Point3<f64>,
) -> Option<(Point2<f64>, SMatrix<f64, 2, 6>, SMatrix<f64, 2, 8>)> {
    let rt = target_to_camera.rotation.inverse();
    let rel = p_target.coords - target_to_camera.translation.vector;
    let pc = rt * rel;
    if pc.z <= MIN_DEPTH_MM {
        return None;
    }
    let n = Vector2::new(pc.x / pc.z, pc.y / pc.z);
    let d = cam.distort(&n);
    let uv = cam.normalized_to_pixel(&d);
    let dn_dp = Matrix2x3::new(
        1.0 / pc.z,
        0.0,
        -pc.x / (pc.z * pc.z),
        0.0,
        1.0 / pc.z,
        -pc.y / (pc.z * pc.z),
    );
    let f = nalgebra::Matrix2::new(cam.fx, 0.0, 0.0, cam.fy);
    let duv_dp = f * cam.distort_jacobian(&n) * dn_dp;
    let r_t = rt.to_rotation_matrix().into_inner();
    let dp_dt: Matrix3<f64> = -r_t;
    let dp_dr: Matrix3<f64> = r_t * rel.cross_matrix();
    let mut j_pose = SMatrix::<f64, 2, 6>::zeros();
    j_pose
        .fixed_view_mut::<2, 3>(0, 0)
        .copy_from(&(duv_dp * dp_dt));
    j_pose
        .fixed_view_mut::<2, 3>(0, 3)
        .copy_from(&(duv_dp * dp_dr));
    let (x, y) = (n.x, n.y);
    let r2 = x * x + y * y;
    let (fx, fy) = (cam.fx, cam.fy);
    let j_cam = SMatrix::<f64, 2, 8>::from_row_slice(&[
        d.x,
        0.0,
        1.0,
        0.0,
        fx * x * r2,
        fx * x * r2 * r2,
        fx * 2.0 * x * y,
        fx * (r2 + 2.0 * x * x),
        0.0,
        d.y,
        0.0,
        1.0,
        fy * y * r2,
        fy * y * r2 * r2,
        fy * (r2 + 2.0 * y * y),
        fy * 2.0 * x * y,
    ]);
    Some((uv, j_pose, j_cam))
}

/// Intrinsics moved by `delta` in the order of [`INTRINSIC_NAMES`].
pub fn apply_intrinsics(cam: &Intrinsics, delta: &[f64]) -> Intrinsics {
    Intrinsics {
        fx: cam.fx + delta[0],
        fy: cam.fy + delta[1],
        cx: cam.cx + delta[2],
        cy: cam.cy + delta[3],
        k1: cam.k1 + delta[4],
        k2: cam.k2 + delta[5],
        p1: cam.p1 + delta[6],
        p2: cam.p2 + delta[7],
        k3: cam.k3,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{perturb_left, pose_from_xyz_rpy_deg};
    use nalgebra::Vector6;

    #[test]
    fn projection_jacobians_match_finite_differences() {
        let cam = Intrinsics {
            fx: 3500.0,
            fy: 3490.0,
            cx: 1020.0,
            cy: 770.0,
            k1: -0.1,
            k2: 0.05,
            p1: 3e-4,
            p2: -2e-4,
            k3: 0.0,
        };
        let pose = pose_from_xyz_rpy_deg([50.0, 80.0, -800.0], [10.0, -25.0, 5.0]).unwrap();
        let p = Point3::new(150.0, 25.0, 0.0);
        let (uv, jp, jc) = project_with_jacobians(&cam, &pose, &p).unwrap();
        let h = 1e-6;
        for k in 0..6 {
            let mut d = Vector6::zeros();
            d[k] = h;
            let plus = cam
                .project(&(perturb_left(&pose, &d).inverse() * p))
                .unwrap();
            d[k] = -h;
            let minus = cam
                .project(&(perturb_left(&pose, &d).inverse() * p))
                .unwrap();
            let fd = (plus - minus) / (2.0 * h);
            assert!(
                (fd - jp.column(k)).amax() < 1e-4 * (1.0 + fd.amax()),
                "pose {k}"
            );
        }
        for k in 0..8 {
            let mut d = [0.0; 8];
            d[k] = h;
            let plus = apply_intrinsics(&cam, &d)
                .project(&(pose.inverse() * p))
                .unwrap();
            d[k] = -h;
            let minus = apply_intrinsics(&cam, &d)
                .project(&(pose.inverse() * p))
                .unwrap();
            let fd = (plus - minus) / (2.0 * h);
            assert!(
                (fd - jc.column(k)).amax() < 1e-4 * (1.0 + fd.amax()),
                "cam {k}"
            );
        }
        assert!((uv - cam.project(&(pose.inverse() * p)).unwrap()).norm() < 1e-9);
    }
}
