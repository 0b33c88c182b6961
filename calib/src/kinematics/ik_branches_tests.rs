//! The closed-form branch seeds (`ik_branches.rs`) on the nominal presets,
//! where they are exact.

use rand::{rngs::StdRng, Rng, SeedableRng};

use super::ik_branches::{ArmConfiguration, SphericalWristArm};
use crate::geometry::pose_error;
use crate::kinematics::{presets, RobotModel};

/// Poses tried per preset.
const POSES: usize = 200;
/// Poses this close (rad) to the wrist singularity are skipped.
const SINGULAR_MARGIN_RAD: f64 = 0.05;

/// A seed this close (rad, every joint) to the truth stands for it near a
/// singularity, where the two seeds of a pair are kept apart.
const NEAR_SINGULAR_RAD: f64 = 0.1;
/// At most this fraction of the poses may be near a singularity.
const MAX_NEAR_SINGULAR: f64 = 0.05;

fn same_angle(a: f64, b: f64) -> bool {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d < 1e-6 || std::f64::consts::TAU - d < 1e-6
}

fn check_branches_are_exact(robot: RobotModel, seed: u64) {
    let arm = SphericalWristArm::of(&robot).expect("a spherical-wrist arm");
    let mut rng = StdRng::seed_from_u64(seed);
    let mut near_singular = 0;
    for k in 0..POSES {
        let q: Vec<f64> = robot
            .joints
            .iter()
            .map(|j| rng.random_range(j.min_rad..=j.max_rad))
            .collect();
        if (q[4] + robot.joints[4].theta_offset_rad).sin().abs() < SINGULAR_MARGIN_RAD {
            continue; // wrist singular: joints 4 and 6 are a continuum
        }
        let flange = robot.base_to_flange(&q).unwrap();
        let seeds = arm.branch_seeds(&flange);
        assert!(seeds.len() >= 8);
        let mut configurations: Vec<ArmConfiguration> = Vec::new();
        let mut found_truth = false;
        for s in &seeds {
            let e = pose_error(&flange, &robot.base_to_flange(s).unwrap());
            if e.norm() > 1e-6 {
                continue; // a branch the arm cannot take for this pose
            }
            found_truth |= s.iter().zip(&q).all(|(a, b)| same_angle(*a, *b));
            let c = arm.configuration(s).unwrap();
            assert!(!configurations.contains(&c), "pose {k}: {c:?} twice");
            configurations.push(c);
        }
        if !found_truth {
            let near = seeds.iter().any(|s| {
                s.iter()
                    .zip(&q)
                    .all(|(a, b)| (a - b).abs() < NEAR_SINGULAR_RAD)
            });
            assert!(near, "pose {k}: {q:?} not among {seeds:?}");
            near_singular += 1;
        } else {
            let truth = arm.configuration(&q).unwrap();
            assert!(configurations.contains(&truth), "pose {k}: {truth:?}");
        }
    }
    assert!(
        (near_singular as f64) < MAX_NEAR_SINGULAR * POSES as f64,
        "{near_singular}"
    );
}

#[test]
fn irb2400_branch_seeds_include_the_truth_and_name_distinct_configurations() {
    check_branches_are_exact(presets::irb2400(), 1);
}

#[test]
fn puma560_branch_seeds_include_the_truth_and_name_distinct_configurations() {
    check_branches_are_exact(presets::puma560(), 2);
}

#[test]
fn other_structures_have_no_branch_seeds() {
    assert!(SphericalWristArm::of(&presets::ur5()).is_none());
    let mut robot = presets::irb2400();
    robot.joints.pop();
    assert!(SphericalWristArm::of(&robot).is_none());
    let mut offset_wrist = presets::irb2400();
    offset_wrist.joints[4].d_mm = 120.0;
    assert!(SphericalWristArm::of(&offset_wrist).is_none());
}
