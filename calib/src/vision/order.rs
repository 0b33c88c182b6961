//! Board orientation: which lattice corner is the origin and which lattice
//! direction is +x (method.md §1). The larger origin dot fixes the corner;
//! image handedness (the cross product of the +x and +y edge vectors in
//! (u, v) is positive, since the board is never seen mirrored) fixes the axes,
//! so the ordering is right under any camera roll.

use nalgebra::Vector2;

use super::error::DetectError;
use super::grid::Lattice;
use super::target::TargetSpec;

/// A lattice node mapped to its board position.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OrderedNode {
    pub row: usize,
    pub col: usize,
    /// Index into the candidate list.
    pub index: usize,
}

/// Ordered nodes, row-major, and whether the ordering is unique (marker seen)
/// or only defined up to the grid's symmetry (board without marker).
#[derive(Debug, Clone, PartialEq)]
pub struct Ordering {
    pub nodes: Vec<OrderedNode>,
    pub unique: bool,
}

/// One way of reading the lattice: origin corner, step signs, axis swap.
#[derive(Debug, Clone, Copy)]
struct Reading {
    corner: (i32, i32),
    si: i32,
    sj: i32,
    /// Lattice i runs along target x (columns) when true.
    i_is_x: bool,
}

impl Reading {
    fn map(&self, (i, j): (i32, i32)) -> (usize, usize) {
        let a = ((i - self.corner.0) * self.si) as usize;
        let b = ((j - self.corner.1) * self.sj) as usize;
        if self.i_is_x {
            (b, a)
        } else {
            (a, b)
        }
    }
}

fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Readings of a full lattice for all four corners; `consistent` ones give
/// the target's rows/cols with the right handedness.
fn readings(lat: &Lattice, c: &[Vector2<f64>], t: &TargetSpec) -> Vec<(Reading, bool)> {
    let (i0, i1, j0, j1) = lat.extents();
    let (ni, nj) = lat.shape();
    let mut out = Vec::new();
    for (ci, si) in [(i0, 1), (i1, -1)] {
        for (cj, sj) in [(j0, 1), (j1, -1)] {
            let p = c[lat.nodes[&(ci, cj)]];
            let ei = c[lat.nodes[&(ci + si, cj)]] - p;
            let ej = c[lat.nodes[&(ci, cj + sj)]] - p;
            // +x then +y must turn clockwise as displayed: cross > 0.
            let i_is_x = cross(ei, ej) > 0.0;
            let (cols, rows) = if i_is_x { (ni, nj) } else { (nj, ni) };
            let r = Reading {
                corner: (ci, cj),
                si,
                sj,
                i_is_x,
            };
            out.push((r, cols == t.cols && rows == t.rows));
        }
    }
    out
}

fn ordered(lat: &Lattice, r: &Reading, unique: bool) -> Ordering {
    let mut nodes: Vec<OrderedNode> = lat
        .nodes
        .iter()
        .map(|(&ij, &index)| {
            let (row, col) = r.map(ij);
            OrderedNode { row, col, index }
        })
        .collect();
    nodes.sort_by_key(|n| (n.row, n.col));
    Ordering { nodes, unique }
}

/// Size of a node relative to the median of its 8-neighbours.
fn relative_size(lat: &Lattice, sizes: &[f64], ij: (i32, i32)) -> f64 {
    let mut nb: Vec<f64> = Vec::new();
    for di in -1..=1 {
        for dj in -1..=1 {
            if (di, dj) != (0, 0) {
                if let Some(&k) = lat.nodes.get(&(ij.0 + di, ij.1 + dj)) {
                    nb.push(sizes[k]);
                }
            }
        }
    }
    nb.sort_by(f64::total_cmp);
    sizes[lat.nodes[&ij]] / nb[nb.len() / 2]
}

/// Orders a full lattice whose shape matches the target (either way round).
/// `areas` are dot areas in pixels, used to find the origin marker.
pub fn order_lattice(
    lat: &Lattice,
    centres: &[Vector2<f64>],
    areas: &[f64],
    t: &TargetSpec,
) -> Result<Ordering, DetectError> {
    let all = readings(lat, centres, t);
    let valid: Vec<Reading> = all.iter().filter(|r| r.1).map(|r| r.0).collect();
    if valid.is_empty() {
        let (ni, nj) = lat.shape();
        return Err(DetectError::GridMismatch(format!(
            "lattice is {ni}x{nj} but no corner reads as {} rows x {} cols with the board's handedness (mirrored image?)",
            t.rows, t.cols
        )));
    }
    let Some(marker_mm) = t.origin_marker_diameter_mm else {
        // No marker: pick the origin nearest the image's top-left corner.
        let best = valid
            .iter()
            .min_by(|a, b| {
                let pa = centres[lat.nodes[&a.corner]];
                let pb = centres[lat.nodes[&b.corner]];
                (pa.x + pa.y).total_cmp(&(pb.x + pb.y))
            })
            .copied()
            .expect("valid is non-empty");
        return Ok(ordered(lat, &best, valid.len() == 1));
    };
    // Expected area ratio marker/dot; decide at its geometric mean with 1.
    let expected = (marker_mm / t.dot_diameter_mm).powi(2);
    let threshold = expected.sqrt();
    let big: Vec<(i32, i32)> = lat
        .nodes
        .keys()
        .copied()
        .filter(|&ij| relative_size(lat, areas, ij) > threshold)
        .collect();
    let corners: Vec<(i32, i32)> = all.iter().map(|r| r.0.corner).collect();
    if big.iter().any(|ij| !corners.contains(ij)) {
        return Err(DetectError::MarkerAmbiguous(format!(
            "{} enlarged dot(s), at least one away from a corner",
            big.len()
        )));
    }
    match big.len() {
        0 => Err(DetectError::MarkerNotFound(format!(
            "no corner dot is {threshold:.2}x larger in area than its neighbours"
        ))),
        1 => match valid.iter().find(|r| r.corner == big[0]) {
            Some(r) => Ok(ordered(lat, r, true)),
            None => Err(DetectError::GridMismatch(
                "origin marker found at a corner whose edges do not match rows/cols with the board's handedness (mirrored image or rows/cols swapped?)".into(),
            )),
        },
        n => Err(DetectError::MarkerAmbiguous(format!(
            "{n} corner dots look like the origin marker"
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lattice_3x4(rot: f64, mirror: bool) -> (Lattice, Vec<Vector2<f64>>, Vec<f64>) {
        // Board 3 rows x 4 cols; marker at (0, 0); lattice i = row, j = col.
        let mut lat = Lattice::default();
        let (mut c, mut a) = (Vec::new(), Vec::new());
        let (s, co) = rot.sin_cos();
        for row in 0..3 {
            for col in 0..4 {
                let (x, y) = (col as f64 * 30.0, row as f64 * 30.0);
                let y = if mirror { -y } else { y };
                c.push(Vector2::new(500.0 + co * x - s * y, 400.0 + s * x + co * y));
                a.push(if row == 0 && col == 0 { 220.0 } else { 100.0 });
                lat.nodes.insert((row, col), c.len() - 1);
            }
        }
        (lat, c, a)
    }

    fn target() -> TargetSpec {
        TargetSpec {
            rows: 3,
            cols: 4,
            pitch_mm: 25.0,
            dot_diameter_mm: 8.0,
            origin_marker_diameter_mm: Some(12.0),
        }
    }

    #[test]
    fn any_roll_gives_the_true_ordering() {
        for k in 0..12 {
            let (lat, c, a) = lattice_3x4(k as f64 * 0.5, false);
            let o = order_lattice(&lat, &c, &a, &target()).unwrap();
            assert!(o.unique);
            for n in &o.nodes {
                assert_eq!(n.index, n.row * 4 + n.col, "roll step {k}");
            }
        }
    }

    #[test]
    fn mirrored_board_and_missing_marker_are_errors() {
        let (lat, c, a) = lattice_3x4(0.3, true);
        assert!(matches!(
            order_lattice(&lat, &c, &a, &target()),
            Err(DetectError::GridMismatch(_))
        ));
        let (lat, c, _) = lattice_3x4(0.3, false);
        let flat = vec![100.0; c.len()];
        assert!(matches!(
            order_lattice(&lat, &c, &flat, &target()),
            Err(DetectError::MarkerNotFound(_))
        ));
        let mut no_marker = target();
        no_marker.origin_marker_diameter_mm = None;
        let o = order_lattice(&lat, &c, &flat, &no_marker).unwrap();
        assert!(!o.unique && o.nodes.len() == 12);
    }
}
