//! Extending a campaign (issue 30, "tell the user what to shoot next"):
//! the information of the calibration poses a campaign already has seeds
//! the selection, so the new poses go where the existing ones leave the
//! parameters undetermined, and the plan predicts the campaign's
//! validation error without and with them (the gain of shooting them).

use nalgebra::DMatrix;

use super::error::PlanError;
use super::information::{pose_factor, Columns};
use super::predict::{predict, Prediction};
use super::request::PlanRequest;
use crate::kinematics::CalibratedModel;

/// Field of [`PlanError::Invalid`] for the existing poses.
pub const EXISTING_FIELD: &str = "existing_joints_rad";

/// What the existing campaign alone is predicted to achieve.
#[derive(Debug, Clone, PartialEq)]
pub enum ExistingCampaign {
    Predicted(Prediction),
    /// Its poses do not determine every parameter (a job would fix some at
    /// their start values): no validation error can be predicted, these
    /// parameters are the least determined.
    Undetermined {
        parameters: Vec<String>,
    },
}

impl ExistingCampaign {
    /// The predicted validation error (mm), when determined.
    pub fn validation_error_mean_mm(&self) -> Option<f64> {
        match self {
            ExistingCampaign::Predicted(p) => Some(p.validation_error_mean_mm),
            ExistingCampaign::Undetermined { .. } => None,
        }
    }
}

/// The existing poses' factors: every one must have the robot's joint
/// count and finite values, and at least one must see the board by the
/// planning model (a pose that does not, e.g. by a poor guess of the
/// frames, brings no information and is skipped).
pub fn existing_factors(
    request: &PlanRequest,
    model: &CalibratedModel,
    columns: &Columns,
) -> Result<Vec<DMatrix<f64>>, PlanError> {
    let dof = model.robot.dof();
    for (k, q) in request.existing_joints_rad.iter().enumerate() {
        if q.len() != dof || q.iter().any(|v| !v.is_finite()) {
            return Err(PlanError::Invalid {
                field: EXISTING_FIELD,
                message: format!("pose {k}: needs {dof} finite joint values"),
            });
        }
    }
    let factors: Vec<DMatrix<f64>> = request
        .existing_joints_rad
        .iter()
        .filter_map(|q| pose_factor(request, model, columns, q))
        .collect();
    if factors.is_empty() && !request.existing_joints_rad.is_empty() {
        return Err(PlanError::Invalid {
            field: EXISTING_FIELD,
            message: "no existing pose sees the board by the guesses of the frames".into(),
        });
    }
    Ok(factors)
}

/// The prediction of the existing campaign alone, at the plan's
/// validation poses `probe`.
pub fn predict_existing(
    model: &CalibratedModel,
    columns: &Columns,
    existing: &[DMatrix<f64>],
    probe: &[Vec<f64>],
) -> Result<ExistingCampaign, PlanError> {
    let refs: Vec<&DMatrix<f64>> = existing.iter().collect();
    match predict(model, columns, &refs, probe) {
        Ok(p) => Ok(ExistingCampaign::Predicted(p)),
        Err(PlanError::Unidentifiable { parameters }) => {
            Ok(ExistingCampaign::Undetermined { parameters })
        }
        Err(e) => Err(e),
    }
}
