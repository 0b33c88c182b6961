//! ChArUco detection (issue 14): markers → their board squares → a local
//! homography from the markers around each inner corner → the corner's
//! predicted image position → sub-pixel refinement.
//!
//! Partial views are normal: every inner corner with at least one seen
//! marker in its four squares is predicted from the seen markers within
//! `NEIGHBOUR_RADIUS_SQUARES` (a local homography absorbs lens distortion
//! better than one for the whole board). Marker ids make the ordering unique.

use nalgebra::Vector2;

use super::consistency::consistent_markers;
use super::layout::{corner_mm, inner_corner_grid, marker_cells, squares_around_corner};
use super::spec::CharucoSpec;
use crate::vision::aruco::detect_markers;
use crate::vision::board_point::{BoardDetection, BoardPoint};
use crate::vision::error::DetectError;
use crate::vision::homography::Homography;
use crate::vision::image::GreyLevels;
use crate::vision::saddle::refine_saddle_near;

/// Markers whose square centre lies within this many squares (Chebyshev)
/// of an inner corner take part in its local homography.
pub const NEIGHBOUR_RADIUS_SQUARES: f64 = 2.5;
/// Refinement window half-size as a fraction of the reach of the corner's
/// point symmetry in the image: the gap to the marker plus the marker's
/// dark border cell. Each marker's border is dark and the markers of the
/// two light squares at a corner face each other across it, so the four
/// squares with both marker borders are point-symmetric about the corner up
/// to the first bit cell; only the bits break the symmetry the fit assumes
/// (`vision::saddle`). A window held inside the gap alone (0.9 of it, as
/// before session 10) starves the fit on blurred views.
pub const REFINE_WINDOW_FRACTION: f64 = 0.9;
/// Room kept between the refinement window and the image's edge for the
/// fit's steps, pixels.
pub const EDGE_MARGIN_PX: f64 = 1.0;
/// Bounds of the refinement half window, pixels.
pub const MIN_REFINE_HALF_WINDOW_PX: f64 = 2.0;
pub const MAX_REFINE_HALF_WINDOW_PX: f64 = 15.0;

/// Sub-pixel corner refinement: image, predicted position, half window
/// (pixels) → refined position or `None` when no corner is there. The
/// saddle-point fit `vision::saddle::refine_saddle` has this signature.
pub type CornerRefiner<'a, I> = &'a dyn Fn(&I, [f64; 2], f64) -> Option<[f64; 2]>;

/// Detects the inner corners of `spec` in `img`. With `refine = None` the
/// corners are the local-homography predictions from the marker outlines.
pub fn detect_charuco_with<I: GreyLevels>(
    img: &I,
    spec: &CharucoSpec,
    refine: Option<CornerRefiner<I>>,
) -> Result<BoardDetection, DetectError> {
    let (width, height) = (img.width(), img.height());
    spec.validate()?;
    let dict = spec.dictionary()?;
    let cells = marker_cells(spec);
    let markers: Vec<_> = detect_markers(img, dict)
        .into_iter()
        .filter(|m| m.id < cells.len())
        .collect();
    if markers.is_empty() {
        return Err(DetectError::NoBoard(format!(
            "no marker of {} from this board found",
            dict.name
        )));
    }
    // Markers that disagree with the board are dropped (or the layout is
    // refused) before any corner is predicted from them.
    let markers = consistent_markers(spec, markers)?;
    let mut seen_square = vec![None; spec.cols() * spec.rows()];
    for (k, m) in markers.iter().enumerate() {
        let c = &cells[m.id];
        seen_square[c.row * spec.cols() + c.col] = Some(k);
    }
    let s = spec.square_mm;
    let border_cell_mm = spec.marker_mm / (dict.marker_size + 2) as f64;
    let symmetric_reach_mm = 0.5 * (s - spec.marker_mm) + border_cell_mm;
    let (nx, ny) = inner_corner_grid(spec);
    let mut points = Vec::new();
    for row in 0..ny {
        for col in 0..nx {
            let adjacent_seen = squares_around_corner(row, col)
                .iter()
                .any(|&(c, r)| seen_square[r * spec.cols() + c].is_some());
            if !adjacent_seen {
                continue;
            }
            let (gx, gy) = ((col + 1) as f64, (row + 1) as f64);
            let (mut plane, mut image) = (Vec::new(), Vec::new());
            for m in &markers {
                let c = &cells[m.id];
                let d = (c.col as f64 + 0.5 - gx)
                    .abs()
                    .max((c.row as f64 + 0.5 - gy).abs());
                if d <= NEIGHBOUR_RADIUS_SQUARES {
                    plane.extend(c.corners_mm.iter().map(|p| Vector2::new(p[0], p[1])));
                    image.extend(m.corners_px.iter().map(|p| Vector2::new(p[0], p[1])));
                }
            }
            let Some(h) = Homography::fit(&plane, &image) else {
                continue;
            };
            let t = corner_mm(spec, row, col);
            let here = Vector2::new(t[0], t[1]);
            let (Some(p), Some(px), Some(py)) = (
                h.apply(&here),
                h.apply(&(here + Vector2::new(s, 0.0))),
                h.apply(&(here + Vector2::new(0.0, s))),
            ) else {
                continue;
            };
            let inside =
                p.x >= 0.0 && p.y >= 0.0 && p.x <= (width - 1) as f64 && p.y <= (height - 1) as f64;
            if !inside {
                continue;
            }
            let square_px = (px - p).norm().min((py - p).norm());
            let reach_px = square_px * symmetric_reach_mm / s;
            // A window past the image's edge fails the fit: near the edge
            // it shrinks to fit (partial views), down to the least window.
            let to_edge_px =
                p.x.min(p.y)
                    .min((width - 2) as f64 - p.x)
                    .min((height - 2) as f64 - p.y)
                    - EDGE_MARGIN_PX;
            let half = (REFINE_WINDOW_FRACTION * reach_px)
                .min(to_edge_px)
                .clamp(MIN_REFINE_HALF_WINDOW_PX, MAX_REFINE_HALF_WINDOW_PX);
            let found = match refine {
                None => Some([p.x, p.y]),
                Some(f) => {
                    f(img, [p.x, p.y], half).filter(|q| (q[0] - p.x).hypot(q[1] - p.y) <= half)
                }
            };
            if let Some([x_px, y_px]) = found {
                points.push(BoardPoint {
                    row,
                    col,
                    target_mm: t,
                    x_px,
                    y_px,
                });
            }
        }
    }
    Ok(BoardDetection {
        image_width: width,
        image_height: height,
        points,
        ordering_unique: true,
    })
}

/// Detects the inner corners, refined by the shared point-symmetry fit
/// started at the marker homography's prediction (`vision::saddle::
/// refine_saddle_near`: the prediction is within a pixel or so, so the
/// quadratic pre-fit, which cost most of the refinement, runs only where
/// the symmetry fit alone fails; see `detect_charuco_with`). Generic over the grey
/// levels: the service and the bench give it the decoder's 8-bit image.
pub fn detect_charuco<I: GreyLevels>(
    img: &I,
    spec: &CharucoSpec,
) -> Result<BoardDetection, DetectError> {
    detect_charuco_with(img, spec, Some(&refine_saddle_near::<I>))
}

#[cfg(test)]
#[path = "detect_tests.rs"]
mod tests;
