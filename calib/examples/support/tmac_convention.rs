//! The T-Mac Euler-convention cross-check of `ur10_pose_bench`: the
//! measured rotations under a candidate convention against the nominal
//! UR10 kinematics with its position-fitted `world_to_base` and the best
//! constant tool rotation. The right convention leaves only the nominal
//! model's own error (~0.08°); a wrong one leaves degrees.

use nalgebra::{Matrix3, Unit, UnitQuaternion, Vector3};
use robocal_calib::geometry::{orthonormalize, Pose};
use robocal_calib::kinematics::tracker_csv::TrackerRow;
use robocal_calib::kinematics::tracker_pose::rotation_from_intrinsic_xyz_deg;
use robocal_calib::kinematics::CalibratedModel;

type Convention = Box<dyn Fn([f64; 3]) -> UnitQuaternion<f64>>;

fn about(axis: Vector3<f64>, deg: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Unit::new_normalize(axis), deg.to_radians())
}

/// The found convention, its inverse, the contract's fixed-axis
/// `Rz·Ry·Rx`, and the next best of the hand-eye search.
pub fn candidates() -> Vec<(&'static str, Convention)> {
    vec![
        (
            "Rx(rx)·Ry(ry)·Rz(rz), tool in tracker",
            Box::new(rotation_from_intrinsic_xyz_deg),
        ),
        (
            "its inverse (tracker in tool)",
            Box::new(|a| rotation_from_intrinsic_xyz_deg(a).inverse()),
        ),
        (
            "Rz(rz)·Ry(ry)·Rx(rx) (the contract's rpy)",
            Box::new(|[x, y, z]: [f64; 3]| {
                about(Vector3::z(), z) * about(Vector3::y(), y) * about(Vector3::x(), x)
            }),
        ),
        (
            "Rx(rx)·Ry(ry)·Rx(rz) (next best, hand-eye search)",
            Box::new(|[x, y, z]: [f64; 3]| {
                about(Vector3::x(), x) * about(Vector3::y(), y) * about(Vector3::x(), z)
            }),
        ),
    ]
}

/// Rotation mismatch (deg, rms and max) of `rows` read with `convention`
/// against `model`'s `world_to_base * base_to_flange` times the best
/// constant tool rotation (chordal mean).
pub fn mismatch_deg(
    model: &CalibratedModel,
    rows: &[TrackerRow],
    convention: &Convention,
) -> (f64, f64) {
    let pred: Vec<Pose> = rows
        .iter()
        .map(|r| model.world_to_base * model.robot.base_to_flange(&r.joints_rad).unwrap())
        .collect();
    let measured: Vec<UnitQuaternion<f64>> = rows
        .iter()
        .map(|r| {
            convention(
                r.orientation
                    .expect("T-Mac rows have orientation")
                    .angles_deg,
            )
        })
        .collect();
    let sum: Matrix3<f64> = pred
        .iter()
        .zip(&measured)
        .map(|(p, m)| (p.rotation.inverse() * m).to_rotation_matrix().into_inner())
        .sum();
    let tool = UnitQuaternion::from_rotation_matrix(&orthonormalize(&sum));
    let e: Vec<f64> = pred
        .iter()
        .zip(&measured)
        .map(|(p, m)| (p.rotation * tool).angle_to(m).to_degrees())
        .collect();
    let rms = (e.iter().map(|x| x * x).sum::<f64>() / e.len() as f64).sqrt();
    (rms, e.iter().cloned().fold(0.0, f64::max))
}
