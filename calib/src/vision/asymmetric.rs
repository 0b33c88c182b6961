//! Description of an asymmetric circle grid (issue 14) in OpenCV's
//! convention: the board `cv2.findCirclesGrid(image, (cols, rows),
//! flags=cv2.CALIB_CB_ASYMMETRIC_GRID)` finds and OpenCV's
//! `gen_pattern.py -T acircles` prints.
//!
//! Dot `(row, col)` (row `i` of `rows`, `j` of `cols` dots per row) sits at
//! `((2 j + i mod 2) * pitch, i * pitch, 0)` mm, as in OpenCV's calibration
//! sample (`calcBoardCornerPositions`, `ASYMMETRIC_CIRCLES_GRID`): rows are
//! `pitch` apart, dots within a row `2 * pitch` apart, odd rows shifted by
//! `pitch`. `pitch_mm` is therefore OpenCV's `squareSize`, half the spacing
//! of the dots within a row. The standard OpenCV sheet is 11 rows of 4.
//!
//! The dots form a square lattice turned by 45° (nearest neighbours
//! `pitch * sqrt 2` apart, diagonally). With an odd number of rows the
//! layout has no symmetry that a camera can produce (turns in the plane), so
//! every view is ordered uniquely; with an even number it is symmetric under
//! a half turn, and detections report that ambiguity.

use serde::{Deserialize, Serialize};

use super::error::DetectError;
use super::target::MAX_GRID_SIDE;

/// An asymmetric grid of `rows` rows of `cols` dark dots on a light board.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AsymmetricCirclesSpec {
    /// Rows of dots (OpenCV `patternSize.height`), `pitch_mm` apart in +y.
    pub rows: usize,
    /// Dots per row (OpenCV `patternSize.width`), `2 * pitch_mm` apart in +x.
    pub cols: usize,
    /// Row spacing = half the in-row spacing (OpenCV's `squareSize`).
    pub pitch_mm: f64,
    /// Diameter of every dot.
    pub dot_diameter_mm: f64,
}

impl AsymmetricCirclesSpec {
    /// OpenCV's sample sheet `acircles_pattern.png`: 11 rows of 4 dots;
    /// here on a 20 mm pitch with 14 mm dots (the sheet's proportions).
    pub fn opencv_4x11() -> Self {
        Self {
            rows: 11,
            cols: 4,
            pitch_mm: 20.0,
            dot_diameter_mm: 14.0,
        }
    }

    /// Checks that the board can be printed and detected; the message names
    /// the offending field first (`field: why`).
    pub fn validate(&self) -> Result<(), DetectError> {
        let bad = |why: String| Err(DetectError::InvalidTarget(why));
        for (name, v) in [("rows", self.rows), ("cols", self.cols)] {
            if !(2..=MAX_GRID_SIDE).contains(&v) {
                return bad(format!("{name}: must be 2 to {MAX_GRID_SIDE}, got {v}"));
            }
        }
        if !(self.pitch_mm.is_finite() && self.pitch_mm > 0.0) {
            return bad(format!("pitch_mm: must be positive, got {}", self.pitch_mm));
        }
        // Nearest neighbours are pitch * sqrt(2) apart (diagonal).
        let spacing = self.pitch_mm * std::f64::consts::SQRT_2;
        if !(self.dot_diameter_mm.is_finite()
            && self.dot_diameter_mm > 0.0
            && self.dot_diameter_mm < spacing)
        {
            return bad(format!(
                "dot_diameter_mm: must be positive and below pitch_mm * sqrt(2) = {spacing:.3} (neighbouring dots would touch), got {}",
                self.dot_diameter_mm
            ));
        }
        Ok(())
    }

    /// Number of dots on the board.
    pub fn dot_count(&self) -> usize {
        self.rows * self.cols
    }

    /// Centre of dot `(row, col)` in the target frame, mm (OpenCV's layout).
    pub fn dot_centre_mm(&self, row: usize, col: usize) -> [f64; 3] {
        [
            (2 * col + row % 2) as f64 * self.pitch_mm,
            row as f64 * self.pitch_mm,
            0.0,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_is_opencvs_and_bad_specs_name_the_field() {
        let t = AsymmetricCirclesSpec::opencv_4x11();
        t.validate().unwrap();
        assert_eq!(t.dot_centre_mm(0, 1), [40.0, 0.0, 0.0]);
        assert_eq!(t.dot_centre_mm(1, 0), [20.0, 20.0, 0.0]);
        assert_eq!(t.dot_centre_mm(3, 2), [100.0, 60.0, 0.0]);
        let mut b = t;
        b.dot_diameter_mm = 30.0;
        let e = b.validate().unwrap_err().to_string();
        assert!(e.contains("dot_diameter_mm:"), "{e}");
        let mut b = t;
        b.rows = 1;
        assert!(b.validate().unwrap_err().to_string().contains("rows:"));
        let mut b = t;
        b.pitch_mm = -1.0;
        assert!(b.validate().unwrap_err().to_string().contains("pitch_mm:"));
    }
}
