//! What a board looks like on paper: filled dark shapes in the target frame,
//! millimetres. A printer (SVG, PDF) or a rasteriser draws these exactly; the
//! detectors' target coordinates (`target_mm` of a [`super::BoardPoint`]) are
//! in the same frame, so a printed page and the numbers agree by construction.
//!
//! Axes: x to the right along a row, y down along a column (the target frame
//! of method.md §1 seen from the camera side, as on the page).

use serde::{Deserialize, Serialize};

use super::asymmetric::AsymmetricCirclesSpec;
use super::target::TargetSpec;

/// One filled dark shape, target frame, mm.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Mark {
    /// Axis-aligned rectangle with its top-left corner at `(x_mm, y_mm)`.
    Rect {
        x_mm: f64,
        y_mm: f64,
        width_mm: f64,
        height_mm: f64,
    },
    /// Disc of diameter `diameter_mm` centred at `(cx_mm, cy_mm)`.
    Disc {
        cx_mm: f64,
        cy_mm: f64,
        diameter_mm: f64,
    },
}

/// The whole printable board: its white extent (quiet zone included) and
/// the dark marks on it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BoardDrawing {
    /// Top-left corner of the white board area in the target frame, mm.
    pub min_mm: [f64; 2],
    /// Size of the white board area, mm.
    pub size_mm: [f64; 2],
    pub marks: Vec<Mark>,
}

impl BoardDrawing {
    /// Smallest drawing that holds `marks` with `quiet_mm` of white around.
    pub fn around(marks: Vec<Mark>, quiet_mm: f64) -> Self {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for m in &marks {
            let (a, b) = m.extent_mm();
            for k in 0..2 {
                lo[k] = lo[k].min(a[k]);
                hi[k] = hi[k].max(b[k]);
            }
        }
        if marks.is_empty() {
            lo = [0.0; 2];
            hi = [0.0; 2];
        }
        Self {
            min_mm: [lo[0] - quiet_mm, lo[1] - quiet_mm],
            size_mm: [
                hi[0] - lo[0] + 2.0 * quiet_mm,
                hi[1] - lo[1] + 2.0 * quiet_mm,
            ],
            marks,
        }
    }
}

impl Mark {
    /// Top-left and bottom-right corners of the mark's bounding box, mm.
    pub fn extent_mm(&self) -> ([f64; 2], [f64; 2]) {
        match *self {
            Mark::Rect {
                x_mm,
                y_mm,
                width_mm,
                height_mm,
            } => ([x_mm, y_mm], [x_mm + width_mm, y_mm + height_mm]),
            Mark::Disc {
                cx_mm,
                cy_mm,
                diameter_mm,
            } => {
                let r = diameter_mm / 2.0;
                ([cx_mm - r, cy_mm - r], [cx_mm + r, cy_mm + r])
            }
        }
    }

    /// Whether the point `(x_mm, y_mm)` is dark (inside the mark).
    pub fn covers(&self, x_mm: f64, y_mm: f64) -> bool {
        match *self {
            Mark::Rect { .. } => {
                let (a, b) = self.extent_mm();
                x_mm >= a[0] && x_mm < b[0] && y_mm >= a[1] && y_mm < b[1]
            }
            Mark::Disc {
                cx_mm,
                cy_mm,
                diameter_mm,
            } => (x_mm - cx_mm).hypot(y_mm - cy_mm) <= diameter_mm / 2.0,
        }
    }
}

impl TargetSpec {
    /// The dot board on paper: every dot (the origin marker larger) with one
    /// pitch of white around the grid, so the outer dots' ellipses stay clear
    /// of the sheet's edge.
    pub fn drawing(&self) -> BoardDrawing {
        let marks = (0..self.rows)
            .flat_map(|row| (0..self.cols).map(move |col| (row, col)))
            .map(|(row, col)| {
                let [cx_mm, cy_mm, _] = self.dot_centre_mm(row, col);
                Mark::Disc {
                    cx_mm,
                    cy_mm,
                    diameter_mm: self.dot_diameter_at_mm(row, col),
                }
            })
            .collect();
        BoardDrawing::around(marks, self.pitch_mm - self.dot_diameter_mm / 2.0)
    }
}

impl AsymmetricCirclesSpec {
    /// The asymmetric grid on paper as OpenCV lays it out, with one
    /// in-row spacing (`2 * pitch_mm`) less a dot radius of white around.
    pub fn drawing(&self) -> BoardDrawing {
        let marks = (0..self.rows)
            .flat_map(|row| (0..self.cols).map(move |col| (row, col)))
            .map(|(row, col)| {
                let [cx_mm, cy_mm, _] = self.dot_centre_mm(row, col);
                Mark::Disc {
                    cx_mm,
                    cy_mm,
                    diameter_mm: self.dot_diameter_mm,
                }
            })
            .collect();
        BoardDrawing::around(marks, 2.0 * self.pitch_mm - self.dot_diameter_mm / 2.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dot_board_drawing_has_every_dot_at_its_target_coordinates() {
        let t = TargetSpec::robocal_9x9();
        let d = t.drawing();
        assert_eq!(d.marks.len(), 81);
        // 21 mm of white (pitch - dot radius) beyond the outer dots' edges:
        // the 12 mm origin marker reaches -6 mm, the far dots 204 mm.
        assert!((d.min_mm[0] + 27.0).abs() < 1e-9 && (d.min_mm[1] + 27.0).abs() < 1e-9);
        assert!((d.size_mm[0] - 252.0).abs() < 1e-9);
        assert!(d.marks[0].covers(0.0, 0.0) && d.marks[0].covers(5.9, 0.0));
        assert!(!d.marks[1].covers(25.0 + 4.1, 0.0));
        assert!(d.marks[80].covers(200.0, 200.0));
    }
}
