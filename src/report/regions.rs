//! The regions of a multi-session set (issue 18; the paper's section 5,
//! Figs 7, 9 and 10): each session is one board placement, a region of the
//! workspace with an optional volume; its validation error before and
//! after, and, where the robot had a local (one-session) set of that
//! session when the job ran, that local model's error on the same poses.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

use super::schema::AccuracySummarySchema;
use super::AccuracySummary;

/// One session's (region's) accuracy on its own validation poses.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct RegionReport {
    pub session_id: String,
    /// The session's `region` (free text), when it named one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub region: Option<String>,
    /// The session's `volume` (free text), when it named one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub volume: Option<String>,
    /// The nominal model, its frames fitted on this session's poses.
    #[schema(value_type = AccuracySummarySchema)]
    pub before: AccuracySummary,
    /// The multi-session (global) model with this session's board.
    #[schema(value_type = AccuracySummarySchema)]
    pub after: AccuracySummary,
    /// The newest local set of this session when the job ran: its own
    /// report's validation figures (the same poses), for the side by side.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub local: Option<LocalModel>,
}

/// A local (one-session) set's figures in its region.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct LocalModel {
    /// The local set's version.
    pub version: i64,
    #[schema(value_type = AccuracySummarySchema)]
    pub after: AccuracySummary,
}

impl RegionReport {
    /// Global against local mean error in this region (`None` without a
    /// local set): above 1 the local model is better here.
    pub fn global_over_local(&self) -> Option<f64> {
        let local = self.local.as_ref()?.after.norm.mean_mm;
        (local > 0.0).then(|| self.after.norm.mean_mm / local)
    }
}
