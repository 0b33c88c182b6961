//! Nominal kinematics of the robots the paper calibrated (method.md §5), as
//! standard DH tables; the link between the parallel axes 2 and 3 is turned
//! into Hayati's form by [`choose_conventions`].

use super::model::{choose_conventions, Joint, RobotModel};

/// Preset names accepted by the REST contract (`"preset": "irb2400"`).
pub const PRESET_NAMES: [&str; 2] = ["irb2400", "puma560"];

fn auto(joints: [Joint; 6]) -> RobotModel {
    RobotModel {
        joints: choose_conventions(&joints.map(|j| (None, j))),
    }
}

/// ABB IRB 2400/16.
///
/// Source: ABB "Product specification IRB 2400" (3HAC042195-001), figure
/// "Dimensions": base to axis-2 height 615 mm, axis-1 to axis-2 offset
/// 100 mm, upper arm 705 mm, axis-3 offset 135 mm, axis 3 to wrist centre
/// 755 mm, wrist centre to flange 85 mm; axis working ranges +-180,
/// +110/-100, +65/-60, +-200, +-120, +-400 degrees. The DH frames place
/// the upper arm vertical and the forearm horizontal at zero joints, as the
/// controller's calibration position.
pub fn irb2400() -> RobotModel {
    auto([
        Joint::dh(100.0, -90.0, 615.0, 0.0, (-180.0, 180.0)),
        Joint::dh(705.0, 0.0, 0.0, -90.0, (-100.0, 110.0)),
        Joint::dh(135.0, -90.0, 0.0, 0.0, (-60.0, 65.0)),
        Joint::dh(0.0, 90.0, 755.0, 0.0, (-200.0, 200.0)),
        Joint::dh(0.0, -90.0, 0.0, 0.0, (-120.0, 120.0)),
        Joint::dh(0.0, 0.0, 85.0, 0.0, (-400.0, 400.0)),
    ])
}

/// Unimation PUMA 560.
///
/// Source: B. Armstrong, O. Khatib, J. Burdick, "The explicit dynamic model
/// and inertial parameters of the PUMA 560 arm", ICRA 1986, as tabulated in
/// standard DH form in P. Corke's Robotics Toolbox (`mdl_puma560`):
/// a = (0, 431.8, 20.32, 0, 0, 0) mm, d = (0, 0, 150.05, 431.8, 0, 0) mm,
/// alpha = (90, 0, -90, 90, -90, 0) deg; joint limits (Corke `qlim`)
/// +-160, -45..225, -225..45, -110..170, +-100, +-266 degrees. The base
/// frame is at the shoulder (d1 = 0), the flange at the wrist centre.
pub fn puma560() -> RobotModel {
    auto([
        Joint::dh(0.0, 90.0, 0.0, 0.0, (-160.0, 160.0)),
        Joint::dh(431.8, 0.0, 0.0, 0.0, (-45.0, 225.0)),
        Joint::dh(20.32, -90.0, 150.05, 0.0, (-225.0, 45.0)),
        Joint::dh(0.0, 90.0, 431.8, 0.0, (-110.0, 170.0)),
        Joint::dh(0.0, -90.0, 0.0, 0.0, (-100.0, 100.0)),
        Joint::dh(0.0, 0.0, 0.0, 0.0, (-266.0, 266.0)),
    ])
}

/// Universal Robots UR5 (CB-series), standard DH.
///
/// Source: Universal Robots, "DH parameters for calculations of kinematics
/// and dynamics" (universal-robots.com support article): d1 89.159,
/// a2 -425, a3 -392.25, d4 109.15, d5 94.65, d6 82.3 mm; alpha 90, 0, 0,
/// 90, -90, 0 deg; joint ranges +-360 deg. Checked against the Jacobi 2025
/// laser-tracker data (`calib/tests/data/kinematic/ur5_wam_jacobi2025`): its
/// nominal targets are this model's flange plus a 31 mm tool, to 0.007 mm.
/// Links 2 and 3 (parallel axes 2-3-4) become Hayati.
pub fn ur5() -> RobotModel {
    ur([89.159, -425.0, -392.25, 109.15, 94.65, 82.3])
}

/// Universal Robots UR10 (CB-series), standard DH.
///
/// Source: as [`ur5`]: d1 127.3, a2 -612, a3 -572.3, d4 163.941, d5 115.7,
/// d6 92.2 mm, the same twists and ranges.
pub fn ur10() -> RobotModel {
    ur([127.3, -612.0, -572.3, 163.941, 115.7, 92.2])
}

/// UR joint range (deg), every joint.
const UR_JOINT_RANGE_DEG: f64 = 360.0;

fn ur([d1, a2, a3, d4, d5, d6]: [f64; 6]) -> RobotModel {
    let r = (-UR_JOINT_RANGE_DEG, UR_JOINT_RANGE_DEG);
    auto([
        Joint::dh(0.0, 90.0, d1, 0.0, r),
        Joint::dh(a2, 0.0, 0.0, 0.0, r),
        Joint::dh(a3, 0.0, 0.0, 0.0, r),
        Joint::dh(0.0, 90.0, d4, 0.0, r),
        Joint::dh(0.0, -90.0, d5, 0.0, r),
        Joint::dh(0.0, 0.0, d6, 0.0, r),
    ])
}

/// A preset by its contract name.
pub fn by_name(name: &str) -> Option<RobotModel> {
    match name {
        "irb2400" => Some(irb2400()),
        "puma560" => Some(puma560()),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::Convention;

    #[test]
    fn irb2400_home_is_the_documented_geometry() {
        let flange = irb2400().base_to_flange(&[0.0; 6]).unwrap();
        let t = flange.translation.vector;
        // Wrist centre at reach 100 + 755, height 615 + 705 + 135; flange 85 further.
        assert!((t.x - 940.0).abs() < 1e-9, "{t}");
        assert!(t.y.abs() < 1e-9);
        assert!((t.z - 1455.0).abs() < 1e-9, "{t}");
    }

    #[test]
    fn presets_use_hayati_between_parallel_axes_only() {
        for robot in [irb2400(), puma560()] {
            let kinds: Vec<_> = robot.joints.iter().map(|j| j.convention).collect();
            assert_eq!(kinds[1], Convention::Hayati);
            assert_eq!(
                kinds.iter().filter(|k| **k == Convention::Hayati).count(),
                1
            );
        }
        assert!(by_name("irb2400").is_some() && by_name("kuka").is_none());
    }
}
