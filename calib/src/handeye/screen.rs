//! Poses that lie (issue 14): a pose whose robot data (joints or flange
//! pose) contradict its image must not bend the fit. The flange-pose
//! calibration ([`super::calibrate`]) screens its poses itself (consensus
//! of board estimates, then residual screening with re-fit, each judged by
//! [`super::robust::robust_limit`]).
//!
//! [`screen_joint_poses`] offers the same screening to a joint-based camera
//! campaign (what `kinematics::identify` consumes): the nominal forward
//! kinematics stand in for the controller's flange poses. Kinematic errors
//! then add a pose-dependent misfit shared by all poses, which the
//! median/MAD limit absorbs, while a wrong joint file or a pose recorded
//! before the robot settled stands far out.

use super::calibrate::{screen_pairs, FlangeOptions};
use super::error::HandEyeError;
use super::result::PoseVerdict;
use crate::camera::model::Intrinsics;
use crate::geometry::Pose;
use crate::kinematics::image_pose::ImagePose;
use crate::kinematics::CalibratedModel;

/// Screen a joint-based camera campaign: per pose, whether its joints
/// contradict its image. `model` is the nominal robot with a rough
/// `world_to_base`/`flange_to_tool` (only the robot's forward kinematics
/// is used), `intrinsics` the camera stage's result (held: the nominal
/// kinematics' errors must not bend the camera).
pub fn screen_joint_poses(
    model: &CalibratedModel,
    intrinsics: &Intrinsics,
    poses: &[ImagePose],
) -> Result<Vec<PoseVerdict>, HandEyeError> {
    let flanges: Vec<Pose> = poses
        .iter()
        .enumerate()
        .map(|(k, p)| {
            model
                .robot
                .base_to_flange(&p.joints_rad)
                .map_err(|e| HandEyeError::BadPose {
                    pose: k,
                    reason: e.to_string(),
                })
        })
        .collect::<Result<_, _>>()?;
    let pairs: Vec<&[_]> = poses.iter().map(|p| p.observations.as_slice()).collect();
    let options = FlangeOptions {
        start_intrinsics: *intrinsics,
        distortion: true,
        hold_intrinsics: true,
        fit_board_scale: false,
        estimate_flange_noise: false,
    };
    // The screening alone: the hand-eye's jackknife (a refit per pose)
    // would make a large campaign quadratic.
    Ok(screen_pairs(&flanges, &pairs, &options)?.per_pose)
}
