//! Readings of a dot lattice (`order.rs`): a reading maps lattice sites
//! onto board sites by one of the square lattice's eight linear symmetries
//! and a shift; this file holds that algebra, the test of one reading
//! against the found dots, the marker and the holes, and the errors a view
//! with no (or too many) surviving readings gives.

use std::collections::HashMap;

use super::circle_board::CircleBoard;
use super::error::DetectError;
use super::grid::Lattice;
use super::site_prediction::Predictor;

/// The square lattice's linear symmetries `(m00, m01, m10, m11)`: four
/// turns (det +1), then four mirrors (det -1).
pub(super) const LINEAR: [[i32; 4]; 8] = [
    [1, 0, 0, 1],
    [0, -1, 1, 0],
    [-1, 0, 0, -1],
    [0, 1, -1, 0],
    [1, 0, 0, -1],
    [-1, 0, 0, 1],
    [0, 1, 1, 0],
    [0, -1, -1, 0],
];

/// A reading: board site = `m * lattice site + t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Reading {
    pub m: [i32; 4],
    pub t: (i32, i32),
}

pub(super) fn mul(m: [i32; 4], (i, j): (i32, i32)) -> (i32, i32) {
    (m[0] * i + m[1] * j, m[2] * i + m[3] * j)
}

pub(super) fn det(m: [i32; 4]) -> i32 {
    m[0] * m[3] - m[1] * m[2]
}

/// Inverse of a unimodular integer matrix.
pub(super) fn inverse(m: [i32; 4]) -> [i32; 4] {
    let d = det(m);
    [d * m[3], -d * m[1], -d * m[2], d * m[0]]
}

pub(super) fn compose(a: [i32; 4], b: [i32; 4]) -> [i32; 4] {
    [
        a[0] * b[0] + a[1] * b[2],
        a[0] * b[1] + a[1] * b[3],
        a[2] * b[0] + a[3] * b[2],
        a[2] * b[1] + a[3] * b[3],
    ]
}

impl Reading {
    pub(super) fn board(&self, ij: (i32, i32)) -> (i32, i32) {
        let (a, b) = mul(self.m, ij);
        (a + self.t.0, b + self.t.1)
    }

    pub(super) fn lattice(&self, ab: (i32, i32)) -> (i32, i32) {
        mul(inverse(self.m), (ab.0 - self.t.0, ab.1 - self.t.1))
    }
}

/// Why a reading was refused, most telling first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Refusal {
    /// A found dot falls off the board.
    OffBoard,
    /// The enlarged dot is not where the marker goes, or the marker site
    /// holds an ordinary dot.
    Marker,
    /// The marker would be well inside the image but is not there.
    MarkerMissing,
    /// Too many dots missing inside the image.
    Holes,
}

/// Checks one reading against the found dots, the marker and the holes.
#[allow(clippy::too_many_arguments)]
pub(super) fn check(
    r: &Reading,
    lattice_sites: &[(i32, i32)],
    sites: &HashMap<(i32, i32), (usize, usize)>,
    frontier: &[(i32, i32)],
    big: &[(i32, i32)],
    marker: Option<((i32, i32), f64, f64)>,
    predictor: &mut Predictor,
    board: &CircleBoard,
    max_holes: usize,
) -> Result<(), Refusal> {
    if lattice_sites
        .iter()
        .any(|&s| !sites.contains_key(&r.board(s)))
    {
        return Err(Refusal::OffBoard);
    }
    if let Some((origin, _, scale)) = marker {
        let at = r.lattice(origin);
        match (predictor.lat.nodes.contains_key(&at), big.first()) {
            // The enlarged dot (found, or seen unrefined) is the marker.
            (_, Some(&b)) if b == at => {}
            (true, _) | (false, Some(_)) => return Err(Refusal::Marker),
            (false, None) => {
                if predictor.visible(at, scale) {
                    return Err(Refusal::MarkerMissing);
                }
            }
        }
    }
    let mut holes = 0;
    for &s in frontier.iter().filter(|s| !big.contains(s)) {
        let ab = r.board(s);
        if let Some(&(row, col)) = sites.get(&ab) {
            let scale = board.dot_diameter_at_mm(row, col) / board.dot_diameter_mm();
            if predictor.visible(s, scale) {
                holes += 1;
                if holes > max_holes {
                    return Err(Refusal::Holes);
                }
            }
        }
    }
    Ok(())
}

/// Several placements of a partial view fit: the board runs off the image
/// (or is occluded) where its edges or marker would have fixed the place.
pub(super) fn placement_ambiguous(n: usize, lat: &Lattice, board: &CircleBoard) -> DetectError {
    if lat.nodes.len() < board.dot_count() {
        let (ni, nj) = lat.shape();
        return DetectError::BoardPartlyOutside {
            found_rows: ni.min(nj),
            found_cols: ni.max(nj),
            rows: board.rows(),
            cols: board.cols(),
        };
    }
    DetectError::OrderingAmbiguous(format!(
        "{n} placements of the dots on the board fit the image"
    ))
}

pub(super) fn refusal_error(
    why: Option<Refusal>,
    lat: &Lattice,
    board: &CircleBoard,
) -> DetectError {
    let (ni, nj) = lat.shape();
    let (rows, cols) = (board.rows(), board.cols());
    match why {
        None | Some(Refusal::OffBoard) => DetectError::GridMismatch(format!(
            "a lattice of {} dots ({ni}x{nj}) does not fit the {rows}x{cols} board with its handedness (wrong rows/cols, clutter in line with the board, or a mirrored image?)",
            lat.nodes.len()
        )),
        Some(Refusal::Marker) => DetectError::MarkerNotFound(
            "no reading puts the origin marker on the one enlarged dot (marker diameter wrong?)".into(),
        ),
        Some(Refusal::MarkerMissing) => DetectError::MarkerNotFound(
            "the origin marker would be inside the image but no enlarged dot is there".into(),
        ),
        Some(Refusal::Holes) => {
            if lat.nodes.len() == board.dot_count() {
                DetectError::NoBoard("the lattice has holes".into())
            } else {
                DetectError::BoardPartlyOutside {
                    found_rows: ni.min(nj),
                    found_cols: ni.max(nj),
                    rows,
                    cols,
                }
            }
        }
    }
}
