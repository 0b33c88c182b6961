//! One pose's image points as a calibration job measured them, the
//! document stored on the pose row and served by
//! `GET /v1/sessions/{id}/poses/{pose_id}` (api.md "Measurement sessions"):
//! typed from the pipeline to the store, so a job of a thousand poses holds
//! its points as numbers, not as JSON trees (issue 12: memory flat).

use serde::Serialize;

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeasuredPoint {
    pub row: u32,
    pub col: u32,
    /// The centre the fits use: after a successful camera stage corrected
    /// for perspective bias, else as detected (or uploaded).
    pub x: f64,
    pub y: f64,
    /// The raw centre, as detected or uploaded, when `x`, `y` are corrected.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub raw_x: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub raw_y: Option<f64>,
    /// `[dx, dy]`, observed minus predicted (px); absent for points the
    /// fits leave out (the origin marker).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub residual_px: Option<[f64; 2]>,
    /// Dropped by the camera stage as an outlier.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub outlier: bool,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeasuredPose {
    /// `"image"` (detected) or `"image_points"` (as uploaded).
    pub source: &'static str,
    pub points: Vec<MeasuredPoint>,
    /// Why no point was detected on this pose's image.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// RMS length of the residuals of this pose (px).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub residual_rms_px: Option<f64>,
    /// The job that measured these points (set when the job stores them).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub job_id: Option<String>,
}
