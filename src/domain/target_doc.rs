//! The board a camera session names, as the contract writes it; its
//! checked, typed form is [`super::Target`].

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// Most dots per board side.
pub const MAX_GRID_SIDE: u32 = 1000;

/// What board the camera sees: robocal's dot grid (`kind`
/// `"dots"`, the default, may be omitted), a ChArUco board, a chessboard
/// or OpenCV's asymmetric circle grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum TargetKind {
    #[default]
    Dots,
    Charuco,
    Chessboard,
    AsymmetricCircles,
}

impl TargetKind {
    fn is_dots(&self) -> bool {
        *self == TargetKind::Dots
    }
}

/// The board. Dots: `rows`, `cols`, `pitch_mm`, `dot_diameter_mm`,
/// `origin_marker_diameter_mm` (omitted for a grid without the larger
/// origin dot: its ordering is then known only up to the grid's symmetry).
/// Asymmetric circles (OpenCV's `CALIB_CB_ASYMMETRIC_GRID`, found by
/// `findCirclesGrid(image, (cols, rows))`): `rows`, `cols` (dots per row),
/// `pitch_mm` (OpenCV's `squareSize`: dot `(i, j)` at
/// `((2 j + i mod 2) pitch, i pitch)`, so dots in a row are `2 pitch`
/// apart), `dot_diameter_mm`. ChArUco (OpenCV's `CharucoBoard`):
/// `squares` `[cols, rows]`, `square_mm`, `marker_mm`, `dictionary` (an
/// OpenCV predefined dictionary name, e.g. `DICT_5X5_100`) and
/// `legacy_layout` (boards made by OpenCV < 4.6; default false).
/// Chessboard (OpenCV's `findChessboardCorners`): `inner_corners`
/// `[cols, rows]` and `square_mm`; corners in OpenCV's order. A field of
/// another kind is refused.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TargetDoc {
    #[serde(default, skip_serializing_if = "TargetKind::is_dots")]
    pub kind: TargetKind,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rows: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cols: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pitch_mm: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dot_diameter_mm: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub origin_marker_diameter_mm: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub squares: Option<[u32; 2]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub square_mm: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub marker_mm: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dictionary: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub legacy_layout: Option<bool>,
    /// Chessboard: inner corners `[cols, rows]` (`cols` per row), as
    /// OpenCV's `patternSize`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inner_corners: Option<[u32; 2]>,
}
