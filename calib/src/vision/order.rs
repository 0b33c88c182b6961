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

/// The square lattice's linear symmetries `(m00, m01, m10, m11)`: four
/// turns (det +1), then four mirrors (det -1).
const LINEAR: [[i32; 4]; 8] = [
    [1, 0, 0, 1],
    [0, -1, 1, 0],
    [-1, 0, 0, -1],
    [0, 1, -1, 0],
    [1, 0, 0, -1],
    [-1, 0, 0, 1],
    [0, 1, 1, 0],
    [0, -1, -1, 0],
];

/// A reading: board site = `m * lattice site + t`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Reading {
    m: [i32; 4],
    t: (i32, i32),
}

fn mul(m: [i32; 4], (i, j): (i32, i32)) -> (i32, i32) {
    (m[0] * i + m[1] * j, m[2] * i + m[3] * j)
}

fn det(m: [i32; 4]) -> i32 {
    m[0] * m[3] - m[1] * m[2]
}

/// Inverse of a unimodular integer matrix.
fn inverse(m: [i32; 4]) -> [i32; 4] {
    let d = det(m);
    [d * m[3], -d * m[1], -d * m[2], d * m[0]]
}

fn compose(a: [i32; 4], b: [i32; 4]) -> [i32; 4] {
    [
        a[0] * b[0] + a[1] * b[2],
        a[0] * b[1] + a[1] * b[3],
        a[2] * b[0] + a[3] * b[2],
        a[2] * b[1] + a[3] * b[3],
    ]
}

impl Reading {
    fn board(&self, ij: (i32, i32)) -> (i32, i32) {
        let (a, b) = mul(self.m, ij);
        (a + self.t.0, b + self.t.1)
    }

    fn lattice(&self, ab: (i32, i32)) -> (i32, i32) {
        mul(inverse(self.m), (ab.0 - self.t.0, ab.1 - self.t.1))
    }
}

/// Why a reading was refused, most telling first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Refusal {
    /// A found dot falls off the board.
    OffBoard,
    /// The enlarged dot is not where the marker goes, or the marker site
    /// holds an ordinary dot.
    Marker,
    /// The marker would be well inside the image but is not there.
    MarkerMissing,
    /// Too many dots missing inside the image.
    Holes,
}

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

/// Checks one reading against the found dots, the marker and the holes.
#[allow(clippy::too_many_arguments)]
fn check(
    r: &Reading,
    lattice_sites: &[(i32, i32)],
    sites: &HashMap<(i32, i32), (usize, usize)>,
    frontier: &[(i32, i32)],
    big: &[(i32, i32)],
    marker: Option<((i32, i32), f64, f64)>,
    predictor: &mut Predictor,
    board: &CircleBoard,
    max_holes: usize,
) -> Result<(), Refusal> {
    if lattice_sites
        .iter()
        .any(|&s| !sites.contains_key(&r.board(s)))
    {
        return Err(Refusal::OffBoard);
    }
    if let Some((origin, _, scale)) = marker {
        let at = r.lattice(origin);
        match (predictor.lat.nodes.contains_key(&at), big.first()) {
            // The enlarged dot (found, or seen unrefined) is the marker.
            (_, Some(&b)) if b == at => {}
            (true, _) | (false, Some(_)) => return Err(Refusal::Marker),
            (false, None) => {
                if predictor.visible(at, scale) {
                    return Err(Refusal::MarkerMissing);
                }
            }
        }
    }
    let mut holes = 0;
    for &s in frontier.iter().filter(|s| !big.contains(s)) {
        let ab = r.board(s);
        if let Some(&(row, col)) = sites.get(&ab) {
            let scale = board.dot_diameter_at_mm(row, col) / board.dot_diameter_mm();
            if predictor.visible(s, scale) {
                holes += 1;
                if holes > max_holes {
                    return Err(Refusal::Holes);
                }
            }
        }
    }
    Ok(())
}

/// Several placements of a partial view fit: the board runs off the image
/// (or is occluded) where its edges or marker would have fixed the place.
fn placement_ambiguous(n: usize, lat: &Lattice, board: &CircleBoard) -> DetectError {
    if lat.nodes.len() < board.dot_count() {
        let (ni, nj) = lat.shape();
        return DetectError::BoardPartlyOutside {
            found_rows: ni.min(nj),
            found_cols: ni.max(nj),
            rows: board.rows(),
            cols: board.cols(),
        };
    }
    DetectError::OrderingAmbiguous(format!(
        "{n} placements of the dots on the board fit the image"
    ))
}

fn refusal_error(why: Option<Refusal>, lat: &Lattice, board: &CircleBoard) -> DetectError {
    let (ni, nj) = lat.shape();
    let (rows, cols) = (board.rows(), board.cols());
    match why {
        None | Some(Refusal::OffBoard) => DetectError::GridMismatch(format!(
            "a lattice of {} dots ({ni}x{nj}) does not fit the {rows}x{cols} board with its handedness (wrong rows/cols, clutter in line with the board, or a mirrored image?)",
            lat.nodes.len()
        )),
        Some(Refusal::Marker) => DetectError::MarkerNotFound(
            "no reading puts the origin marker on the one enlarged dot (marker diameter wrong?)".into(),
        ),
        Some(Refusal::MarkerMissing) => DetectError::MarkerNotFound(
            "the origin marker would be inside the image but no enlarged dot is there".into(),
        ),
        Some(Refusal::Holes) => {
            if lat.nodes.len() == board.dot_count() {
                DetectError::NoBoard("the lattice has holes".into())
            } else {
                DetectError::BoardPartlyOutside {
                    found_rows: ni.min(nj),
                    found_cols: ni.max(nj),
                    rows,
                    cols,
                }
            }
        }
    }
}
