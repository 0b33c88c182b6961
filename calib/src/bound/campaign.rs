//! The Cramér–Rao bound of a simulated camera campaign (method.md §6.9):
//! evaluated at the campaign's truth (robot, board, hand–eye, intrinsics
//! and any non-geometric terms), with the spec's dot and encoder noise,
//! over every structurally identifiable parameter, the terms the true
//! robot has, and the intrinsics.

use super::cramer_rao::{cramer_rao, BoundInput, CramerRao};
use super::BoundError;
use crate::kinematics::identifiability::structural_redundancies;
use crate::kinematics::image_information::InformationInput;
use crate::kinematics::image_pose::ImagePose;
use crate::kinematics::{CalibratedModel, Instrument, KinematicsError, ParamLayout};
use crate::sim::campaign::{true_terms, Campaign, CampaignSpec};
use crate::sim::campaign_io::PoseSet;

/// Layout indices of `model` that are not structurally redundant: every
/// unknown a camera campaign could determine.
pub fn identifiable(model: &CalibratedModel) -> Result<Vec<usize>, KinematicsError> {
    let layout = ParamLayout::new(&model.robot, Instrument::Camera);
    let structural = structural_redundancies(&layout, model)?;
    Ok((0..layout.len())
        .filter(|i| !structural.contains(i))
        .collect())
}

/// The bound of `campaign` (simulated from `spec`) for the calibration
/// images `cal` (their joints and the board points each sees; the pixels
/// are not used), judged at the campaign's validation poses. The
/// intrinsics are unknowns unless `hold_intrinsics`.
pub fn campaign_bound(
    spec: &CampaignSpec,
    campaign: &Campaign,
    cal: &[ImagePose],
    hold_intrinsics: bool,
) -> Result<CramerRao, BoundError> {
    if spec.compliance_rad_per_m != 0.0 {
        // That deflection has no parameter in the model: no correct model,
        // no bound.
        return Err(BoundError::Unmodelled);
    }
    let truth = campaign.truth.model()?;
    let terms = true_terms(spec, &truth);
    let free = identifiable(&truth)?;
    let val_joints: Vec<Vec<f64>> = campaign
        .poses
        .iter()
        .filter(|p| p.set == PoseSet::Val)
        .map(|p| p.joints_rad.clone())
        .collect();
    let input = BoundInput {
        information: InformationInput {
            model: &truth,
            intrinsics: &campaign.truth.intrinsics,
            terms: (!terms.terms.is_empty()).then_some(&terms),
            poses: cal,
            free: &free,
            sigma_px: spec.pixel_sigma_px,
            joint_sigma_rad: spec.encoder_sigma_deg.to_radians(),
            hold_intrinsics,
        },
        val_joints: &val_joints,
    };
    Ok(cramer_rao(&input)?)
}
