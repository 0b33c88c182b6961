//! Block structure of the joint refinement's normal equations (method.md
//! §4 **beyond**): every image point's rows touch the intrinsics and its
//! own view's pose only, so `J^T J` is assembled per point into small
//! blocks of a block-arrowhead matrix ([`ArrowMatrix`]: intrinsics head,
//! one 6x6 pose block per view) whose pose blocks are eliminated by a
//! Schur complement.

use nalgebra::{DVector, SMatrix};

use crate::arrow::ArrowMatrix;

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

    /// Add into the arrowhead normal matrix `a` (head: the intrinsics,
    /// `a.head_len()` of them; tail: 6x6 pose blocks) and gradient `g`:
    /// this view's pose is tail block `view`.
    pub(crate) fn write(&self, a: &mut ArrowMatrix, g: &mut DVector<f64>, view: usize) {
        let h = |i: usize, j: usize| self.upper[i.min(j)][i.max(j)];
        let ni = a.head_len();
        let base = a.block_start(view);
        let head = a.head_mut();
        for i in 0..ni {
            for j in 0..ni {
                head[(i, j)] += h(i, j);
            }
            g[i] += self.gradient[i];
        }
        let coupling = a.coupling_mut(view);
        for i in 0..ni {
            for p in 0..POSE_PARAMS {
                coupling[(i, p)] = h(i, INTRINSIC_PARAMS + p);
            }
        }
        let block = a.block_mut(view);
        for p in 0..POSE_PARAMS {
            for q in 0..POSE_PARAMS {
                block[(p, q)] = h(INTRINSIC_PARAMS + p, INTRINSIC_PARAMS + q);
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
    use crate::solver::{LeastSquaresProblem, NormalMatrix};

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
            let (normal, g) = problem.normal_equations(&x, &r).unwrap();
            let NormalMatrix::Arrow(arrow) = &normal else {
                panic!("without reference distances the normal matrix is an arrowhead");
            };
            let a = arrow.to_dense();
            let jac = problem.jacobian(&x).unwrap();
            let (dense_a, dense_g) = (jac.tr_mul(&jac), jac.tr_mul(&r));
            assert!((&a - &dense_a).amax() <= TOL * dense_a.amax());
            assert!((&g - &dense_g).amax() <= TOL * dense_g.amax());
            let ni = problem.block.len();
            let blockwise = problem.intrinsics_inverse_normal(&normal).unwrap();
            let dense = dense_a.clone().cholesky().unwrap().inverse();
            for i in 0..ni {
                for j in 0..ni {
                    let scale = (dense[(i, i)] * dense[(j, j)]).sqrt();
                    assert!((blockwise[(i, j)] - dense[(i, j)]).abs() <= 1e-6 * scale);
                }
            }
            // The Schur step solves the same system as the dense one.
            let step = arrow.solve(&g).unwrap();
            let dense_step: DVector<f64> = dense_a.cholesky().unwrap().solve(&g);
            assert!((&step - &dense_step).amax() <= 1e-6 * dense_step.amax());
        }
    }
}
