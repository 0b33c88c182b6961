//! A ChArUco board on paper ([`crate::vision::BoardDrawing`]): the black
//! squares, and each marker's black cells (border and zero bits) merged into
//! horizontal runs so a printer or rasteriser draws no seams between them.
//! Same frame as the detector's corners (OpenCV's: origin at the board's
//! outer top-left corner, x along a row, y down).

use super::layout::marker_cells;
use super::spec::CharucoSpec;
use crate::vision::drawing::{BoardDrawing, Mark};
use crate::vision::error::DetectError;

/// White around the squares, in squares (OpenCV draws boards to the edge;
/// a quiet zone keeps the outer squares off the sheet's edge).
const QUIET_SQUARES: f64 = 0.5;

impl CharucoSpec {
    /// The printable board; `InvalidTarget` for a spec that cannot be drawn.
    pub fn drawing(&self) -> Result<BoardDrawing, DetectError> {
        self.validate()?;
        let dict = self.dictionary()?;
        let s = self.square_mm;
        let mut marks = Vec::new();
        for row in 0..self.rows() {
            for col in 0..self.cols() {
                if !self.has_marker(col, row) {
                    marks.push(Mark::Rect {
                        x_mm: col as f64 * s,
                        y_mm: row as f64 * s,
                        width_mm: s,
                        height_mm: s,
                    });
                }
            }
        }
        let n = dict.marker_size;
        let cell = self.marker_mm / (n + 2) as f64;
        for m in marker_cells(self) {
            let [x0, y0] = m.corners_mm[0];
            for r in 0..n + 2 {
                let dark = |c: usize| {
                    let inner = (1..=n).contains(&r) && (1..=n).contains(&c);
                    !(inner && dict.bit(m.id, r - 1, c - 1))
                };
                let mut c = 0;
                while c < n + 2 {
                    if !dark(c) {
                        c += 1;
                        continue;
                    }
                    let start = c;
                    while c < n + 2 && dark(c) {
                        c += 1;
                    }
                    marks.push(Mark::Rect {
                        x_mm: x0 + start as f64 * cell,
                        y_mm: y0 + r as f64 * cell,
                        width_mm: (c - start) as f64 * cell,
                        height_mm: cell,
                    });
                }
            }
        }
        let mut drawing = BoardDrawing::around(marks, QUIET_SQUARES * s);
        // The quiet zone is measured from the squares, not the marks.
        drawing.min_mm = [-QUIET_SQUARES * s, -QUIET_SQUARES * s];
        drawing.size_mm = [
            (self.cols() as f64 + 2.0 * QUIET_SQUARES) * s,
            (self.rows() as f64 + 2.0 * QUIET_SQUARES) * s,
        ];
        Ok(drawing)
    }
}
