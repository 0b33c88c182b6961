//! A job's kind and its result, typed once: the kind is read when a job is
//! loaded and decides its options and its result; the stored and served
//! documents are these types' serde forms.

use serde::{Deserialize, Serialize};
use serde_json::Value;
use utoipa::ToSchema;

use super::{CheckDoc, ReleaseStatus};

/// The key of a re-check's verdict in a job's `result`.
const VERDICT_KEY: &str = "verdict";

/// What a job does: `calibration` (identify a parameter set) or `check`
/// (judge a short session against the latest approved set).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum JobKind {
    Calibration,
    Check,
}

impl JobKind {
    /// Every kind the queue runs (what `GET /v1/jobs?kind=` accepts).
    pub const ALL: [JobKind; 2] = [JobKind::Calibration, JobKind::Check];

    /// Its name, as stored in `jobs.kind` and served.
    pub fn as_str(self) -> &'static str {
        match self {
            JobKind::Calibration => "calibration",
            JobKind::Check => "check",
        }
    }

    pub fn parse(s: &str) -> Option<JobKind> {
        JobKind::ALL.into_iter().find(|k| k.as_str() == s)
    }

    /// The names of every kind, for a message (`calibration, check`).
    pub fn names() -> String {
        JobKind::ALL.map(JobKind::as_str).join(", ")
    }
}

/// The job's `result.summary`: the poses it used and, after a calibration,
/// the mean validation error before and after.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(default)]
pub struct JobSummary {
    /// The stage a validation-only run stopped after (`validate`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stage: Option<String>,
    pub calibration_poses: usize,
    pub validation_poses: usize,
    /// The robot's joint count (validation-only runs).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joints: Option<usize>,
    /// Mean validation error of the nominal model (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub before_mean_mm: Option<f64>,
    /// Mean validation error of the identified model (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub after_mean_mm: Option<f64>,
    /// Poses left out as contradicting their image (hand–eye jobs).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub outliers: Option<usize>,
    /// Reprojection RMS of the hand–eye bundle (hand–eye jobs).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reprojection_rms_px: Option<f64>,
    /// The board's fitted scale against its configured spacing (hand–eye
    /// jobs that fit it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub board_scale: Option<f64>,
}

/// A succeeded calibration's `result`: its summary and, when it stored a
/// parameter set, the set's version and the release gate's decision.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct CalibrationResult {
    pub summary: JobSummary,
    /// The robot whose set the job stored.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub serial: Option<String>,
    /// The version the job stored.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub version: Option<i64>,
    /// The release gate's decision on it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub status: Option<ReleaseStatus>,
    /// Why the gate decided so.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub status_reason: Option<String>,
}

/// A succeeded re-check's `result`: the verdict's fields beside the
/// summary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct CheckResult {
    #[serde(flatten)]
    pub job: CalibrationResult,
    #[serde(flatten)]
    pub check: CheckDoc,
}

/// A succeeded job's `result`, by the job's kind.
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
#[serde(untagged)]
pub enum JobResult {
    /// A re-check's verdict.
    Check(CheckResult),
    /// A calibration's summary and stored set.
    Calibration(CalibrationResult),
}

impl JobResult {
    /// A stored `result` document: a re-check's when it holds a verdict
    /// (a check job on a session it cannot judge stores none), else a
    /// calibration's; a document of neither shape is an error.
    pub fn decode(doc: Value) -> Result<JobResult, serde_json::Error> {
        Ok(if doc.get(VERDICT_KEY).is_some() {
            JobResult::Check(serde_json::from_value(doc)?)
        } else {
            JobResult::Calibration(serde_json::from_value(doc)?)
        })
    }

    /// What a succeeded job writes: its summary, the set it stored and a
    /// re-check's verdict.
    pub fn new(job: CalibrationResult, check: Option<CheckDoc>) -> JobResult {
        match check {
            Some(check) => JobResult::Check(CheckResult { job, check }),
            None => JobResult::Calibration(job),
        }
    }

    /// The re-check's verdict document, `None` for a calibration.
    pub fn check(&self) -> Option<&CheckDoc> {
        match self {
            JobResult::Check(r) => Some(&r.check),
            JobResult::Calibration(_) => None,
        }
    }

    /// The summary and the stored set's version, whatever the kind.
    pub fn calibration(&self) -> &CalibrationResult {
        match self {
            JobResult::Check(r) => &r.job,
            JobResult::Calibration(r) => r,
        }
    }
}
