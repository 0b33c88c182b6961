//! The set a pose belongs to: calibration (`cal`, the fit uses it) or
//! validation (`val`, only judged), as uploaded and as stored.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum PoseSet {
    #[default]
    Cal,
    Val,
}

impl PoseSet {
    pub fn as_str(self) -> &'static str {
        match self {
            PoseSet::Cal => "cal",
            PoseSet::Val => "val",
        }
    }
    pub fn parse(s: &str) -> Option<PoseSet> {
        match s {
            "cal" => Some(PoseSet::Cal),
            "val" => Some(PoseSet::Val),
            _ => None,
        }
    }
}
