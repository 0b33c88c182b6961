//! Block structure of the joint refinement's normal equations (method.md
//! §4 **beyond**): every image point's rows touch the intrinsics and its
//! own view's pose only, so `J^T J` is assembled per point into small
//! blocks and the pose blocks are eliminated by a Schur complement.

use nalgebra::{DMatrix, DVector, SMatrix};

use super::projection_jacobian::INTRINSIC_PARAMS;
use super::projection_jacobian::POSE_PARAMS;

/// Parameters one image point's rows depend on: the intrinsics, then its
/// view's pose.
const POINT_PARAMS: usize = INTRINSIC_PARAMS + POSE_PARAMS;

/// One view's share of `J^T J` and `J^T r` over `[intrinsics | pose]`:
/// a symmetric rank-2 update per point on the upper triangle only (the
/// hot loop of every LM iteration: ~17,000 points on the issue-4 campaign).
pub(crate) struct PointNormalAccumulator {
    upper: [[f64; POINT_PARAMS]; POINT_PARAMS],
    gradient: [f64; POINT_PARAMS],
}

impl Default for PointNormalAccumulator {
    fn default() -> Self {
        Self {
            upper: [[0.0; POINT_PARAMS]; POINT_PARAMS],
            gradient: [0.0; POINT_PARAMS],
        }
    }
}

impl PointNormalAccumulator {
    pub(crate) fn add(
        &mut self,
        ji: &SMatrix<f64, 2, INTRINSIC_PARAMS>,
        jp: &SMatrix<f64, 2, POSE_PARAMS>,
        r: [f64; 2],
    ) {
        let mut rows = [[0.0; POINT_PARAMS]; 2];
        for (k, row) in rows.iter_mut().enumerate() {
            for c in 0..INTRINSIC_PARAMS {
                row[c] = ji[(k, c)];
            }
            for c in 0..POSE_PARAMS {
                row[INTRINSIC_PARAMS + c] = jp[(k, c)];
            }
        }
        let [j0, j1] = rows;
        for a in 0..POINT_PARAMS {
            let (u, w) = (j0[a], j1[a]);
            let upper = &mut self.upper[a];
            for b in a..POINT_PARAMS {
                upper[b] += u * j0[b] + w * j1[b];
            }
            self.gradient[a] += u * r[0] + w * r[1];
        }
    }

    /// Add into the full normal matrix `a` and gradient `g`: the first
    /// `ni` intrinsics (the block's length) and the pose at `base`.
    pub(crate) fn write(&self, a: &mut DMatrix<f64>, g: &mut DVector<f64>, ni: usize, base: usize) {
        let h = |i: usize, j: usize| self.upper[i.min(j)][i.max(j)];
        for i in 0..ni {
            for j in 0..ni {
                a[(i, j)] += h(i, j);
            }
            for p in 0..POSE_PARAMS {
                let v = h(i, INTRINSIC_PARAMS + p);
                a[(i, base + p)] = v;
                a[(base + p, i)] = v;
            }
            g[i] += self.gradient[i];
        }
        for p in 0..POSE_PARAMS {
            for q in 0..POSE_PARAMS {
                a[(base + p, base + q)] = h(INTRINSIC_PARAMS + p, INTRINSIC_PARAMS + q);
            }
            g[base + p] = self.gradient[INTRINSIC_PARAMS + p];
        }
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::DVector;

    use crate::camera::refine::{IntrinsicsBlock, JointProblem};
    use crate::sim::point_views::{simulate_views, ViewCampaignSpec};
    use crate::solver::LeastSquaresProblem;

    /// Relative agreement of the blockwise and the dense computations.
    const TOL: f64 = 1e-9;

    #[test]
    fn blockwise_normal_equations_and_schur_inverse_match_dense() {
        let spec = ViewCampaignSpec {
            views: 4,
            ..ViewCampaignSpec::paper_752x582(9)
        };
        let sims = simulate_views(&spec).unwrap();
        let pairs: Vec<_> = sims.iter().map(|s| s.observations.pairs()).collect();
        let poses: Vec<_> = sims.iter().map(|s| s.camera_to_target).collect();
        for with_k3 in [false, true] {
            let problem = JointProblem {
                views: &pairs,
                block: IntrinsicsBlock::Free { with_k3 },
                references: &[],
                reference_weight: 0.0,
            };
            let mut intr = spec.intrinsics;
            intr.cx += 0.7;
            let x = problem.encode(&intr, &poses);
            let r = problem.residuals(&x).unwrap();
            let (a, g) = problem.normal_equations(&x, &r).unwrap();
            let jac = problem.jacobian(&x).unwrap();
            let (dense_a, dense_g) = (jac.tr_mul(&jac), jac.tr_mul(&r));
            assert!((&a - &dense_a).amax() <= TOL * dense_a.amax());
            assert!((&g - &dense_g).amax() <= TOL * dense_g.amax());
            let ni = problem.block.len();
            let blockwise = problem.intrinsics_inverse_normal(&a).unwrap();
            let dense = dense_a.clone().cholesky().unwrap().inverse();
            for i in 0..ni {
                for j in 0..ni {
                    let scale = (dense[(i, i)] * dense[(j, j)]).sqrt();
                    assert!((blockwise[(i, j)] - dense[(i, j)]).abs() <= 1e-6 * scale);
                }
            }
            // The Schur step solves the same system as the dense one.
            let step = problem.solve_normal(&a, &g).unwrap();
            let dense_step: DVector<f64> = dense_a.cholesky().unwrap().solve(&g);
            assert!((&step - &dense_step).amax() <= 1e-6 * dense_step.amax());
        }
    }
}
