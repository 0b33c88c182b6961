//! The model every simulated identification starts from (method.md §6).

use super::campaign::CampaignSpec;
use crate::geometry::Pose;
use crate::kinematics::identify::{IdentifyError, Measurement};
use crate::kinematics::initial::initial_world_to_base;
use crate::kinematics::CalibratedModel;

/// Start model: nominal kinematics, hand–eye guess, base by registration.
pub fn start_model(
    spec: &CampaignSpec,
    cal: &[Measurement],
) -> Result<CalibratedModel, IdentifyError> {
    let mut m = CalibratedModel {
        robot: spec.nominal.clone(),
        world_to_base: Pose::identity(),
        flange_to_tool: spec.flange_to_camera_guess,
    };
    m.world_to_base = initial_world_to_base(&m, cal)?;
    Ok(m)
}
