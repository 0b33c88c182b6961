//! A chessboard on paper ([`crate::vision::BoardDrawing`]): its black
//! squares, outer top-left one black (the colour convention the detector
//! orders by), in the detector's target frame (corner `(row, col)` at
//! `(col, row) * square_mm`).

use super::spec::ChessboardSpec;
use crate::vision::drawing::{BoardDrawing, Mark};
use crate::vision::error::DetectError;

/// White around the squares, in squares: detectors (OpenCV's too) need a
/// light border around the outer squares.
const QUIET_SQUARES: f64 = 1.0;

impl ChessboardSpec {
    /// The printable board; `InvalidTarget` for a spec that cannot be drawn.
    pub fn drawing(&self) -> Result<BoardDrawing, DetectError> {
        self.validate()?;
        let s = self.square_mm;
        let mut marks = Vec::new();
        for row in -1..self.rows() as isize {
            for col in -1..self.cols() as isize {
                if Self::square_is_black(row, col) {
                    marks.push(Mark::Rect {
                        x_mm: col as f64 * s,
                        y_mm: row as f64 * s,
                        width_mm: s,
                        height_mm: s,
                    });
                }
            }
        }
        let quiet = QUIET_SQUARES * s;
        let mut drawing = BoardDrawing::around(marks, quiet);
        // The quiet zone is measured from the squares, not the black marks.
        drawing.min_mm = [-s - quiet, -s - quiet];
        drawing.size_mm = [
            (self.cols() + 1) as f64 * s + 2.0 * quiet,
            (self.rows() + 1) as f64 * s + 2.0 * quiet,
        ];
        Ok(drawing)
    }
}
