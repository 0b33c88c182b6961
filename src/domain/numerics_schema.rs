//! OpenAPI shapes of the numerics' types the report and parameter sets
//! carry (`robocal-calib` stays free of HTTP and documentation crates, so
//! its types are mirrored here, field for field, for the schema only).

#![allow(dead_code)] // schema types: never built, only described

use utoipa::ToSchema;

/// Summary of error magnitudes, mm.
#[derive(ToSchema)]
#[schema(as = ErrorStats)]
pub struct ErrorStatsSchema {
    pub n: usize,
    pub mean_mm: f64,
    pub median_mm: f64,
    /// Sample standard deviation (n - 1) of the magnitudes.
    pub std_mm: f64,
    pub max_mm: f64,
    pub rms_mm: f64,
}

/// 3-D position-error statistics (the `ErrorStats` fields of the error
/// norm) plus the same per axis (`|e_x|`, `|e_y|`, `|e_z|`), world frame.
#[derive(ToSchema)]
#[schema(as = AccuracySummary)]
pub struct AccuracySummarySchema {
    pub n: usize,
    pub mean_mm: f64,
    pub median_mm: f64,
    pub std_mm: f64,
    pub max_mm: f64,
    pub rms_mm: f64,
    pub x: ErrorStatsSchema,
    pub y: ErrorStatsSchema,
    pub z: ErrorStatsSchema,
}

/// Pinhole intrinsics (px) and Brown–Conrady distortion.
#[derive(ToSchema)]
#[schema(as = Intrinsics)]
pub struct IntrinsicsSchema {
    pub fx: f64,
    pub fy: f64,
    pub cx: f64,
    pub cy: f64,
    pub k1: f64,
    pub k2: f64,
    pub p1: f64,
    pub p2: f64,
    pub k3: f64,
}

/// Standard deviations of the intrinsics, same units.
#[derive(ToSchema)]
#[schema(as = IntrinsicsStd)]
pub struct IntrinsicsStdSchema {
    pub fx: f64,
    pub fy: f64,
    pub scale_ratio: f64,
    pub cx: f64,
    pub cy: f64,
    pub k1: f64,
    pub k2: f64,
    pub p1: f64,
    pub p2: f64,
    pub k3: f64,
}
