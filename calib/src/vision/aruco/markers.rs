//! Reading markers (issue 14): sample the bit grid of each candidate quad
//! through its homography, split dark from light by two-means, require a
//! dark border, and match the bits to the dictionary in four rotations.

use nalgebra::Vector2;

use super::dictionary::{code_from_bits, Dictionary};
use super::quads::{find_quads, Quad};
use crate::vision::homography::Homography;
use crate::vision::image::GreyLevels;

/// Samples per bit cell and axis, at these fractions of the cell.
const SAMPLE_FRACTIONS: [f64; 3] = [0.3, 0.5, 0.7];
/// Least grey-level difference between the dark and light cell means.
pub const MIN_BIT_CONTRAST_GREY: f64 = 20.0;
/// Largest fraction of light border cells (OpenCV: 0.35).
pub const MAX_BORDER_ERROR_RATE: f64 = 0.2;
/// Two-means iterations for the bit threshold.
const TWO_MEANS_ITERATIONS: usize = 8;

/// One identified marker.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MarkerObservation {
    pub id: usize,
    /// Image corners in the marker's own order (top-left, top-right,
    /// bottom-right, bottom-left of the marker as printed), pixels.
    pub corners_px: [[f64; 2]; 4],
    /// Bits corrected when matching.
    pub corrected_bits: usize,
}

/// Bilinear grey level at a sub-pixel position (pixel-centre convention).
pub fn bilinear<I: GreyLevels>(img: &I, x: f64, y: f64) -> Option<f64> {
    let (w, h) = (img.width(), img.height());
    if !(x >= 0.0 && y >= 0.0 && x <= (w - 1) as f64 && y <= (h - 1) as f64) {
        return None;
    }
    let (x0, y0) = (x.floor() as usize, y.floor() as usize);
    let (x1, y1) = ((x0 + 1).min(w - 1), (y0 + 1).min(h - 1));
    let (fx, fy) = (x - x0 as f64, y - y0 as f64);
    let at = |x: usize, y: usize| f64::from(img.level(y * w + x));
    let top = at(x0, y0) * (1.0 - fx) + at(x1, y0) * fx;
    let bottom = at(x0, y1) * (1.0 - fx) + at(x1, y1) * fx;
    Some(top * (1.0 - fy) + bottom * fy)
}

/// Mean grey level of each of the `(size + 2)^2` cells, row-major.
fn sample_cells<I: GreyLevels>(img: &I, quad: &Quad, cells: usize) -> Option<Vec<f64>> {
    let n = cells as f64;
    let unit = [[0.0, 0.0], [n, 0.0], [n, n], [0.0, n]].map(|p| Vector2::new(p[0], p[1]));
    let corners = quad.map(|p| Vector2::new(p[0], p[1]));
    let h = Homography::fit(&unit, &corners)?;
    let mut out = Vec::with_capacity(cells * cells);
    for r in 0..cells {
        for c in 0..cells {
            let mut sum = 0.0;
            for fy in SAMPLE_FRACTIONS {
                for fx in SAMPLE_FRACTIONS {
                    let p = h.apply(&Vector2::new(c as f64 + fx, r as f64 + fy))?;
                    sum += bilinear(img, p.x, p.y)?;
                }
            }
            out.push(sum / (SAMPLE_FRACTIONS.len() * SAMPLE_FRACTIONS.len()) as f64);
        }
    }
    Some(out)
}

/// Threshold between the dark and light cell means (1-D two-means).
fn two_means(values: &[f64]) -> Option<f64> {
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if hi - lo < MIN_BIT_CONTRAST_GREY {
        return None;
    }
    let mut t = 0.5 * (lo + hi);
    for _ in 0..TWO_MEANS_ITERATIONS {
        let (mut s0, mut n0, mut s1, mut n1) = (0.0, 0.0, 0.0, 0.0);
        for &v in values {
            if v < t {
                (s0, n0) = (s0 + v, n0 + 1.0);
            } else {
                (s1, n1) = (s1 + v, n1 + 1.0);
            }
        }
        if n0 == 0.0 || n1 == 0.0 {
            break;
        }
        t = 0.5 * (s0 / n0 + s1 / n1);
    }
    Some(t)
}

/// Reads one quad; `None` when it is not a marker of `dict`.
pub fn read_marker<I: GreyLevels>(
    img: &I,
    quad: &Quad,
    dict: &Dictionary,
) -> Option<MarkerObservation> {
    let size = dict.marker_size;
    let cells = size + 2;
    let values = sample_cells(img, quad, cells)?;
    let t = two_means(&values)?;
    let is_border = |r: usize, c: usize| r == 0 || c == 0 || r == cells - 1 || c == cells - 1;
    let border_light = (0..cells * cells)
        .filter(|&k| is_border(k / cells, k % cells) && values[k] >= t)
        .count();
    let border_total = 4 * (cells - 1);
    if border_light as f64 > MAX_BORDER_ERROR_RATE * border_total as f64 {
        return None;
    }
    let bits: Vec<bool> = (1..=size)
        .flat_map(|r| (1..=size).map(move |c| (r, c)))
        .map(|(r, c)| values[r * cells + c] >= t)
        .collect();
    let hit = dict.identify(code_from_bits(&bits, size))?;
    // `rotation` clockwise turns of the sampled grid give the marker, so the
    // marker's top-left is the quad corner that many steps counter-clockwise.
    let corners_px = std::array::from_fn(|i| quad[(4 - hit.rotation + i) % 4]);
    Some(MarkerObservation {
        id: hit.id,
        corners_px,
        corrected_bits: hit.distance,
    })
}

/// Every marker of `dict` in the image; one observation per id (the one
/// with the fewest corrected bits) since a board prints each id once.
pub fn detect_markers<I: GreyLevels>(img: &I, dict: &Dictionary) -> Vec<MarkerObservation> {
    let mut found: Vec<MarkerObservation> = Vec::new();
    for quad in find_quads(img) {
        let Some(m) = read_marker(img, &quad, dict) else {
            continue;
        };
        match found.iter_mut().find(|f| f.id == m.id) {
            Some(f) if m.corrected_bits < f.corrected_bits => *f = m,
            Some(_) => {}
            None => found.push(m),
        }
    }
    found.sort_by_key(|m| m.id);
    found
}

#[cfg(test)]
#[path = "markers_tests.rs"]
mod tests;
