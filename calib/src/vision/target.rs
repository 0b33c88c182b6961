//! Description of the printed dot-grid board (method.md §1).
//!
//! Target frame: dot `(row, col)` sits at `(col * pitch, row * pitch, 0)` mm;
//! the origin dot `(0, 0)` may be printed larger (the origin marker) so that
//! the ordering is unique under any camera roll.

use serde::{Deserialize, Serialize};

use super::error::DetectError;

/// Largest grid side accepted: protects every later allocation.
pub const MAX_GRID_SIDE: usize = 200;

/// A flat board of `rows x cols` dark circular dots on a light background.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TargetSpec {
    /// Dots along a column (target +y direction).
    pub rows: usize,
    /// Dots along a row (target +x direction).
    pub cols: usize,
    /// Centre-to-centre spacing in x and y.
    pub pitch_mm: f64,
    /// Diameter of an ordinary dot.
    pub dot_diameter_mm: f64,
    /// Diameter of the larger origin dot `(0, 0)`; `None` for boards without
    /// a marker (ordering is then known only up to the grid's symmetry).
    pub origin_marker_diameter_mm: Option<f64>,
}

impl TargetSpec {
    /// The robocal production board: 9x9 dots of 8 mm on a 25 mm pitch with a
    /// 12 mm origin marker.
    pub fn robocal_9x9() -> Self {
        Self {
            rows: 9,
            cols: 9,
            pitch_mm: 25.0,
            dot_diameter_mm: 8.0,
            origin_marker_diameter_mm: Some(12.0),
        }
    }

    /// Checks that the description is physically meaningful.
    pub fn validate(&self) -> Result<(), DetectError> {
        let bad = |why: &str| Err(DetectError::InvalidTarget(why.to_string()));
        if self.rows < 2 || self.cols < 2 {
            return bad("rows and cols must be at least 2");
        }
        if self.rows > MAX_GRID_SIDE || self.cols > MAX_GRID_SIDE {
            return bad("rows and cols must be at most 200");
        }
        if !(self.pitch_mm.is_finite() && self.pitch_mm > 0.0) {
            return bad("pitch_mm must be positive");
        }
        if !(self.dot_diameter_mm.is_finite()
            && self.dot_diameter_mm > 0.0
            && self.dot_diameter_mm < self.pitch_mm)
        {
            return bad("dot_diameter_mm must be positive and below pitch_mm");
        }
        if let Some(m) = self.origin_marker_diameter_mm {
            if !(m.is_finite()
                && m > self.dot_diameter_mm
                && m < 2.0 * self.pitch_mm - self.dot_diameter_mm)
            {
                return bad("origin_marker_diameter_mm must exceed dot_diameter_mm and not touch neighbours");
            }
        }
        Ok(())
    }

    /// Number of dots on the board.
    pub fn dot_count(&self) -> usize {
        self.rows * self.cols
    }

    /// Centre of dot `(row, col)` in the target frame, mm (method.md §1).
    pub fn dot_centre_mm(&self, row: usize, col: usize) -> [f64; 3] {
        [col as f64 * self.pitch_mm, row as f64 * self.pitch_mm, 0.0]
    }

    /// Diameter of dot `(row, col)`, mm: the origin marker is larger.
    pub fn dot_diameter_at_mm(&self, row: usize, col: usize) -> f64 {
        match self.origin_marker_diameter_mm {
            Some(m) if row == 0 && col == 0 => m,
            _ => self.dot_diameter_mm,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn production_board_is_valid_and_marker_is_origin() {
        let t = TargetSpec::robocal_9x9();
        t.validate().unwrap();
        assert_eq!(t.dot_centre_mm(2, 3), [75.0, 50.0, 0.0]);
        assert_eq!(t.dot_diameter_at_mm(0, 0), 12.0);
        assert_eq!(t.dot_diameter_at_mm(0, 1), 8.0);
    }

    #[test]
    fn degenerate_targets_are_rejected() {
        let mut t = TargetSpec::robocal_9x9();
        t.rows = 1;
        assert!(t.validate().is_err());
        let mut t = TargetSpec::robocal_9x9();
        t.dot_diameter_mm = 30.0;
        assert!(t.validate().is_err());
        let mut t = TargetSpec::robocal_9x9();
        t.origin_marker_diameter_mm = Some(5.0);
        assert!(t.validate().is_err());
        let mut t = TargetSpec::robocal_9x9();
        t.pitch_mm = f64::NAN;
        assert!(t.validate().is_err());
    }
}
