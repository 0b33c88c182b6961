//! Description of a printed chessboard (issue 14) as OpenCV's
//! `findChessboardCorners(patternSize = (cols, rows))` sees it: only the
//! inner corners count, `cols` corners per row.

use serde::{Deserialize, Serialize};

use crate::vision::error::DetectError;

/// Fewest inner corners per side (a corner needs a 2x2 block of squares;
/// a lattice needs two corners per side).
pub const MIN_INNER_CORNERS: usize = 2;
/// Most inner corners per side: protects every allocation.
pub const MAX_INNER_CORNERS: usize = 200;
/// Largest square side, mm (a 10 m square is no calibration board).
pub const MAX_SQUARE_MM: f64 = 10_000.0;

/// A chessboard with `inner_corners[0] x inner_corners[1]` (cols x rows)
/// inner corners and squares of `square_mm`.
///
/// Corner `(row, col)` sits at `(col * square_mm, row * square_mm, 0)` in the
/// target frame (OpenCV's usual object points): x along a row, y to the next
/// row, z into the board (away from a camera that sees it).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChessboardSpec {
    /// Inner corners along x (per row) and along y (per column).
    pub inner_corners: [usize; 2],
    /// Side of a square.
    pub square_mm: f64,
}

impl ChessboardSpec {
    /// Inner corners per row.
    pub fn cols(&self) -> usize {
        self.inner_corners[0]
    }

    /// Rows of inner corners.
    pub fn rows(&self) -> usize {
        self.inner_corners[1]
    }

    /// Number of inner corners.
    pub fn corner_count(&self) -> usize {
        self.cols() * self.rows()
    }

    /// Whether a half turn of the board maps its pattern onto itself (both
    /// sides even or both odd): images then fix the corner order only up
    /// to a 180° rotation, which robot data must resolve.
    pub fn ambiguous_180(&self) -> bool {
        (self.cols() + self.rows()).is_multiple_of(2)
    }

    /// Target-frame position of corner `(row, col)`, mm.
    pub fn corner_mm(&self, row: usize, col: usize) -> [f64; 3] {
        [
            col as f64 * self.square_mm,
            row as f64 * self.square_mm,
            0.0,
        ]
    }

    /// Checks that the board can be printed and detected; the message starts
    /// with the offending field (issue 14 "Bad input").
    pub fn validate(&self) -> Result<(), DetectError> {
        let bad = |why: String| Err(DetectError::InvalidTarget(why));
        for &n in &self.inner_corners {
            if !(MIN_INNER_CORNERS..=MAX_INNER_CORNERS).contains(&n) {
                return bad(format!(
                    "inner_corners: each side must be {MIN_INNER_CORNERS} to {MAX_INNER_CORNERS}, got {:?}",
                    self.inner_corners
                ));
            }
        }
        if self.cols() == self.rows() && self.cols() % 2 == 1 {
            return bad(format!(
                "inner_corners: a square board with an odd side ({:?}) looks the same after a quarter turn, so no corner order can be fixed; use a board with different sides",
                self.inner_corners
            ));
        }
        if !(self.square_mm.is_finite() && self.square_mm > 0.0 && self.square_mm <= MAX_SQUARE_MM)
        {
            return bad(format!(
                "square_mm: must be above 0 and at most {MAX_SQUARE_MM} mm, got {}",
                self.square_mm
            ));
        }
        Ok(())
    }

    /// Whether the square whose top-left corner is inner corner `(row, col)`
    /// is black (`row`, `col` may be -1: the outer squares). The outer
    /// top-left square is black, as OpenCV's `findChessboardCorners` assumes
    /// when it starts its order at a black corner square.
    pub fn square_is_black(row: isize, col: isize) -> bool {
        (row + col).rem_euclid(2) == 0
    }
}
