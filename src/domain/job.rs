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
// One per job, moved a few times: a box would buy nothing measurable.
#[allow(clippy::large_enum_variant)]
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

#[cfg(test)]
mod tests {
    use serde_json::json;

    use super::*;

    /// A calibration's result reads back as one; a re-check's (it holds a
    /// verdict) as a check with its fields at the top level, as served.
    #[test]
    fn a_stored_result_reads_as_its_kind() {
        let calibration = JobResult::new(
            CalibrationResult {
                summary: JobSummary {
                    calibration_poses: 4,
                    ..JobSummary::default()
                },
                serial: Some("R1".into()),
                version: Some(2),
                status: Some(ReleaseStatus::Candidate),
                status_reason: Some("worse".into()),
            },
            None,
        );
        let doc = serde_json::to_value(&calibration).unwrap();
        assert_eq!(doc["status"], "candidate");
        assert_eq!(doc["summary"]["calibration_poses"], 4);
        assert_eq!(JobResult::decode(doc).unwrap(), calibration);
        let check = json!({"summary": {"calibration_poses": 0, "validation_poses": 5},
            "verdict": "drift", "mean_mm": 0.2, "expected_mean_mm": 0.1, "p_value": 0.001,
            "base_p_value": 0.002, "chi2": 40.0, "dof": 15, "significance": 0.01,
            "test": "chi-square", "checked_against": "R1/1", "checked_version": 1,
            "joint_noise_deg": 0.001, "poses": 5, "suspects": []});
        let read = JobResult::decode(check.clone()).unwrap();
        assert_eq!(
            read.check().map(|c| c.verdict),
            Some(super::super::CheckVerdict::Drift)
        );
        assert_eq!(read.calibration().summary.validation_poses, 5);
        assert_eq!(serde_json::to_value(&read).unwrap(), check);
    }

    /// A verdict document of the wrong shape is an error, not a
    /// calibration result without a verdict.
    #[test]
    fn a_broken_check_result_is_an_error() {
        let broken = json!({"summary": {}, "verdict": "maybe"});
        assert!(JobResult::decode(broken).is_err());
    }

    #[test]
    fn kinds_parse_their_names() {
        for kind in JobKind::ALL {
            assert_eq!(JobKind::parse(kind.as_str()), Some(kind));
            assert_eq!(serde_json::to_value(kind).unwrap(), kind.as_str());
        }
        assert_eq!(JobKind::parse("plan"), None);
    }
}
