//! What a job gives back: the parameter set with its report, a summary and
//! every pose's image points; or why it stopped.

use crate::domain::{CalibratedSet, Release};
use crate::report::Report;
use crate::schema::FieldError;
use crate::store::{NewParameterSet, PoseDetection};

/// The set a job identified with its report and the gate's decision, as
/// the store takes them; a report that does not serialise fails the
/// report stage instead of storing `null`.
pub fn new_set(
    parameters: CalibratedSet,
    report: &Report,
    release: Release,
) -> Result<NewParameterSet, PipelineError> {
    let report = serde_json::to_value(report)
        .map_err(|e| PipelineError::numerical(super::Stage::Report, format!("report: {e}")))?;
    Ok(NewParameterSet {
        parameters,
        report,
        release,
    })
}

#[derive(Debug, Clone)]
pub struct Output {
    /// The identified parameter set and its accuracy report, when the job
    /// identified one (stored as the serial's next version).
    pub parameter_set: Option<NewParameterSet>,
    /// A short summary for the job's `result`.
    pub summary: Summary,
    /// Every camera pose's image points with their reprojection residuals
    /// (empty for tracker sessions and validation-only runs).
    pub detections: Vec<PoseDetection>,
    /// A quick re-check's verdict: the job's `result` then
    /// holds its fields.
    pub check: Option<crate::domain::CheckDoc>,
}

/// The job's `result.summary` (the domain's [`JobSummary`]).
pub use crate::domain::JobSummary as Summary;

#[derive(Debug, Clone, thiserror::Error)]
pub enum PipelineError {
    /// The session's data cannot be calibrated as it is: not retried.
    #[error("invalid input: {}", describe(.0))]
    Invalid(Vec<FieldError>),
    /// A numerical stage failed (degenerate data): not retried.
    #[error("{stage}: {message}")]
    Numerical {
        stage: &'static str,
        message: String,
    },
    #[error("cancelled")]
    Cancelled,
}

impl PipelineError {
    /// The session's data is wrong in `field`.
    pub fn invalid(field: &str, message: impl Into<String>) -> PipelineError {
        PipelineError::Invalid(vec![FieldError::new(field, message.into())])
    }

    /// `stage` failed on degenerate data.
    pub fn numerical(stage: super::Stage, message: impl std::fmt::Display) -> PipelineError {
        PipelineError::Numerical {
            stage: stage.as_str(),
            message: message.to_string(),
        }
    }
}

fn describe(errors: &[FieldError]) -> String {
    errors
        .iter()
        .map(|e| format!("{}: {}", e.field, e.message))
        .collect::<Vec<_>>()
        .join("; ")
}
