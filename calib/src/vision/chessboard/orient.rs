//! From a grown lattice to OpenCV's corner order.
//!
//! The lattice fixes the corners up to the board's symmetries: it is first
//! cut to a window of exactly `cols x rows` (or `rows x cols`) cells, made
//! right-handed in the image (x along a row, y to the next row, so the
//! board's z points away from the camera, as OpenCV's object points), and
//! then the half turn is decided by the squares' colours: the outer
//! top-left square is black, so the square between corners `(r, c)` and
//! `(r + 1, c + 1)` is black when `r + c` is even. A half turn changes that
//! parity only when `cols + rows` is odd; otherwise the order is known up to
//! a half turn and the detection says so (`ordering_unique: false`).

use nalgebra::Vector2;

use super::candidates::bilinear;
use super::lattice::Lattice;
use super::spec::ChessboardSpec;
use crate::vision::error::DetectError;
use crate::vision::image::GrayImage;

/// The squares' mean grey levels must separate the two colours by at least
/// this much (8-bit scale) for the colour to decide the half turn.
const MIN_COLOUR_CONTRAST: f64 = 5.0;

/// Corner positions in OpenCV order (row-major, `cols` per row), level coordinates.
pub type Ordered = Vec<Vector2<f64>>;

/// The single fully filled `ni x nj` window of the lattice (origin cell), if exactly one.
fn full_window(lattice: &Lattice, ni: i32, nj: i32) -> Result<Option<(i32, i32)>, ()> {
    let (imin, imax) = lattice
        .keys()
        .fold((i32::MAX, i32::MIN), |(a, b), k| (a.min(k.0), b.max(k.0)));
    let (jmin, jmax) = lattice
        .keys()
        .fold((i32::MAX, i32::MIN), |(a, b), k| (a.min(k.1), b.max(k.1)));
    let mut found = None;
    for i0 in imin..=imax - ni + 1 {
        for j0 in jmin..=jmax - nj + 1 {
            let full = (0..ni).all(|a| (0..nj).all(|b| lattice.contains_key(&(i0 + a, j0 + b))));
            if full {
                if found.is_some() {
                    return Err(());
                }
                found = Some((i0, j0));
            }
        }
    }
    Ok(found)
}

fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Mean grey level difference (white minus black squares) when corner
/// `(r, c)` of `grid` is read with OpenCV's colour convention.
fn colour_score(grid: &[Vector2<f64>], spec: &ChessboardSpec, smoothed: &GrayImage) -> f64 {
    let (cols, rows) = (spec.cols(), spec.rows());
    let (mut white, mut black, mut nw, mut nb) = (0.0, 0.0, 0usize, 0usize);
    for r in 0..rows - 1 {
        for c in 0..cols - 1 {
            let centre = (grid[r * cols + c]
                + grid[r * cols + c + 1]
                + grid[(r + 1) * cols + c]
                + grid[(r + 1) * cols + c + 1])
                * 0.25;
            let Some(g) = bilinear(smoothed, centre.x, centre.y) else {
                continue;
            };
            if ChessboardSpec::square_is_black(r as isize, c as isize) {
                black += g as f64;
                nb += 1;
            } else {
                white += g as f64;
                nw += 1;
            }
        }
    }
    if nw == 0 || nb == 0 {
        return 0.0;
    }
    white / nw as f64 - black / nb as f64
}

/// Orders the lattice's corners as OpenCV does; the flag says whether the
/// order is unique (false: known up to a half turn).
pub fn order(
    lattice: &Lattice,
    pos: &dyn Fn(usize) -> Vector2<f64>,
    spec: &ChessboardSpec,
    smoothed: &GrayImage,
) -> Result<(Ordered, bool), DetectError> {
    let (cols, rows) = (spec.cols() as i32, spec.rows() as i32);
    let mismatch = || {
        DetectError::GridMismatch(format!(
            "inner_corners: the corner lattice seen is larger than {cols} x {rows}; check target.inner_corners"
        ))
    };
    // Window along the lattice's first index = cols (a) or rows (b).
    let a = full_window(lattice, cols, rows).map_err(|_| mismatch())?;
    let b = if cols == rows {
        None
    } else {
        full_window(lattice, rows, cols).map_err(|_| mismatch())?
    };
    let (transposed, (i0, j0)) = match (a, b) {
        (Some(o), None) => (false, o),
        (None, Some(o)) => (true, o),
        (Some(_), Some(_)) => return Err(mismatch()),
        (None, None) => {
            return Err(DetectError::NoBoard(format!(
                "{} of the {cols} x {rows} inner corners found in one lattice; a chessboard has no ids, so a partial view is refused",
                lattice.len()
            )))
        }
    };
    let (ni, nj) = if transposed {
        (rows, cols)
    } else {
        (cols, rows)
    };
    let at = |i: i32, j: i32| pos(lattice[&(i0 + i, j0 + j)]);
    // Mean steps along the lattice's two indices.
    let di =
        (at(ni - 1, 0) - at(0, 0) + at(ni - 1, nj - 1) - at(0, nj - 1)) / (2.0 * (ni - 1) as f64);
    let dj =
        (at(0, nj - 1) - at(0, 0) + at(ni - 1, nj - 1) - at(ni - 1, 0)) / (2.0 * (nj - 1) as f64);
    let mirrored = cross(di, dj) < 0.0;
    // (col, row) → lattice (i, j), right-handed, before the half turn.
    let cell = |c: i32, r: i32| -> (i32, i32) {
        let (i, j) = if transposed { (ni - 1 - r, c) } else { (c, r) };
        // Transposing by (c, r) → (ni-1-r, c) keeps the handedness; a
        // mirrored lattice is made right-handed by reversing j.
        if mirrored {
            if transposed {
                (r, c)
            } else {
                (i, nj - 1 - j)
            }
        } else {
            (i, j)
        }
    };
    let grid: Vec<Vector2<f64>> = (0..rows)
        .flat_map(|r| (0..cols).map(move |c| (c, r)))
        .map(|(c, r)| {
            let (i, j) = cell(c, r);
            at(i, j)
        })
        .collect();
    let turned: Vec<Vector2<f64>> = grid.iter().rev().copied().collect();
    if spec.ambiguous_180() {
        // Colour cannot tell; keep the order whose rows run rightwards in
        // the image (ties: downwards), so neighbouring poses agree.
        let step = grid[1] - grid[0];
        let keep = step.x > 0.0 || (step.x == 0.0 && step.y > 0.0);
        return Ok((if keep { grid } else { turned }, false));
    }
    let score = colour_score(&grid, spec, smoothed);
    if score.abs() < MIN_COLOUR_CONTRAST {
        return Err(DetectError::NoBoard(format!(
            "the squares' colours cannot be told apart (contrast {score:.1})"
        )));
    }
    Ok((if score > 0.0 { grid } else { turned }, true))
}
