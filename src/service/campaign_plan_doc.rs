//! A computed campaign plan as the served document, and the planner's
//! errors as the service's (an infeasible request names the binding
//! constraint and every filter's survivors).

use std::collections::BTreeMap;

use robocal_calib::plan::extension::EXISTING_FIELD;
use robocal_calib::plan::planner::PlannedSet;
use robocal_calib::plan::{CampaignPlan, ExistingCampaign, PlanError, PlanPurpose};

use super::campaign_plan_extension::FIELD as EXTEND_FIELD;
use super::campaign_plan_noise::DotNoise;
use super::error::ServiceError;
use crate::domain::now_rfc3339;
use crate::schema::campaign_plan::{
    CampaignPlanOut, ExistingPredictedDoc, FilterCountDoc, PlanPurposeDoc, PlannedPoseDoc,
    PredictedDoc,
};
use crate::schema::session::PoseSet;
use crate::schema::FieldError;

/// Decimals of the joint values served (1e-6 deg).
const JOINT_DECIMALS: f64 = 1e6;

fn round_deg(rad: f64) -> f64 {
    (rad.to_degrees() * JOINT_DECIMALS).round() / JOINT_DECIMALS
}

/// The planner's error as the service's: an infeasible request is a 422
/// whose first field is the binding constraint, then every filter's survivors.
pub fn plan_error(e: PlanError) -> ServiceError {
    match e {
        // The existing poses are the extended session's.
        PlanError::Invalid { field, message } if field == EXISTING_FIELD => {
            ServiceError::invalid(EXTEND_FIELD, message)
        }
        PlanError::Invalid { field, message } => ServiceError::invalid(field, message),
        PlanError::Infeasible {
            constraint,
            feasible,
            wanted,
            filters,
        } => {
            let mut errors = vec![FieldError::new(
                constraint,
                format!(
                    "this constraint bound: {feasible} feasible poses for {wanted} asked (survivors per filter follow)"
                ),
            )];
            errors.extend(filters.iter().map(|f| {
                FieldError::new(
                    format!("candidates.{}", f.constraint),
                    format!("{} survived", f.survivors),
                )
            }));
            ServiceError::Invalid(errors)
        }
        PlanError::Unidentifiable { parameters } => ServiceError::invalid(
            "view_angle_deg",
            format!("the feasible poses do not determine {parameters:?}: widen the ranges"),
        ),
        PlanError::Model(message) => ServiceError::invalid("kinematics", message),
    }
}

/// The served document of `plan`: joints in degrees rounded to
/// [`JOINT_DECIMALS`], angle σ in degrees (`layout_angles` names them),
/// the dot noise with its source.
pub fn plan_doc(
    id: String,
    serial: &str,
    model_name: String,
    plan: &CampaignPlan,
    noise: &DotNoise,
    layout_angles: &dyn Fn(&str) -> bool,
) -> CampaignPlanOut {
    CampaignPlanOut {
        id,
        serial: serial.to_string(),
        poses: plan
            .poses
            .iter()
            .map(|p| PlannedPoseDoc {
                joints_deg: p.joints_rad.iter().map(|q| round_deg(*q)).collect(),
                set: match p.set {
                    PlannedSet::Cal => PoseSet::Cal,
                    PlannedSet::Val => PoseSet::Val,
                },
            })
            .collect(),
        predicted: PredictedDoc {
            validation_error_mean_mm: plan.prediction.validation_error_mean_mm,
            parameter_std_devs: plan
                .prediction
                .parameter_std_devs
                .iter()
                .map(|(name, sd)| {
                    let v = if layout_angles(name) {
                        sd.to_degrees()
                    } else {
                        *sd
                    };
                    (name.clone(), v)
                })
                .collect::<BTreeMap<_, _>>(),
            condition_number: plan.prediction.condition_number,
            sigma_px: noise.sigma_px,
            sigma_px_source: Some(noise.source.clone()),
            existing: plan.existing.as_ref().map(|e| existing_doc(plan, e)),
        },
        purpose: match plan.purpose {
            PlanPurpose::Calibration => PlanPurposeDoc::Calibration,
            PlanPurpose::QuickCheck => PlanPurposeDoc::QuickCheck,
        },
        start_joints_deg: plan
            .start_joints_rad
            .iter()
            .map(|q| round_deg(*q))
            .collect(),
        path_length_deg: plan.path_length_rad.to_degrees(),
        candidates: plan
            .filters
            .iter()
            .map(|f| FilterCountDoc {
                constraint: f.constraint.to_string(),
                survivors: f.survivors,
            })
            .collect(),
        model: model_name,
        extend_session: None,
        created_at: now_rfc3339(),
    }
}

/// An extension's existing campaign alone, with the planned poses' gain.
fn existing_doc(plan: &CampaignPlan, existing: &ExistingCampaign) -> ExistingPredictedDoc {
    let before = existing.validation_error_mean_mm();
    ExistingPredictedDoc {
        poses: plan.existing_poses,
        validation_error_mean_mm: before,
        gain_mm: before.map(|b| b - plan.prediction.validation_error_mean_mm),
        undetermined: match existing {
            ExistingCampaign::Predicted(_) => Vec::new(),
            ExistingCampaign::Undetermined { parameters } => parameters.clone(),
        },
    }
}
