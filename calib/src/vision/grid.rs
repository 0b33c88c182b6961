//! Lattice recovery: grow the dot lattice from a seed with local homographies
//! (method.md §1). One global fit cannot follow strong perspective plus lens
//! distortion; a homography fitted to the already-found dots within two
//! lattice steps predicts each next dot well enough to accept it by distance.

use std::collections::{HashMap, VecDeque};

use nalgebra::{Matrix3, Vector2, Vector3};

use super::homography::Homography;

/// Nearest neighbours examined when looking for a seed.
const SEED_NEIGHBOURS: usize = 6;
/// Two neighbours are opposite when `|a + b| < OPPOSITE_TOL * max(|a|, |b|)`.
const OPPOSITE_TOL: f64 = 0.25;
/// The two seed axes must be at least this far from parallel (|sin angle|).
const MIN_AXIS_SIN: f64 = 0.35;
/// Largest ratio of the two seed axis lengths (perspective foreshortening).
const MAX_AXIS_RATIO: f64 = 4.0;
/// A candidate is accepted within this fraction of the local step length
/// from the predicted position.
const ACCEPT_TOL: f64 = 0.3;
/// The second-nearest candidate must be at least this many times farther
/// from the predicted position than the accepted one.
const AMBIGUITY_RATIO: f64 = 3.0;
/// Lattice neighbourhood (Chebyshev radius) used for local prediction.
const LOCAL_RADIUS: i32 = 2;
/// Dots needed before a local homography replaces the affine prediction.
const MIN_HOMOGRAPHY_DOTS: usize = 6;
/// Seeds tried before giving up.
pub const MAX_SEED_ATTEMPTS: usize = 40;
/// Lattices smaller than this are clutter, not a board.
pub const MIN_LATTICE_DOTS: usize = 6;

/// A grown lattice: integer coordinates `(i, j)` to candidate index.
#[derive(Debug, Clone, Default)]
pub struct Lattice {
    pub nodes: HashMap<(i32, i32), usize>,
}

impl Lattice {
    /// Inclusive extents `(i_min, i_max, j_min, j_max)`.
    pub fn extents(&self) -> (i32, i32, i32, i32) {
        let mut e = (i32::MAX, i32::MIN, i32::MAX, i32::MIN);
        for &(i, j) in self.nodes.keys() {
            e = (e.0.min(i), e.1.max(i), e.2.min(j), e.3.max(j));
        }
        e
    }

    /// Sizes `(n_i, n_j)` of the bounding box of the lattice.
    pub fn shape(&self) -> (usize, usize) {
        let (a, b, c, d) = self.extents();
        ((b - a + 1) as usize, (d - c + 1) as usize)
    }

    /// Whether every position inside the bounding box holds a dot.
    pub fn is_full(&self) -> bool {
        let (ni, nj) = self.shape();
        ni * nj == self.nodes.len()
    }
}

/// Candidate dots for the lattice search.
pub struct Candidates<'a> {
    pub centres: &'a [Vector2<f64>],
    /// A size measure per candidate (e.g. sqrt of area), for consistency checks.
    pub sizes: &'a [f64],
    /// Largest accepted size ratio between lattice neighbours.
    pub max_size_ratio: f64,
}

fn k_nearest(c: &[Vector2<f64>], i: usize, k: usize) -> Vec<usize> {
    let mut d: Vec<(f64, usize)> = c
        .iter()
        .enumerate()
        .filter(|(j, _)| *j != i)
        .map(|(j, p)| ((p - c[i]).norm_squared(), j))
        .collect();
    let k = k.min(d.len());
    if k == 0 {
        return Vec::new();
    }
    d.select_nth_unstable_by(k - 1, |a, b| a.0.total_cmp(&b.0));
    d.truncate(k);
    d.sort_by(|a, b| a.0.total_cmp(&b.0));
    d.into_iter().map(|(_, j)| j).collect()
}

/// A seed: a candidate and its four lattice neighbours as two opposite pairs.
struct Seed {
    centre: usize,
    axis: [(usize, usize); 2],
    score: f64,
}

fn find_seed(cand: &Candidates, i: usize) -> Option<Seed> {
    let c = cand.centres;
    let nn = k_nearest(c, i, SEED_NEIGHBOURS);
    let similar = |j: usize| {
        let r = cand.sizes[j] / cand.sizes[i];
        r < cand.max_size_ratio.sqrt() && r > 1.0 / cand.max_size_ratio.sqrt()
    };
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (x, &a) in nn.iter().enumerate() {
        for &b in &nn[x + 1..] {
            let (va, vb) = (c[a] - c[i], c[b] - c[i]);
            let err = (va + vb).norm() / va.norm().max(vb.norm());
            if err < OPPOSITE_TOL && similar(a) && similar(b) {
                pairs.push((err, a, b));
            }
        }
    }
    pairs.sort_by(|p, q| p.0.total_cmp(&q.0));
    let mut best: Option<Seed> = None;
    for (x, p) in pairs.iter().enumerate() {
        for q in &pairs[x + 1..] {
            let (u, v) = (c[p.1] - c[i], c[q.1] - c[i]);
            let sin = (u.x * v.y - u.y * v.x).abs() / (u.norm() * v.norm());
            let ratio = u.norm().max(v.norm()) / u.norm().min(v.norm());
            if sin < MIN_AXIS_SIN || ratio > MAX_AXIS_RATIO {
                continue;
            }
            // Lattice axes are the shortest steps: penalise long pairs.
            let len = (u.norm() + v.norm()) / (c[nn[0]] - c[i]).norm();
            let score = p.0 + q.0 + 0.1 * len;
            if best.as_ref().is_none_or(|b| score < b.score) {
                best = Some(Seed {
                    centre: i,
                    axis: [(p.1, p.2), (q.1, q.2)],
                    score,
                });
            }
        }
    }
    best
}

fn fit_affine(lat: &[Vector2<f64>], img: &[Vector2<f64>]) -> Option<Matrix3<f64>> {
    let mut ata = Matrix3::<f64>::zeros();
    let (mut bx, mut by) = (Vector3::zeros(), Vector3::zeros());
    for (l, p) in lat.iter().zip(img) {
        let r = Vector3::new(l.x, l.y, 1.0);
        ata += r * r.transpose();
        bx += r * p.x;
        by += r * p.y;
    }
    let inv = ata.try_inverse()?;
    let (ax, ay) = (inv * bx, inv * by);
    Some(Matrix3::new(
        ax[0], ax[1], ax[2], ay[0], ay[1], ay[2], 0.0, 0.0, 1.0,
    ))
}

/// Predicts the image position of lattice node `t` from found nodes nearby.
fn predict(lattice: &Lattice, c: &[Vector2<f64>], t: (i32, i32)) -> Option<Vector2<f64>> {
    let (mut lat, mut img) = (Vec::new(), Vec::new());
    for di in -LOCAL_RADIUS..=LOCAL_RADIUS {
        for dj in -LOCAL_RADIUS..=LOCAL_RADIUS {
            if let Some(&k) = lattice.nodes.get(&(t.0 + di, t.1 + dj)) {
                lat.push(Vector2::new((t.0 + di) as f64, (t.1 + dj) as f64));
                img.push(c[k]);
            }
        }
    }
    let tv = Vector2::new(t.0 as f64, t.1 as f64);
    if lat.len() >= MIN_HOMOGRAPHY_DOTS {
        if let Some(p) = Homography::fit(&lat, &img).and_then(|h| h.apply(&tv)) {
            return Some(p);
        }
    }
    if lat.len() >= 3 {
        let a = fit_affine(&lat, &img)?;
        let p = a * Vector3::new(tv.x, tv.y, 1.0);
        return Some(Vector2::new(p.x, p.y));
    }
    None
}

fn grow(cand: &Candidates, seed: &Seed, used: &mut [bool]) -> Lattice {
    let c = cand.centres;
    let mut lattice = Lattice::default();
    let init = [
        ((0, 0), seed.centre),
        ((1, 0), seed.axis[0].0),
        ((-1, 0), seed.axis[0].1),
        ((0, 1), seed.axis[1].0),
        ((0, -1), seed.axis[1].1),
    ];
    let mut queue = VecDeque::new();
    for (ij, k) in init {
        lattice.nodes.insert(ij, k);
        used[k] = true;
        queue.push_back(ij);
    }
    while let Some((i, j)) = queue.pop_front() {
        let from = lattice.nodes[&(i, j)];
        for (di, dj) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
            let t = (i + di, j + dj);
            if lattice.nodes.contains_key(&t) {
                continue;
            }
            let Some(p) = predict(&lattice, c, t) else {
                continue;
            };
            let step = (p - c[from]).norm();
            // Nearest and second-nearest candidate (used ones included): the
            // match must be close and unambiguous, so dense clutter or noise
            // cannot pass for a lattice.
            let (mut first, mut second) = ((f64::MAX, usize::MAX), f64::MAX);
            for (k, q) in c.iter().enumerate() {
                let d = (q - p).norm();
                if d < first.0 {
                    second = first.0;
                    first = (d, k);
                } else if d < second {
                    second = d;
                }
            }
            let (dist, k) = first;
            if k == usize::MAX || used[k] {
                continue;
            }
            let ratio = cand.sizes[k] / cand.sizes[from];
            if dist < ACCEPT_TOL * step
                && second > AMBIGUITY_RATIO * dist
                && ratio < cand.max_size_ratio
                && ratio > 1.0 / cand.max_size_ratio
            {
                lattice.nodes.insert(t, k);
                used[k] = true;
                queue.push_back(t);
            }
        }
    }
    lattice
}

/// Grows lattices from the best seeds, each candidate used at most once;
/// returns those with at least `MIN_LATTICE_DOTS` dots, largest first.
pub fn grow_lattices(cand: &Candidates) -> Vec<Lattice> {
    let n = cand.centres.len();
    let mut seeds: Vec<Seed> = (0..n).filter_map(|i| find_seed(cand, i)).collect();
    seeds.sort_by(|a, b| a.score.total_cmp(&b.score));
    let mut used = vec![false; n];
    let mut out = Vec::new();
    for seed in seeds.iter().take(MAX_SEED_ATTEMPTS) {
        let members = [
            seed.centre,
            seed.axis[0].0,
            seed.axis[0].1,
            seed.axis[1].0,
            seed.axis[1].1,
        ];
        if members.iter().any(|&k| used[k]) {
            continue;
        }
        let mut trial = used.clone();
        let lattice = grow(cand, seed, &mut trial);
        if lattice.nodes.len() >= MIN_LATTICE_DOTS {
            used = trial;
            out.push(lattice);
        }
    }
    out.sort_by_key(|l| std::cmp::Reverse(l.nodes.len()));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn perspective_lattice_with_clutter_is_recovered_completely() {
        let h = Homography(Matrix3::new(
            40.0, 8.0, 300.0, -5.0, 30.0, 200.0, 0.02, 0.03, 1.0,
        ));
        let mut centres = Vec::new();
        for i in 0..7 {
            for j in 0..5 {
                centres.push(h.apply(&Vector2::new(i as f64, j as f64)).unwrap());
            }
        }
        // Clutter: isolated blobs away from the lattice sites.
        centres.push(Vector2::new(10.0, 10.0));
        centres.push(Vector2::new(900.0, 20.0));
        let sizes = vec![5.0; centres.len()];
        let cand = Candidates {
            centres: &centres,
            sizes: &sizes,
            max_size_ratio: 3.0,
        };
        let lats = grow_lattices(&cand);
        assert_eq!(lats[0].nodes.len(), 35);
        assert!(lats[0].is_full());
        let (ni, nj) = lats[0].shape();
        assert_eq!(ni * nj, 35);
        assert!(!lats[0].nodes.values().any(|&k| k >= 35));
    }
}
