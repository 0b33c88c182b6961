//! Where every marker and inner corner of a ChArUco board sits, in OpenCV's
//! conventions (issue 14): origin at the board's outer top-left corner, x
//! along a row, y down the columns, z = 0 on the board (as in
//! `CharucoBoard.getObjPoints` / `getChessboardCorners`).
//!
//! Marker ids count the marker squares row by row from 0; a marker's
//! corners run top-left, top-right, bottom-right, bottom-left. Inner corner
//! `(row, col)` (0-based) has OpenCV id `row * (cols - 1) + col` and sits at
//! `((col + 1) square, (row + 1) square, 0)`.

use super::spec::CharucoSpec;

/// One marker of the board.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MarkerCell {
    pub id: usize,
    /// Square the marker sits in.
    pub col: usize,
    pub row: usize,
    /// Corners in the target frame, mm (TL, TR, BR, BL).
    pub corners_mm: [[f64; 2]; 4],
}

/// Every marker, in id order.
pub fn marker_cells(spec: &CharucoSpec) -> Vec<MarkerCell> {
    let (s, m) = (spec.square_mm, spec.marker_mm);
    let inset = 0.5 * (s - m);
    let mut out = Vec::with_capacity(spec.marker_count());
    for row in 0..spec.rows() {
        for col in 0..spec.cols() {
            if !spec.has_marker(col, row) {
                continue;
            }
            let (x0, y0) = (col as f64 * s + inset, row as f64 * s + inset);
            out.push(MarkerCell {
                id: out.len(),
                col,
                row,
                corners_mm: [[x0, y0], [x0 + m, y0], [x0 + m, y0 + m], [x0, y0 + m]],
            });
        }
    }
    out
}

/// Inner corners per row and per column: `(cols - 1, rows - 1)`.
pub fn inner_corner_grid(spec: &CharucoSpec) -> (usize, usize) {
    (spec.cols() - 1, spec.rows() - 1)
}

/// Inner corner `(row, col)` in the target frame, mm.
pub fn corner_mm(spec: &CharucoSpec, row: usize, col: usize) -> [f64; 3] {
    [
        (col + 1) as f64 * spec.square_mm,
        (row + 1) as f64 * spec.square_mm,
        0.0,
    ]
}

/// Squares touching inner corner `(row, col)`: `(col, row)` of the four.
pub fn squares_around_corner(row: usize, col: usize) -> [(usize, usize); 4] {
    [
        (col, row),
        (col + 1, row),
        (col, row + 1),
        (col + 1, row + 1),
    ]
}

#[cfg(test)]
#[path = "layout_tests.rs"]
mod tests;
