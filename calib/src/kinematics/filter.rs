//! Filtered targets for a controller that runs the robot's *nominal* model
//! (issue "Deploy the result"; RoboDK's "filter", done exactly).
//!
//! A cell that cannot load identified parameters into its controller sends
//! it Cartesian targets instead. For a desired tool pose `T` (tool in the
//! target frame) the calibrated model gives the joints `q` that put the real
//! tool there (compensation, method.md §8); the controller reaches `q` when
//! asked for the flange pose its nominal model computes at `q`:
//! `nominal_target = nominal.base_to_flange(q)`. The controller's own
//! inverse kinematics of that pose, in the seed's branch, returns `q` again,
//! and the real robot puts the tool on `T`. The residual reported is that
//! round trip replayed: nominal IK of the filtered target, then the
//! calibrated model's tool pose at the joints it gives.

use super::ik::{nearest_within_limits, IkError, IkSolution};
use super::params::CalibratedModel;
use super::term_model::TermModel;
use super::RobotModel;
use crate::geometry::Pose;

/// One target filtered.
#[derive(Debug, Clone, PartialEq)]
pub struct FilteredTarget {
    /// The flange pose to send to the nominal controller, in its base frame.
    pub nominal_base_to_flange: Pose,
    /// The joints the real robot takes (calibrated model), radians.
    pub joints_rad: Vec<f64>,
    /// How the calibrated IK found them.
    pub solution: IkSolution,
    /// Distance (mm) between `T` and where the calibrated model puts the tool
    /// at the joints the nominal controller computes for the filtered target.
    pub residual_mm: f64,
}

/// Filters one desired tool pose. `calibrated` carries the identified chain,
/// base (`world_to_base`) and the deployment tool (`flange_to_tool`);
/// `nominal` is the controller's chain; `seed_rad` selects the branch.
pub fn filter_target(
    calibrated: &CalibratedModel,
    nominal: &RobotModel,
    world_to_tool: &Pose,
    seed_rad: &[f64],
) -> Result<FilteredTarget, IkError> {
    let geometric = TermModel::geometric(calibrated.clone());
    filter_target_with_terms(&geometric, nominal, world_to_tool, seed_rad)
}

/// [`filter_target`] for a model with non-geometric terms (issue 19): the
/// joints are the commanded ones (the controller's, which the terms then
/// deflect onto the target), so the nominal target is the nominal flange
/// at the commanded joints.
pub fn filter_target_with_terms(
    calibrated: &TermModel,
    nominal: &RobotModel,
    world_to_tool: &Pose,
    seed_rad: &[f64],
) -> Result<FilteredTarget, IkError> {
    let solution = calibrated.nearest_within_limits(world_to_tool, seed_rad)?;
    let nominal_base_to_flange = nominal.base_to_flange(&solution.joints_rad)?;
    // Replay the controller: its IK of the filtered target from the same
    // seed, in its own (nominal) model with no base or tool.
    let controller = CalibratedModel {
        robot: nominal.clone(),
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::identity(),
    };
    let replay = nearest_within_limits(&controller, &nominal_base_to_flange, &solution.joints_rad)?;
    let reached = calibrated.world_to_tool(&replay.joints_rad)?;
    let residual_mm = (reached.translation.vector - world_to_tool.translation.vector).norm();
    Ok(FilteredTarget {
        nominal_base_to_flange,
        joints_rad: solution.joints_rad.clone(),
        solution,
        residual_mm,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::pose_from_xyz_rpy_deg;
    use crate::kinematics::ik_branches::SphericalWristArm;
    use crate::kinematics::presets;
    use crate::sim::campaign::{perturb_robot, CampaignSpec};
    use rand::{rngs::StdRng, Rng, SeedableRng};

    /// Targets of the test and the bar they must meet on the true robot.
    const TARGETS: usize = 50;
    const MAX_TRUE_ERROR_MM: f64 = 1e-4;

    /// With the calibrated model equal to the true robot, the nominal
    /// controller driven by the filtered targets puts the true tool on every
    /// target; unfiltered, it misses by the kinematic error. Every solution
    /// keeps the seed's configuration (shoulder, elbow, wrist).
    #[test]
    fn nominal_controller_reaches_targets_through_the_filter() {
        let spec = CampaignSpec::standard("irb2400", 3).unwrap();
        let mut rng = StdRng::seed_from_u64(3);
        let truth = CalibratedModel {
            robot: perturb_robot(&spec.nominal, &spec, &mut rng),
            world_to_base: pose_from_xyz_rpy_deg([700.0, -250.0, 30.0], [1.0, -2.0, 175.0])
                .unwrap(),
            flange_to_tool: pose_from_xyz_rpy_deg([0.0, 0.0, 150.0], [0.0, 0.0, 0.0]).unwrap(),
        };
        let nominal = presets::irb2400();
        let controller = CalibratedModel {
            robot: nominal.clone(),
            world_to_base: Pose::identity(),
            flange_to_tool: Pose::identity(),
        };
        let seed = vec![0.1, 0.3, 0.2, 0.1, 0.8, 0.1];
        let arm = SphericalWristArm::of(&truth.robot).unwrap();
        let seed_branch = arm.configuration(&seed).unwrap();
        let (mut worst, mut unfiltered) = (0.0f64, 0.0f64);
        for _ in 0..TARGETS {
            let q: Vec<f64> = seed
                .iter()
                .map(|s| s + rng.random_range(-0.4..0.4))
                .collect();
            let target = truth.world_to_tool(&q).unwrap();
            let f = filter_target(&truth, &nominal, &target, &seed).unwrap();
            assert_eq!(arm.configuration(&f.joints_rad), Some(seed_branch));
            // The controller's IK of the filtered target, driven on the truth.
            let q_ctrl = nearest_within_limits(&controller, &f.nominal_base_to_flange, &seed)
                .unwrap()
                .joints_rad;
            let reached = truth.world_to_tool(&q_ctrl).unwrap();
            let err = (reached.translation.vector - target.translation.vector).norm();
            worst = worst.max(err);
            assert!(f.residual_mm < MAX_TRUE_ERROR_MM, "{}", f.residual_mm);
            // Unfiltered: the controller asked for the target's flange pose
            // as the nominal model sees it.
            let naive_flange =
                truth.world_to_base.inverse() * target * truth.flange_to_tool.inverse();
            let q_naive = nearest_within_limits(&controller, &naive_flange, &seed)
                .unwrap()
                .joints_rad;
            let missed = truth.world_to_tool(&q_naive).unwrap();
            unfiltered =
                unfiltered.max((missed.translation.vector - target.translation.vector).norm());
        }
        assert!(worst < MAX_TRUE_ERROR_MM, "worst {worst} mm");
        assert!(
            unfiltered > 0.5,
            "the robot's errors are not visible: {unfiltered} mm"
        );
    }
}
