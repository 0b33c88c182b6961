//! A 6-DoF tracker probe's orientation as a full-pose measurement (issue
//! 19, method.md §6): the Euler convention of the Leica T-Mac angles in the
//! Landgraf 2021 UR10 files and the `[dp mm; dr rad]` covariance that
//! [`crate::geometry::pose_error`] whitens.
//!
//! Convention (found on the data, `docs/decisions/0030-tmac-euler-convention.md`):
//! `rx, ry, rz` (deg) are intrinsic X-Y-Z angles,
//! `R = Rx(rx) · Ry(ry) · Rz(rz)`, and `R` with the measured position is
//! the probe's pose in the tracker frame (`tracker_to_probe`, which maps
//! probe coordinates to tracker coordinates, i.e. the calib
//! `world_to_tool`). Note it is **not** the contract's fixed-axis
//! `Rz · Ry · Rx` of [`crate::geometry::pose_from_xyz_rpy_deg`].

use nalgebra::{Matrix3, Matrix6, UnitQuaternion, Vector3};

/// The Leica T-Mac's stated rotation accuracy (deg): added in quadrature
/// to the per-row standard deviations of the file (0.001–0.017°), which
/// are the scatter of the averaged samples, not the probe's accuracy.
pub const PROBE_ROTATION_FLOOR_DEG: f64 = 0.01;
/// The laser tracker's position accuracy at the campaign's 2.3–3.7 m
/// (mm): about half the Leica AT901's MPE of 15 µm + 6 µm/m there
/// (33–37 µm), "typical results are half the MPE". Added in quadrature
/// to the file's per-axis position standard deviations (0.002–0.08 mm).
pub const TRACKER_POSITION_FLOOR_MM: f64 = 0.02;

/// `R = Rx(rx) · Ry(ry) · Rz(rz)`, angles in degrees (the T-Mac's output).
pub fn rotation_from_intrinsic_xyz_deg(angles_deg: [f64; 3]) -> UnitQuaternion<f64> {
    let [rx, ry, rz] = angles_deg.map(f64::to_radians);
    UnitQuaternion::from_axis_angle(&Vector3::x_axis(), rx)
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), ry)
        * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), rz)
}

/// Inverse of [`rotation_from_intrinsic_xyz_deg`]: `ry` in [-90°, 90°].
/// `R^T = Rz(-rz) Ry(-ry) Rx(-rx)` is nalgebra's roll-pitch-yaw form.
pub fn intrinsic_xyz_deg(rotation: &UnitQuaternion<f64>) -> [f64; 3] {
    let (a, b, c) = rotation.inverse().euler_angles();
    [-a, -b, -c].map(f64::to_degrees)
}

/// Covariance (rad², outer = tracker frame, the frame of
/// [`crate::geometry::pose_error`]'s `dr`) of the small rotation `dr`
/// with `R_measured = exp(dr) · R_true`, from independent angle
/// standard deviations `std_deg` of the intrinsic X-Y-Z angles
/// `angles_deg`, plus `floor_deg` isotropic (in quadrature). To first
/// order `dr = x · d(rx) + Rx(rx) y · d(ry) + Rx(rx) Ry(ry) z · d(rz)`.
pub fn orientation_covariance_rad2(
    angles_deg: [f64; 3],
    std_deg: [f64; 3],
    floor_deg: f64,
) -> Matrix3<f64> {
    let [rx, ry, _] = angles_deg.map(f64::to_radians);
    let qx = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), rx);
    let qxy = qx * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), ry);
    let rates = Matrix3::from_columns(&[Vector3::x(), qx * Vector3::y(), qxy * Vector3::z()]);
    let angles_cov =
        Matrix3::from_diagonal(&Vector3::from(std_deg.map(|s| s.to_radians().powi(2))));
    rates * angles_cov * rates.transpose() + Matrix3::identity() * floor_deg.to_radians().powi(2)
}

/// The 6x6 `[dp mm; dr rad]` covariance of a probe pose: per-axis position
/// standard deviations plus [`TRACKER_POSITION_FLOOR_MM`] in quadrature,
/// the orientation by [`orientation_covariance_rad2`] with
/// [`PROBE_ROTATION_FLOOR_DEG`]; position and orientation uncorrelated.
pub fn probe_pose_covariance(
    position_std_mm: &Vector3<f64>,
    angles_deg: [f64; 3],
    angle_std_deg: [f64; 3],
) -> Matrix6<f64> {
    let mut c = Matrix6::zeros();
    for k in 0..3 {
        c[(k, k)] = position_std_mm[k].powi(2) + TRACKER_POSITION_FLOOR_MM.powi(2);
    }
    c.fixed_view_mut::<3, 3>(3, 3)
        .copy_from(&orientation_covariance_rad2(
            angles_deg,
            angle_std_deg,
            PROBE_ROTATION_FLOOR_DEG,
        ));
    c
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use nalgebra::Rotation3;

    #[test]
    fn intrinsic_xyz_is_rx_ry_rz_and_round_trips() {
        let angles = [-104.11792, 5.5122913, -171.42391];
        let q = rotation_from_intrinsic_xyz_deg(angles);
        let [a, b, c] = angles.map(f64::to_radians);
        let expected = Rotation3::from_axis_angle(&Vector3::x_axis(), a)
            * Rotation3::from_axis_angle(&Vector3::y_axis(), b)
            * Rotation3::from_axis_angle(&Vector3::z_axis(), c);
        assert_relative_eq!(
            q.to_rotation_matrix().matrix(),
            expected.matrix(),
            epsilon = 1e-12
        );
        let back = intrinsic_xyz_deg(&q);
        for k in 0..3 {
            assert!((back[k] - angles[k]).abs() < 1e-9, "{back:?}");
        }
    }

    #[test]
    fn angle_noise_maps_to_the_tracker_frame_rotation() {
        // A small change of one angle is a rotation about the axis the
        // formula names, on the left (tracker frame).
        let angles = [-90.2738, -78.802752, -90.384222];
        let step = 1e-4;
        let cov = orientation_covariance_rad2(angles, [0.0, 1.0, 0.0], 0.0);
        let moved = rotation_from_intrinsic_xyz_deg([angles[0], angles[1] + step, angles[2]]);
        let dr_per_rad = (moved * rotation_from_intrinsic_xyz_deg(angles).inverse()).scaled_axis()
            / step.to_radians();
        let expected = dr_per_rad * dr_per_rad.transpose() * 1f64.to_radians().powi(2);
        assert_relative_eq!(cov, expected, epsilon = 1e-10);
        // The floor alone is isotropic.
        let floor = orientation_covariance_rad2(angles, [0.0; 3], PROBE_ROTATION_FLOOR_DEG);
        assert_relative_eq!(
            floor,
            Matrix3::identity() * PROBE_ROTATION_FLOOR_DEG.to_radians().powi(2),
            epsilon = 1e-20
        );
    }
}
