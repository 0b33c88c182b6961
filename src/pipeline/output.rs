//! What a job gives back: the parameter set with its report, a summary and
//! every pose's image points; or why it stopped.

use serde::Serialize;

use crate::schema::FieldError;
use crate::store::{NewParameterSet, PoseDetection};

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

/// The job's `result.summary`: the poses it used and, after a calibration,
/// the mean validation error before and after.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Summary {
    /// The stage a validation-only run stopped after (`validate`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stage: Option<&'static str>,
    pub calibration_poses: usize,
    pub validation_poses: usize,
    /// The robot's joint count (validation-only runs).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joints: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub before_mean_mm: Option<f64>,
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
