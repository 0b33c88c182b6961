//! The report section of a stage session's set (issue 18, paper section 4):
//! the measurement system's own accuracy per sequence, as the paper's
//! Table 1 (mean, median, standard deviation per axis of the 3-D position
//! error by the average-rotation method) with its maximum, the travelled
//! distance checked against the stage, and the distance Fig. 5 plots them
//! against. Beside it the stage-referenced table: the average-rotation
//! method cannot see an image's depth noise, the stage can (calib
//! `stage::assessment`).

use robocal_calib::stage::assessment::AxisTable;
use robocal_calib::stage::SequenceAccuracy;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct MeasurementAccuracyReport {
    /// One row per sequence, ascending.
    pub sequences: Vec<SequenceAccuracyReport>,
}

/// Table 1's row of one sequence.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct SequenceAccuracyReport {
    pub sequence: u32,
    /// Mean distance from the camera to the board's centre (mm).
    pub distance_mm: f64,
    pub images: usize,
    /// Per target axis `[x, y, z]`: statistics of the absolute position
    /// error (mm) by the average-rotation method.
    pub mean_mm: [f64; 3],
    pub median_mm: [f64; 3],
    pub std_mm: [f64; 3],
    pub max_mm: [f64; 3],
    /// Largest 3-D position error of the sequence (mm).
    pub max_3d_mm: f64,
    /// Over every pair of the sequence's images: measured travel minus
    /// the stage's (absolute, mm).
    pub travelled_distance_error_mm: TravelErrorReport,
    /// The same statistics of each image's position against the stage's
    /// readings fitted rigidly to the sequence (per axis, absolute, mm):
    /// unlike the average-rotation figures they hold depth noise. Neither
    /// sees an offset common to the whole sequence. Absent in reports
    /// made before it existed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stage_referenced_mm: Option<AxisStatsReport>,
    /// σ per target axis (mm) of the offset common to every image of the
    /// sequence, propagated from the dots' errors through the intrinsics
    /// and each image's pose fit: the part of the error neither table
    /// sees. Absent in reports made before it existed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub offset_sd_mm: Option<[f64; 3]>,
}

/// Per target axis `[x, y, z]` (mm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct AxisStatsReport {
    pub mean: [f64; 3],
    pub median: [f64; 3],
    pub std: [f64; 3],
    pub max: [f64; 3],
}

impl From<&AxisTable> for AxisStatsReport {
    fn from(t: &AxisTable) -> Self {
        Self {
            mean: t.mean_mm,
            median: t.median_mm,
            std: t.std_mm,
            max: t.max_mm,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, ToSchema)]
pub struct TravelErrorReport {
    pub mean: f64,
    pub max: f64,
}

impl From<&SequenceAccuracy> for SequenceAccuracyReport {
    fn from(a: &SequenceAccuracy) -> Self {
        Self {
            sequence: a.sequence,
            distance_mm: a.distance_mm,
            images: a.images,
            mean_mm: a.mean_mm,
            median_mm: a.median_mm,
            std_mm: a.std_mm,
            max_mm: a.max_mm,
            max_3d_mm: a.max_3d_mm,
            travelled_distance_error_mm: TravelErrorReport {
                mean: a.travelled_distance_error_mm.mean_mm,
                max: a.travelled_distance_error_mm.max_mm,
            },
            stage_referenced_mm: Some(AxisStatsReport::from(&a.stage_referenced)),
            offset_sd_mm: Some(a.offset_sd_mm),
        }
    }
}
