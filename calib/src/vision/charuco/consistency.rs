//! Do the decoded markers agree about where they sit on the board? (issue 14)
//!
//! One homography from board to image explains every marker up to lens
//! distortion (a few pixels); a marker off by a square or more is misread,
//! from another board, or the spec's `legacy_layout` is wrong. Markers that
//! disagree are dropped one at a time (worst first); if the other layout
//! explains all of them, the spec is refused instead, naming the field.

use nalgebra::Vector2;

use super::layout::{marker_cells, MarkerCell};
use super::spec::CharucoSpec;
use crate::vision::aruco::MarkerObservation;
use crate::vision::error::DetectError;
use crate::vision::homography::Homography;

/// Largest marker-corner residual under the board homography, as a fraction
/// of the median marker side in the image (distortion stays well below;
/// a marker in the wrong square is off by more than a side).
pub const MAX_BOARD_RESIDUAL_FRACTION: f64 = 0.6;

fn side_px(m: &MarkerObservation) -> f64 {
    let c = m.corners_px;
    (0..4)
        .map(|i| (c[i][0] - c[(i + 1) % 4][0]).hypot(c[i][1] - c[(i + 1) % 4][1]))
        .sum::<f64>()
        / 4.0
}

/// Indices of `markers` that disagree with the rest under `cells`.
fn outliers(cells: &[MarkerCell], markers: &[MarkerObservation]) -> Vec<usize> {
    let mut sides: Vec<f64> = markers.iter().map(side_px).collect();
    sides.sort_by(f64::total_cmp);
    let limit = MAX_BOARD_RESIDUAL_FRACTION * sides.get(sides.len() / 2).copied().unwrap_or(0.0);
    let mut keep: Vec<usize> = (0..markers.len()).collect();
    let mut out = Vec::new();
    while keep.len() >= 2 {
        let plane: Vec<_> = keep
            .iter()
            .flat_map(|&k| {
                cells[markers[k].id]
                    .corners_mm
                    .map(|p| Vector2::new(p[0], p[1]))
            })
            .collect();
        let image: Vec<_> = keep
            .iter()
            .flat_map(|&k| markers[k].corners_px.map(|p| Vector2::new(p[0], p[1])))
            .collect();
        let Some(h) = Homography::fit(&plane, &image) else {
            break;
        };
        let residual = |k: usize| {
            let c = &cells[markers[k].id];
            (0..4)
                .map(|i| {
                    let p = Vector2::new(c.corners_mm[i][0], c.corners_mm[i][1]);
                    let q = Vector2::new(markers[k].corners_px[i][0], markers[k].corners_px[i][1]);
                    h.apply(&p).map_or(f64::INFINITY, |r| (r - q).norm())
                })
                .fold(0.0, f64::max)
        };
        let (worst_at, worst) = keep
            .iter()
            .enumerate()
            .map(|(i, &k)| (i, residual(k)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((0, 0.0));
        if worst <= limit {
            break;
        }
        out.push(keep.remove(worst_at));
    }
    out
}

/// The markers that agree with the board, or `GridMismatch` when the other
/// layout (`legacy_layout` flipped) explains markers this one cannot.
pub fn consistent_markers(
    spec: &CharucoSpec,
    markers: Vec<MarkerObservation>,
) -> Result<Vec<MarkerObservation>, DetectError> {
    let cells = marker_cells(spec);
    let bad = outliers(&cells, &markers);
    if bad.is_empty() {
        return Ok(markers);
    }
    let flipped = CharucoSpec {
        legacy_layout: !spec.legacy_layout,
        ..spec.clone()
    };
    let flipped_cells = marker_cells(&flipped);
    if flipped_cells != cells
        && markers.iter().all(|m| m.id < flipped_cells.len())
        && outliers(&flipped_cells, &markers).is_empty()
    {
        return Err(DetectError::GridMismatch(format!(
            "legacy_layout: the markers match the {} layout; set legacy_layout to {}",
            if flipped.legacy_layout {
                "legacy (OpenCV < 4.6)"
            } else {
                "current (OpenCV >= 4.6)"
            },
            flipped.legacy_layout
        )));
    }
    Ok(markers
        .into_iter()
        .enumerate()
        .filter(|(k, _)| !bad.contains(k))
        .map(|(_, m)| m)
        .collect())
}
