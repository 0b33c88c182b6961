//! The calibrated model as a URDF (metres, radians) whose chain reproduces
//! `forward` exactly (method.md §5).
//!
//! Every link transform factors as `A_i(q) = Rz(q) · A_i(0)` (the joint
//! offset, `d`, `a`, twist and Hayati tilt all sit in `A_i(0)`), so joint
//! `i` of the URDF rotates about its parent's z axis at an origin equal to
//! the previous link's `A_{i-1}(0)`, and the flange hangs off the last
//! link at `A_n(0)`. URDF joint positions are then the controller's joint
//! angles, unchanged. The camera (or tracker tool) is a fixed child of the
//! flange; the board (or tracker) a fixed child of the base.

use std::fmt::Write;

use robocal_calib::geometry::Pose;
use robocal_calib::kinematics::CalibratedModel;

use crate::domain::{FrameNames, TermsDoc};

/// Millimetres per metre.
const MM_PER_M: f64 = 1000.0;
/// URDF requires `effort` and `velocity` on a revolute joint's limit;
/// robocal identifies neither, so these placeholders say "not given"
/// (ROS tools read 0 as "no limit known"); the controller's values govern.
const UNKNOWN_EFFORT: f64 = 0.0;
const UNKNOWN_VELOCITY: f64 = 0.0;

/// The URDF document of `model`, robot named `name`; `terms`, the set's
/// kept non-geometric terms, are named in a comment: a URDF has no element
/// for a joint deflection that depends on the configuration.
pub fn write_urdf(
    name: &str,
    model: &CalibratedModel,
    frames: FrameNames,
    terms: Option<&TermsDoc>,
) -> String {
    let mut s = String::new();
    let _ = writeln!(s, r#"<?xml version="1.0"?>"#);
    if let Some(t) = terms {
        s.push_str(&terms_comment(t));
    }
    let _ = writeln!(
        s,
        "<!-- robocal calibrated model of {}: lengths in metres, angles in radians.\n     \
         Joint positions are the controller's joint angles. -->",
        xml(name)
    );
    let _ = writeln!(s, r#"<robot name="{}">"#, xml(name));
    let mut links = vec!["base_link".to_string()];
    links.extend((1..=model.robot.dof()).map(|i| format!("link_{i}")));
    links.push("flange".into());
    links.push(frames.end.into());
    links.push(frames.world.into());
    for link in &links {
        let _ = writeln!(s, r#"  <link name="{link}"/>"#);
    }
    let mut origin = Pose::identity();
    for (i, joint) in model.robot.joints.iter().enumerate() {
        let _ = writeln!(
            s,
            r#"  <joint name="joint_{n}" type="revolute">
    <parent link="{parent}"/>
    <child link="link_{n}"/>
{origin}    <axis xyz="0 0 1"/>
    <limit lower="{lower:e}" upper="{upper:e}" effort="{UNKNOWN_EFFORT}" velocity="{UNKNOWN_VELOCITY}"/>
  </joint>"#,
            n = i + 1,
            parent = links[i],
            origin = origin_element(&origin),
            lower = joint.min_rad,
            upper = joint.max_rad,
        );
        origin = joint.link_transform(0.0);
    }
    let n = model.robot.dof();
    fixed(&mut s, "flange_joint", &links[n], "flange", &origin);
    fixed(
        &mut s,
        &format!("{}_joint", frames.end),
        "flange",
        frames.end,
        &model.flange_to_tool,
    );
    fixed(
        &mut s,
        &format!("{}_joint", frames.world),
        "base_link",
        frames.world,
        &model.world_to_base.inverse(),
    );
    let _ = writeln!(s, "</robot>");
    s
}

/// What a URDF leaves out of a set with terms, and the error that leaves.
fn terms_comment(terms: &TermsDoc) -> String {
    let mut s = String::from(
        "<!-- This parameter set also keeps non-geometric joint terms, which URDF cannot hold:\n     \
         each deflects its joint by value * basis(q) before the chain (periodic: basis sin/cos of\n     \
         the joint angle, at most 1; compliance: the gravity torque in N*m of the lumped mass).\n     \
         A tool driven by this URDF misses those deflections: the error left is the difference\n     \
         between `forward` of this set and this chain, up to |value| rad on the joint for a\n     \
         periodic term, times the joint's lever arm to the tool. Use `forward`, `compensate`\n     \
         or `filter` (or the dh-json/csv export's terms table) to include them.\n",
    );
    for k in &terms.terms {
        let _ = writeln!(
            s,
            "     {}: {:e} +- {:e} {}",
            xml(&k.name),
            k.value,
            k.std_dev,
            xml(&k.unit)
        );
    }
    s.push_str("-->\n");
    s
}

fn fixed(s: &mut String, name: &str, parent: &str, child: &str, pose: &Pose) {
    let _ = writeln!(
        s,
        r#"  <joint name="{name}" type="fixed">
    <parent link="{parent}"/>
    <child link="{child}"/>
{}  </joint>"#,
        origin_element(pose)
    );
}

/// `<origin xyz rpy>`: URDF's rpy is fixed-axis X, then Y, then Z, i.e.
/// `R = Rz(yaw) Ry(pitch) Rx(roll)`, nalgebra's `euler_angles` order.
/// Numbers in Rust's shortest round-trip form: nothing is lost.
fn origin_element(pose: &Pose) -> String {
    let t = pose.translation.vector / MM_PER_M;
    let (roll, pitch, yaw) = pose.rotation.euler_angles();
    format!(
        "    <origin xyz=\"{:?} {:?} {:?}\" rpy=\"{roll:?} {pitch:?} {yaw:?}\"/>\n",
        t.x, t.y, t.z
    )
}

/// XML attribute and comment escaping of a robot name.
fn xml(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace("--", "-&#45;")
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Isometry3, Vector3};
    use robocal_calib::kinematics::presets;

    /// A tracker set's frames (api.md "export"): the chain ends in a fixed
    /// `tool` link on the flange (the tool point, translation only, in
    /// metres) and the tracker hangs off the base as a fixed link.
    #[test]
    fn a_tracker_set_ends_in_a_tool_link_and_hangs_the_tracker_off_the_base() {
        let tool_mm = Vector3::new(12.0, -30.0, 95.0);
        let tracker_to_base_mm = Vector3::new(1500.0, 200.0, -300.0);
        let model = CalibratedModel {
            robot: presets::ur5(),
            world_to_base: Isometry3::translation(
                tracker_to_base_mm.x,
                tracker_to_base_mm.y,
                tracker_to_base_mm.z,
            ),
            flange_to_tool: Isometry3::translation(tool_mm.x, tool_mm.y, tool_mm.z),
        };
        let frames = FrameNames {
            world_to_base: "instrument_to_base",
            flange_to_end: "flange_to_tool",
            world: "tracker",
            end: "tool",
        };
        let urdf = write_urdf("UR5-T", &model, frames, None);
        assert!(urdf.contains(r#"<link name="tool"/>"#), "{urdf}");
        assert!(!urdf.contains(r#"<link name="camera"/>"#), "{urdf}");
        let tool_joint = urdf
            .split("<joint ")
            .find(|j| j.contains(r#"name="tool_joint""#))
            .expect("a tool_joint");
        assert!(tool_joint.contains(r#"type="fixed""#), "{tool_joint}");
        assert!(
            tool_joint.contains(r#"<parent link="flange"/>"#),
            "{tool_joint}"
        );
        assert!(
            tool_joint.contains(r#"<child link="tool"/>"#),
            "{tool_joint}"
        );
        let xyz: Vec<f64> = tool_joint
            .split(r#"xyz=""#)
            .nth(1)
            .and_then(|rest| rest.split('"').next())
            .expect("an origin xyz")
            .split_whitespace()
            .map(|v| v.parse().expect("a number"))
            .collect();
        let expected_m = tool_mm / MM_PER_M;
        for (got, want) in xyz.iter().zip(expected_m.iter()) {
            assert!(
                (got - want).abs() < 1e-12,
                "tool origin {xyz:?} vs {expected_m:?}"
            );
        }
        let tracker_joint = urdf
            .split("<joint ")
            .find(|j| j.contains(r#"name="tracker_joint""#))
            .expect("a tracker_joint");
        assert!(tracker_joint.contains(r#"<parent link="base_link"/>"#));
        assert!(tracker_joint.contains(r#"<child link="tracker"/>"#));
    }
}
