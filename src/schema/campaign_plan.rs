//! `POST /v1/robots/{serial}/campaign-plans` request and response documents
//! (issue 16). Outside tools are written against these names: change them
//! only additively.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::session::{CameraDoc, PoseSet, TargetDoc};
use super::{Checker, FieldError, PoseDoc, MAX_ANGLE_DEG, MAX_LENGTH_MM};

/// Most poses a plan may ask for (calibration plus validation).
pub const MAX_PLAN_POSES: u32 = 500;
/// Most keep-out boxes.
pub const MAX_KEEP_OUT: usize = 100;
/// Largest dot noise a request may state (px).
pub const MAX_SIGMA_PX: f64 = 10.0;

fn default_distance() -> [f64; 2] {
    [600.0, 1000.0]
}

fn default_view_angle() -> [f64; 2] {
    [20.0, 45.0]
}

/// A box in the robot's base frame the flange and the camera must stay out of.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct KeepOutDoc {
    #[schema(min_items = 3, max_items = 3)]
    pub min_mm: [f64; 3],
    #[schema(min_items = 3, max_items = 3)]
    pub max_mm: [f64; 3],
}

/// What the plan is for; by default a plan of 5 to 10 poses is a quick check.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum PlanPurposeDoc {
    /// Every parameter a calibration job identifies.
    Calibration,
    /// A re-check: the poses most sensitive to drift of the joint zeros and the base.
    QuickCheck,
}

/// `POST /v1/robots/{serial}/campaign-plans` body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct CampaignPlanBody {
    /// The board, as in a session (with `extend_session`: default the
    /// session's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target: Option<TargetDoc>,
    /// The camera, as in a session (or give `camera_calibration_id`; with
    /// `extend_session`: default the session's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<CameraDoc>,
    /// A parameter set `"{serial}/{version}"` (or `"/latest"`) whose camera
    /// intrinsics the campaign's job will reuse and hold.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera_calibration_id: Option<String>,
    /// The camera in the flange frame; omitted: the robot's latest
    /// parameter set's `flange_to_camera` (a 422 when it has none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flange_to_camera_guess: Option<PoseDoc>,
    /// The board in the base frame's terms, the same frame as a parameter
    /// set's `target_to_base`; omitted: the robot's latest set's (a 422
    /// when it has none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target_to_base_guess: Option<PoseDoc>,
    /// Calibration poses to plan (5 to 10: a quick check by default).
    pub poses: u32,
    #[serde(default)]
    pub validation_poses: u32,
    /// Camera-to-board-centre distance range.
    #[serde(default = "default_distance")]
    #[schema(min_items = 2, max_items = 2)]
    pub distance_mm: [f64; 2],
    /// Range of the angle between the line of sight and the board normal.
    #[serde(default = "default_view_angle")]
    #[schema(min_items = 2, max_items = 2)]
    pub view_angle_deg: [f64; 2],
    /// Per joint `[min, max]`, tighter than the robot's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub joint_limits_deg: Option<Vec<[f64; 2]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub keep_out: Option<Vec<KeepOutDoc>>,
    /// Where the robot stands before the campaign; the path starts here.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start_joints_deg: Option<Vec<f64>>,
    /// Dot noise for the prediction (px per image axis); default: what the
    /// robot's newest camera job measured on images of this size, else 0.1 px.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma_px: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub purpose: Option<PlanPurposeDoc>,
    /// A camera session of this robot whose campaign the plan extends:
    /// its `cal` poses' joints seed the selection, only the poses to add
    /// are returned (`poses` of them), and `predicted` says what the
    /// session's campaign achieves alone and with them. The purpose is then
    /// a calibration unless stated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extend_session: Option<String>,
}

impl CampaignPlanBody {
    /// Field checks that need no robot (the rest are the planner's).
    pub fn check(&self) -> Result<(), Vec<FieldError>> {
        let mut c = Checker::default();
        match &self.target {
            Some(target) => {
                if let Err(errors) = crate::domain::Target::from_doc(target) {
                    c.errors.extend(errors);
                }
            }
            None => c.fail("target", "required (or extend a session that has one)"),
        }
        if self.camera.is_none() && self.camera_calibration_id.is_none() {
            c.fail("camera", "give camera or camera_calibration_id");
        }
        if let Some(p) = &self.flange_to_camera_guess {
            p.check(&mut c, "flange_to_camera_guess");
        }
        if let Some(p) = &self.target_to_base_guess {
            p.check(&mut c, "target_to_base_guess");
        }
        if self.poses == 0 || self.poses.saturating_add(self.validation_poses) > MAX_PLAN_POSES {
            c.fail(
                "poses",
                format!("1 to {MAX_PLAN_POSES} poses with the validation poses"),
            );
        }
        let [d0, d1] = self.distance_mm;
        if !(d0.is_finite() && d1.is_finite() && 0.0 < d0 && d0 <= d1 && d1 <= MAX_LENGTH_MM) {
            c.fail("distance_mm", "[min, max] with 0 < min <= max");
        }
        let [a0, a1] = self.view_angle_deg;
        if !(a0.is_finite() && a1.is_finite() && 0.0 <= a0 && a0 <= a1 && a1 < 90.0) {
            c.fail("view_angle_deg", "[min, max] with 0 <= min <= max < 90");
        }
        for (i, [lo, hi]) in self.joint_limits_deg.iter().flatten().enumerate() {
            if !(lo.is_finite()
                && hi.is_finite()
                && lo < hi
                && lo.abs().max(hi.abs()) <= MAX_ANGLE_DEG)
            {
                c.fail(
                    format!("joint_limits_deg[{i}]"),
                    "[min, max] with min < max",
                );
            }
        }
        let boxes = self.keep_out.as_deref().unwrap_or_default();
        if boxes.len() > MAX_KEEP_OUT {
            c.fail("keep_out", format!("at most {MAX_KEEP_OUT} boxes"));
        }
        for (i, b) in boxes.iter().enumerate() {
            let ok = (0..3).all(|k| {
                b.min_mm[k].is_finite()
                    && b.max_mm[k].is_finite()
                    && b.min_mm[k] <= b.max_mm[k]
                    && b.max_mm[k].abs().max(b.min_mm[k].abs()) <= MAX_LENGTH_MM
            });
            if !ok {
                c.fail(format!("keep_out[{i}]"), "finite min_mm <= max_mm per axis");
            }
        }
        for (i, q) in self.start_joints_deg.iter().flatten().enumerate() {
            c.bounded(format!("start_joints_deg[{i}]"), *q, MAX_ANGLE_DEG, "deg");
        }
        if let Some(s) = self.sigma_px {
            c.positive("sigma_px", s, MAX_SIGMA_PX, "px");
        }
        c.finish()
    }
}

/// One planned pose: the joints to move to, and the set its image goes in.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct PlannedPoseDoc {
    pub joints_deg: Vec<f64>,
    pub set: PoseSet,
}

/// What the plan predicts for the campaign.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct PredictedDoc {
    /// Mean 3-D camera position error (mm) the calibrated model will show
    /// at random validation poses in the same ranges.
    pub validation_error_mean_mm: f64,
    /// 1σ of every identified parameter: mm for lengths and translations,
    /// degrees for angles, pixels for `fx fy cx cy`, unitless for distortion.
    pub parameter_std_devs: BTreeMap<String, f64>,
    /// `s_max / s_min` of the column-scaled image-level Jacobian.
    pub condition_number: f64,
    /// The dot noise the prediction assumed (px per image axis).
    pub sigma_px: f64,
    /// Where `sigma_px` came from: `"request"` (the body's `sigma_px`), the
    /// parameter set `"{serial}/{version}"` whose job measured it (its
    /// report's reprojection RMS / sqrt 2, on images of the plan's size), or
    /// `"default"` (0.1 px). Absent only in plans stored before it existed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma_px_source: Option<String>,
    /// An extension's (`extend_session`) existing campaign alone: what
    /// it is predicted to achieve without the planned poses.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub existing: Option<ExistingPredictedDoc>,
}

/// What the session a plan extends is predicted to achieve alone; the
/// plan's `validation_error_mean_mm` is the campaign with the planned
/// poses added.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct ExistingPredictedDoc {
    /// The session's `cal` poses with joints that seeded the plan.
    pub poses: usize,
    /// Mean 3-D camera position error (mm) at the same validation poses;
    /// absent when the session's poses do not determine every parameter.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub validation_error_mean_mm: Option<f64>,
    /// The predicted gain of shooting the planned poses: this error minus
    /// the extended campaign's (mm); absent with the error.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gain_mm: Option<f64>,
    /// The least determined parameters when the session's poses leave
    /// some undetermined (the planned poses are chosen to determine them).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub undetermined: Vec<String>,
}

/// How many candidate poses survived one filter.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct FilterCountDoc {
    pub constraint: String,
    pub survivors: usize,
}

/// A stored campaign plan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct CampaignPlanOut {
    pub id: String,
    pub serial: String,
    /// In path order.
    pub poses: Vec<PlannedPoseDoc>,
    pub predicted: PredictedDoc,
    pub purpose: PlanPurposeDoc,
    /// Where the path starts.
    pub start_joints_deg: Vec<f64>,
    /// Sum over the moves of the largest joint change (deg).
    pub path_length_deg: f64,
    /// Survivors of every candidate filter, in order.
    pub candidates: Vec<FilterCountDoc>,
    /// `"nominal"` or the parameter set `"{serial}/{version}"` whose
    /// kinematics the plan used.
    pub model: String,
    /// The session the plan extends (the request's `extend_session`): the
    /// poses are the ones to add to it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extend_session: Option<String>,
    pub created_at: String,
}
