//! The calibrated arm as the `kinematics.yaml` Universal Robots' ROS
//! drivers and description packages read (issue 34): six segments
//! `shoulder … wrist_3`, each `{x, y, z, roll, pitch, yaw}` (metres,
//! radians), and `hash`.
//!
//! The UR description builds its chain as `O_1 Rz(q1) O_2 Rz(q2) … O_6
//! Rz(q6)` from the controller's base frame (its `base_link_inertia`, the
//! REP-103 `base_link` turned by π about z) to `wrist_3_link` (= `tool0`),
//! each `O_i` a URDF origin (xyz, then fixed-axis roll-pitch-yaw). A link
//! of robocal's chain factors as `A_i(0) = Z_i X_i` with `Z_i = Rz(offset)
//! Tz(d)`, which commutes with the joint's rotation, and `X_i` the rest
//! (`Tx(a) Rx(alpha)`, Hayati's `Ry(beta)`). So `O_1 = Z_1`, `O_i =
//! X_{i-1} Z_i` reproduce `forward` exactly, provided the chain ends on
//! joint 6's rotation: `X_6` must be the identity (`a_6`, `alpha_6`,
//! `beta_6` zero), or the format cannot hold the flange.

use std::fmt::Write;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use robocal_calib::geometry::Pose;
use robocal_calib::kinematics::{Convention, RobotModel};
use sha2::{Digest, Sha256};

use super::header::ExportHeader;

/// The segments of the UR description, joint 1 to 6.
pub const SEGMENTS: [&str; 6] = [
    "shoulder",
    "upper_arm",
    "forearm",
    "wrist_1",
    "wrist_2",
    "wrist_3",
];
/// The keys of each segment, in the order they are written and hashed.
pub const KEYS: [&str; 6] = ["x", "y", "z", "roll", "pitch", "yaw"];
/// Prefix of robocal's hash, so it is never taken for a controller's.
pub const HASH_PREFIX: &str = "robocal_";
/// Bytes of the SHA-256 kept in the hash (16 hex digits).
const HASH_BYTES: usize = 8;
/// `X_6` below these is taken as the identity: far below anything a
/// calibration resolves, and below the export's own rounding.
const EXACT_LENGTH_MM: f64 = 1e-9;
const EXACT_ANGLE_RAD: f64 = 1e-12;
const MM_PER_M: f64 = 1000.0;

/// The six segments' numbers (metres, radians), `KEYS` order.
#[derive(Debug, Clone, PartialEq)]
pub struct UrKinematics {
    pub segments: [[f64; 6]; 6],
}

/// Why a set cannot be written as a UR `kinematics.yaml`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UrRefusal {
    #[error("ur-kinematics holds exactly 6 joints; this robot has {0}")]
    JointCount(usize),
    #[error(
        "ur-kinematics ends the chain on joint 6's rotation, so the flange must lie on joint 6's axis with no twist: this set's link 6 has a = {a_mm} mm, alpha = {alpha_deg} deg, beta = {beta_deg} deg, which the format cannot represent; use dh-table or urdf"
    )]
    FlangeOffAxis {
        a_mm: f64,
        alpha_deg: f64,
        beta_deg: f64,
    },
    #[error(
        "this set keeps non-geometric joint terms ({0}), which kinematics.yaml cannot hold: the file would not reproduce forward; use dh-table (with the dh-json terms) or calibrate with non_geometric: false"
    )]
    Terms(String),
}

/// The commuting part `Z_i = Rz(offset) Tz(d)` of a link at zero.
fn z_part(offset_rad: f64, d_mm: f64) -> Pose {
    Isometry3::from_parts(
        Translation3::new(0.0, 0.0, d_mm),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), offset_rad),
    )
}

/// The six UR origins of `robot` (see the module doc); `terms` names the
/// set's kept non-geometric terms, if any.
pub fn ur_kinematics(robot: &RobotModel, terms: &[String]) -> Result<UrKinematics, UrRefusal> {
    if robot.dof() != SEGMENTS.len() {
        return Err(UrRefusal::JointCount(robot.dof()));
    }
    if !terms.is_empty() {
        return Err(UrRefusal::Terms(terms.join(", ")));
    }
    let mut segments = [[0.0; 6]; 6];
    let mut carried = Pose::identity();
    for (i, joint) in robot.joints.iter().enumerate() {
        let d_mm = match joint.convention {
            Convention::Dh => joint.d_mm,
            Convention::Hayati => 0.0,
        };
        let z = z_part(joint.theta_offset_rad, d_mm);
        segments[i] = origin_numbers(&(carried * z));
        carried = z.inverse() * joint.link_transform(0.0);
    }
    let last = robot.joints[5];
    if carried.translation.vector.norm() > EXACT_LENGTH_MM
        || carried.rotation.angle() > EXACT_ANGLE_RAD
    {
        return Err(UrRefusal::FlangeOffAxis {
            a_mm: last.a_mm,
            alpha_deg: last.alpha_rad.to_degrees(),
            beta_deg: last.beta_rad.to_degrees(),
        });
    }
    Ok(UrKinematics { segments })
}

/// A URDF origin's numbers: metres, then fixed-axis roll-pitch-yaw
/// (`R = Rz(yaw) Ry(pitch) Rx(roll)`).
fn origin_numbers(pose: &Pose) -> [f64; 6] {
    let t = pose.translation.vector / MM_PER_M;
    let (roll, pitch, yaw) = pose.rotation.euler_angles();
    [t.x, t.y, t.z, roll, pitch, yaw]
}

/// A number as written: positional decimal, shortest text that reads back
/// to the same f64 (Rust's `Display`), never exponent notation, which
/// YAML 1.1 readers (PyYAML, hence xacro) take for a string.
fn number(v: f64) -> String {
    format!("{v}")
}

/// robocal's hash of the exported numbers: the first 8 bytes of the
/// SHA-256 of the 36 values as written, `SEGMENTS` then `KEYS` order, each
/// followed by `\n`, in hex after `robocal_`. The same numbers give the
/// same hash on any machine, so a driver or a user can tell which set is
/// loaded (README "Exports").
pub fn hash(k: &UrKinematics) -> String {
    let mut text = String::new();
    for v in k.segments.iter().flatten() {
        text.push_str(&number(*v));
        text.push('\n');
    }
    let digest = Sha256::digest(text.as_bytes());
    format!("{HASH_PREFIX}{}", hex::encode(&digest[..HASH_BYTES]))
}

/// The `kinematics.yaml` document with the export header.
pub fn write_ur_yaml(header: &ExportHeader, k: &UrKinematics) -> String {
    let mut s = header.comment("ur-kinematics", "#");
    s.push_str(
        "# Segments chain from the controller's base frame (the description's\n\
         # base_link_inertia) to wrist_3_link = tool0: each origin (metres,\n\
         # fixed-axis roll-pitch-yaw in radians), then the joint's rotation about z.\n\
         # hash is robocal's (README \"Exports\"), not the controller's checksum:\n\
         # a driver comparing them reports a mismatch by design.\n",
    );
    s.push_str("kinematics:\n");
    for (name, values) in SEGMENTS.iter().zip(&k.segments) {
        let _ = writeln!(s, "  {name}:");
        for (key, v) in KEYS.iter().zip(values) {
            let _ = writeln!(s, "    {key}: {}", number(*v));
        }
    }
    let _ = writeln!(s, "  hash: {}", hash(k));
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use robocal_calib::kinematics::presets;

    fn rebuilt(k: &UrKinematics, q: &[f64]) -> Pose {
        k.segments
            .iter()
            .zip(q)
            .fold(Pose::identity(), |acc, (o, &qi)| {
                let origin = Isometry3::from_parts(
                    Translation3::new(o[0] * MM_PER_M, o[1] * MM_PER_M, o[2] * MM_PER_M),
                    UnitQuaternion::from_euler_angles(o[3], o[4], o[5]),
                );
                acc * origin * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), qi)
            })
    }

    #[test]
    fn the_ur5_preset_gives_the_description_defaults_and_the_same_chain() {
        let robot = presets::ur5();
        let k = ur_kinematics(&robot, &[]).unwrap();
        assert!((k.segments[0][2] - 0.089159).abs() < 1e-12, "{k:?}");
        assert!((k.segments[2][0] + 0.425).abs() < 1e-12, "{k:?}");
        let q = [0.3, -1.2, 0.8, 2.0, -0.4, 1.1];
        let want = robot.base_to_flange(&q).unwrap();
        let got = rebuilt(&k, &q);
        assert!((want.to_homogeneous() - got.to_homogeneous()).amax() < 1e-9);
        assert_eq!(hash(&k), hash(&k.clone()));
        assert!(hash(&k).starts_with(HASH_PREFIX) && hash(&k).len() == 24);
    }

    #[test]
    fn a_twisted_last_link_or_a_seventh_joint_is_refused() {
        let mut robot = presets::ur5();
        robot.joints[5].alpha_rad = 0.01;
        assert!(matches!(
            ur_kinematics(&robot, &[]),
            Err(UrRefusal::FlangeOffAxis { .. })
        ));
        let mut seven = presets::ur5();
        seven.joints.push(seven.joints[5]);
        assert_eq!(ur_kinematics(&seven, &[]), Err(UrRefusal::JointCount(7)));
    }
}
