//! Property tests of the pose conversions (issue 13): every form the
//! contract accepts (xyz + roll–pitch–yaw in degrees, 4x4 rows, the 6-vector
//! of the solvers) converts to the same pose and back.

use proptest::prelude::*;

use super::*;

/// Translations within a robot cell's reach (mm).
const REACH_MM: f64 = 5_000.0;
/// Pitch stays this far from +-90 deg, where roll and yaw merge.
const GIMBAL_MARGIN_DEG: f64 = 1.0;
/// Round-off allowed on translations (mm) and rotation entries.
const TOL_MM: f64 = 1e-9;
const TOL_ROT: f64 = 1e-12;
const TOL_DEG: f64 = 1e-7;

fn translation() -> impl Strategy<Value = [f64; 3]> {
    prop::array::uniform3(-REACH_MM..REACH_MM)
}

fn rotation_deg() -> impl Strategy<Value = [f64; 3]> {
    let pitch = -90.0 + GIMBAL_MARGIN_DEG..90.0 - GIMBAL_MARGIN_DEG;
    (-180.0..180.0f64, pitch, -180.0..180.0f64).prop_map(|(r, p, y)| [r, p, y])
}

fn same_pose(a: &Pose, b: &Pose) -> bool {
    (a.translation.vector - b.translation.vector).amax() < TOL_MM
        && (a.rotation.to_rotation_matrix().matrix() - b.rotation.to_rotation_matrix().matrix())
            .amax()
            < TOL_ROT
}

/// Angle difference folded into (-180, 180].
fn angle_gap_deg(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    if d > 180.0 {
        360.0 - d
    } else {
        d
    }
}

proptest! {
    #[test]
    fn xyz_rpy_round_trips(t in translation(), r in rotation_deg()) {
        let pose = pose_from_xyz_rpy_deg(t, r).unwrap();
        let (t2, r2) = pose_to_xyz_rpy_deg(&pose);
        for k in 0..3 {
            prop_assert!((t[k] - t2[k]).abs() < TOL_MM);
            prop_assert!(angle_gap_deg(r[k], r2[k]) < TOL_DEG, "{:?} vs {:?}", r, r2);
        }
    }

    #[test]
    fn matrix_rows_round_trip(t in translation(), r in rotation_deg()) {
        let pose = pose_from_xyz_rpy_deg(t, r).unwrap();
        let rows = pose_to_matrix_rows(&pose);
        prop_assert_eq!(rows[3], [0.0, 0.0, 0.0, 1.0]);
        let back = pose_from_matrix_rows(&rows).unwrap();
        prop_assert!(same_pose(&pose, &back));
    }

    #[test]
    fn the_solver_vector_round_trips(t in translation(), r in rotation_deg()) {
        let pose = pose_from_xyz_rpy_deg(t, r).unwrap();
        let back = pose_from_vector(&pose_to_vector(&pose));
        prop_assert!(same_pose(&pose, &back));
        prop_assert!(pose_error(&pose, &back).amax() < TOL_MM);
    }

    #[test]
    fn the_rows_form_is_the_rpy_composition(t in translation(), r in rotation_deg()) {
        // R = Rz(yaw) Ry(pitch) Rx(roll), built from plain matrices.
        let [rx, ry, rz] = r.map(f64::to_radians);
        let (sx, cx, sy, cy, sz, cz) = (rx.sin(), rx.cos(), ry.sin(), ry.cos(), rz.sin(), rz.cos());
        let mx = Matrix3::new(1.0, 0.0, 0.0, 0.0, cx, -sx, 0.0, sx, cx);
        let my = Matrix3::new(cy, 0.0, sy, 0.0, 1.0, 0.0, -sy, 0.0, cy);
        let mz = Matrix3::new(cz, -sz, 0.0, sz, cz, 0.0, 0.0, 0.0, 1.0);
        let expected = mz * my * mx;
        let rows = pose_to_matrix_rows(&pose_from_xyz_rpy_deg(t, r).unwrap());
        for i in 0..3 {
            for j in 0..3 {
                prop_assert!((rows[i][j] - expected[(i, j)]).abs() < TOL_ROT);
            }
            prop_assert!((rows[i][3] - t[i]).abs() < TOL_MM);
        }
    }

    #[test]
    fn non_rigid_rows_are_refused(t in translation(), r in rotation_deg(), scale in 1.01..2.0f64) {
        let mut rows = pose_to_matrix_rows(&pose_from_xyz_rpy_deg(t, r).unwrap());
        for row in rows.iter_mut().take(3) {
            row[0] *= scale;
        }
        prop_assert!(pose_from_matrix_rows(&rows).is_err());
    }
}
