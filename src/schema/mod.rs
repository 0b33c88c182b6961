//! The REST contract's request documents (`docs/api.md`) as typed
//! values, and their validation. Shared by the HTTP layer (parsing) and the
//! job workers (reading stored documents back); no I/O here.

use serde::Serialize;
use utoipa::ToSchema;

pub mod campaign_plan;
/// The controller's flange pose document (its type lives in the domain).
pub mod flange_pose {
    pub use crate::domain::FlangePoseDoc;
}
pub mod job;
pub mod nul;
pub mod pose_body;
pub mod robot;
pub mod session;
pub mod webhook;

pub use crate::domain::{Checker, FieldError, PoseOut, MAX_ANGLE_DEG, MAX_LENGTH_MM};

/// A pose in the contract form: translation in mm, fixed-axis X-Y-Z angles in
/// degrees (`R = Rz(rz) Ry(ry) Rx(rx)`), optionally a 4x4 row-major matrix.
#[derive(Debug, Clone, PartialEq, serde::Deserialize, Serialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct PoseDoc {
    #[schema(min_items = 3, max_items = 3)]
    pub translation_mm: [f64; 3],
    #[schema(min_items = 3, max_items = 3)]
    pub rotation_deg: [f64; 3],
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schema(schema_with = matrix4_schema)]
    pub matrix: Option<[[f64; 4]; 4]>,
}

/// The schema of an optional 4x4 row-major homogeneous matrix.
fn matrix4_schema() -> utoipa::openapi::schema::Array {
    crate::domain::flange_pose_doc::optional_matrix_schema(
        4,
        "4x4 row-major homogeneous matrix (optional)",
    )
}

impl PoseDoc {
    pub fn check(&self, c: &mut Checker, field: &str) {
        for (i, v) in self.translation_mm.iter().enumerate() {
            c.bounded(
                format!("{field}.translation_mm[{i}]"),
                *v,
                MAX_LENGTH_MM,
                "mm",
            );
        }
        for (i, v) in self.rotation_deg.iter().enumerate() {
            c.bounded(
                format!("{field}.rotation_deg[{i}]"),
                *v,
                MAX_ANGLE_DEG,
                "deg",
            );
        }
        if let Some(m) = &self.matrix {
            if m.iter()
                .flatten()
                .any(|v| !v.is_finite() || v.abs() > MAX_LENGTH_MM)
            {
                c.fail(
                    format!("{field}.matrix"),
                    "entries must be finite and bounded",
                );
            }
        }
    }
}
