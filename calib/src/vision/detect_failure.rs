//! Why the circle-board detector read no board: the clearest error from
//! the lattices it grew and the candidates it dropped (dots too small or
//! too blurred, more dots than the board, an ordering error, a board
//! running off the image).

use nalgebra::Vector2;

use super::circle_board::CircleBoard;
use super::dot_candidates::{CandidateSet, MAX_CANDIDATES, MIN_DOT_AREA_PX, SIZE_RATIO_SLACK};
use super::error::DetectError;
use super::grid::{grow_lattices, Candidates, Lattice};
use super::image::GrayImage;

/// An incomplete lattice of dots below this area is reported as too small.
pub const SMALL_DOT_AREA_PX: f64 = 30.0;
/// Fraction of a lattice step beyond the next dot that must still be inside
/// the image for that dot to count as visible.
const EDGE_FIT_FRACTION: f64 = 0.5;

/// Whether the lattice continues past its border outside the image.
fn runs_off_image(lat: &Lattice, c: &[Vector2<f64>], w: usize, h: usize) -> bool {
    let inside = |p: Vector2<f64>| p.x >= 0.0 && p.y >= 0.0 && p.x < w as f64 && p.y < h as f64;
    lat.nodes.iter().any(|(&(i, j), &k)| {
        [(1, 0), (-1, 0), (0, 1), (0, -1)].iter().any(|&(di, dj)| {
            let beyond = (i + di, j + dj);
            let back = (i - di, j - dj);
            match (lat.nodes.get(&beyond), lat.nodes.get(&back)) {
                (None, Some(&kb)) => {
                    let step = c[k] - c[kb];
                    // The next dot would not fit with its half-pitch surround.
                    !inside(c[k] + step * (1.0 + EDGE_FIT_FRACTION))
                }
                _ => false,
            }
        })
    })
}

/// Median area of a lattice of at least half the board's dots among
/// rejected blobs, if there is one (the board is there but unusable).
fn rejected_lattice(rejected: &[(Vector2<f64>, f64)], n_dots: usize) -> Option<f64> {
    if rejected.len() < n_dots / 2 || rejected.len() > MAX_CANDIDATES {
        return None;
    }
    let centres: Vec<Vector2<f64>> = rejected.iter().map(|r| r.0).collect();
    let areas: Vec<f64> = rejected.iter().map(|r| r.1).collect();
    let cand = Candidates {
        centres: &centres,
        sizes: &areas,
        max_size_ratio: SIZE_RATIO_SLACK * 2.0,
    };
    let best = grow_lattices(&cand).into_iter().next()?;
    if best.nodes.len() < n_dots / 2 {
        return None;
    }
    let mut a: Vec<f64> = best.nodes.values().map(|&k| areas[k]).collect();
    a.sort_by(f64::total_cmp);
    Some(a[a.len() / 2])
}

/// The clearest error when no board was read: the first lattice's
/// ordering error if there was one, else what the candidates show.
pub(super) fn explain_failure(
    lattices: &[Lattice],
    set: &CandidateSet,
    centres: &[Vector2<f64>],
    img: &GrayImage,
    board: &CircleBoard,
    ordering_error: Option<DetectError>,
) -> DetectError {
    let n_dots = board.dot_count();
    let Some(best) = lattices.first() else {
        if let Some(median_area_px) = rejected_lattice(&set.too_small, n_dots) {
            return DetectError::DotsTooSmall {
                median_area_px,
                min_area_px: MIN_DOT_AREA_PX,
            };
        }
        if let Some(area) = rejected_lattice(&set.unsharp, n_dots) {
            return DetectError::DotsTooBlurred(format!(
                "a lattice of dots (median area {area:.0} px) has too little contrast or ragged edges"
            ));
        }
        return DetectError::NoBoard(format!("no lattice among {} dot candidates", centres.len()));
    };
    let (ni, nj) = best.shape();
    let (rows, cols) = (board.rows(), board.cols());
    if best.nodes.len() > n_dots {
        return DetectError::GridMismatch(format!(
            "found a lattice of {} dots ({ni}x{nj}), more than the {rows}x{cols} target (clutter in line with the board?)",
            best.nodes.len()
        ));
    }
    let mut areas: Vec<f64> = best.nodes.values().map(|&k| set.blobs[k].area).collect();
    areas.sort_by(f64::total_cmp);
    let median_area_px = areas[areas.len() / 2];
    if median_area_px < SMALL_DOT_AREA_PX && best.nodes.len() < n_dots {
        return DetectError::DotsTooSmall {
            median_area_px,
            min_area_px: SMALL_DOT_AREA_PX,
        };
    }
    if let Some(e) = ordering_error {
        return e;
    }
    if runs_off_image(best, centres, img.width, img.height) {
        return DetectError::BoardPartlyOutside {
            found_rows: ni.min(nj),
            found_cols: ni.max(nj),
            rows,
            cols,
        };
    }
    DetectError::NoBoard(format!(
        "best lattice has {} dots in a {ni}x{nj} box, target is {rows}x{cols} (dots occluded or unreadable?)",
        best.nodes.len(),
    ))
}
