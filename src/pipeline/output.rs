//! What a job gives back: the parameter set with its report, a summary and
//! every pose's image points; or why it stopped.

use crate::domain::{NewParameterSet, PoseDetection};
use crate::schema::FieldError;

#[derive(Debug, Clone)]
pub struct Output {
    /// The identified parameter set and its accuracy report, when the job
    /// identified one (stored as the serial's next version).
    pub parameter_set: Option<NewParameterSet>,
    /// A short summary for the job's `result`.
    pub summary: serde_json::Value,
    /// Every camera pose's image points with their reprojection residuals
    /// (empty for tracker sessions and validation-only runs).
    pub detections: Vec<PoseDetection>,
}

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

fn describe(errors: &[FieldError]) -> String {
    errors
        .iter()
        .map(|e| format!("{}: {}", e.field, e.message))
        .collect::<Vec<_>>()
        .join("; ")
}
