//! Candidate marker outlines (issue 14): dark connected regions of the
//! locally thresholded image whose convex hull is close to a quadrilateral.
//!
//! A marker is a dark border with dark bits attached, isolated inside a
//! white square, so it is one 4-connected dark region; its hull is the
//! marker outline whatever the bits are.

use crate::vision::image::GreyLevels;
use crate::vision::threshold::{auto_window_radius, local_threshold};

/// Fewest pixels of a candidate region (a 5x5-bit marker at ~1.5 px per bit).
pub const MIN_REGION_PX: usize = 40;
/// Largest region as a fraction of the image area.
pub const MAX_REGION_FRACTION: f64 = 0.25;
/// Shortest accepted quad side, pixels.
pub const MIN_SIDE_PX: f64 = 6.0;
/// Least ratio of quad area to hull area (a marker's hull is its quad, less
/// its corners' rounding under blur: a blurred view's small markers, ~35 px
/// a side at sigma 2 px, measured 0.87–0.89, which 0.90 refused; the
/// dictionary read rejects what is not a marker).
pub const MIN_QUAD_HULL_RATIO: f64 = 0.85;

/// Four image corners, clockwise as seen with y down, pixel-centre
/// convention, on the region's outer boundary.
pub type Quad = [[f64; 2]; 4];

/// Dark mask of the image by the local-mean threshold.
fn dark_mask<I: GreyLevels>(img: &I) -> Vec<bool> {
    let (w, h) = (img.width(), img.height());
    let thr = local_threshold(img, auto_window_radius(w, h));
    let mut row = vec![0.0f32; w];
    let mut scratch = Vec::new();
    let mut mask = vec![false; w * h];
    for y in 0..h {
        thr.row(y, &mut row, &mut scratch);
        let base = y * w;
        for (x, (m, t)) in mask[base..base + w].iter_mut().zip(&row).enumerate() {
            *m = img.level(base + x) < *t;
        }
    }
    mask
}

/// Every 4-connected dark region that does not touch the image border, as
/// the leftmost and rightmost pixel of each of its rows: the region's
/// convex hull is theirs, so the hull sorts two points a row instead of
/// every boundary pixel (issue 14's time per image). The fill clears the
/// mask as it goes (the mask is its own "seen" set).
fn region_row_extremes(mut mask: Vec<bool>, w: usize, h: usize) -> Vec<Vec<[f64; 2]>> {
    let max_px = (MAX_REGION_FRACTION * (w * h) as f64) as usize;
    let mut out = Vec::new();
    let mut stack = Vec::new();
    // Per row from the region's first (top) row: leftmost, rightmost x.
    let mut rows: Vec<(usize, usize)> = Vec::new();
    for start in 0..mask.len() {
        if !mask[start] {
            continue;
        }
        mask[start] = false;
        stack.push(start);
        rows.clear();
        let top = start / w;
        let mut count = 0usize;
        let mut touches_border = false;
        while let Some(p) = stack.pop() {
            count += 1;
            let (x, y) = (p % w, p / w);
            let k = y - top;
            if k >= rows.len() {
                rows.resize(k + 1, (usize::MAX, 0));
            }
            let r = &mut rows[k];
            (r.0, r.1) = (r.0.min(x), r.1.max(x));
            if x == 0 || y == 0 || x + 1 == w || y + 1 == h {
                touches_border = true;
                continue;
            }
            for q in [p - 1, p + 1, p - w, p + w] {
                if mask[q] {
                    mask[q] = false;
                    stack.push(q);
                }
            }
        }
        if touches_border || count < MIN_REGION_PX || count > max_px {
            continue;
        }
        let mut extremes = Vec::with_capacity(2 * rows.len());
        for (k, &(lo, hi)) in rows.iter().enumerate() {
            let y = (top + k) as f64;
            extremes.push([lo as f64, y]);
            if hi != lo {
                extremes.push([hi as f64, y]);
            }
        }
        out.push(extremes);
    }
    out
}

fn cross(o: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
}

/// Convex hull (Andrew's monotone chain); its orientation does not matter,
/// `hull_quad` orders the quad clockwise (as seen with y down) itself.
fn convex_hull(mut pts: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &[f64; 2]>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// Shoelace area (positive when clockwise as seen with y down).
pub fn signed_area(poly: &[[f64; 2]]) -> f64 {
    let n = poly.len();
    0.5 * (0..n)
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The quadrilateral of hull vertices: farthest pair as one diagonal, the
/// farthest vertices on either side of it as the other.
fn hull_quad(hull: &[[f64; 2]]) -> Option<Quad> {
    let mut best = (0.0, 0, 0);
    for i in 0..hull.len() {
        for j in i + 1..hull.len() {
            let d = dist(hull[i], hull[j]);
            if d > best.0 {
                best = (d, i, j);
            }
        }
    }
    let (a, c) = (hull[best.1], hull[best.2]);
    let side = |p: &[f64; 2]| cross(a, c, *p);
    let b = *hull.iter().max_by(|p, q| side(p).total_cmp(&side(q)))?;
    let d = *hull.iter().min_by(|p, q| side(p).total_cmp(&side(q)))?;
    if side(&b) <= 0.0 || side(&d) >= 0.0 {
        return None;
    }
    let mut quad = [a, b, c, d];
    if signed_area(&quad) < 0.0 {
        quad.swap(1, 3);
    }
    Some(quad)
}

/// Pushes each corner half a pixel outwards along its diagonal: the hull
/// runs through boundary pixel centres, the outline along their outer edges.
fn to_outline(quad: Quad) -> Quad {
    let cx = quad.iter().map(|p| p[0]).sum::<f64>() / 4.0;
    let cy = quad.iter().map(|p| p[1]).sum::<f64>() / 4.0;
    quad.map(|p| {
        let (dx, dy) = (p[0] - cx, p[1] - cy);
        let n = dx.hypot(dy).max(f64::MIN_POSITIVE);
        let push = std::f64::consts::FRAC_1_SQRT_2;
        [p[0] + push * dx / n, p[1] + push * dy / n]
    })
}

/// Candidate marker quads of an image.
pub fn find_quads<I: GreyLevels>(img: &I) -> Vec<Quad> {
    let mask = dark_mask(img);
    region_row_extremes(mask, img.width(), img.height())
        .into_iter()
        .filter_map(|extremes| {
            let hull = convex_hull(extremes);
            if hull.len() < 4 {
                return None;
            }
            let quad = hull_quad(&hull)?;
            let sides_ok = (0..4).all(|i| dist(quad[i], quad[(i + 1) % 4]) >= MIN_SIDE_PX);
            let ratio = signed_area(&quad) / signed_area(&hull).abs().max(f64::MIN_POSITIVE);
            (sides_ok && ratio >= MIN_QUAD_HULL_RATIO).then(|| to_outline(quad))
        })
        .collect()
}
