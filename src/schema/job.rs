//! Calibration job options.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::{Checker, FieldError};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum Measurement {
    Pose,
    Position,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum ValidationNamed {
    ValSet,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct Holdout {
    /// The share of poses held out for validation, strictly between 0 and 1.
    #[schema(exclusive_minimum = 0.0, exclusive_maximum = 1.0)]
    pub holdout_fraction: f64,
}

/// `"val_set"` (the poses uploaded with `set: "val"`) or `{"holdout_fraction": f}`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(untagged)]
pub enum Validation {
    Named(ValidationNamed),
    Holdout(Holdout),
}

/// `POST /v1/sessions/{id}/calibrations` body; every field optional.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CalibrationOptions {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measurement: Option<Measurement>,
    /// `false`: the camera intrinsics are the paper's Tsai-sequence
    /// estimates, not refined (`camera_mode: "paper"` in the parameter set);
    /// the joint refinement, which would re-fit them, is then skipped.
    #[serde(default = "yes")]
    pub refine_intrinsics: bool,
    /// The final fit of kinematics, hand–eye and intrinsics to the image
    /// points; skipped when the intrinsics are held (`refine_intrinsics:
    /// false`, or a session `camera_calibration_id`).
    #[serde(default = "yes")]
    pub joint_refinement: bool,
    #[serde(default = "val_set")]
    pub validation: Validation,
}

fn yes() -> bool {
    true
}
fn val_set() -> Validation {
    Validation::Named(ValidationNamed::ValSet)
}

impl Default for CalibrationOptions {
    fn default() -> Self {
        CalibrationOptions {
            measurement: None,
            refine_intrinsics: true,
            joint_refinement: true,
            validation: val_set(),
        }
    }
}

impl CalibrationOptions {
    pub fn check(&self) -> Result<(), Vec<FieldError>> {
        let mut c = Checker::default();
        if let Validation::Holdout(h) = self.validation {
            if !h.holdout_fraction.is_finite()
                || h.holdout_fraction <= 0.0
                || h.holdout_fraction >= 1.0
            {
                c.fail(
                    "validation.holdout_fraction",
                    "must be between 0 and 1 (exclusive)",
                );
            }
        }
        c.finish()
    }
}
