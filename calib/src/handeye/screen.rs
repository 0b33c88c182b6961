//! Poses that lie (issue 14): a pose whose robot data (joints or flange
//! pose) contradict its image must not bend the fit. A pose is judged by a
//! robust limit over its peers: it is out when its figure exceeds
//! `max(RATIO x median, median + MADS x 1.4826 MAD)` of the poses in the
//! fit. The same limit serves the consensus of board estimates (mm) and
//! the reprojection of each pose under a fit of the others (px).
//!
//! [`screen_joint_poses`] offers the same screening to a joint-based camera
//! campaign (what `kinematics::identify` consumes): the nominal forward
//! kinematics stand in for the controller's flange poses. Kinematic errors
//! then add a pose-dependent misfit shared by all poses, which the
//! median/MAD limit absorbs, while a wrong joint file or a pose recorded
//! before the robot settled stands far out.

use super::calibrate::{calibrate_pairs, FlangeOptions};
use super::error::HandEyeError;
use super::result::PoseVerdict;
use super::start::median;
use crate::camera::model::Intrinsics;
use crate::geometry::Pose;
use crate::kinematics::image_pose::ImagePose;
use crate::kinematics::CalibratedModel;

/// A pose is out beyond this multiple of the median of its peers ...
pub const OUTLIER_RATIO: f64 = 3.0;
/// ... and beyond this many robust standard deviations above it.
pub const OUTLIER_MADS: f64 = 5.0;
/// MAD to standard deviation for Gaussian data.
const MAD_TO_SIGMA: f64 = 1.4826;

/// The robust limit of the module doc over the figures of the poses in the fit.
pub fn robust_limit(figures: &[f64]) -> f64 {
    let med = median(figures);
    let deviations: Vec<f64> = figures.iter().map(|v| (v - med).abs()).collect();
    let mad = median(&deviations);
    (OUTLIER_RATIO * med).max(med + OUTLIER_MADS * MAD_TO_SIGMA * mad)
}

/// Screen a joint-based camera campaign: per pose, whether its joints
/// contradict its image. `model` is the nominal robot with a rough
/// `world_to_base`/`flange_to_tool` (only the robot's forward kinematics
/// is used), `intrinsics` the camera stage's result (refined again here).
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
        fit_board_scale: false,
    };
    Ok(calibrate_pairs(&flanges, &pairs, &options)?.per_pose)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limit_follows_the_median_and_the_spread() {
        let tight = [1.0, 1.01, 0.99, 1.0, 1.02];
        assert!((robust_limit(&tight) - 3.0).abs() < 1e-9);
        let spread = [1.0, 2.0, 3.0, 4.0, 5.0];
        // median 3, MAD 1: 3 + 5 * 1.4826 = 10.4 > 9.
        assert!((robust_limit(&spread) - (3.0 + 5.0 * MAD_TO_SIGMA)).abs() < 1e-9);
    }
}
