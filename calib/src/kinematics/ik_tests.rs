//! Unit tests of the seeded inverse kinematics (`ik.rs`).

use super::ik::*;
use crate::geometry::Pose;
use crate::kinematics::{presets, CalibratedModel, KinematicsError};

#[test]
fn ik_recovers_joints_and_rejects_unreachable_targets() {
    let model = CalibratedModel {
        robot: presets::irb2400(),
        world_to_base: Pose::translation(10.0, 20.0, 30.0),
        flange_to_tool: Pose::translation(0.0, 0.0, 120.0),
    };
    let q_true = [0.2, 0.3, -0.2, 0.5, 0.8, -0.4];
    let target = model.world_to_tool(&q_true).unwrap();
    let seed: Vec<f64> = q_true.iter().map(|q| q + 0.1).collect();
    let sol = inverse_kinematics(&model, &target, std::slice::from_ref(&seed)).unwrap();
    assert!(sol.residual_mm < 1e-6, "{sol:?}");
    let reached = model.world_to_tool(&sol.joints_rad).unwrap();
    assert!((reached.translation.vector - target.translation.vector).norm() < 1e-6);
    let far = Pose::translation(5000.0, 0.0, 0.0) * target;
    assert!(matches!(
        inverse_kinematics(&model, &far, &[seed]),
        Err(IkError::OutOfReach { .. })
    ));
    assert!(matches!(
        inverse_kinematics(&model, &target, &[]),
        Err(IkError::NoSeed)
    ));
}

#[test]
fn default_seeds_find_a_solution_without_a_user_seed() {
    let model = CalibratedModel {
        robot: presets::puma560(),
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::translation(0.0, 0.0, 100.0),
    };
    let seeds = default_seeds(&model);
    assert_eq!(seeds.len(), 81);
    let target = model
        .world_to_tool(&[0.4, 1.2, -2.0, 0.3, 0.9, -0.5])
        .unwrap();
    let sol = inverse_kinematics(&model, &target, &seeds).unwrap();
    assert!(sol.residual_mm < 1e-6);
    model.robot.check_limits(&sol.joints_rad).unwrap();
}

#[test]
fn targets_needing_joints_beyond_limits_are_errors() {
    let mut model = CalibratedModel {
        robot: presets::irb2400(),
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::translation(0.0, 0.0, 120.0),
    };
    let q = [0.2, 0.3, -0.2, 0.5, 0.8, -0.4];
    let target = model.world_to_tool(&q).unwrap();
    model.robot.joints[4].max_rad = 0.5; // joint 5 must reach 0.8
    assert!(matches!(
        inverse_kinematics(&model, &target, &[q.to_vec()]),
        Err(IkError::Limits(KinematicsError::OutsideLimits {
            joint: 5,
            ..
        }))
    ));
}

#[test]
fn a_seed_whose_branch_leaves_the_limits_gets_the_flipped_wrist() {
    let mut model = CalibratedModel {
        robot: presets::irb2400(),
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::translation(0.0, 0.0, 120.0),
    };
    let q = [0.2, 0.3, -0.2, 0.5, 0.8, -0.4];
    let target = model.world_to_tool(&q).unwrap();
    model.robot.joints[4].max_rad = 0.5; // joint 5 cannot reach 0.8 ...
    let sol = nearest_within_limits(&model, &target, &q).unwrap();
    // ... so the other wrist: joint 5 at -0.8, joints 4 and 6 half a turn on.
    assert_eq!(sol.start, IkStart::Branch);
    // (Joint 6 is half a turn from the seed either way: a tie.)
    let pi = std::f64::consts::PI;
    let flipped = [0.2, 0.3, -0.2, 0.5 - pi, -0.8, -0.4 + pi];
    for (got, want) in sol.joints_rad.iter().zip(flipped) {
        let turns = (got - want) / std::f64::consts::TAU;
        assert!((turns - turns.round()).abs() < 1e-7, "{sol:?}");
    }
    assert!((sol.joints_rad[3] - (0.5 - pi)).abs() < 1e-6, "{sol:?}");
    // Joint 5 within [-0.5, 0.5]: no branch reaches, an error naming joint 5.
    model.robot.joints[4].min_rad = -0.5;
    assert!(matches!(
        nearest_within_limits(&model, &target, &q),
        Err(IkError::Limits(KinematicsError::OutsideLimits {
            joint: 5,
            ..
        }))
    ));
    let far = Pose::translation(5000.0, 0.0, 0.0) * target;
    assert!(matches!(
        nearest_within_limits(&model, &far, &q),
        Err(IkError::OutOfReach { .. })
    ));
}

#[test]
fn whole_turns_go_toward_the_seed() {
    let model = CalibratedModel {
        robot: presets::irb2400(),
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::identity(),
    };
    // Joint 6 spans +-400 deg: 0.3 rad and 0.3 + 2 pi are the same pose.
    let q = [0.1, 0.2, 0.1, 0.4, 0.6, 0.3];
    let target = model.world_to_tool(&q).unwrap();
    let mut seed = q.to_vec();
    seed[5] = 6.0;
    let sol = nearest_within_limits(&model, &target, &seed).unwrap();
    assert!(
        (sol.joints_rad[5] - (0.3 + std::f64::consts::TAU)).abs() < 1e-6,
        "{sol:?}"
    );
}

#[test]
fn arms_without_a_spherical_wrist_fall_back_to_the_grid() {
    let mut model = CalibratedModel {
        robot: presets::ur5(),
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::identity(),
    };
    assert!(crate::kinematics::ik_branches::SphericalWristArm::of(&model.robot).is_none());
    let q = [0.3, -1.2, 1.4, -0.8, 1.1, 0.2];
    let target = model.world_to_tool(&q).unwrap();
    // Another solution, with the elbow the other way (joint 3 negative) ...
    let other = default_seeds(&model)
        .iter()
        .filter_map(|s| inverse_kinematics(&model, &target, std::slice::from_ref(s)).ok())
        .find(|s| s.joints_rad[2] < -0.1)
        .expect("an elbow-down solution");
    // ... as the seed, with joint 3 limited to the positive side: the
    // seed's own run stays out of limits, the grid finds the other elbow.
    model.robot.joints[2].min_rad = 0.0;
    model.robot.joints[2].max_rad = std::f64::consts::PI;
    let sol = nearest_within_limits(&model, &target, &other.joints_rad).unwrap();
    model.robot.check_limits(&sol.joints_rad).unwrap();
    assert_eq!(sol.start, IkStart::MultiStart, "{sol:?}");
    assert!(sol.residual_mm < 1e-6);
}
