//! Joint Levenberg–Marquardt refinement over all images (method.md §4
//! **beyond**): `fx, m, cx, cy, k1, k2, p1, p2` (optionally `k3`) and every
//! image's pose, minimising the reprojection error; optional reference
//! distances between camera stations (the paper's CMM travel) tune `fx`.
//!
//! Parameter vector: the intrinsics block (empty when intrinsics are fixed)
//! followed by `[t, rotation vector]` of each view's `camera_to_target`.

use nalgebra::{DMatrix, DVector, Isometry3, Point2, Point3, Vector6};
use serde::{Deserialize, Serialize};

use super::model::Intrinsics;
use crate::geometry::{pose_from_vector, pose_to_vector};
use crate::solver::{LeastSquaresProblem, NormalEquations, FINITE_DIFFERENCE_STEP};

/// Pose parameters per view.
pub const POSE_PARAMS: usize = 6;

/// A measured distance between the camera stations of two views (method.md §4).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StationDistance {
    pub view_a: usize,
    pub view_b: usize,
    pub distance_mm: f64,
    pub sigma_mm: f64,
}

/// Which intrinsics are free.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum IntrinsicsBlock {
    /// `[fx, m, cx, cy, k1, k2, p1, p2]`, plus `k3` when `with_k3`.
    Free {
        with_k3: bool,
    },
    Fixed(Intrinsics),
}

impl IntrinsicsBlock {
    pub fn len(&self) -> usize {
        match self {
            Self::Free { with_k3: true } => 9,
            Self::Free { with_k3: false } => 8,
            Self::Fixed(_) => 0,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Parameter values of `intr` in this block's layout.
    pub fn encode(&self, intr: &Intrinsics) -> Vec<f64> {
        let all = [
            intr.fx,
            intr.fy / intr.fx,
            intr.cx,
            intr.cy,
            intr.k1,
            intr.k2,
            intr.p1,
            intr.p2,
            intr.k3,
        ];
        all[..self.len()].to_vec()
    }

    pub fn decode(&self, x: &[f64]) -> Intrinsics {
        match self {
            Self::Fixed(i) => *i,
            Self::Free { with_k3 } => Intrinsics {
                fx: x[0],
                fy: x[0] * x[1],
                cx: x[2],
                cy: x[3],
                k1: x[4],
                k2: x[5],
                p1: x[6],
                p2: x[7],
                k3: if *with_k3 { x[8] } else { 0.0 },
            },
        }
    }
}

/// The joint reprojection problem; `views[v]` are the (bias-corrected)
/// observations still in use.
pub struct JointProblem<'a> {
    pub views: &'a [Vec<(Point3<f64>, Point2<f64>)>],
    pub block: IntrinsicsBlock,
    pub references: &'a [StationDistance],
    /// Weight of a reference-distance residual: pixel sigma / distance sigma.
    pub reference_weight: f64,
}

impl JointProblem<'_> {
    pub fn parameter_count(&self) -> usize {
        self.block.len() + POSE_PARAMS * self.views.len()
    }

    fn row_offsets(&self) -> Vec<usize> {
        let mut offsets = Vec::with_capacity(self.views.len() + 1);
        let mut o = 0;
        for v in self.views {
            offsets.push(o);
            o += 2 * v.len();
        }
        offsets.push(o);
        offsets
    }

    pub fn pose(&self, x: &DVector<f64>, view: usize) -> Isometry3<f64> {
        let o = self.block.len() + POSE_PARAMS * view;
        pose_from_vector(&Vector6::from_column_slice(
            &x.as_slice()[o..o + POSE_PARAMS],
        ))
    }

    /// Initial parameter vector.
    pub fn encode(&self, intr: &Intrinsics, camera_to_target: &[Isometry3<f64>]) -> DVector<f64> {
        let mut x = self.block.encode(intr);
        for p in camera_to_target {
            x.extend_from_slice(pose_to_vector(p).as_slice());
        }
        DVector::from_vec(x)
    }

    pub fn intrinsics(&self, x: &DVector<f64>) -> Intrinsics {
        self.block.decode(&x.as_slice()[..self.block.len()])
    }

    fn view_residuals(
        intr: &Intrinsics,
        pose: &Isometry3<f64>,
        obs: &[(Point3<f64>, Point2<f64>)],
        out: &mut [f64],
    ) -> Option<()> {
        super::pose::reprojection_residuals(intr, pose, obs, out)
    }

    fn reference_residual(
        &self,
        a: &Isometry3<f64>,
        b: &Isometry3<f64>,
        r: &StationDistance,
    ) -> f64 {
        // Camera position in the target frame: -R^T T (paper eqs. 37–39).
        let ca = a.inverse().translation.vector;
        let cb = b.inverse().translation.vector;
        self.reference_weight * ((ca - cb).norm() - r.distance_mm)
    }
}

impl LeastSquaresProblem for JointProblem<'_> {
    fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
        let intr = self.intrinsics(x);
        let offsets = self.row_offsets();
        let n_rows = offsets[self.views.len()] + self.references.len();
        let mut r = DVector::zeros(n_rows);
        for (v, obs) in self.views.iter().enumerate() {
            let pose = self.pose(x, v);
            Self::view_residuals(
                &intr,
                &pose,
                obs,
                &mut r.as_mut_slice()[offsets[v]..offsets[v + 1]],
            )?;
        }
        let base = offsets[self.views.len()];
        for (k, rf) in self.references.iter().enumerate() {
            r[base + k] =
                self.reference_residual(&self.pose(x, rf.view_a), &self.pose(x, rf.view_b), rf);
        }
        Some(r)
    }

    fn normal_equations(&self, x: &DVector<f64>, r: &DVector<f64>) -> Option<NormalEquations> {
        let jac = self.jacobian(x)?;
        let (jtj, jtr) = self.block_normal_equations(&jac, r);
        Some(NormalEquations { jtj, jtr })
    }

    /// Central differences that exploit the block structure: intrinsics
    /// touch every image row, a pose only its own image's rows.
    fn jacobian(&self, x: &DVector<f64>) -> Option<DMatrix<f64>> {
        let offsets = self.row_offsets();
        let n_img_rows = offsets[self.views.len()];
        let n_rows = n_img_rows + self.references.len();
        let ni = self.block.len();
        let mut jac = DMatrix::zeros(n_rows, x.len());
        let intr = self.intrinsics(x);
        let poses: Vec<_> = (0..self.views.len()).map(|v| self.pose(x, v)).collect();
        let step = |value: f64| FINITE_DIFFERENCE_STEP * value.abs().max(1.0);
        let mut plus = vec![0.0; n_img_rows];
        let mut minus = vec![0.0; n_img_rows];
        let mut probe = x.clone();
        for j in 0..ni {
            let h = step(x[j]);
            probe[j] = x[j] + h;
            let ip = self.intrinsics(&probe);
            probe[j] = x[j] - h;
            let im = self.intrinsics(&probe);
            probe[j] = x[j];
            for (v, obs) in self.views.iter().enumerate() {
                let rows = offsets[v]..offsets[v + 1];
                Self::view_residuals(&ip, &poses[v], obs, &mut plus[rows.clone()])?;
                Self::view_residuals(&im, &poses[v], obs, &mut minus[rows])?;
            }
            for row in 0..n_img_rows {
                jac[(row, j)] = (plus[row] - minus[row]) / (2.0 * h);
            }
        }
        for (v, obs) in self.views.iter().enumerate() {
            let rows = offsets[v]..offsets[v + 1];
            let base = ni + POSE_PARAMS * v;
            let refs: Vec<usize> = (0..self.references.len())
                .filter(|&k| self.references[k].view_a == v || self.references[k].view_b == v)
                .collect();
            for c in 0..POSE_PARAMS {
                let j = base + c;
                let h = step(x[j]);
                probe[j] = x[j] + h;
                let pp = self.pose(&probe, v);
                Self::view_residuals(&intr, &pp, obs, &mut plus[rows.clone()])?;
                let ref_plus: Vec<f64> = refs.iter().map(|&k| self.ref_at(&probe, k)).collect();
                probe[j] = x[j] - h;
                let pm = self.pose(&probe, v);
                Self::view_residuals(&intr, &pm, obs, &mut minus[rows.clone()])?;
                let ref_minus: Vec<f64> = refs.iter().map(|&k| self.ref_at(&probe, k)).collect();
                probe[j] = x[j];
                for row in rows.clone() {
                    jac[(row, j)] = (plus[row] - minus[row]) / (2.0 * h);
                }
                for (i, &k) in refs.iter().enumerate() {
                    jac[(n_img_rows + k, j)] = (ref_plus[i] - ref_minus[i]) / (2.0 * h);
                }
            }
        }
        Some(jac)
    }
}

impl JointProblem<'_> {
    /// `(J^T J, J^T r)` using the block structure: the rows of view `v`
    /// touch only the intrinsics and pose `v`; reference rows are dense.
    pub fn block_normal_equations(
        &self,
        jac: &DMatrix<f64>,
        r: &DVector<f64>,
    ) -> (DMatrix<f64>, DVector<f64>) {
        let n = jac.ncols();
        let ni = self.block.len();
        let offsets = self.row_offsets();
        let mut a = DMatrix::zeros(n, n);
        let mut g = DVector::zeros(n);
        for v in 0..self.views.len() {
            let (o, rows) = (offsets[v], offsets[v + 1] - offsets[v]);
            let p = ni + POSE_PARAMS * v;
            let jp = jac.view((o, p), (rows, POSE_PARAMS));
            let rv = r.rows(o, rows);
            a.view_mut((p, p), (POSE_PARAMS, POSE_PARAMS))
                .copy_from(&jp.tr_mul(&jp));
            g.rows_mut(p, POSE_PARAMS).copy_from(&jp.tr_mul(&rv));
            if ni > 0 {
                let ji = jac.view((o, 0), (rows, ni));
                let mut aii = a.view_mut((0, 0), (ni, ni));
                aii += ji.tr_mul(&ji);
                let aip = ji.tr_mul(&jp);
                a.view_mut((0, p), (ni, POSE_PARAMS)).copy_from(&aip);
                a.view_mut((p, 0), (POSE_PARAMS, ni))
                    .copy_from(&aip.transpose());
                let mut gi = g.rows_mut(0, ni);
                gi += ji.tr_mul(&rv);
            }
        }
        let base = offsets[self.views.len()];
        for k in 0..self.references.len() {
            let row = jac.row(base + k);
            a += row.transpose() * row;
            g += row.transpose() * r[base + k];
        }
        (a, g)
    }

    fn ref_at(&self, x: &DVector<f64>, k: usize) -> f64 {
        let rf = &self.references[k];
        self.reference_residual(&self.pose(x, rf.view_a), &self.pose(x, rf.view_b), rf)
    }
}
