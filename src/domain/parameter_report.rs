//! One row of a parameter set and its report: an identified parameter
//! against its nominal value (or guess), with its standard deviation.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// One identified parameter against its nominal value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct ParameterReport {
    /// E.g. "joint2.a_mm", "joint3.beta_deg", "target_to_base.tx_mm".
    pub name: String,
    pub unit: String,
    pub nominal: f64,
    pub identified: f64,
    pub std: f64,
    /// Held fixed as unidentifiable (redundant with another parameter).
    pub fixed: bool,
}
