//! Calibration job options.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::session::Instrument;
use super::{Checker, FieldError};
use crate::domain::JobKind;

pub use crate::domain::Measurement;

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

/// What a calibration re-fits.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum CalibrationScope {
    /// Kinematics, base and hand–eye frames, intrinsics: a whole calibration.
    #[default]
    Full,
    /// Only `target_to_base` (`instrument_to_base`): the board moved. The
    /// kinematics, the hand–eye transform and the camera intrinsics are
    /// held at the robot's latest approved set.
    Base,
    /// Only `flange_to_camera` (`flange_to_tool`): the camera was
    /// re-mounted. Everything else is held at the latest approved set.
    HandEye,
}

impl CalibrationScope {
    pub fn is_full(&self) -> bool {
        *self == CalibrationScope::Full
    }

    pub fn as_str(self) -> &'static str {
        match self {
            CalibrationScope::Full => "full",
            CalibrationScope::Base => "base",
            CalibrationScope::HandEye => "hand_eye",
        }
    }
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
    /// `full` (default), `base` or `hand_eye`: a partial re-fit from a few
    /// poses holding everything else at the latest approved set.
    #[serde(default, skip_serializing_if = "CalibrationScope::is_full")]
    pub scope: CalibrationScope,
    /// Select non-geometric terms (joint compliance, angle-periodic joint
    /// errors) after the geometric fit and keep those the campaign
    /// identifies and that lower the held-out error; `false`:
    /// geometry only. Absent: on for tracker sessions, off for camera
    /// sessions (see [`CalibrationOptions::non_geometric_for`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub non_geometric: Option<bool>,
    /// `POST /v1/robots/{serial}/calibrations` only: the
    /// sessions (board placements, regions) of one robot fitted together:
    /// one kinematic model and hand–eye, one `target_to_base` per session,
    /// the camera intrinsics shared. Empty for a one-session job.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sessions: Vec<String>,
}

/// A re-check's options: none (the session and the latest approved set
/// are the whole input).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct CheckOptions {}

/// A job's `options`, by its kind: a calibration's request body, or a
/// re-check's (empty). Described as `anyOf`, not `oneOf`: a calibration's
/// options are also a valid (empty-schema) re-check's, and the job's
/// `kind` beside them says which they are.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum JobOptions {
    Calibration(CalibrationOptions),
    Check(CheckOptions),
}

impl utoipa::PartialSchema for JobOptions {
    fn schema() -> utoipa::openapi::RefOr<utoipa::openapi::schema::Schema> {
        use utoipa::openapi::schema::AnyOfBuilder;
        use utoipa::openapi::Ref;
        AnyOfBuilder::new()
            .item(Ref::from_schema_name("CalibrationOptions"))
            .item(Ref::from_schema_name("CheckOptions"))
            .description(Some(
                "A job's `options`, by its `kind`: a calibration's request body, or a \
                 re-check's (empty).",
            ))
            .into()
    }
}

impl utoipa::ToSchema for JobOptions {
    fn schemas(
        schemas: &mut Vec<(
            String,
            utoipa::openapi::RefOr<utoipa::openapi::schema::Schema>,
        )>,
    ) {
        for (name, schema) in [
            (
                "CalibrationOptions",
                <CalibrationOptions as utoipa::PartialSchema>::schema(),
            ),
            (
                "CheckOptions",
                <CheckOptions as utoipa::PartialSchema>::schema(),
            ),
        ] {
            schemas.push((name.into(), schema));
        }
        <CalibrationOptions as utoipa::ToSchema>::schemas(schemas);
    }
}

impl JobOptions {
    /// The kind of job these options are for.
    pub fn kind(&self) -> JobKind {
        match self {
            JobOptions::Calibration(_) => JobKind::Calibration,
            JobOptions::Check(_) => JobKind::Check,
        }
    }

    /// The stored `options` of a `kind` job, read as that kind's.
    pub fn decode(kind: JobKind, doc: serde_json::Value) -> Result<JobOptions, serde_json::Error> {
        Ok(match kind {
            JobKind::Calibration => JobOptions::Calibration(serde_json::from_value(doc)?),
            JobKind::Check => JobOptions::Check(serde_json::from_value(doc)?),
        })
    }

    /// A calibration's options; a re-check runs with the defaults (it
    /// measures the session as a full calibration would).
    pub fn calibration(&self) -> CalibrationOptions {
        match self {
            JobOptions::Calibration(o) => o.clone(),
            JobOptions::Check(_) => CalibrationOptions::default(),
        }
    }
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
            scope: CalibrationScope::Full,
            non_geometric: None,
            sessions: Vec::new(),
        }
    }
}

impl CalibrationOptions {
    /// Whether the job selects non-geometric terms for a session measured
    /// by `instrument`: the request's `non_geometric`, else on for a
    /// tracker and off otherwise. A camera session is opt-in for its cost:
    /// the terms are selected again on the image points (calib's
    /// `image_term_selection`: three to five joint refinements instead of
    /// one), and a camera campaign's narrow configurations leave most
    /// candidates unidentifiable anyway; a tracker's pose-level fit is cheap.
    /// A stage session identifies no robot, so it has no terms either.
    pub fn non_geometric_for(&self, instrument: Instrument) -> bool {
        self.non_geometric
            .unwrap_or(instrument == Instrument::Tracker)
    }
}

impl CalibrationOptions {
    /// A job over several sessions.
    pub fn is_multi_session(&self) -> bool {
        self.sessions.len() > 1
    }

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

/// One Server-Sent Event of `GET /v1/jobs/{id}/events`, as a client's SSE
/// parser sees it: its name and its `data` line (a JSON document).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct JobEventFrame {
    /// `stage` (`data`: `{"stage", "progress"}`) when the job enters a
    /// stage, `progress` (same `data`) as it advances, `end` (`data`: the
    /// job, as `GET /v1/jobs/{id}` answers) when it ended; the stream then
    /// closes.
    #[schema(pattern = "^(stage|progress|end)$")]
    pub event: String,
    /// The event's JSON document, as text.
    pub data: String,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Term selection is on by default for a tracker and opt-in for a
    /// camera (its image-level selection costs several refinements); an
    /// explicit `non_geometric` wins either way.
    #[test]
    fn non_geometric_defaults_on_for_trackers_only() {
        let absent: CalibrationOptions = serde_json::from_str("{}").unwrap();
        assert!(absent.non_geometric_for(Instrument::Tracker));
        assert!(!absent.non_geometric_for(Instrument::Camera));
        assert!(!absent.non_geometric_for(Instrument::Stage));
        let on: CalibrationOptions = serde_json::from_str(r#"{"non_geometric": true}"#).unwrap();
        assert!(on.non_geometric_for(Instrument::Camera));
        let off: CalibrationOptions = serde_json::from_str(r#"{"non_geometric": false}"#).unwrap();
        assert!(!off.non_geometric_for(Instrument::Tracker));
    }
}
