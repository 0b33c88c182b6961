//! Board orientation (method.md §1, issue 14): which board dot each lattice
//! node is, for full and partial views of any circle board.
//!
//! Every reading of the lattice is a map of its sites onto the board's
//! (`circle_board.rs`): one of the square lattice's turns, with mirror
//! images excluded by image handedness (the board is never seen mirrored:
//! +x then +y turn clockwise as displayed), plus a shift. A reading must
//! put every found dot on a board dot; the origin marker, if the board has
//! one, on the one enlarged dot (or out of view if none is enlarged); and
//! no board dot where the image shows none although the dot would be well
//! inside the image (a hole: at most `MAX_HOLE_FRACTION` of the dots, for
//! glare or a dirty dot). What survives is the board's own symmetry at most
//! (a half or quarter turn of a marker-less board): that is reported, never
//! silently resolved; anything else is an error.

use std::collections::HashMap;

use nalgebra::Vector2;

use super::circle_board::{CircleBoard, SiteTurn};
use super::error::DetectError;
use super::grid::Lattice;
use super::order_reading::{
    check, compose, det, inverse, mul, placement_ambiguous, refusal_error, Reading, Refusal, LINEAR,
};
use super::site_prediction::{enlarged_blob_at, relative_size, Predictor};

/// A lattice node mapped to its board position.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OrderedNode {
    pub row: usize,
    pub col: usize,
    /// Index into the candidate list.
    pub index: usize,
}

/// Ordered nodes, row-major, and the turns of the board (quarter turns,
/// 1..=3) that read the same image equally well: empty when the ordering is
/// unique.
#[derive(Debug, Clone, PartialEq)]
pub struct Ordering {
    pub nodes: Vec<OrderedNode>,
    pub equivalent_turns: Vec<u8>,
}

impl Ordering {
    pub fn unique(&self) -> bool {
        self.equivalent_turns.is_empty()
    }
}

/// Fraction of the found dots that may be missing where the image should
/// show a dot (glare, a dirty or damaged dot).
const MAX_HOLE_FRACTION: f64 = 0.05;
/// Most shifts tried per turn when no marker pins the shift.
const MAX_SHIFTS: usize = 100_000;

/// Sign of the lattice's handedness in the image: +1 when `i` then `j`
/// turn clockwise as displayed.
fn handedness(lat: &Lattice, c: &[Vector2<f64>]) -> i32 {
    let mut vote = 0i64;
    for (&(i, j), &k) in &lat.nodes {
        if let (Some(&a), Some(&b)) = (lat.nodes.get(&(i + 1, j)), lat.nodes.get(&(i, j + 1))) {
            let (u, v) = (c[a] - c[k], c[b] - c[k]);
            vote += if u.x * v.y - u.y * v.x > 0.0 { 1 } else { -1 };
        }
    }
    if vote >= 0 {
        1
    } else {
        -1
    }
}

/// Orders a lattice (full or partial) as dots of `board`. `areas` are dot
/// areas in pixels (to find the origin marker); `unrefined` are the centres
/// and areas of dot-like blobs whose outline failed the sub-pixel tests (a
/// marker may be one: it identifies the board without being measured);
/// `image_size` is `(width, height)` for the visibility of missing dots.
pub fn order_lattice(
    lat: &Lattice,
    centres: &[Vector2<f64>],
    areas: &[f64],
    unrefined: &[(Vector2<f64>, f64)],
    board: &CircleBoard,
    image_size: (usize, usize),
) -> Result<Ordering, DetectError> {
    let sites = board.sites();
    let mut bb = (i32::MAX, i32::MIN, i32::MAX, i32::MIN);
    for &(a, b) in sites.keys() {
        bb = (bb.0.min(a), bb.1.max(a), bb.2.min(b), bb.3.max(b));
    }
    let marker = board.marker_diameter_mm().map(|m| {
        // Decide at the geometric mean of the expected area ratio and 1.
        let ratio = m / board.dot_diameter_mm();
        (board.site(0, 0), ratio, ratio)
    });
    let mut big: Vec<(i32, i32)> = match marker {
        Some((_, threshold, _)) => lat
            .nodes
            .keys()
            .copied()
            .filter(|&ij| relative_size(lat, areas, ij) > threshold)
            .collect(),
        None => Vec::new(),
    };
    let lattice_sites: Vec<(i32, i32)> = lat.nodes.keys().copied().collect();
    let extents = lat.extents();
    let mut predictor = Predictor {
        lat,
        centres,
        extents,
        global: None,
        size: (image_size.0 as f64, image_size.1 as f64),
        radius_per_step: 0.5 * board.dot_diameter_mm() / board.site_step_mm(),
        cache: HashMap::new(),
    };
    predictor.global = predictor.fit(&lattice_sites);
    // Lattice sites next to found dots but not found themselves.
    let mut frontier: Vec<(i32, i32)> = lattice_sites
        .iter()
        .flat_map(|&(i, j)| [(i + 1, j), (i - 1, j), (i, j + 1), (i, j - 1)])
        .filter(|s| !lat.nodes.contains_key(s))
        .collect();
    frontier.sort_unstable();
    frontier.dedup();
    // A marker seen but not measured: an enlarged unrefined blob where a
    // lattice neighbour of the found dots would be.
    if let Some((_, threshold, _)) = marker {
        big.extend(
            frontier
                .iter()
                .copied()
                .filter(|&s| enlarged_blob_at(&predictor, s, areas, unrefined, threshold)),
        );
    }
    if big.len() > 1 {
        return Err(DetectError::MarkerAmbiguous(format!(
            "{} dots look like the origin marker",
            big.len()
        )));
    }
    let max_holes = (MAX_HOLE_FRACTION * lat.nodes.len() as f64) as usize;
    let sign = handedness(lat, centres);
    let mut survivors: Vec<Reading> = Vec::new();
    let mut refusals: Vec<Refusal> = Vec::new();
    for m in LINEAR.into_iter().filter(|&m| det(m) == sign) {
        let mapped: Vec<(i32, i32)> = lattice_sites.iter().map(|&s| mul(m, s)).collect();
        let mut e = (i32::MAX, i32::MIN, i32::MAX, i32::MIN);
        for &(a, b) in &mapped {
            e = (e.0.min(a), e.1.max(a), e.2.min(b), e.3.max(b));
        }
        let shifts: Vec<(i32, i32)> = match (marker, big.first()) {
            (Some((origin, _, _)), Some(&b)) => {
                let mb = mul(m, b);
                vec![(origin.0 - mb.0, origin.1 - mb.1)]
            }
            _ => {
                let (ta, tb) = ((bb.0 - e.0)..=(bb.1 - e.1), (bb.2 - e.2)..=(bb.3 - e.3));
                if ta.clone().count() * tb.clone().count() > MAX_SHIFTS {
                    return Err(placement_ambiguous(MAX_SHIFTS, lat, board));
                }
                ta.flat_map(|a| tb.clone().map(move |b| (a, b))).collect()
            }
        };
        for t in shifts {
            let r = Reading { m, t };
            match check(
                &r,
                &lattice_sites,
                &sites,
                &frontier,
                &big,
                marker,
                &mut predictor,
                board,
                max_holes,
            ) {
                Ok(()) => survivors.push(r),
                Err(why) => refusals.push(why),
            }
        }
    }
    let Some(&first) = survivors.first() else {
        return Err(refusal_error(refusals.iter().max().copied(), lat, board));
    };
    // A marker board is read uniquely or not at all.
    if marker.is_some() && survivors.len() > 1 {
        return Err(placement_ambiguous(survivors.len(), lat, board));
    }
    // Every survivor must be the first turned by a symmetry of the board.
    let first_inv = inverse(first.m);
    let mut turned: Vec<(Reading, u8)> = Vec::new();
    for r in &survivors {
        let g = compose(r.m, first_inv);
        let Some(k) = (0..4u8).find(|&k| LINEAR[k as usize] == g) else {
            return Err(DetectError::OrderingAmbiguous(
                "readings differ by a mirror".into(),
            ));
        };
        let turn = SiteTurn::of_board(&sites, k);
        let same = turn.is_some_and(|turn| {
            lattice_sites
                .iter()
                .all(|&s| turn.apply(first.board(s)) == r.board(s))
        });
        if !same {
            return Err(placement_ambiguous(survivors.len(), lat, board));
        }
        turned.push((*r, k));
    }
    // Report one reading: the one whose first dot (row-major) is nearest
    // the image's top-left corner, with the turns that give the others.
    let first_dot = |r: &Reading| {
        let (_, _, k) = lattice_sites
            .iter()
            .map(|&s| {
                let (row, col) = sites[&r.board(s)];
                (row, col, lat.nodes[&s])
            })
            .min()
            .expect("lattice is not empty");
        centres[k].x + centres[k].y
    };
    let (chosen, k0) = turned
        .iter()
        .copied()
        .min_by(|a, b| first_dot(&a.0).total_cmp(&first_dot(&b.0)))
        .expect("survivors are not empty");
    let mut equivalent_turns: Vec<u8> = turned
        .iter()
        .map(|&(_, k)| (k + 4 - k0) % 4)
        .filter(|&k| k != 0)
        .collect();
    equivalent_turns.sort_unstable();
    let mut nodes: Vec<OrderedNode> = lat
        .nodes
        .iter()
        .map(|(&ij, &index)| {
            let (row, col) = sites[&chosen.board(ij)];
            OrderedNode { row, col, index }
        })
        .collect();
    nodes.sort_by_key(|n| (n.row, n.col));
    Ok(Ordering {
        nodes,
        equivalent_turns,
    })
}
