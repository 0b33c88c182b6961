//! One image point as uploaded: a dot's board index and its position.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// A dot's board index and its image position in pixels.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct ImagePointDoc {
    pub row: u32,
    pub col: u32,
    pub x: f64,
    pub y: f64,
}
