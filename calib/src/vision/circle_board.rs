//! The circle boards the dot detector reads (issue 14): robocal's symmetric
//! grid (with or without its origin marker) and OpenCV's asymmetric grid,
//! seen as one thing: dots on the sites of a square lattice.
//!
//! The lattice grower (`grid.rs`) finds dots as integer sites `(i, j)` of a
//! square lattice; each board says which lattice site `(a, b)` each of its
//! dots occupies, with `a` and `b` turning like the board's +x and +y (so a
//! board seen unmirrored keeps its handedness in lattice coordinates).
//! Symmetric grid: `(a, b) = (col, row)`. Asymmetric grid: the dots are the
//! lattice `(x, y)` (pitch units) with `x + y` even, a square lattice turned
//! by 45°: `a = (x + y) / 2`, `b = (y - x) / 2`.

use std::collections::HashMap;

use super::asymmetric::AsymmetricCirclesSpec;
use super::error::DetectError;
use super::target::TargetSpec;

/// A board of circular dots.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CircleBoard {
    /// Symmetric grid, origin marker optional.
    Dots(TargetSpec),
    /// OpenCV's asymmetric grid.
    Asymmetric(AsymmetricCirclesSpec),
}

impl CircleBoard {
    pub fn rows(&self) -> usize {
        match self {
            CircleBoard::Dots(t) => t.rows,
            CircleBoard::Asymmetric(t) => t.rows,
        }
    }

    pub fn cols(&self) -> usize {
        match self {
            CircleBoard::Dots(t) => t.cols,
            CircleBoard::Asymmetric(t) => t.cols,
        }
    }

    pub fn dot_count(&self) -> usize {
        self.rows() * self.cols()
    }

    pub fn validate(&self) -> Result<(), DetectError> {
        match self {
            CircleBoard::Dots(t) => t.validate(),
            CircleBoard::Asymmetric(t) => t.validate(),
        }
    }

    /// Centre of dot `(row, col)`, target frame, mm.
    pub fn dot_centre_mm(&self, row: usize, col: usize) -> [f64; 3] {
        match self {
            CircleBoard::Dots(t) => t.dot_centre_mm(row, col),
            CircleBoard::Asymmetric(t) => t.dot_centre_mm(row, col),
        }
    }

    /// Diameter of an ordinary dot, mm.
    pub fn dot_diameter_mm(&self) -> f64 {
        match self {
            CircleBoard::Dots(t) => t.dot_diameter_mm,
            CircleBoard::Asymmetric(t) => t.dot_diameter_mm,
        }
    }

    /// Diameter of dot `(row, col)`, mm (the origin marker is larger).
    pub fn dot_diameter_at_mm(&self, row: usize, col: usize) -> f64 {
        match self {
            CircleBoard::Dots(t) => t.dot_diameter_at_mm(row, col),
            CircleBoard::Asymmetric(t) => t.dot_diameter_mm,
        }
    }

    /// Diameter of the origin marker (dot `(0, 0)`), if the board has one.
    pub fn marker_diameter_mm(&self) -> Option<f64> {
        match self {
            CircleBoard::Dots(t) => t.origin_marker_diameter_mm,
            CircleBoard::Asymmetric(_) => None,
        }
    }

    /// Lattice site `(a, b)` of dot `(row, col)`.
    pub fn site(&self, row: usize, col: usize) -> (i32, i32) {
        match self {
            CircleBoard::Dots(_) => (col as i32, row as i32),
            CircleBoard::Asymmetric(_) => {
                let (x, y) = ((2 * col + row % 2) as i32, row as i32);
                ((x + y) / 2, (y - x) / 2)
            }
        }
    }

    /// Distance between neighbouring lattice sites, mm.
    pub fn site_step_mm(&self) -> f64 {
        match self {
            CircleBoard::Dots(t) => t.pitch_mm,
            CircleBoard::Asymmetric(t) => t.pitch_mm * std::f64::consts::SQRT_2,
        }
    }

    /// Every dot by its lattice site.
    pub fn sites(&self) -> HashMap<(i32, i32), (usize, usize)> {
        let mut out = HashMap::with_capacity(self.dot_count());
        for row in 0..self.rows() {
            for col in 0..self.cols() {
                out.insert(self.site(row, col), (row, col));
            }
        }
        out
    }

    /// The dot a turn of the board by `quarter_turns` x 90° (about its
    /// centre, +x towards +y) puts where dot `(row, col)` was, if the turn
    /// maps the board onto itself; `None` otherwise. A detection whose
    /// ordering is ambiguous lists the turns that give other valid readings
    /// (`Detection::equivalent_turns`): apply this to read it another way.
    pub fn turned(&self, quarter_turns: u8, row: usize, col: usize) -> Option<(usize, usize)> {
        let sites = self.sites();
        let turn = SiteTurn::of_board(&sites, quarter_turns)?;
        sites.get(&turn.apply(self.site(row, col))).copied()
    }
}

/// A rotation of lattice sites by quarter turns about a (half-)integer
/// centre, kept in doubled coordinates to stay integral.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SiteTurn {
    quarter_turns: u8,
    /// Twice the centre of rotation.
    centre2: (i32, i32),
}

impl SiteTurn {
    /// The turn about the centre of the board's site bounding box, if it
    /// maps every site onto a site.
    pub(crate) fn of_board(
        sites: &HashMap<(i32, i32), (usize, usize)>,
        quarter_turns: u8,
    ) -> Option<Self> {
        let mut e = (i32::MAX, i32::MIN, i32::MAX, i32::MIN);
        for &(a, b) in sites.keys() {
            e = (e.0.min(a), e.1.max(a), e.2.min(b), e.3.max(b));
        }
        let turn = SiteTurn {
            quarter_turns: quarter_turns % 4,
            centre2: (e.0 + e.1, e.2 + e.3),
        };
        sites
            .keys()
            .all(|&s| sites.contains_key(&turn.apply(s)))
            .then_some(turn)
    }

    pub(crate) fn apply(&self, (a, b): (i32, i32)) -> (i32, i32) {
        let (cx, cy) = self.centre2;
        let (mut x, mut y) = (2 * a - cx, 2 * b - cy);
        for _ in 0..self.quarter_turns {
            (x, y) = (-y, x);
        }
        ((x + cx) / 2, (y + cy) / 2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn asymmetric_sites_are_a_square_lattice_with_the_boards_handedness() {
        let b = CircleBoard::Asymmetric(AsymmetricCirclesSpec::opencv_4x11());
        let sites = b.sites();
        assert_eq!(sites.len(), 44);
        // Nearest neighbours of dot (1, 0) at (1, 1) in pitch units: rows 0
        // and 2, columns 0 and 1, one lattice step away each.
        let s = b.site(1, 0);
        for (r, c) in [(0, 0), (0, 1), (2, 0), (2, 1)] {
            let t = b.site(r, c);
            assert_eq!((t.0 - s.0).abs() + (t.1 - s.1).abs(), 1, "({r}, {c})");
        }
        // +a is +x+y, +b is -x+y: same turning sense as (x, y).
        assert_eq!(b.site(0, 1), (1, -1));
    }

    #[test]
    fn board_symmetries_are_found_only_where_they_exist() {
        let mut t = TargetSpec::robocal_9x9();
        t.origin_marker_diameter_mm = None;
        let square = CircleBoard::Dots(t);
        assert_eq!(square.turned(1, 0, 0), Some((0, 8)));
        assert_eq!(square.turned(2, 0, 0), Some((8, 8)));
        t.cols = 7;
        let oblong = CircleBoard::Dots(t);
        assert_eq!(oblong.turned(1, 0, 0), None);
        assert_eq!(oblong.turned(2, 0, 1), Some((8, 5)));
        let odd = CircleBoard::Asymmetric(AsymmetricCirclesSpec::opencv_4x11());
        assert_eq!(odd.turned(2, 0, 0), None);
        let mut even = AsymmetricCirclesSpec::opencv_4x11();
        even.rows = 10;
        assert_eq!(CircleBoard::Asymmetric(even).turned(2, 0, 0), Some((9, 3)));
    }
}
