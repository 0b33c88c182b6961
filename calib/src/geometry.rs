//! Rigid transforms and the contract's pose form.
//!
//! Frames are named `a_to_b` = the pose of frame b expressed in frame a
//! (`p_a = a_to_b * p_b`, method.md §1). Inside the numerics a pose is an
//! `Isometry3<f64>` with millimetre translation; the REST contract carries
//! `{"translation_mm":[x,y,z],"rotation_deg":[rx,ry,rz]}` with fixed-axis
//! X-Y-Z roll–pitch–yaw, `R = Rz(rz) Ry(ry) Rx(rx)`, or a 4x4 row-major matrix.

use nalgebra::{
    Isometry3, Matrix3, Matrix4, Point3, Rotation3, Translation3, UnitQuaternion, Vector3, Vector6,
};
use serde::{Deserialize, Serialize};

/// A rigid pose, translation in millimetres.
pub type Pose = Isometry3<f64>;

/// How far a given 3x3 block may be from a rotation before it is refused.
pub const ROTATION_ORTHONORMALITY_TOL: f64 = 1e-6;

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GeometryError {
    #[error("matrix is not a rigid transform: {0}")]
    NotRigid(String),
    #[error("pose contains a non-finite number")]
    NotFinite,
}

/// The contract's pose form (api.md "Poses").
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PoseXyzRpy {
    pub translation_mm: [f64; 3],
    pub rotation_deg: [f64; 3],
}

impl PoseXyzRpy {
    pub fn to_pose(&self) -> Result<Pose, GeometryError> {
        pose_from_xyz_rpy_deg(self.translation_mm, self.rotation_deg)
    }

    pub fn from_pose(pose: &Pose) -> Self {
        let (translation_mm, rotation_deg) = pose_to_xyz_rpy_deg(pose);
        Self {
            translation_mm,
            rotation_deg,
        }
    }
}

/// `R = Rz(rz) Ry(ry) Rx(rx)`; nalgebra's `from_euler_angles(roll, pitch, yaw)`
/// is exactly this composition.
pub fn pose_from_xyz_rpy_deg(
    translation_mm: [f64; 3],
    rotation_deg: [f64; 3],
) -> Result<Pose, GeometryError> {
    if translation_mm
        .iter()
        .chain(rotation_deg.iter())
        .any(|v| !v.is_finite())
    {
        return Err(GeometryError::NotFinite);
    }
    let [rx, ry, rz] = rotation_deg.map(f64::to_radians);
    Ok(Isometry3::from_parts(
        Translation3::new(translation_mm[0], translation_mm[1], translation_mm[2]),
        UnitQuaternion::from_euler_angles(rx, ry, rz),
    ))
}

/// Inverse of [`pose_from_xyz_rpy_deg`].
pub fn pose_to_xyz_rpy_deg(pose: &Pose) -> ([f64; 3], [f64; 3]) {
    let (rx, ry, rz) = pose.rotation.euler_angles();
    let t = pose.translation.vector;
    ([t.x, t.y, t.z], [rx, ry, rz].map(f64::to_degrees))
}

/// The 4x4 homogeneous matrix, row-major.
pub fn pose_to_matrix_rows(pose: &Pose) -> [[f64; 4]; 4] {
    let m = pose.to_homogeneous();
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

/// Parse a 4x4 row-major matrix; the rotation block must be orthonormal with
/// determinant +1 within [`ROTATION_ORTHONORMALITY_TOL`] and the last row
/// `[0,0,0,1]`. The rotation is re-orthonormalised so that round-off does
/// not accumulate.
pub fn pose_from_matrix_rows(rows: &[[f64; 4]; 4]) -> Result<Pose, GeometryError> {
    if rows.iter().flatten().any(|v| !v.is_finite()) {
        return Err(GeometryError::NotFinite);
    }
    let m = Matrix4::from_fn(|i, j| rows[i][j]);
    let last = m.row(3);
    if (last - nalgebra::RowVector4::new(0.0, 0.0, 0.0, 1.0)).amax() > ROTATION_ORTHONORMALITY_TOL {
        return Err(GeometryError::NotRigid("last row must be [0,0,0,1]".into()));
    }
    let r: Matrix3<f64> = m.fixed_view::<3, 3>(0, 0).into_owned();
    let defect = (r.transpose() * r - Matrix3::identity()).amax();
    if defect > ROTATION_ORTHONORMALITY_TOL || r.determinant() <= 0.0 {
        return Err(GeometryError::NotRigid(
            "rotation block is not orthonormal with determinant +1".into(),
        ));
    }
    let rotation = orthonormalize(&r);
    Ok(Isometry3::from_parts(
        Translation3::new(m[(0, 3)], m[(1, 3)], m[(2, 3)]),
        UnitQuaternion::from_rotation_matrix(&rotation),
    ))
}

/// The axis-aligned bounding box `(lo, hi)` of `points`; for no points
/// `lo` is +∞ and `hi` −∞ in every coordinate (callers decide what an
/// empty box means).
pub fn bounding_box(points: impl Iterator<Item = Point3<f64>>) -> (Vector3<f64>, Vector3<f64>) {
    let (mut lo, mut hi) = (
        Vector3::repeat(f64::INFINITY),
        Vector3::repeat(f64::NEG_INFINITY),
    );
    for p in points {
        lo = lo.inf(&p.coords);
        hi = hi.sup(&p.coords);
    }
    (lo, hi)
}

/// Nearest rotation (Frobenius norm) to a 3x3 matrix, by SVD; used after
/// linear estimates such as Tsai's stage 1 (method.md §3).
pub fn orthonormalize(m: &Matrix3<f64>) -> Rotation3<f64> {
    let svd = m.svd(true, true);
    let (u, v_t) = (svd.u.expect("u requested"), svd.v_t.expect("v_t requested"));
    let mut d = Matrix3::identity();
    if (u * v_t).determinant() < 0.0 {
        d[(2, 2)] = -1.0;
    }
    Rotation3::from_matrix_unchecked(u * d * v_t)
}

/// Rotation from a rotation vector (axis times angle, radians).
pub fn rotation_from_vector(v: &Vector3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::from_scaled_axis(*v)
}

/// Rotation vector (axis times angle, radians) of a rotation.
pub fn rotation_vector(q: &UnitQuaternion<f64>) -> Vector3<f64> {
    q.scaled_axis()
}

/// Pose from the 6-vector `[tx, ty, tz, rvx, rvy, rvz]` (mm, rotation vector
/// in radians): the minimal parameterisation used by the solvers.
pub fn pose_from_vector(v: &Vector6<f64>) -> Pose {
    Isometry3::from_parts(
        Translation3::new(v[0], v[1], v[2]),
        rotation_from_vector(&Vector3::new(v[3], v[4], v[5])),
    )
}

/// Inverse of [`pose_from_vector`].
pub fn pose_to_vector(pose: &Pose) -> Vector6<f64> {
    let t = pose.translation.vector;
    let r = rotation_vector(&pose.rotation);
    Vector6::new(t.x, t.y, t.z, r.x, r.y, r.z)
}

/// Apply a small correction `delta = [dt; dr]` on the left of a pose:
/// translation added, rotation `exp(dr) * R` (both in the outer frame).
/// Identification updates `target_to_base` and `flange_to_camera` this way
/// so that the nominal pose is the zero of the parameter (method.md §6).
pub fn perturb_left(pose: &Pose, delta: &Vector6<f64>) -> Pose {
    let dt = Vector3::new(delta[0], delta[1], delta[2]);
    let dr = rotation_from_vector(&Vector3::new(delta[3], delta[4], delta[5]));
    Isometry3::from_parts(
        Translation3::from(pose.translation.vector + dt),
        dr * pose.rotation,
    )
}

/// Measured minus predicted pose, 6 rows (method.md §6): position
/// difference in mm and the small-angle orientation error
/// `log(R_measured R_predicted^T)` in radians, both in the outer frame.
pub fn pose_error(measured: &Pose, predicted: &Pose) -> Vector6<f64> {
    let dt = measured.translation.vector - predicted.translation.vector;
    let dr = rotation_vector(&(measured.rotation * predicted.rotation.inverse()));
    Vector6::new(dt.x, dt.y, dt.z, dr.x, dr.y, dr.z)
}

#[cfg(test)]
#[path = "geometry_proptests.rs"]
mod proptests;

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn rpy_is_rz_ry_rx() {
        let pose = pose_from_xyz_rpy_deg([1.0, 2.0, 3.0], [10.0, 20.0, 30.0]).unwrap();
        let expected = Rotation3::from_axis_angle(&Vector3::z_axis(), 30f64.to_radians())
            * Rotation3::from_axis_angle(&Vector3::y_axis(), 20f64.to_radians())
            * Rotation3::from_axis_angle(&Vector3::x_axis(), 10f64.to_radians());
        assert_relative_eq!(
            pose.rotation.to_rotation_matrix().matrix(),
            expected.matrix(),
            epsilon = 1e-12
        );
        let (t, r) = pose_to_xyz_rpy_deg(&pose);
        assert_relative_eq!(t.as_slice(), [1.0, 2.0, 3.0].as_slice(), epsilon = 1e-12);
        assert_relative_eq!(r.as_slice(), [10.0, 20.0, 30.0].as_slice(), epsilon = 1e-9);
    }

    #[test]
    fn matrix_round_trip_and_rejection() {
        let pose = pose_from_xyz_rpy_deg([100.0, -5.0, 7.5], [-170.0, 45.0, 90.0]).unwrap();
        let rows = pose_to_matrix_rows(&pose);
        let back = pose_from_matrix_rows(&rows).unwrap();
        assert_relative_eq!(
            back.to_homogeneous(),
            pose.to_homogeneous(),
            epsilon = 1e-12
        );
        let mut bad = rows;
        bad[0][1] += 0.5;
        assert!(matches!(
            pose_from_matrix_rows(&bad),
            Err(GeometryError::NotRigid(_))
        ));
        let mut mirrored = rows;
        for row in mirrored.iter_mut().take(3) {
            row[2] = -row[2];
        }
        assert!(pose_from_matrix_rows(&mirrored).is_err());
        assert!(pose_from_xyz_rpy_deg([f64::NAN, 0.0, 0.0], [0.0; 3]).is_err());
    }

    #[test]
    fn vector_form_and_error_are_inverse_of_perturbation() {
        let pose = pose_from_xyz_rpy_deg([10.0, 20.0, 30.0], [5.0, -60.0, 120.0]).unwrap();
        assert_relative_eq!(
            pose_from_vector(&pose_to_vector(&pose)).to_homogeneous(),
            pose.to_homogeneous(),
            epsilon = 1e-12
        );
        let delta = Vector6::new(0.3, -0.2, 0.1, 1e-3, -2e-3, 5e-4);
        let moved = perturb_left(&pose, &delta);
        assert_relative_eq!(pose_error(&moved, &pose), delta, epsilon = 1e-12);
    }

    #[test]
    fn orthonormalize_recovers_rotation_from_noisy_matrix() {
        let r = Rotation3::from_euler_angles(0.3, -0.2, 1.0);
        let noisy = r.matrix() + Matrix3::new(1e-3, 0.0, -2e-3, 0.0, 1e-3, 0.0, 5e-4, 0.0, 0.0);
        let fixed = orthonormalize(&noisy);
        assert_relative_eq!(fixed.matrix().determinant(), 1.0, epsilon = 1e-12);
        assert!(r.angle_to(&fixed) < 3e-3);
    }
}
