//! Compensation from one seed over the whole workspace (issue 12): for both
//! presets, a simulated (perturbed) robot, random in-limit joints spread over
//! every joint's range, their tool poses as targets, all solved from ONE seed.
//! Every answer must stay within the limits and reach its target.

use rand::{rngs::StdRng, Rng, SeedableRng};

use super::ik::{nearest_within_limits, IkStart};
use crate::geometry::{pose_error, Pose};
use crate::kinematics::{CalibratedModel, RobotModel};
use crate::sim::campaign::{perturb_robot, CampaignSpec};

/// Targets per simulated robot.
const TARGETS: usize = 500;
/// Simulated (perturbed) robots per preset.
const ROBOTS: u64 = 3;
/// Joint 5 this close to its singular zero (rad) is not sampled: the wrist
/// axes 4 and 6 align and the solution is a continuum.
const WRIST_SINGULAR_MARGIN_RAD: f64 = 0.05;
const REACH_MM: f64 = 1e-6;
const REACH_RAD: f64 = 1e-9;

/// A calibrated-looking model: the simulator's perturbed robot, a camera tool
/// and a target frame away from the base.
fn simulated_model(preset: &str, seed: u64) -> (CalibratedModel, Vec<f64>) {
    let spec = CampaignSpec::standard(preset, seed).unwrap();
    let mut rng = StdRng::seed_from_u64(seed);
    let robot = perturb_robot(&spec.nominal, &spec, &mut rng);
    let model = CalibratedModel {
        robot,
        world_to_base: crate::geometry::pose_from_xyz_rpy_deg(
            [800.0, -300.0, 40.0],
            [2.0, -3.0, 170.0],
        )
        .unwrap(),
        flange_to_tool: spec.flange_to_camera_guess,
    };
    (model, spec.home_joints_rad)
}

fn random_in_limits(robot: &RobotModel, rng: &mut StdRng) -> Vec<f64> {
    loop {
        let q: Vec<f64> = robot
            .joints
            .iter()
            .map(|j| rng.random_range(j.min_rad..=j.max_rad))
            .collect();
        let wrist = q[4] + robot.joints[4].theta_offset_rad;
        if wrist.sin().abs() > WRIST_SINGULAR_MARGIN_RAD {
            return q;
        }
    }
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

fn assert_one_seed_reaches_everything_within_limits(preset: &str, seed: u64) {
    let (model, home) = simulated_model(preset, seed);
    let mut rng = StdRng::seed_from_u64(seed + 100);
    let mut beyond_first_start = 0;
    for k in 0..TARGETS {
        let q_true = random_in_limits(&model.robot, &mut rng);
        let target: Pose = model.world_to_tool(&q_true).unwrap();
        let sol = nearest_within_limits(&model, &target, &home)
            .unwrap_or_else(|e| panic!("{preset} target {k} ({q_true:?}): {e}"));
        model.robot.check_limits(&sol.joints_rad).unwrap();
        let e = pose_error(&target, &model.world_to_tool(&sol.joints_rad).unwrap());
        assert!(
            e.rows(0, 3).norm() < REACH_MM && e.rows(3, 3).norm() < REACH_RAD,
            "{preset} target {k}: {e:?}"
        );
        if sol.start != IkStart::Seed {
            beyond_first_start += 1;
            // The truth is one in-limit solution: the answer is no farther.
            assert!(
                distance(&sol.joints_rad, &home) <= distance(&q_true, &home) + 1e-6,
                "{preset} target {k}: {sol:?} farther from the seed than {q_true:?}"
            );
        }
    }
    // The workspace is spread wide enough that the seed's branch alone fails.
    assert!(beyond_first_start > TARGETS / 10, "{beyond_first_start}");
}

#[test]
fn one_seed_reaches_irb2400_targets_over_the_workspace_within_limits() {
    for seed in 0..ROBOTS {
        assert_one_seed_reaches_everything_within_limits("irb2400", 21 + seed);
    }
}

#[test]
fn one_seed_reaches_puma560_targets_over_the_workspace_within_limits() {
    for seed in 0..ROBOTS {
        assert_one_seed_reaches_everything_within_limits("puma560", 31 + seed);
    }
}

/// Targets whose wrist centre is within this (mm) of joint 1's axis.
const NEAR_AXIS_MM: f64 = 5.0;
const NEAR_AXIS_TARGETS: usize = 100;

/// The wrist centre's signed distance from joint 1's axis along the arm.
fn wrist_ahead_mm(robot: &RobotModel, q: &[f64]) -> f64 {
    let frames: Vec<Pose> = (0..5)
        .scan(Pose::identity(), |acc, i| {
            *acc *= robot.joints[i].link_transform(q[i]);
            Some(*acc)
        })
        .collect();
    let wc = frames[4].translation.vector;
    let ahead = frames[0].rotation * nalgebra::Vector3::x();
    wc.x * ahead.x + wc.y * ahead.y
}

/// In-limit joints with the wrist centre within [`NEAR_AXIS_MM`] of joint
/// 1's axis (the shoulder singularity): joint 3 bisected onto the axis.
fn near_shoulder_axis(robot: &RobotModel, rng: &mut StdRng) -> Vec<f64> {
    let j3 = robot.joints[2];
    loop {
        let mut q = random_in_limits(robot, rng);
        let mut at = |v: f64| {
            q[2] = v;
            wrist_ahead_mm(robot, &q)
        };
        let (mut lo, mut hi) = (j3.min_rad, j3.max_rad);
        if at(lo).signum() == at(hi).signum() {
            continue;
        }
        let sign_lo = at(lo).signum();
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if at(mid).signum() == sign_lo {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        q[2] = lo;
        let step = rng.random_range(-1.0..=1.0) * NEAR_AXIS_MM;
        let lever = (wrist_ahead_mm(robot, &{
            let mut p = q.clone();
            p[2] += 1e-3;
            p
        }) / 1e-3)
            .abs();
        q[2] += step / lever.max(1.0);
        if robot.check_limits(&q).is_ok() && wrist_ahead_mm(robot, &q).abs() <= NEAR_AXIS_MM {
            return q;
        }
    }
}

#[test]
fn one_seed_reaches_targets_over_joint_1s_axis_within_limits() {
    for (preset, seed) in [("irb2400", 41), ("puma560", 42)] {
        let (model, home) = simulated_model(preset, seed);
        let mut rng = StdRng::seed_from_u64(seed);
        for k in 0..NEAR_AXIS_TARGETS {
            let q_true = near_shoulder_axis(&model.robot, &mut rng);
            let target = model.world_to_tool(&q_true).unwrap();
            let sol = nearest_within_limits(&model, &target, &home)
                .unwrap_or_else(|e| panic!("{preset} target {k} ({q_true:?}): {e}"));
            model.robot.check_limits(&sol.joints_rad).unwrap();
            assert!(sol.residual_mm < REACH_MM, "{preset} target {k}: {sol:?}");
        }
    }
}
