//! Growing the lattice of chessboard corners from saddle candidates.
//!
//! A seed is a candidate whose four nearest candidates form two opposite
//! pairs (its row and column neighbours) and whose diagonal neighbour is
//! where the parallelogram puts it. From the seed the lattice grows one cell
//! at a time: each empty cell next to the lattice is predicted by linear
//! extrapolation along a row or column (or by a parallelogram) and takes the
//! nearest unused candidate within a fraction of the local spacing.

use std::collections::HashMap;

use nalgebra::Vector2;

use super::candidates::Candidate;
use super::seed::seed_neighbours;
use crate::vision::image::GrayImage;

/// A candidate must lie within this fraction of the local corner spacing of
/// the predicted position.
const ACCEPT_FRACTION: f64 = 0.3;
/// Seeds tried, strongest candidates first.
pub const MAX_SEEDS: usize = 40;

/// Lattice cell → candidate index.
pub type Lattice = HashMap<(i32, i32), usize>;

const STEPS: [(i32, i32); 4] = [(1, 0), (-1, 0), (0, 1), (0, -1)];

fn nearest(cands: &[Candidate], p: Vector2<f64>, used: &[bool]) -> Option<(usize, f64)> {
    cands
        .iter()
        .enumerate()
        .filter(|(k, _)| !used[*k])
        .map(|(k, c)| (k, (c.pos - p).norm()))
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// Predicted position of `cell` from its known neighbours, and the local spacing.
fn predict(
    lattice: &Lattice,
    cands: &[Candidate],
    cell: (i32, i32),
) -> Option<(Vector2<f64>, f64)> {
    let at = |i: i32, j: i32| lattice.get(&(i, j)).map(|&k| cands[k].pos);
    let (i, j) = cell;
    let (mut sum, mut spacing, mut n) = (Vector2::zeros(), 0.0, 0usize);
    for (di, dj) in STEPS {
        if let (Some(p1), Some(p2)) = (at(i - di, j - dj), at(i - 2 * di, j - 2 * dj)) {
            // Quadratic extrapolation where a third corner is known: it
            // follows perspective's shrinking steps, the linear one lags.
            sum += match at(i - 3 * di, j - 3 * dj) {
                Some(p3) => 3.0 * p1 - 3.0 * p2 + p3,
                None => 2.0 * p1 - p2,
            };
            spacing += (p1 - p2).norm();
            n += 1;
        }
    }
    if n == 0 {
        // Parallelogram: a known neighbour and a known cell beside both.
        for (di, dj) in STEPS {
            let Some(p1) = at(i - di, j - dj) else {
                continue;
            };
            for (ei, ej) in STEPS.into_iter().filter(|&(ei, ej)| ei * di + ej * dj == 0) {
                if let (Some(q1), Some(q0)) = (at(i + ei, j + ej), at(i - di + ei, j - dj + ej)) {
                    sum += p1 + q1 - q0;
                    spacing += (q1 - q0).norm().min((p1 - q0).norm());
                    n += 1;
                }
            }
        }
    }
    (n > 0).then(|| (sum / n as f64, spacing / n as f64))
}

/// Grows the lattice from seed candidate `k`, or `None` if `k` is no seed
/// (`smoothed`: the level image the candidates were found on).
pub fn grow(
    cands: &[Candidate],
    k: usize,
    max_cells: usize,
    smoothed: &GrayImage,
) -> Option<Lattice> {
    let seed = seed_neighbours(cands, k, smoothed)?;
    let mut used = vec![false; cands.len()];
    let mut lattice = Lattice::new();
    lattice.insert((0, 0), k);
    used[k] = true;
    for (cell, j) in [(1, 0), (-1, 0), (0, 1), (0, -1)].into_iter().zip(seed) {
        lattice.insert(cell, j);
        used[j] = true;
    }
    loop {
        let mut frontier: Vec<(i32, i32)> = lattice
            .keys()
            .flat_map(|&(i, j)| STEPS.map(|(di, dj)| (i + di, j + dj)))
            .filter(|cell| !lattice.contains_key(cell))
            .collect();
        frontier.sort_unstable();
        frontier.dedup();
        let mut added = false;
        for cell in frontier {
            let Some((p, spacing)) = predict(&lattice, cands, cell) else {
                continue;
            };
            if let Some((j, d)) = nearest(cands, p, &used) {
                if d <= ACCEPT_FRACTION * spacing {
                    lattice.insert(cell, j);
                    used[j] = true;
                    added = true;
                }
            }
        }
        if !added || lattice.len() > max_cells {
            break;
        }
    }
    Some(lattice)
}
