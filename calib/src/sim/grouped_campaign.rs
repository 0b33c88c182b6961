//! Campaigns shot in configuration groups (method.md §7.6 "Held-out
//! groups"), as many real hand–eye campaigns are: a few shoulder/elbow
//! configurations, and within each only the wrist moves to look at the
//! board from another angle. Links 1–3 are then weakly excited: the
//! situation in which identifying the full kinematics can predict unseen
//! configurations worse than the nominal model. The validation poses are
//! spread over the workspace (each its own configuration), so they judge
//! exactly that.

use rand::{rngs::StdRng, Rng, SeedableRng};

use super::campaign::{pose_at, setup, station_joints, Campaign, CampaignSpec, SimError};
use super::campaign_io::PoseSet;

/// Attempts per accepted pose before the campaign is declared impossible.
const MAX_ATTEMPTS_PER_POSE: usize = 400;

/// How the calibration poses are grouped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grouping {
    pub groups: usize,
    pub per_group: usize,
    /// Joints 1–3 stay within ± this of the group's first pose (deg).
    pub shoulder_jitter_deg: f64,
    /// Joints 4–6 move within ± this of the group's first pose (deg).
    pub wrist_range_deg: f64,
}

impl Grouping {
    /// The real campaigns' structure: 6 groups of 4, joints 1–3 within ±1°.
    pub const SIX_BY_FOUR: Self = Self {
        groups: 6,
        per_group: 4,
        shoulder_jitter_deg: 1.0,
        wrist_range_deg: 12.0,
    };
}

/// `spec` with its calibration poses shot in `grouping`'s groups (the
/// spec's `cal_poses` is replaced by `groups × per_group`) and its
/// `val_poses` spread over the workspace. The true robot, hand–eye and
/// board are `spec`'s, as [`super::campaign::simulate_campaign`] draws them.
pub fn simulate_grouped_campaign(
    spec: &CampaignSpec,
    grouping: Grouping,
) -> Result<Campaign, SimError> {
    let spec = CampaignSpec {
        cal_poses: grouping.groups * grouping.per_group,
        ..spec.clone()
    };
    let mut rng = StdRng::seed_from_u64(spec.seed);
    let setup = setup(&spec, &mut rng)?;
    let wanted = spec.cal_poses + spec.val_poses;
    let limit = MAX_ATTEMPTS_PER_POSE * wanted;
    let mut poses = Vec::with_capacity(wanted);
    let mut attempts = 0;
    let unreachable = |placed| SimError::Unreachable { placed, wanted };
    for _ in 0..grouping.groups {
        // The group's configuration: a reachable station's joints.
        let anchor = loop {
            attempts += 1;
            if attempts > limit {
                return Err(unreachable(poses.len()));
            }
            let Some(joints) = station_joints(&spec, &setup, &mut rng) else {
                continue;
            };
            if let Some(pose) = pose_at(&spec, &setup, joints.clone(), PoseSet::Cal, &mut rng) {
                poses.push(pose);
                break joints;
            }
        };
        let mut placed = 1;
        while placed < grouping.per_group {
            attempts += 1;
            if attempts > limit {
                return Err(unreachable(poses.len()));
            }
            let joints: Vec<f64> = anchor
                .iter()
                .enumerate()
                .map(|(j, q)| {
                    let range = if j < 3 {
                        grouping.shoulder_jitter_deg
                    } else {
                        grouping.wrist_range_deg
                    };
                    q + rng.random_range(-range..=range).to_radians()
                })
                .collect();
            if let Some(pose) = pose_at(&spec, &setup, joints, PoseSet::Cal, &mut rng) {
                poses.push(pose);
                placed += 1;
            }
        }
    }
    while poses.len() < wanted {
        attempts += 1;
        if attempts > limit {
            return Err(unreachable(poses.len()));
        }
        let Some(joints) = station_joints(&spec, &setup, &mut rng) else {
            continue;
        };
        if let Some(pose) = pose_at(&spec, &setup, joints, PoseSet::Val, &mut rng) {
            poses.push(pose);
        }
    }
    Ok(setup.into_campaign(&spec, poses))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::config_groups::{configuration_groups, group_count};

    #[test]
    fn groups_share_their_shoulder_and_validation_is_spread() {
        let mut spec = CampaignSpec::standard("irb2400", 3).unwrap();
        spec.val_poses = 10;
        let c = simulate_grouped_campaign(&spec, Grouping::SIX_BY_FOUR).unwrap();
        assert_eq!(c.poses.len(), 34);
        let joints: Vec<Vec<f64>> = c.poses.iter().map(|p| p.joints_rad.clone()).collect();
        let groups = configuration_groups(&joints[..24], &[]);
        assert_eq!(group_count(&groups), 6, "{groups:?}");
        for g in 0..6 {
            assert!(groups[g * 4..g * 4 + 4].iter().all(|&x| x == groups[g * 4]));
        }
        let all = configuration_groups(&joints, &[]);
        assert!(group_count(&all) >= 14, "{all:?}");
        assert!(c.poses[24..].iter().all(|p| p.set == PoseSet::Val));
    }
}
