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
use super::normal_blocks::PointNormalAccumulator;
use super::projection_jacobian::{projection_jacobian_at, PoseLinearisation};
use crate::arrow::ArrowMatrix;
use crate::geometry::{pose_from_vector, pose_to_vector};
use crate::solver::{LeastSquaresProblem, NormalMatrix, FINITE_DIFFERENCE_STEP};

pub use super::projection_jacobian::POSE_PARAMS;

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

    /// Assembled point by point from the analytic projection Jacobian,
    /// never forming the dense (mostly zero) Jacobian, into a block
    /// arrowhead (intrinsics head, one 6x6 pose block per view) that the
    /// solver eliminates by its Schur complement: memory and time linear
    /// in the number of views. Reference-distance rows couple two poses,
    /// so with them the matrix is dense (their campaigns are small).
    fn normal_equations(
        &self,
        x: &DVector<f64>,
        r: &DVector<f64>,
    ) -> Option<(NormalMatrix, DVector<f64>)> {
        let n = x.len();
        let ni = self.block.len();
        let offsets = self.row_offsets();
        let intr = self.intrinsics(x);
        let mut a = ArrowMatrix::zeros(ni, POSE_PARAMS, self.views.len());
        let mut g = DVector::zeros(n);
        for (v, obs) in self.views.iter().enumerate() {
            let base = ni + POSE_PARAMS * v;
            let pose = PoseLinearisation::new(&Vector6::from_column_slice(
                &x.as_slice()[base..base + POSE_PARAMS],
            ));
            let mut acc = PointNormalAccumulator::default();
            for (i, (p, _)) in obs.iter().enumerate() {
                let (ji, jp) = projection_jacobian_at(&intr, &pose, p)?;
                // Residual = observed - projected: J = -d projection, so
                // J^T r = d projection^T (-r).
                let row = offsets[v] + 2 * i;
                acc.add(&ji, &jp, [-r[row], -r[row + 1]]);
            }
            acc.write(&mut a, &mut g, v);
        }
        if self.references.is_empty() {
            return Some((a.into(), g));
        }
        let mut a = a.to_dense();
        let base = offsets[self.views.len()];
        let jac = self.reference_jacobian(x);
        for k in 0..self.references.len() {
            let row = jac.row(k);
            a += row.transpose() * row;
            g += row.transpose() * r[base + k];
        }
        Some((a.into(), g))
    }

    /// Analytic image rows ([`projection_jacobian_at`]): intrinsics touch
    /// every image row, a pose only its own image's rows; the few
    /// reference-distance rows by central differences.
    fn jacobian(&self, x: &DVector<f64>) -> Option<DMatrix<f64>> {
        let offsets = self.row_offsets();
        let n_img_rows = offsets[self.views.len()];
        let n_rows = n_img_rows + self.references.len();
        let ni = self.block.len();
        let mut jac = DMatrix::zeros(n_rows, x.len());
        let intr = self.intrinsics(x);
        for (v, obs) in self.views.iter().enumerate() {
            let base = ni + POSE_PARAMS * v;
            let pose = PoseLinearisation::new(&Vector6::from_column_slice(
                &x.as_slice()[base..base + POSE_PARAMS],
            ));
            for (i, (p, _)) in obs.iter().enumerate() {
                let (ji, jp) = projection_jacobian_at(&intr, &pose, p)?;
                let row = offsets[v] + 2 * i;
                for k in 0..2 {
                    // Residual = observed - projected.
                    for j in 0..ni {
                        jac[(row + k, j)] = -ji[(k, j)];
                    }
                    for j in 0..POSE_PARAMS {
                        jac[(row + k, base + j)] = -jp[(k, j)];
                    }
                }
            }
        }
        let refs = self.reference_jacobian(x);
        for k in 0..self.references.len() {
            jac.row_mut(n_img_rows + k).copy_from(&refs.row(k));
        }
        Some(jac)
    }
}

impl JointProblem<'_> {
    /// `(J^T J)^-1` restricted to the intrinsics, from the normal matrix
    /// `a` ([`Self::normal_equations`]'): the inverse of the Schur
    /// complement of the pose blocks, so the full (intrinsics + 6 per view)
    /// matrix is never formed nor inverted. With reference rows (poses
    /// coupled, a dense `a`) the dense inverse.
    pub fn intrinsics_inverse_normal(&self, a: &NormalMatrix) -> Option<DMatrix<f64>> {
        let ni = self.block.len();
        match a {
            NormalMatrix::Arrow(a) => Some(a.invert()?.head),
            NormalMatrix::Dense(a) => {
                let inv = a.clone().cholesky()?.inverse();
                Some(inv.view((0, 0), (ni, ni)).into_owned())
            }
        }
    }

    /// Rows of the reference-distance residuals (central differences over
    /// the two poses involved).
    fn reference_jacobian(&self, x: &DVector<f64>) -> DMatrix<f64> {
        let ni = self.block.len();
        let mut jac = DMatrix::zeros(self.references.len(), x.len());
        let mut probe = x.clone();
        for (k, rf) in self.references.iter().enumerate() {
            for view in [rf.view_a, rf.view_b] {
                for c in 0..POSE_PARAMS {
                    let j = ni + POSE_PARAMS * view + c;
                    let h = FINITE_DIFFERENCE_STEP * x[j].abs().max(1.0);
                    probe[j] = x[j] + h;
                    let plus = self.ref_at(&probe, k);
                    probe[j] = x[j] - h;
                    let minus = self.ref_at(&probe, k);
                    probe[j] = x[j];
                    jac[(k, j)] = (plus - minus) / (2.0 * h);
                }
            }
        }
        jac
    }

    fn ref_at(&self, x: &DVector<f64>, k: usize) -> f64 {
        let rf = &self.references[k];
        self.reference_residual(&self.pose(x, rf.view_a), &self.pose(x, rf.view_b), rf)
    }
}
