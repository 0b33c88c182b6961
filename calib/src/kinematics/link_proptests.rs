//! Property tests of the link transforms (issue 13): a DH or Hayati link
//! equals its defining product of elementary transforms (method.md §5), and
//! its parameters are read back from the transform it makes.

use nalgebra::{Matrix4, Vector3};
use proptest::prelude::*;

use super::*;

const LENGTH_MM: f64 = 2_000.0;
const PI: f64 = std::f64::consts::PI;
/// Hayati links are used where consecutive axes are nearly parallel: the
/// tilt stays well inside +-90 deg, where it is read back uniquely.
const MAX_TILT_RAD: f64 = 1.2;
const TOL: f64 = 1e-9;

fn rot_z(t: f64) -> Matrix4<f64> {
    let (s, c) = t.sin_cos();
    Matrix4::new(
        c, -s, 0.0, 0.0, s, c, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    )
}
fn rot_x(t: f64) -> Matrix4<f64> {
    let (s, c) = t.sin_cos();
    Matrix4::new(
        1.0, 0.0, 0.0, 0.0, 0.0, c, -s, 0.0, 0.0, s, c, 0.0, 0.0, 0.0, 0.0, 1.0,
    )
}
fn rot_y(t: f64) -> Matrix4<f64> {
    let (s, c) = t.sin_cos();
    Matrix4::new(
        c, 0.0, s, 0.0, 0.0, 1.0, 0.0, 0.0, -s, 0.0, c, 0.0, 0.0, 0.0, 0.0, 1.0,
    )
}
fn shift(v: Vector3<f64>) -> Matrix4<f64> {
    Matrix4::new_translation(&v)
}

fn joint(convention: Convention, a: f64, alpha: f64, d: f64, theta0: f64, beta: f64) -> Joint {
    Joint {
        convention,
        a_mm: a,
        alpha_rad: alpha,
        d_mm: if convention == Convention::Dh { d } else { 0.0 },
        theta_offset_rad: theta0,
        beta_rad: if convention == Convention::Hayati {
            beta
        } else {
            0.0
        },
        min_rad: -PI,
        max_rad: PI,
    }
}

fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(2.0 * PI);
    d.min(2.0 * PI - d)
}

proptest! {
    #[test]
    fn dh_link_is_rz_tz_tx_rx(
        a in -LENGTH_MM..LENGTH_MM, alpha in -PI..PI, d in -LENGTH_MM..LENGTH_MM,
        theta0 in -PI..PI, q in -PI..PI,
    ) {
        let j = joint(Convention::Dh, a, alpha, d, theta0, 0.0);
        let expected = rot_z(q + theta0) * shift(Vector3::z() * d) * shift(Vector3::x() * a) * rot_x(alpha);
        let got = j.link_transform(q).to_homogeneous();
        prop_assert!((got - expected).amax() < TOL, "{got} vs {expected}");
    }

    #[test]
    fn hayati_link_is_rz_tx_rx_ry(
        a in -LENGTH_MM..LENGTH_MM, alpha in -PI..PI, beta in -MAX_TILT_RAD..MAX_TILT_RAD,
        theta0 in -PI..PI, q in -PI..PI,
    ) {
        let j = joint(Convention::Hayati, a, alpha, 0.0, theta0, beta);
        let expected = rot_z(q + theta0) * shift(Vector3::x() * a) * rot_x(alpha) * rot_y(beta);
        let got = j.link_transform(q).to_homogeneous();
        prop_assert!((got - expected).amax() < TOL, "{got} vs {expected}");
    }

    /// DH parameters from the transform: `R = Rz(th) Rx(al)`,
    /// `p = (a cos th, a sin th, d)`.
    #[test]
    fn dh_parameters_read_back_from_the_transform(
        a in -LENGTH_MM..LENGTH_MM, alpha in -PI..PI, d in -LENGTH_MM..LENGTH_MM, theta in -PI..PI,
    ) {
        let m = joint(Convention::Dh, a, alpha, d, 0.0, 0.0).link_transform(theta).to_homogeneous();
        let theta_back = m[(1, 0)].atan2(m[(0, 0)]);
        let alpha_back = m[(2, 1)].atan2(m[(2, 2)]);
        let a_back = m[(0, 3)] * theta_back.cos() + m[(1, 3)] * theta_back.sin();
        prop_assert!(angle_gap(theta_back, theta) < TOL);
        prop_assert!(angle_gap(alpha_back, alpha) < TOL);
        prop_assert!((a_back - a).abs() < TOL * LENGTH_MM);
        prop_assert!((m[(2, 3)] - d).abs() < TOL * LENGTH_MM);
    }

    /// Hayati parameters from the transform: `Rz(th)^T R = Rx(al) Ry(be)`,
    /// `p = Rz(th) (a, 0, 0)`.
    #[test]
    fn hayati_parameters_read_back_from_the_transform(
        a in -LENGTH_MM..LENGTH_MM, alpha in -PI..PI, beta in -MAX_TILT_RAD..MAX_TILT_RAD, theta in -PI..PI,
    ) {
        let j = joint(Convention::Hayati, a, alpha, 0.0, 0.0, beta);
        let m = j.link_transform(theta).to_homogeneous();
        let local = rot_z(theta).transpose() * m;
        let alpha_back = local[(2, 1)].atan2(local[(1, 1)]);
        let beta_back = local[(0, 2)].atan2(local[(0, 0)]);
        prop_assert!(angle_gap(alpha_back, alpha) < TOL);
        prop_assert!((beta_back - beta).abs() < TOL);
        prop_assert!((local[(0, 3)] - a).abs() < TOL * LENGTH_MM);
        prop_assert!(local[(1, 3)].abs() < TOL * LENGTH_MM && m[(2, 3)].abs() < TOL * LENGTH_MM);
    }
}
