//! The REST contract's request documents (`docs/api.md`) as typed
//! values, and their validation. Shared by the HTTP layer (parsing) and the
//! job workers (reading stored documents back); no I/O here.

use serde::Serialize;
use utoipa::ToSchema;

pub mod campaign_plan;
pub mod flange_pose;
mod frame_pose;
pub mod job;
pub mod nul;
pub mod pose_body;
pub mod robot;
pub mod session;
pub mod webhook;

pub use frame_pose::PoseOut;

/// One validation failure, naming the field by its JSON path (`kinematics.joints[1].a_mm`).
#[derive(Debug, Clone, PartialEq, Serialize, ToSchema)]
pub struct FieldError {
    pub field: String,
    pub message: String,
}

impl FieldError {
    pub fn new(field: impl Into<String>, message: impl Into<String>) -> FieldError {
        FieldError {
            field: field.into(),
            message: message.into(),
        }
    }
}

/// Collects field errors while a document is checked.
#[derive(Debug, Default)]
pub struct Checker {
    pub errors: Vec<FieldError>,
}

impl Checker {
    pub fn fail(&mut self, field: impl Into<String>, message: impl Into<String>) {
        self.errors.push(FieldError::new(field, message));
    }

    /// A finite number within `[-bound, bound]`.
    pub fn bounded(&mut self, field: impl Into<String>, value: f64, bound: f64, unit: &str) {
        if !value.is_finite() || value.abs() > bound {
            self.fail(
                field,
                format!("must be a finite number within ±{bound} {unit}"),
            );
        }
    }

    /// A finite number within `(0, max]`.
    pub fn positive(&mut self, field: impl Into<String>, value: f64, max: f64, unit: &str) {
        if !value.is_finite() || value <= 0.0 || value > max {
            self.fail(field, format!("must be positive and at most {max} {unit}"));
        }
    }

    pub fn finish(self) -> Result<(), Vec<FieldError>> {
        if self.errors.is_empty() {
            Ok(())
        } else {
            Err(self.errors)
        }
    }
}

/// Largest length accepted anywhere, millimetres (a 100 m robot is not a robot).
pub const MAX_LENGTH_MM: f64 = 100_000.0;
/// Largest angle accepted anywhere, degrees.
pub const MAX_ANGLE_DEG: f64 = 720.0;

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

/// The schema of an optional 4x4 row-major matrix: four rows of four
/// numbers (serde reads fixed-size arrays, any other length is refused).
fn matrix4_schema() -> utoipa::openapi::schema::Array {
    use utoipa::openapi::schema::{ArrayBuilder, ObjectBuilder, SchemaType, Type};
    const SIDE: usize = 4;
    let row = ArrayBuilder::new()
        .items(ObjectBuilder::new().schema_type(Type::Number))
        .min_items(Some(SIDE))
        .max_items(Some(SIDE));
    ArrayBuilder::new()
        .schema_type(SchemaType::from_iter([Type::Array, Type::Null]))
        .items(row)
        .min_items(Some(SIDE))
        .max_items(Some(SIDE))
        .description(Some("4x4 row-major homogeneous matrix (optional)"))
        .build()
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
