//! The flange-pose bundle as a least-squares problem
//! ([`super::bundle_model`] holds its unknowns). Its normal equations are
//! assembled point by point from the analytic Jacobian rows and never
//! from the dense Jacobian (issue 12: memory flat in the number of poses):
//! without flange corrections they are the small dense head (at most 21
//! unknowns); with them a block arrowhead (head, one 6x6 block per pose)
//! that the solver eliminates by its Schur complement (`crate::schur`).

use nalgebra::{DMatrix, DVector, Matrix3, Matrix6, SMatrix, SVector, Vector2, Vector3, Vector6};

use super::bundle_model::{BundleFreedom, BundleModel, Pairs, BUNDLE_INTRINSICS, POSE_PARAMS};
use crate::arrow::ArrowMatrix;
use crate::camera::projection_jacobian::so3_left_jacobian;
use crate::geometry::{perturb_left, Pose};
use crate::kinematics::projection::{apply_intrinsics, project_with_jacobians};
use crate::normal_matrix::NormalMatrix;
use crate::solver::LeastSquaresProblem;

/// Most head unknowns: every intrinsic, two transforms, the board scale.
const MAX_HEAD: usize = BUNDLE_INTRINSICS + 2 * POSE_PARAMS + 1;
/// A point's two Jacobian rows over the head (columns past
/// [`Bundle::head`] stay zero).
type HeadRows = SMatrix<f64, 2, MAX_HEAD>;
/// A point's two Jacobian rows over its own view's flange correction.
type CorrectionRows = SMatrix<f64, 2, POSE_PARAMS>;

/// The least-squares problem about a reference model (module doc).
pub(super) struct Bundle<'a> {
    pub(super) views: &'a [(Pose, &'a Pairs)],
    pub(super) reference: BundleModel,
    pub(super) freedom: &'a BundleFreedom,
}

impl Bundle<'_> {
    fn ni(&self) -> usize {
        self.freedom.intrinsics.len()
    }

    /// Unknowns before the per-pose flange corrections.
    pub(super) fn head(&self) -> usize {
        self.ni() + 2 * POSE_PARAMS + usize::from(self.freedom.board_scale)
    }

    pub(super) fn corrections(&self) -> usize {
        match self.freedom.flange_weights {
            Some(_) => POSE_PARAMS * self.views.len(),
            None => 0,
        }
    }

    pub(super) fn params(&self) -> usize {
        self.head() + self.corrections()
    }

    pub(super) fn pixel_rows(&self) -> usize {
        2 * self.views.iter().map(|(_, p)| p.len()).sum::<usize>()
    }

    /// Flange pose of view `k` with its correction in `x` applied.
    pub(super) fn flange(&self, x: &DVector<f64>, k: usize) -> Pose {
        match self.freedom.flange_weights {
            Some(_) => perturb_left(
                &self.views[k].0,
                &Self::delta(x, self.head() + POSE_PARAMS * k),
            ),
            None => self.views[k].0,
        }
    }

    /// The prior rows `weights .* correction` of every view.
    fn prior(&self, x: &DVector<f64>) -> Vec<f64> {
        let Some(w) = self.freedom.flange_weights else {
            return Vec::new();
        };
        let h = self.head();
        (0..self.corrections())
            .map(|i| w[i % POSE_PARAMS] * x[h + i])
            .collect()
    }

    pub(super) fn delta(x: &DVector<f64>, at: usize) -> Vector6<f64> {
        Vector6::from_column_slice(&x.as_slice()[at..at + POSE_PARAMS])
    }

    pub(super) fn unpack(&self, x: &DVector<f64>) -> BundleModel {
        let mut d = [0.0; BUNDLE_INTRINSICS];
        for (k, &i) in self.freedom.intrinsics.iter().enumerate() {
            d[i] = x[k];
        }
        let ni = self.ni();
        let r = &self.reference;
        BundleModel {
            intrinsics: apply_intrinsics(&r.intrinsics, &d),
            target_to_base: perturb_left(&r.target_to_base, &Self::delta(x, ni)),
            flange_to_camera: perturb_left(&r.flange_to_camera, &Self::delta(x, ni + POSE_PARAMS)),
            board_scale: r.board_scale
                + if self.freedom.board_scale {
                    x[ni + 2 * POSE_PARAMS]
                } else {
                    0.0
                },
        }
    }
}

/// `[I, -[c - t]x J; 0, J]`-style map from a transform's parameters to the
/// left perturbation of `target_to_camera` (see [`Bundle::visit_point_rows`]).
fn block(top_left: Matrix3<f64>, top_right: Matrix3<f64>, bottom: Matrix3<f64>) -> Matrix6<f64> {
    let mut m = Matrix6::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&top_left);
    m.fixed_view_mut::<3, 3>(0, 3).copy_from(&top_right);
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(&bottom);
    m
}

impl Bundle<'_> {
    /// Visit the two analytic Jacobian rows of every point, view by view:
    /// `visit(view, first residual row, head columns, the view's correction
    /// columns)`, the last present with flange weights.
    ///
    /// With `C = T M` (`M = B_k X`), moving `T` by `(dt, dr)` moves `C` by
    /// `dt - [C_t - T_t]x dr` and `dr`; moving `X` by `(dt, dr)` moves `C`
    /// by `A_R dt`, `A_R dr` (`A = T B_k`). Rotation parameters enter
    /// through the SO(3) left Jacobian at their current value. The board
    /// scale moves each target point along itself. A flange correction
    /// `(dt, dr)` moves `C` by `T_R dt - T_R [B_R X_t]x dr` and `T_R dr`.
    pub(super) fn visit_point_rows(
        &self,
        x: &DVector<f64>,
        mut visit: impl FnMut(usize, usize, &HeadRows, Option<&CorrectionRows>),
    ) -> Option<()> {
        let model = self.unpack(x);
        let ni = self.ni();
        let (ot, ox) = (ni, ni + POSE_PARAMS);
        let rot = |at: usize| so3_left_jacobian(&Vector3::new(x[at + 3], x[at + 4], x[at + 5]));
        let (jl_t, jl_x) = (rot(ot), rot(ox));
        let t_t = model.target_to_base.translation.vector;
        let t_r = model
            .target_to_base
            .rotation
            .to_rotation_matrix()
            .into_inner();
        let x_t = model.flange_to_camera.translation.vector;
        let mut row = 0;
        let mut head = HeadRows::zeros();
        for (view, (_, pairs)) in self.views.iter().enumerate() {
            let b = self.flange(x, view);
            let ob = self.head() + POSE_PARAMS * view;
            let m_b = self.freedom.flange_weights.map(|_| {
                let jl_b = rot(ob);
                let b_r = b.rotation.to_rotation_matrix().into_inner();
                block(t_r, -t_r * (b_r * x_t).cross_matrix() * jl_b, t_r * jl_b)
            });
            let a = model.target_to_base * b;
            let c = a * model.flange_to_camera;
            let a_r = a.rotation.to_rotation_matrix().into_inner();
            let m_t = block(
                Matrix3::identity(),
                -(c.translation.vector - t_t).cross_matrix() * jl_t,
                jl_t,
            );
            let m_x = block(a_r, Matrix3::zeros(), a_r * jl_x);
            for (p0, _) in pairs.iter() {
                let p = p0 * model.board_scale;
                let (_, jp, jc) = project_with_jacobians(&model.intrinsics, &c, &p)?;
                for (k, &i) in self.freedom.intrinsics.iter().enumerate() {
                    head.set_column(k, &jc.column(i));
                }
                head.fixed_view_mut::<2, POSE_PARAMS>(0, ot)
                    .copy_from(&(jp * m_t));
                head.fixed_view_mut::<2, POSE_PARAMS>(0, ox)
                    .copy_from(&(jp * m_x));
                if self.freedom.board_scale {
                    // d uv / d P_target = -(translation columns of jp).
                    let d = -(jp.fixed_view::<2, 3>(0, 0) * p0.coords);
                    head.set_column(ox + POSE_PARAMS, &d);
                }
                let correction = m_b.map(|m_b| jp * m_b);
                visit(view, row, &head, correction.as_ref());
                row += 2;
            }
        }
        Some(())
    }
}

impl LeastSquaresProblem for Bundle<'_> {
    fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
        let model = self.unpack(x);
        let mut r = Vec::with_capacity(self.pixel_rows() + self.corrections());
        for (k, (_, pairs)) in self.views.iter().enumerate() {
            r.extend(model.view_residuals(&self.flange(x, k), pairs)?);
        }
        r.extend(self.prior(x));
        Some(DVector::from_vec(r))
    }

    /// The dense Jacobian: the solver does not ask for it (see
    /// [`Self::normal_equations`]); it is what the tests check the rows
    /// against finite differences with.
    fn jacobian(&self, x: &DVector<f64>) -> Option<DMatrix<f64>> {
        let h = self.head();
        let mut jac = DMatrix::zeros(self.pixel_rows() + self.corrections(), self.params());
        self.visit_point_rows(x, |view, row, head, correction| {
            jac.view_mut((row, 0), (2, h))
                .copy_from(&head.columns(0, h));
            if let Some(c) = correction {
                jac.view_mut((row, h + POSE_PARAMS * view), (2, POSE_PARAMS))
                    .copy_from(c);
            }
        })?;
        if let Some(w) = self.freedom.flange_weights {
            let row = self.pixel_rows();
            for i in 0..self.corrections() {
                jac[(row + i, h + i)] = w[i % POSE_PARAMS];
            }
        }
        Some(jac)
    }

    /// `(J^T J, J^T r)` point by point: the dense head alone without flange
    /// corrections, else the block arrowhead whose tail blocks are the
    /// per-pose corrections (their prior rows add `w^2` on the diagonal).
    fn normal_equations(
        &self,
        x: &DVector<f64>,
        r: &DVector<f64>,
    ) -> Option<(NormalMatrix, DVector<f64>)> {
        let h = self.head();
        let views = self.views.len();
        let mut a_hh = SMatrix::<f64, MAX_HEAD, MAX_HEAD>::zeros();
        let mut g_h = SVector::<f64, MAX_HEAD>::zeros();
        let corrected = self.freedom.flange_weights.is_some();
        let tail = if corrected { views } else { 0 };
        let mut a_hk = vec![SMatrix::<f64, MAX_HEAD, POSE_PARAMS>::zeros(); tail];
        let mut a_kk = vec![Matrix6::<f64>::zeros(); tail];
        let mut g_k = vec![Vector6::<f64>::zeros(); tail];
        self.visit_point_rows(x, |view, row, head, correction| {
            let r2 = Vector2::new(r[row], r[row + 1]);
            a_hh += head.tr_mul(head);
            g_h += head.tr_mul(&r2);
            if let Some(c) = correction {
                a_hk[view] += head.tr_mul(c);
                a_kk[view] += c.tr_mul(c);
                g_k[view] += c.tr_mul(&r2);
            }
        })?;
        let mut g = DVector::zeros(self.params());
        g.rows_mut(0, h).copy_from(&g_h.rows(0, h));
        let head = DMatrix::from_fn(h, h, |i, j| a_hh[(i, j)]);
        let Some(w) = self.freedom.flange_weights else {
            return Some((head.into(), g));
        };
        let prior_row = self.pixel_rows();
        let mut a = ArrowMatrix::zeros(h, POSE_PARAMS, views);
        *a.head_mut() = head;
        for k in 0..views {
            for i in 0..POSE_PARAMS {
                let at = POSE_PARAMS * k + i;
                a_kk[k][(i, i)] += w[i] * w[i];
                g_k[k][i] += w[i] * r[prior_row + at];
            }
            a.coupling_mut(k).copy_from(&a_hk[k].rows(0, h));
            a.block_mut(k).copy_from(&a_kk[k]);
            g.rows_mut(h + POSE_PARAMS * k, POSE_PARAMS)
                .copy_from(&g_k[k]);
        }
        Some((a.into(), g))
    }
}
