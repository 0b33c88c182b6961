//! Where lattice sites without a found dot would appear in the image
//! (`order.rs`): whether a missing board dot should have been seen, and
//! whether an enlarged blob that failed the sub-pixel tests sits on a site.

use std::collections::HashMap;

use nalgebra::Vector2;

use super::grid::Lattice;
use super::homography::Homography;

/// A missing dot counts as visible when its predicted centre is inside the
/// image by this many of its predicted radii plus `EDGE_SLACK_PX` (blobs
/// touching the border are dropped, and the prediction extrapolates).
const EDGE_RADII: f64 = 1.5;
const EDGE_SLACK_PX: f64 = 2.0;
/// Lattice neighbourhood (Chebyshev radius) of the local prediction.
const PREDICT_RADIUS: i32 = 3;
/// Nodes needed for a local homography prediction.
const MIN_PREDICT_NODES: usize = 6;
/// An unrefined blob counts as the marker within this fraction of the
/// lattice step from the site's predicted position.
const UNREFINED_MARKER_TOL: f64 = 0.3;

/// Predicts where lattice sites outside the lattice would appear and how
/// big, for the visibility test; cached per site.
pub(crate) struct Predictor<'a> {
    pub(crate) lat: &'a Lattice,
    pub(crate) centres: &'a [Vector2<f64>],
    pub(crate) extents: (i32, i32, i32, i32),
    pub(crate) global: Option<Homography>,
    /// Image size.
    pub(crate) size: (f64, f64),
    /// Dot radius per lattice step (board geometry).
    pub(crate) radius_per_step: f64,
    pub(crate) cache: HashMap<(i32, i32), bool>,
}

impl Predictor<'_> {
    pub(crate) fn fit(&self, sites: &[(i32, i32)]) -> Option<Homography> {
        let plane: Vec<Vector2<f64>> = sites
            .iter()
            .map(|&(i, j)| Vector2::new(i as f64, j as f64))
            .collect();
        let image: Vec<Vector2<f64>> = sites
            .iter()
            .map(|s| self.centres[self.lat.nodes[s]])
            .collect();
        Homography::fit(&plane, &image)
    }

    /// Where lattice site `ij` (not found) would appear and the local
    /// lattice step there, px: a local homography of the nearest found
    /// dots, else the global one.
    pub(crate) fn predict(&self, ij: (i32, i32)) -> Option<(Vector2<f64>, f64)> {
        let (i0, i1, j0, j1) = self.extents;
        let near = (ij.0.clamp(i0, i1), ij.1.clamp(j0, j1));
        let mut local = Vec::new();
        for di in -PREDICT_RADIUS..=PREDICT_RADIUS {
            for dj in -PREDICT_RADIUS..=PREDICT_RADIUS {
                let s = (near.0 + di, near.1 + dj);
                if self.lat.nodes.contains_key(&s) {
                    local.push(s);
                }
            }
        }
        let h = if local.len() >= MIN_PREDICT_NODES {
            self.fit(&local).or(self.global)
        } else {
            self.global
        }?;
        let at = |i: f64, j: f64| h.apply(&Vector2::new(i, j));
        let (fi, fj) = (ij.0 as f64, ij.1 as f64);
        let p = at(fi, fj)?;
        let step = (at(fi + 1.0, fj)? - p)
            .norm()
            .max((at(fi, fj + 1.0)? - p).norm());
        Some((p, step))
    }

    /// Whether a dot at lattice site `ij` (not found), `radius_scale` times
    /// an ordinary dot's size, would be well inside the image; `false` when
    /// it cannot be predicted.
    pub(crate) fn visible(&mut self, ij: (i32, i32), radius_scale: f64) -> bool {
        if let Some(&v) = self.cache.get(&ij) {
            return v;
        }
        let v = self.predict(ij).is_some_and(|(p, step)| {
            let margin = EDGE_RADII * radius_scale * self.radius_per_step * step + EDGE_SLACK_PX;
            let (w, h) = self.size;
            p.x > margin && p.y > margin && p.x < w - 1.0 - margin && p.y < h - 1.0 - margin
        });
        self.cache.insert(ij, v);
        v
    }
}

/// Size of a node relative to the median of its 8-neighbours.
pub(crate) fn relative_size(lat: &Lattice, sizes: &[f64], ij: (i32, i32)) -> f64 {
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
    if nb.is_empty() {
        return 1.0;
    }
    nb.sort_by(f64::total_cmp);
    sizes[lat.nodes[&ij]] / nb[nb.len() / 2]
}

/// Whether an unrefined blob `threshold` times larger (in area) than the
/// found dots around it sits where lattice site `ij` is predicted.
pub(crate) fn enlarged_blob_at(
    predictor: &Predictor,
    ij: (i32, i32),
    areas: &[f64],
    unrefined: &[(Vector2<f64>, f64)],
    threshold: f64,
) -> bool {
    let Some((p, step)) = predictor.predict(ij) else {
        return false;
    };
    let mut nb: Vec<f64> = Vec::new();
    for di in -1..=1 {
        for dj in -1..=1 {
            if let Some(&k) = predictor.lat.nodes.get(&(ij.0 + di, ij.1 + dj)) {
                nb.push(areas[k]);
            }
        }
    }
    if nb.is_empty() {
        return false;
    }
    nb.sort_by(f64::total_cmp);
    let typical = nb[nb.len() / 2];
    unrefined
        .iter()
        .any(|&(c, a)| (c - p).norm() < UNREFINED_MARKER_TOL * step && a > threshold * typical)
}
