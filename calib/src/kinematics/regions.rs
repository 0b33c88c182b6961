//! One model from several board placements (the paper's regions, section
//! 5; method.md §6–7): every session is one placement of the board in the
//! workspace with its own `target_to_base`, while the kinematics, the
//! hand–eye `flange_to_camera` and the camera intrinsics are shared. All
//! sessions' image points go into one joint refinement
//! ([`super::joint_refine`]), so the model carries the information of the
//! whole workspace instead of one region's.

use super::identify_error::IdentifyError;
use super::image_pose::{ImageNoise, ImagePose};
use super::joint_refine::{refine_sessions, Extras, JointRefinement};
use super::nongeometric::NonGeometric;
use super::params::CalibratedModel;
use crate::camera::model::Intrinsics;
use crate::geometry::Pose;

/// One session's data: its board placement's starting `target_to_base`
/// (from its own pose-level identification) and its calibration poses.
#[derive(Debug, Clone, PartialEq)]
pub struct RegionPoses {
    pub target_to_base_start: Pose,
    pub poses: Vec<ImagePose>,
}

/// The session (region index) of every pose of `regions`, in the order
/// the fit takes them: what [`super::joint_covariance::joint_refine_covariance_sessions`]
/// needs beside the poses.
pub fn session_of(regions: &[RegionPoses]) -> Vec<usize> {
    regions
        .iter()
        .enumerate()
        .flat_map(|(s, r)| std::iter::repeat_n(s, r.poses.len()))
        .collect()
}

/// Refine kinematics, hand–eye and intrinsics on the image points of every
/// region, one `target_to_base` per region. `start` holds the starting
/// kinematics and hand–eye (its `world_to_base` is ignored); `free` are the
/// layout indices identified, the same for every region (a base value held
/// in one is held in all). The result's `model.world_to_base` is region
/// 0's and `session_target_to_base[i]` region `i`'s.
pub fn joint_refine_regions(
    start: &CalibratedModel,
    intrinsics: &Intrinsics,
    regions: &[RegionPoses],
    free: &[usize],
    noise: ImageNoise,
    hold_intrinsics: bool,
) -> Result<JointRefinement, IdentifyError> {
    refine_regions(
        start,
        intrinsics,
        regions,
        free,
        None,
        noise,
        hold_intrinsics,
    )
}

/// [`joint_refine_regions`] with non-geometric terms (issue 19) refined
/// with the shared model, starting from their values in `terms`: an error
/// the geometry cannot hold (a joint's compliance) otherwise leaks into the
/// shared kinematics and depth scale, and the one model of several regions
/// loses its advantage over a local one (docs/decisions/0029-regions-judged-over-campaigns.md).
/// The result's `terms` holds them with their covariance.
pub fn joint_refine_regions_with_terms(
    start: &CalibratedModel,
    intrinsics: &Intrinsics,
    regions: &[RegionPoses],
    free: &[usize],
    terms: &NonGeometric,
    noise: ImageNoise,
    hold_intrinsics: bool,
) -> Result<JointRefinement, IdentifyError> {
    refine_regions(
        start,
        intrinsics,
        regions,
        free,
        Some(terms),
        noise,
        hold_intrinsics,
    )
}

fn refine_regions(
    start: &CalibratedModel,
    intrinsics: &Intrinsics,
    regions: &[RegionPoses],
    free: &[usize],
    terms: Option<&NonGeometric>,
    noise: ImageNoise,
    hold_intrinsics: bool,
) -> Result<JointRefinement, IdentifyError> {
    let first = regions.first().ok_or(IdentifyError::NoPoses)?;
    if let Some(region) = regions.iter().position(|r| r.poses.is_empty()) {
        return Err(IdentifyError::EmptyRegion { region });
    }
    let start = CalibratedModel {
        world_to_base: first.target_to_base_start,
        ..start.clone()
    };
    let extra_bases: Vec<Pose> = regions[1..]
        .iter()
        .map(|r| r.target_to_base_start)
        .collect();
    let session_of = session_of(regions);
    let poses: Vec<ImagePose> = regions.iter().flat_map(|r| r.poses.clone()).collect();
    let sessions = Extras {
        extra_bases: &extra_bases,
        session_of: &session_of,
        terms,
        prior: None,
    };
    refine_sessions(
        &start,
        intrinsics,
        &poses,
        free,
        noise,
        hold_intrinsics,
        sessions,
    )
}

#[cfg(test)]
#[path = "regions_fixture.rs"]
mod fixture;

#[cfg(test)]
#[path = "regions_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "regions_pairs_tests.rs"]
mod pairs_tests;
