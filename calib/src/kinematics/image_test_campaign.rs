//! Test set-up shared by the image-level fits' tests: a simulated camera
//! campaign as the joint refinement reads it, and the free parameters a
//! camera campaign identifies (everything but the first joint's offset and
//! `d`, which the board frame absorbs, and the last joint's, which the
//! hand–eye absorbs).

use super::image_pose::ImagePose;
use super::params::{CalibratedModel, Instrument, ParamLayout};
use crate::sim::campaign::{simulate_campaign, Campaign, CampaignSpec};

/// Parameters a camera campaign cannot separate from the frames.
const HELD: [&str; 6] = ["dtheta_1", "d_1", "dtheta_6", "a_6", "d_6", "alpha_6"];

pub(super) struct ImageCampaign {
    pub campaign: Campaign,
    pub truth: CalibratedModel,
    pub poses: Vec<ImagePose>,
    pub layout: ParamLayout,
    pub free: Vec<usize>,
}

/// `spec` simulated, its poses as image points, the camera layout and its
/// free parameters.
pub(super) fn image_campaign(spec: &CampaignSpec) -> ImageCampaign {
    let campaign = simulate_campaign(spec).unwrap();
    let truth = campaign.truth.model().unwrap();
    let poses = campaign
        .poses
        .iter()
        .map(|p| ImagePose {
            joints_rad: p.joints_rad.clone(),
            observations: p.observations(&campaign.truth.board),
        })
        .collect();
    let layout = ParamLayout::new(&truth.robot, Instrument::Camera);
    let free = (0..layout.len())
        .filter(|&i| !HELD.contains(&layout.params[i].name.as_str()))
        .collect();
    ImageCampaign {
        campaign,
        truth,
        poses,
        layout,
        free,
    }
}
