//! Field errors: a check of a document (a request body, a stored row, a
//! domain value) collects every failure, each naming its field by its JSON
//! path, and the HTTP edge answers them as one problem (api.md
//! "Conventions"); with the bounds every check shares.

use serde::Serialize;
use utoipa::ToSchema;

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
