//! Chessboard detection (issue 14): saddle candidates on a decimated image
//! → lattice grown from a seed → OpenCV's order (colour decides the half
//! turn where it can) → every corner refined at full resolution by the
//! saddle/point-symmetry fit (`vision::saddle`).
//!
//! Only a complete board is accepted: chessboard corners carry no ids, so a
//! partial view could not be numbered without guessing. A lattice larger
//! than the spec is refused naming `inner_corners`, never cut arbitrarily.

use nalgebra::Vector2;

use super::candidates::{decimate, find_candidates, MAX_CANDIDATES_PER_CORNER};
use super::lattice::{grow, Lattice, MAX_SEEDS};
use super::orient::order;
use super::spec::ChessboardSpec;
use crate::vision::board_point::{BoardDetection, BoardPoint};
use crate::vision::error::DetectError;
use crate::vision::image::{GrayImage, GreyLevels};
use crate::vision::saddle::refine_saddle_near;

/// Candidates are searched on copies decimated to at most these long sides,
/// coarsest first (cheap: most boards are found there), then at full
/// resolution if every level fails (small squares).
pub const LEVEL_LONG_SIDES_PX: [usize; 2] = [400, 1000];
/// Largest decimation factor: a candidate's position is good to a fraction
/// of a level pixel, and the refinement must start within a pixel or two
/// of the junction (a sharp one gives its fits no slope farther out).
pub const MAX_LEVEL_FACTOR: usize = 4;
/// Smallest image side accepted, pixels.
pub const MIN_IMAGE_SIDE_PX: usize = 16;
/// Refinement half window as a fraction of the distance to the nearest
/// lattice neighbour (the window holds the four squares' edges only).
pub const REFINE_WINDOW_FRACTION: f64 = 0.4;
/// Bounds of the refinement half window, pixels. The upper one trades
/// noise against time: on blurred boards (σ 2 px, noise 3) 12 px gave a
/// corner RMS of 0.0302 px, 14 px 0.0282, 16 px 0.0276, at a cost growing
/// with the window's area (BENCHMARKS.md, "Detection").
pub const MIN_REFINE_HALF_WINDOW_PX: f64 = 2.0;
pub const MAX_REFINE_HALF_WINDOW_PX: f64 = 14.0;

/// The largest lattice grown from any seed (a complete one ends the search).
fn best_lattice(
    cands: &[super::candidates::Candidate],
    spec: &ChessboardSpec,
    smoothed: &GrayImage,
) -> Option<Lattice> {
    let mut best: Option<Lattice> = None;
    let cap = 4 * spec.corner_count();
    for k in 0..cands.len().min(MAX_SEEDS) {
        let Some(l) = grow(cands, k, cap, smoothed) else {
            continue;
        };
        let done = l.len() >= spec.corner_count();
        if best.as_ref().is_none_or(|b| l.len() > b.len()) {
            best = Some(l);
        }
        if done {
            break;
        }
    }
    best
}

/// One attempt at decimation `factor`: ordered corners in full-resolution
/// pixels (unrefined) and whether the order is unique.
fn at_level<I: GreyLevels>(
    img: &I,
    spec: &ChessboardSpec,
    factor: usize,
) -> Result<(Vec<Vector2<f64>>, bool), DetectError> {
    let level = decimate(img, factor);
    let (cands, smoothed) =
        find_candidates(&level, MAX_CANDIDATES_PER_CORNER * spec.corner_count());
    let lattice = best_lattice(&cands, spec, &smoothed).ok_or_else(|| {
        DetectError::NoBoard(format!(
            "no chessboard corner lattice found ({} saddle candidates)",
            cands.len()
        ))
    })?;
    let pos = |k: usize| cands[k].pos;
    let (grid, unique) = order(&lattice, &pos, spec, &smoothed)?;
    let f = factor as f64;
    let to_full = |p: Vector2<f64>| (p + Vector2::repeat(0.5)) * f - Vector2::repeat(0.5);
    Ok((grid.into_iter().map(to_full).collect(), unique))
}

/// Distance from corner `k` to its nearest row/column neighbour in `grid`.
fn neighbour_gap(grid: &[Vector2<f64>], spec: &ChessboardSpec, k: usize) -> f64 {
    let (cols, rows) = (spec.cols(), spec.rows());
    let (r, c) = (k / cols, k % cols);
    let mut gap = f64::INFINITY;
    if c > 0 {
        gap = gap.min((grid[k] - grid[k - 1]).norm());
    }
    if c + 1 < cols {
        gap = gap.min((grid[k] - grid[k + 1]).norm());
    }
    if r > 0 {
        gap = gap.min((grid[k] - grid[k - cols]).norm());
    }
    if r + 1 < rows {
        gap = gap.min((grid[k] - grid[k + cols]).norm());
    }
    gap
}

/// Detects the complete chessboard `spec` in `img`, corners in OpenCV's
/// order (`row * cols + col`), refined to sub-pixel. `ordering_unique` is
/// false for a board that looks the same after a half turn
/// ([`ChessboardSpec::ambiguous_180`]): the caller resolves the half turn
/// from robot data or refuses. Corners whose refinement fails are left out.
/// `img` is the decoder's 8-bit image or an f32 [`GrayImage`].
pub fn detect_chessboard<I: GreyLevels>(
    img: &I,
    spec: &ChessboardSpec,
) -> Result<BoardDetection, DetectError> {
    spec.validate()?;
    let (width, height) = (img.width(), img.height());
    if width.min(height) < MIN_IMAGE_SIDE_PX {
        return Err(DetectError::ImageTooSmall {
            width,
            height,
            min_side: MIN_IMAGE_SIDE_PX,
        });
    }
    let long = width.max(height);
    let mut factors: Vec<usize> = LEVEL_LONG_SIDES_PX
        .iter()
        .map(|&side| long.div_ceil(side).clamp(1, MAX_LEVEL_FACTOR))
        .chain([1])
        .collect();
    factors.dedup();
    let mut found = Err(DetectError::NoBoard("no decimation level tried".into()));
    for factor in factors {
        found = at_level(img, spec, factor);
        match &found {
            Ok(_) | Err(DetectError::GridMismatch(_)) => break,
            Err(_) => {}
        }
    }
    let (grid, unique) = found?;
    let points = grid
        .iter()
        .enumerate()
        .filter_map(|(k, p)| {
            let half = (REFINE_WINDOW_FRACTION * neighbour_gap(&grid, spec, k))
                .clamp(MIN_REFINE_HALF_WINDOW_PX, MAX_REFINE_HALF_WINDOW_PX);
            let [x_px, y_px] = refine_saddle_near(img, [p.x, p.y], half)?;
            let (row, col) = (k / spec.cols(), k % spec.cols());
            Some(BoardPoint {
                row,
                col,
                target_mm: spec.corner_mm(row, col),
                x_px,
                y_px,
            })
        })
        .collect();
    Ok(BoardDetection {
        image_width: width,
        image_height: height,
        points,
        ordering_unique: unique,
    })
}

#[cfg(test)]
#[path = "detect_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "real_data_tests.rs"]
mod real_data_tests;
