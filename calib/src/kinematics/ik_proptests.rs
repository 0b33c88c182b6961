//! Property test of compensation (issue 13): `ik(forward(q)) = q`. For
//! in-limit joints `q` of either preset, the tool pose `forward(q)` solved
//! from a seed a little off `q` gives back `q` itself (method.md §8), not
//! merely some other joints reaching the same pose.
//!
//! `q` must be the only solution near the seed for that to hold, so joints
//! near a singularity are not sampled: where the Jacobian's smallest
//! singular value falls below [`MIN_SINGULAR_MM`] (the wrist or shoulder
//! continuum), or another closed-form branch (the eight arm
//! configurations) comes within [`MIN_BRANCH_GAP_RAD`] of `q` (the elbow).

use proptest::prelude::*;

use nalgebra::DMatrix;

use super::ik::{nearest_within_limits, IK_ROTATION_SCALE_MM};
use super::ik_branches::SphericalWristArm;
use super::{presets, CalibratedModel, RobotModel};
use crate::geometry::{pose_error, pose_from_xyz_rpy_deg, Pose};

/// How far (rad, per joint) the seed is from `q`.
const SEED_OFFSET_RAD: f64 = 0.03;
/// `q` is kept this far (rad) inside each joint limit, so the seed is too.
const LIMIT_MARGIN_RAD: f64 = 0.05;
/// Every other branch solution is at least this far (rad, joint-space
/// distance) from `q`: far beyond the seed's offset (at most
/// `SEED_OFFSET_RAD * sqrt(6)`), so the nearest solution is `q`'s.
const MIN_BRANCH_GAP_RAD: f64 = 0.3;
/// A branch solution this close to `q` (rad) is `q`'s own.
const SAME_BRANCH_RAD: f64 = 1e-6;
/// How close the answer must be to `q`, per joint (rad).
const ROUND_TRIP_RAD: f64 = 1e-7;
/// Smallest singular value of the tool Jacobian (mm per rad, rotation
/// rows scaled as the solver scales them) of a sampled `q`.
const MIN_SINGULAR_MM: f64 = 20.0;
/// Finite-difference step of that Jacobian (rad).
const JACOBIAN_STEP_RAD: f64 = 1e-6;
const CASES: u32 = 64;

/// The preset with a target frame away from its base and a camera-like
/// tool, so both frames enter the round trip.
fn model(robot: RobotModel) -> CalibratedModel {
    CalibratedModel {
        robot,
        world_to_base: pose_from_xyz_rpy_deg([800.0, -300.0, 40.0], [2.0, -3.0, 170.0]).unwrap(),
        flange_to_tool: pose_from_xyz_rpy_deg([10.0, -5.0, 120.0], [0.0, 15.0, 90.0]).unwrap(),
    }
}

/// `q` from fractions of each joint's range (inside the margin).
fn joints_at(robot: &RobotModel, fractions: &[f64]) -> Vec<f64> {
    robot
        .joints
        .iter()
        .zip(fractions)
        .map(|(j, f)| {
            let (lo, hi) = (j.min_rad + LIMIT_MARGIN_RAD, j.max_rad - LIMIT_MARGIN_RAD);
            lo + f * (hi - lo)
        })
        .collect()
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Whether every closed-form branch other than `q`'s own lies at least
/// [`MIN_BRANCH_GAP_RAD`] from `q` (angles compared modulo whole turns).
fn isolated(model: &CalibratedModel, q: &[f64], target: &Pose) -> bool {
    let Some(arm) = SphericalWristArm::of(&model.robot) else {
        return false;
    };
    let base_to_flange = model.world_to_base.inverse() * target * model.flange_to_tool.inverse();
    let wrapped = |a: &[f64]| -> Vec<f64> {
        a.iter()
            .zip(q)
            .map(|(x, r)| {
                let turns = ((r - x) / std::f64::consts::TAU).round();
                x + turns * std::f64::consts::TAU
            })
            .collect()
    };
    arm.branch_seeds(&base_to_flange).iter().all(|b| {
        let d = distance(&wrapped(b), q);
        !(SAME_BRANCH_RAD..=MIN_BRANCH_GAP_RAD).contains(&d)
    })
}

/// The smallest singular value of the tool pose's Jacobian at `q`, by
/// forward differences (rotation rows scaled by the solver's scale).
fn smallest_singular_mm(model: &CalibratedModel, q: &[f64], target: &Pose) -> f64 {
    let j = DMatrix::from_fn(6, q.len(), |r, c| {
        let mut moved = q.to_vec();
        moved[c] += JACOBIAN_STEP_RAD;
        let e = pose_error(&model.world_to_tool(&moved).unwrap(), target);
        let scale = if r >= 3 { IK_ROTATION_SCALE_MM } else { 1.0 };
        e[r] * scale / JACOBIAN_STEP_RAD
    });
    j.singular_values().min()
}

fn round_trip(robot: RobotModel, fractions: &[f64], offsets: &[f64]) -> Result<(), TestCaseError> {
    let model = model(robot);
    let q = joints_at(&model.robot, fractions);
    let target = model.world_to_tool(&q).unwrap();
    prop_assume!(smallest_singular_mm(&model, &q, &target) > MIN_SINGULAR_MM);
    prop_assume!(isolated(&model, &q, &target));
    let seed: Vec<f64> = q.iter().zip(offsets).map(|(a, o)| a + o).collect();
    let solution = nearest_within_limits(&model, &target, &seed)
        .map_err(|e| TestCaseError::fail(format!("q {q:?} from seed {seed:?}: {e}")))?;
    for (i, (got, want)) in solution.joints_rad.iter().zip(&q).enumerate() {
        prop_assert!(
            (got - want).abs() < ROUND_TRIP_RAD,
            "joint {}: {} rad, q has {} (q {:?}, seed {:?})",
            i + 1,
            got,
            want,
            q,
            seed
        );
    }
    Ok(())
}

fn fractions() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(0.0..=1.0f64, 6)
}

fn offsets() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(-SEED_OFFSET_RAD..=SEED_OFFSET_RAD, 6)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(CASES))]

    #[test]
    fn irb2400_ik_of_forward_is_the_identity(f in fractions(), o in offsets()) {
        round_trip(presets::irb2400(), &f, &o)?;
    }

    #[test]
    fn puma560_ik_of_forward_is_the_identity(f in fractions(), o in offsets()) {
        round_trip(presets::puma560(), &f, &o)?;
    }
}
