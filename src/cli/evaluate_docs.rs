//! The documents `robocal forward`, `compensate` and `filter` exchange with
//! the service: the request bodies they build (from flags, a table or a
//! JSON file) and the fields of the answers their tables print. They
//! mirror the contract's shapes (api.md); the server checks the values.

use serde::{Deserialize, Serialize};

use crate::schema::PoseDoc;

/// A pose row: x, y, z (mm), rx, ry, rz (deg, fixed-axis X-Y-Z).
pub const POSE_WIDTH: usize = 6;

/// The pose of a row of [`POSE_WIDTH`] numbers; `what` names the row in
/// the error.
pub fn pose_doc(row: &[f64], what: &str) -> Result<PoseDoc, String> {
    match row {
        &[x, y, z, rx, ry, rz] => Ok(PoseDoc {
            translation_mm: [x, y, z],
            rotation_deg: [rx, ry, rz],
            matrix: None,
        }),
        _ => Err(format!(
            "{what} has {POSE_WIDTH} numbers (x,y,z mm, rx,ry,rz deg), not {}",
            row.len()
        )),
    }
}

/// `POST …/forward`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForwardBody {
    #[serde(default)]
    pub joints_deg: Vec<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tool: Option<PoseDoc>,
}

/// One seed for all targets, or one per target.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Seeds {
    One(Vec<f64>),
    PerTarget(Vec<Vec<f64>>),
}

/// `POST …/compensate`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompensateBody {
    #[serde(default)]
    pub targets: Vec<PoseDoc>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tool: Option<PoseDoc>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed_joints_deg: Option<Seeds>,
}

/// `POST …/filter`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FilterBody {
    pub targets: Vec<PoseDoc>,
    pub tool: PoseDoc,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seed_joints_deg: Option<Vec<f64>>,
}

/// A pose as answered; a number the server could not give is `null`.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
pub struct PoseNumbers {
    #[serde(default)]
    pub translation_mm: Vec<Option<f64>>,
    #[serde(default)]
    pub rotation_deg: Vec<Option<f64>>,
}

/// One row of the `forward` answer.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
pub struct ForwardRow {
    pub camera_in_target: Option<PoseNumbers>,
    pub tool_in_target: Option<PoseNumbers>,
    /// A joint outside its limits, …
    #[serde(default)]
    pub warnings: Vec<String>,
}

/// The `forward` answer.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
pub struct ForwardAnswer {
    #[serde(default)]
    pub poses: Vec<ForwardRow>,
}

/// The `compensate` answer: per target, `null` where `errors` names it.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
pub struct CompensateAnswer {
    #[serde(default)]
    pub joints_deg: Vec<Option<Vec<Option<f64>>>>,
    #[serde(default)]
    pub residual_mm: Vec<Option<f64>>,
    #[serde(default)]
    pub errors: Vec<TargetError>,
}

/// A target the server could not filter.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct TargetError {
    pub index: usize,
    pub message: String,
}

/// The message of the error `errors` names `index` with, if any.
pub fn error_of(errors: &[TargetError], index: usize) -> Option<String> {
    errors
        .iter()
        .find(|e| e.index == index)
        .map(|e| e.message.clone())
}

/// One line of a streamed `filter` answer: the target's answer, or `error`.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
pub struct FilterLine {
    pub index: usize,
    pub nominal_target: Option<PoseNumbers>,
    pub joints_deg: Option<Vec<Option<f64>>>,
    pub residual_mm: Option<f64>,
    pub error: Option<String>,
}

/// One line of a streamed `compensate` answer.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
pub struct CompensateLine {
    pub index: usize,
    pub joints_deg: Option<Vec<Option<f64>>>,
    pub residual_mm: Option<f64>,
    pub error: Option<String>,
}

/// The `filter` answer: per target, `null` where `errors` names it.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
pub struct FilterAnswer {
    #[serde(default)]
    pub nominal_targets: Vec<Option<PoseNumbers>>,
    #[serde(default)]
    pub joints_deg: Vec<Option<Vec<Option<f64>>>>,
    #[serde(default)]
    pub residual_mm: Vec<Option<f64>>,
    #[serde(default)]
    pub errors: Vec<TargetError>,
}
