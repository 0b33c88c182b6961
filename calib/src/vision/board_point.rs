//! One output shape for every target kind (dots, chessboard, ChArUco,
//! asymmetric circles): an identified feature of the board, where it sits on
//! the board and where it was found in the image.
//!
//! Each detector keeps its own richer diagnostics; the camera and kinematic
//! stages (method.md §2–§4) need only `target_mm` ↔ `(x_px, y_px)` pairs with
//! a stable identity, which is what this type carries.

use serde::{Deserialize, Serialize};

/// One identified board feature (dot centre or chessboard corner).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BoardPoint {
    /// Row of the feature in the board's own indexing (corner or dot row).
    pub row: usize,
    /// Column of the feature in the board's own indexing.
    pub col: usize,
    /// Feature position in the target frame, millimetres (z = 0 on the board).
    pub target_mm: [f64; 3],
    /// Sub-pixel image position, pixels, pixel-centre convention
    /// (the centre of the top-left pixel is (0, 0)), after any bias correction.
    pub x_px: f64,
    pub y_px: f64,
}

/// Every feature found in one image, with how far its ordering can be trusted.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BoardDetection {
    pub image_width: usize,
    pub image_height: usize,
    pub points: Vec<BoardPoint>,
    /// False when the board's symmetry leaves the ordering known only up to a
    /// rotation of the board (a 180°-symmetric chessboard, a marker-less dot
    /// grid); the caller must resolve it (e.g. from robot data) or refuse.
    pub ordering_unique: bool,
}
