//! Analytic derivatives of the projection `u = fx xd + cx, v = m fx yd + cy`
//! (Brown–Conrady distortion of `(x/z, y/z)`, `P_c = R(theta) P + t`) with
//! respect to the refined intrinsics `[fx, m, cx, cy, k1, k2, p1, p2, k3]`
//! and the pose vector `[t, theta]` (rotation vector), for the joint
//! refinement of method.md §4 **beyond**.

use nalgebra::{Matrix2x3, Matrix3, Point3, SMatrix, Vector3, Vector6};

use super::model::{Intrinsics, MIN_DEPTH_MM};
use crate::geometry::pose_from_vector;

/// Intrinsic parameters in the refinement's order.
pub const INTRINSIC_PARAMS: usize = 9;
/// Pose parameters per view.
pub const POSE_PARAMS: usize = 6;
/// Below this rotation angle (rad) the left Jacobian uses its series.
const SMALL_ANGLE: f64 = 1e-8;

fn skew(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// Left Jacobian of SO(3): `exp(theta + d) ~ exp(J_l(theta) d) exp(theta)`.
pub fn so3_left_jacobian(theta: &Vector3<f64>) -> Matrix3<f64> {
    let t = theta.norm();
    let k = skew(theta);
    if t < SMALL_ANGLE {
        return Matrix3::identity() + 0.5 * k;
    }
    Matrix3::identity() + ((1.0 - t.cos()) / (t * t)) * k + ((t - t.sin()) / (t * t * t)) * (k * k)
}

/// The per-view part of the derivatives: the pose's rotation matrix and
/// the SO(3) left Jacobian of its rotation vector, computed once per view
/// rather than once per point (each costs a sine and a cosine).
#[derive(Debug, Clone, Copy)]
pub struct PoseLinearisation {
    rotation: Matrix3<f64>,
    translation: Vector3<f64>,
    left_jacobian: Matrix3<f64>,
}

impl PoseLinearisation {
    /// For the pose vector `[t, theta]` of `camera_to_target`.
    pub fn new(pose: &Vector6<f64>) -> Self {
        let iso = pose_from_vector(pose);
        let theta = Vector3::new(pose[3], pose[4], pose[5]);
        Self {
            rotation: iso.rotation.to_rotation_matrix().into_inner(),
            translation: iso.translation.vector,
            left_jacobian: so3_left_jacobian(&theta),
        }
    }
}

/// `d(u, v)/d intrinsics` (2x9) and `d(u, v)/d pose` (2x6) of one point;
/// `None` behind the camera.
pub fn projection_jacobian(
    intr: &Intrinsics,
    pose: &Vector6<f64>,
    p: &Point3<f64>,
) -> Option<(SMatrix<f64, 2, INTRINSIC_PARAMS>, SMatrix<f64, 2, 6>)> {
    projection_jacobian_at(intr, &PoseLinearisation::new(pose), p)
}

/// [`projection_jacobian`] with the view's part precomputed.
pub fn projection_jacobian_at(
    intr: &Intrinsics,
    pose: &PoseLinearisation,
    p: &Point3<f64>,
) -> Option<(SMatrix<f64, 2, INTRINSIC_PARAMS>, SMatrix<f64, 2, 6>)> {
    let rp = pose.rotation * p.coords;
    let pc = rp + pose.translation;
    if pc.z <= MIN_DEPTH_MM {
        return None;
    }
    let inv_z = 1.0 / pc.z;
    let (x, y) = (pc.x * inv_z, pc.y * inv_z);
    let n = nalgebra::Vector2::new(x, y);
    let d = intr.distort(&n);
    let r2 = x * x + y * y;
    let m = intr.fy / intr.fx;
    let (fx, fy) = (intr.fx, intr.fy);
    let mut ji = SMatrix::<f64, 2, INTRINSIC_PARAMS>::zeros();
    ji[(0, 0)] = d.x;
    ji[(1, 0)] = m * d.y;
    ji[(1, 1)] = fx * d.y;
    ji[(0, 2)] = 1.0;
    ji[(1, 3)] = 1.0;
    let r4 = r2 * r2;
    for (col, power) in [(4, r2), (5, r4), (8, r4 * r2)] {
        ji[(0, col)] = fx * x * power;
        ji[(1, col)] = fy * y * power;
    }
    ji[(0, 6)] = fx * 2.0 * x * y;
    ji[(1, 6)] = fy * (r2 + 2.0 * y * y);
    ji[(0, 7)] = fx * (r2 + 2.0 * x * x);
    ji[(1, 7)] = fy * 2.0 * x * y;
    // Chain: pixel <- distorted <- normalised <- camera point <- pose.
    let dd = intr.distort_jacobian(&n);
    let d_pixel_d_norm = nalgebra::Matrix2::new(
        fx * dd[(0, 0)],
        fx * dd[(0, 1)],
        fy * dd[(1, 0)],
        fy * dd[(1, 1)],
    );
    let d_norm_d_pc = Matrix2x3::new(inv_z, 0.0, -x * inv_z, 0.0, inv_z, -y * inv_z);
    let d_pixel_d_pc = d_pixel_d_norm * d_norm_d_pc;
    // d pc / d theta = -[R p]x J_l(theta).
    let d_pixel_d_theta = -(d_pixel_d_pc * skew(&rp)) * pose.left_jacobian;
    let mut jp = SMatrix::<f64, 2, 6>::zeros();
    jp.fixed_view_mut::<2, 3>(0, 0).copy_from(&d_pixel_d_pc);
    jp.fixed_view_mut::<2, 3>(0, 3).copy_from(&d_pixel_d_theta);
    Some((ji, jp))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn analytic_projection_jacobian_matches_finite_differences() {
        let intr = Intrinsics {
            fx: 1200.0,
            fy: 1185.0,
            cx: 640.0,
            cy: 500.0,
            k1: -0.12,
            k2: 0.09,
            p1: 3e-4,
            p2: -2e-4,
            k3: 0.01,
        };
        let pose = Vector6::new(-80.0, -60.0, 750.0, 0.5, -0.4, 2.2);
        let p = Point3::new(150.0, 75.0, 0.0);
        let (ji, jp) = projection_jacobian(&intr, &pose, &p).unwrap();
        let encode = |i: &Intrinsics| [i.fx, i.fy / i.fx, i.cx, i.cy, i.k1, i.k2, i.p1, i.p2, i.k3];
        let decode = |v: [f64; 9]| Intrinsics {
            fx: v[0],
            fy: v[0] * v[1],
            cx: v[2],
            cy: v[3],
            k1: v[4],
            k2: v[5],
            p1: v[6],
            p2: v[7],
            k3: v[8],
        };
        let project = |i: &Intrinsics, q: &Vector6<f64>| {
            i.project(&(pose_from_vector(q) * p)).unwrap().coords
        };
        for k in 0..INTRINSIC_PARAMS {
            let h = 1e-6 * encode(&intr)[k].abs().max(1e-3);
            let (mut a, mut b) = (encode(&intr), encode(&intr));
            a[k] += h;
            b[k] -= h;
            let numeric = (project(&decode(a), &pose) - project(&decode(b), &pose)) / (2.0 * h);
            assert!(
                (ji.column(k) - numeric).norm() < 1e-5 * numeric.norm().max(1.0),
                "intrinsic {k}"
            );
        }
        for k in 0..6 {
            let h = 1e-7;
            let (mut a, mut b) = (pose, pose);
            a[k] += h;
            b[k] -= h;
            let numeric = (project(&intr, &a) - project(&intr, &b)) / (2.0 * h);
            assert!(
                (jp.column(k) - numeric).norm() < 1e-5 * numeric.norm().max(1.0),
                "pose {k}: {} vs {numeric}",
                jp.column(k)
            );
        }
    }
}
