//! The seed of a chessboard lattice: a candidate corner and its four row
//! and column neighbours.
//!
//! Under a steep view the board's squares are foreshortened and sheared, so
//! a corner's four nearest candidates may include a diagonal neighbour, and
//! the two neighbours along a row differ in length (perspective). The seed
//! is therefore chosen from the eight nearest candidates: opposite pairs
//! (nearly collinear through the corner, lengths within a ratio) whose two
//! halves both run along a square's edge. That is the test which tells a
//! row or column step from a diagonal: across the middle of a step the two
//! sides are a black and a white square, across the middle of a diagonal
//! they are the same square.

use nalgebra::Vector2;

use super::candidates::{bilinear, Candidate};
use crate::vision::image::GrayImage;

/// Neighbours considered around a seed candidate.
const SEED_NEIGHBOURS: usize = 8;
/// Opposite neighbours: `|a x b|` below this fraction of `|a| |b|` (about
/// 12 degrees from collinear)...
const SEED_COLLINEAR_SIN: f64 = 0.2;
/// ...and lengths within this ratio (perspective shrinks one side).
const SEED_MAX_PAIR_RATIO: f64 = 1.8;
/// Row and column steps differ in length by at most this ratio.
const SEED_MAX_ASPECT: f64 = 3.0;
/// The two steps must be further from parallel than this |cos|.
const SEED_MAX_COS: f64 = 0.8;
/// Across a step's middle, samples this fraction of its length to each side.
const EDGE_PROBE_FRACTION: f64 = 0.25;
/// A step is along an edge when its contrast across is at least this
/// fraction of the best among the seed's neighbours (a diagonal shows ~0).
const EDGE_CONTRAST_FRACTION: f64 = 0.5;

/// Grey-level difference across the middle of the step `d` from `c`.
fn across(s: &GrayImage, c: Vector2<f64>, d: Vector2<f64>) -> Option<f64> {
    let n = Vector2::new(-d.y, d.x) * EDGE_PROBE_FRACTION;
    let m = c + d * 0.5;
    let a = bilinear(s, m.x + n.x, m.y + n.y)?;
    let b = bilinear(s, m.x - n.x, m.y - n.y)?;
    Some((a - b).abs() as f64)
}

/// The seed's neighbours `[+u, -u, +v, -v]` (candidate indices), or `None`
/// if candidate `k` is no lattice corner. `smoothed` is the level image the
/// candidates were found on.
pub fn seed_neighbours(cands: &[Candidate], k: usize, smoothed: &GrayImage) -> Option<[usize; 4]> {
    let c = cands[k].pos;
    let mut near: Vec<(usize, f64)> = cands
        .iter()
        .enumerate()
        .filter(|(j, _)| *j != k)
        .map(|(j, o)| (j, (o.pos - c).norm()))
        .collect();
    if near.len() < 4 {
        return None;
    }
    let m = SEED_NEIGHBOURS.min(near.len());
    near.select_nth_unstable_by(m - 1, |a, b| a.1.total_cmp(&b.1));
    near.truncate(m);
    let d = |j: usize| cands[j].pos - c;
    let contrast: Vec<f64> = near
        .iter()
        .map(|&(j, _)| across(smoothed, c, d(j)).unwrap_or(0.0))
        .collect();
    let best = contrast.iter().copied().fold(0.0, f64::max);
    if best <= 0.0 {
        return None;
    }
    let edge = |a: usize| contrast[a] >= EDGE_CONTRAST_FRACTION * best;
    // Opposite pairs along edges, shortest first: (mean length, a, b).
    let mut axes: Vec<(f64, usize, usize)> = Vec::new();
    for a in 0..m {
        for b in a + 1..m {
            let (da, db) = (d(near[a].0), d(near[b].0));
            let (la, lb) = (da.norm(), db.norm());
            let cross = (da.x * db.y - da.y * db.x).abs();
            let opposite = da.dot(&db) < 0.0 && cross <= SEED_COLLINEAR_SIN * la * lb;
            if opposite && la.max(lb) <= SEED_MAX_PAIR_RATIO * la.min(lb) && edge(a) && edge(b) {
                axes.push((0.5 * (la + lb), a, b));
            }
        }
    }
    axes.sort_by(|x, y| x.0.total_cmp(&y.0));
    let &(lu, ua, ub) = axes.first()?;
    let u = d(near[ua].0) - d(near[ub].0);
    let &(lv, va, vb) = axes.iter().skip(1).find(|&&(_, a, b)| {
        let v = d(near[a].0) - d(near[b].0);
        (u.dot(&v) / (u.norm() * v.norm())).abs() < SEED_MAX_COS
    })?;
    if lu.max(lv) > SEED_MAX_ASPECT * lu.min(lv) {
        return None;
    }
    Some([near[ua].0, near[ub].0, near[va].0, near[vb].0])
}
