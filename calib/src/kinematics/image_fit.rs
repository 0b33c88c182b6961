//! The joint refinement's least-squares problem (method.md §6 **beyond**,
//! see [`super::joint_refine`]): residuals of every dot of every image,
//! weighted by the dot noise, and the priors of the per-pose joint
//! corrections; the analytic Jacobian and the normal equations assembled
//! per pose from 6x6 sums over its dots, as a block arrowhead (head: the
//! kinematics and intrinsics; one block per pose: its joint corrections).
//!
//! Several board placements (sessions, the paper's regions, method.md §7):
//! pose `k` sees the board of session `session_of[k]`; session 0's
//! `target_to_base` is the layout's, every further session has its own
//! copy of the free base values in the head, after the layout's free
//! values. Kinematics, hand–eye and intrinsics stay shared.
//!
//! Non-geometric terms (issue 19, method.md §6 "beyond"): with
//! [`ImageTerms`] each term's value is an unknown of the head after the
//! base values; it deflects its joint by `value · f(q)` before the chain, so
//! its column is that joint's `dθ` column times the pose's basis value.

use nalgebra::{DMatrix, DVector, Matrix6, SMatrix};

use super::image_pose::{ImageNoise, ImagePose};
use super::jacobian::tool_pose_jacobian;
use super::nongeometric::NonGeometric;
use super::params::{CalibratedModel, ParamKind, ParamLayout};
use super::prior::PriorRows;
use super::projection::{apply_intrinsics, project_with_jacobians, INTRINSIC_NAMES};
use crate::arrow::ArrowMatrix;
use crate::camera::model::Intrinsics;
use crate::geometry::{perturb_left, Pose};
use crate::solver::{LeastSquaresProblem, NormalMatrix};

/// Intrinsic parameters refined with the kinematics.
pub(super) const INTRINSICS: usize = INTRINSIC_NAMES.len();

pub(super) struct ImageFit<'a> {
    pub(super) layout: &'a ParamLayout,
    pub(super) reference: &'a CalibratedModel,
    pub(super) intrinsics: &'a Intrinsics,
    pub(super) free: &'a [usize],
    pub(super) poses: &'a [ImagePose],
    pub(super) noise: ImageNoise,
    /// The intrinsics are held at `intrinsics` (a reused camera).
    pub(super) hold_intrinsics: bool,
    /// Reference `target_to_base` of sessions 1.. (empty: one session).
    pub(super) extra_bases: &'a [Pose],
    /// Session of each pose (empty: every pose in session 0).
    pub(super) session_of: &'a [usize],
    /// Non-geometric terms fitted with the geometry (`None`: geometry only).
    pub(super) terms: Option<ImageTerms<'a>>,
    /// Priors on the free layout values (`None`: maximum likelihood), one
    /// pseudo-observation each after every other residual (method.md §6
    /// "Priors", [`super::prior`]).
    pub(super) prior: Option<&'a PriorRows>,
}

/// The terms an image-level fit refines: their starting values (`x` adds
/// to them) and each pose's basis values `f_t(q_k)` (fixed: the bases are
/// evaluated on the terms' own fixed chain at the recorded joints).
#[derive(Debug, Clone, Copy)]
pub(super) struct ImageTerms<'a> {
    pub(super) terms: &'a NonGeometric,
    /// `bases[k][t]`: term `t`'s basis at pose `k`.
    pub(super) bases: &'a [Vec<f64>],
}

/// One pose's linearisation: the tool-pose Jacobian's free and joint
/// columns, and the sums over its dots in the 6-D pose perturbation.
struct PoseBlock {
    t_free: DMatrix<f64>,
    t_joint: DMatrix<f64>,
    h_pp: Matrix6<f64>,
    h_pc: SMatrix<f64, 6, INTRINSICS>,
    h_cc: SMatrix<f64, INTRINSICS, INTRINSICS>,
    g_p: nalgebra::Vector6<f64>,
    g_c: SMatrix<f64, INTRINSICS, 1>,
}

impl ImageFit<'_> {
    /// Intrinsic parameters in the unknowns: none when held.
    pub(super) fn ni(&self) -> usize {
        if self.hold_intrinsics {
            0
        } else {
            INTRINSICS
        }
    }

    pub(super) fn joints(&self) -> usize {
        if self.noise.joint_sigma_rad() > 0.0 {
            self.layout.joints()
        } else {
            0
        }
    }

    /// Positions in `free` of the free base values (each further session
    /// has one value per position).
    pub(super) fn base_slots(&self) -> Vec<usize> {
        (0..self.free.len())
            .filter(|&k| matches!(self.layout.params[self.free[k]].kind, ParamKind::Base(_)))
            .collect()
    }

    /// Position in `x` of the first term value.
    pub(super) fn term_start(&self) -> usize {
        self.free.len() + self.base_slots().len() * self.extra_bases.len()
    }

    /// Number of term values among the unknowns.
    pub(super) fn nt(&self) -> usize {
        self.terms.map_or(0, |t| t.terms.terms.len())
    }

    /// Kinematic unknowns: the layout's free values, the further sessions'
    /// base values, then the term values.
    pub(super) fn nk(&self) -> usize {
        self.term_start() + self.nt()
    }

    /// The terms with their values at `x` (`None`: geometry only).
    pub(super) fn terms_at(&self, x: &DVector<f64>) -> Option<NonGeometric> {
        let t = self.terms?;
        let start = self.term_start();
        let mut out = t.terms.clone();
        for (k, v) in out.values.iter_mut().enumerate() {
            *v += x[start + k];
        }
        Some(out)
    }

    fn session(&self, k: usize) -> usize {
        self.session_of.get(k).copied().unwrap_or(0)
    }

    /// Session 0's model and the intrinsics at `x`.
    pub(super) fn unpack(&self, x: &DVector<f64>) -> (CalibratedModel, Intrinsics) {
        let mut full = DVector::zeros(self.layout.len());
        for (k, &i) in self.free.iter().enumerate() {
            full[i] = x[k];
        }
        let nk = self.nk();
        let cam = match self.ni() {
            0 => *self.intrinsics,
            ni => apply_intrinsics(self.intrinsics, &x.as_slice()[nk..nk + ni]),
        };
        (self.layout.apply(self.reference, &full), cam)
    }

    /// `target_to_base` of every session at `x` (session 0 first).
    pub(super) fn session_bases(&self, x: &DVector<f64>, model: &CalibratedModel) -> Vec<Pose> {
        let slots = self.base_slots();
        let nf = self.free.len();
        let mut bases = vec![model.world_to_base];
        for (s, reference) in self.extra_bases.iter().enumerate() {
            let mut v = nalgebra::Vector6::zeros();
            for (j, &k) in slots.iter().enumerate() {
                if let ParamKind::Base(c) = self.layout.params[self.free[k]].kind {
                    v[c] = x[nf + s * slots.len() + j];
                }
            }
            bases.push(perturb_left(reference, &v));
        }
        bases
    }

    /// `model` moved to the board of pose `k`'s session.
    fn pose_model(&self, model: &CalibratedModel, bases: &[Pose], k: usize) -> CalibratedModel {
        CalibratedModel {
            world_to_base: bases[self.session(k)],
            ..model.clone()
        }
    }

    /// Joints of pose `k` as the chain sees them: deflected by the terms
    /// at `x`, with the pose's correction in `x` applied.
    fn pose_joints(&self, x: &DVector<f64>, k: usize) -> Vec<f64> {
        let q = &self.poses[k].joints_rad;
        let nj = self.joints();
        let start = self.head() + k * nj;
        let mut out: Vec<f64> = (0..q.len())
            .map(|j| q[j] + if j < nj { x[start + j] } else { 0.0 })
            .collect();
        if let Some(t) = self.terms {
            let first = self.term_start();
            for (i, kind) in t.terms.terms.iter().enumerate() {
                if let Some(qj) = out.get_mut(kind.joint()) {
                    *qj += (t.terms.values[i] + x[first + i]) * t.bases[k][i];
                }
            }
        }
        out
    }

    pub(super) fn image_rows(&self) -> usize {
        2 * self
            .poses
            .iter()
            .map(|p| p.observations.len())
            .sum::<usize>()
    }

    /// Unknowns before the joint corrections: kinematics, then intrinsics.
    pub(super) fn head(&self) -> usize {
        self.nk() + self.ni()
    }

    pub(super) fn params(&self) -> usize {
        self.head() + self.poses.len() * self.joints()
    }

    /// Pose `k` linearised at `x`; `per_dot` sees each dot's weighted
    /// Jacobians (pose, intrinsics) in order.
    fn linearise_pose(
        &self,
        x: &DVector<f64>,
        model: &CalibratedModel,
        cam: &Intrinsics,
        k: usize,
        mut per_dot: impl FnMut(&SMatrix<f64, 2, 6>, &SMatrix<f64, 2, 8>),
    ) -> Option<PoseBlock> {
        let q = self.pose_joints(x, k);
        let (t2c, jt) = tool_pose_jacobian(self.layout, model, &q).ok()?;
        let offsets = self.layout.joint_offset_indices();
        let mut t_free = DMatrix::zeros(6, self.nk());
        for (c, &i) in self.free.iter().enumerate() {
            t_free.set_column(c, &jt.column(i));
        }
        let session = self.session(k);
        if session > 0 {
            // This board's base values move it, not session 0's.
            let slots = self.base_slots();
            let first = self.free.len() + (session - 1) * slots.len();
            for (j, &c) in slots.iter().enumerate() {
                t_free.set_column(first + j, &jt.column(self.free[c]));
                t_free.column_mut(c).fill(0.0);
            }
        }
        if let Some(t) = self.terms {
            let first = self.term_start();
            for (i, kind) in t.terms.terms.iter().enumerate() {
                let column = jt.column(offsets[kind.joint()]) * t.bases[k][i];
                t_free.set_column(first + i, &column);
            }
        }
        let mut block = PoseBlock {
            t_free,
            t_joint: DMatrix::from_fn(6, self.joints(), |r, c| jt[(r, offsets[c])]),
            h_pp: Matrix6::zeros(),
            h_pc: SMatrix::zeros(),
            h_cc: SMatrix::zeros(),
            g_p: nalgebra::Vector6::zeros(),
            g_c: SMatrix::zeros(),
        };
        let s = self.noise.sigma_px;
        for (p, uv) in &self.poses[k].observations {
            let (pred, jp, jc) = project_with_jacobians(cam, &t2c, p)?;
            let (jp, jc) = (jp / s, jc / s);
            let r = nalgebra::Vector2::new((pred.x - uv.x) / s, (pred.y - uv.y) / s);
            per_dot(&jp, &jc);
            block.h_pp += jp.transpose() * jp;
            block.h_pc += jp.transpose() * jc;
            block.h_cc += jc.transpose() * jc;
            block.g_p += jp.transpose() * r;
            block.g_c += jc.transpose() * r;
        }
        Some(block)
    }

    /// `J^T J` and `J^T r` from each pose's 6-D sums (module doc): a
    /// block arrowhead whose tail blocks are the poses' joint corrections
    /// (the solver eliminates them by the Schur complement); without joint
    /// corrections only the head.
    pub(super) fn arrow_normal_equations(
        &self,
        x: &DVector<f64>,
    ) -> Option<(ArrowMatrix, DVector<f64>)> {
        let (model, cam) = self.unpack(x);
        let bases = self.session_bases(x, &model);
        let (nf, nj, ni, n) = (self.nk(), self.joints(), self.ni(), self.params());
        let poses_with_blocks = if nj > 0 { self.poses.len() } else { 0 };
        let mut a = ArrowMatrix::zeros(self.head(), nj, poses_with_blocks);
        let mut g = DVector::zeros(n);
        let prior = self.prior(x);
        let c0 = nf;
        for k in 0..self.poses.len() {
            let pose_model = self.pose_model(&model, &bases, k);
            let b = self.linearise_pose(x, &pose_model, &cam, k, |_, _| {})?;
            let hf = b.h_pp * &b.t_free;
            let head = a.head_mut();
            let mut add = |r0: usize, c0: usize, m: &DMatrix<f64>| {
                let mut v = head.view_mut((r0, c0), (m.nrows(), m.ncols()));
                v += m;
            };
            add(0, 0, &(b.t_free.transpose() * &hf));
            // Held intrinsics (ni = 0) drop out of every block.
            let h_pc = DMatrix::from_column_slice(6, INTRINSICS, b.h_pc.as_slice())
                .columns(0, ni)
                .into_owned();
            let kc = b.t_free.transpose() * &h_pc;
            add(0, c0, &kc);
            add(c0, 0, &kc.transpose());
            let h_cc = DMatrix::from_column_slice(INTRINSICS, INTRINSICS, b.h_cc.as_slice());
            add(c0, c0, &h_cc.view((0, 0), (ni, ni)).into_owned());
            let gp = DVector::from_column_slice(b.g_p.as_slice());
            let mut gk = g.rows_mut(0, nf);
            gk += b.t_free.transpose() * &gp;
            let mut gc = g.rows_mut(c0, ni);
            gc += DVector::from_column_slice(&b.g_c.as_slice()[..ni]);
            if nj > 0 {
                let q0 = a.block_start(k);
                let hj = b.h_pp * &b.t_joint;
                let coupling = a.coupling_mut(k);
                coupling
                    .rows_mut(0, nf)
                    .copy_from(&(b.t_free.transpose() * &hj));
                coupling
                    .rows_mut(c0, ni)
                    .copy_from(&(h_pc.transpose() * &b.t_joint));
                let prior_weight = self.noise.joint_sigma_rad().powi(-2);
                let qq = b.t_joint.transpose() * &hj + DMatrix::identity(nj, nj) * prior_weight;
                a.block_mut(k).copy_from(&qq);
                let mut gq = g.rows_mut(q0, nj);
                gq += b.t_joint.transpose() * &gp
                    + prior.rows(k * nj, nj) / self.noise.joint_sigma_rad();
            }
        }
        if let Some(p) = self.prior {
            let head = a.head_mut();
            for k in 0..p.len().min(self.free.len()) {
                head[(k, k)] += p.weight[k] * p.weight[k];
                g[k] += p.weight[k] * p.residual(k, x[k]);
            }
        }
        Some((a, g))
    }

    /// Rows of the kinematic prior's pseudo-observations (0 without one).
    pub(super) fn prior_rows(&self) -> usize {
        self.prior.map_or(0, |p| p.len().min(self.free.len()))
    }

    /// The prior residuals `e / sigma_q` of every joint correction.
    fn prior(&self, x: &DVector<f64>) -> DVector<f64> {
        let start = self.head();
        DVector::from_fn(self.poses.len() * self.joints(), |i, _| {
            x[start + i] / self.noise.joint_sigma_rad()
        })
    }
}

impl LeastSquaresProblem for ImageFit<'_> {
    fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
        let (model, cam) = self.unpack(x);
        let bases = self.session_bases(x, &model);
        let prior = self.prior(x);
        let mut r = DVector::zeros(self.image_rows() + prior.len() + self.prior_rows());
        let mut row = 0;
        for (k, pose) in self.poses.iter().enumerate() {
            let inv = self
                .pose_model(&model, &bases, k)
                .world_to_tool(&self.pose_joints(x, k))
                .ok()?
                .inverse();
            for (p, uv) in &pose.observations {
                let pred = cam.project(&(inv * p))?;
                r[row] = (pred.x - uv.x) / self.noise.sigma_px;
                r[row + 1] = (pred.y - uv.y) / self.noise.sigma_px;
                row += 2;
            }
        }
        r.rows_mut(row, prior.len()).copy_from(&prior);
        row += prior.len();
        if let Some(p) = self.prior {
            for k in 0..self.prior_rows() {
                r[row + k] = p.residual(k, x[k]);
            }
        }
        Some(r)
    }

    /// The dense Jacobian (`O(rows x poses)`: the solver uses
    /// [`Self::normal_equations`] instead; this is the reference they are
    /// tested against).
    fn jacobian(&self, x: &DVector<f64>) -> Option<DMatrix<f64>> {
        let (model, cam) = self.unpack(x);
        let bases = self.session_bases(x, &model);
        let (nf, nj, ni) = (self.nk(), self.joints(), self.ni());
        let mut jac = DMatrix::zeros(
            self.image_rows() + self.poses.len() * nj + self.prior_rows(),
            self.params(),
        );
        let mut row = 0;
        for k in 0..self.poses.len() {
            let mut dots = Vec::new();
            let pose_model = self.pose_model(&model, &bases, k);
            let block = self.linearise_pose(x, &pose_model, &cam, k, |jp, jc| {
                dots.push((*jp, *jc));
            })?;
            for (jp, jc) in dots {
                let jp = DMatrix::from_column_slice(2, 6, jp.as_slice());
                jac.view_mut((row, 0), (2, nf))
                    .copy_from(&(&jp * &block.t_free));
                jac.view_mut((row, nf), (2, ni))
                    .copy_from(&jc.columns(0, ni));
                jac.view_mut((row, nf + ni + k * nj), (2, nj))
                    .copy_from(&(&jp * &block.t_joint));
                row += 2;
            }
        }
        for i in 0..self.poses.len() * nj {
            jac[(row + i, nf + ni + i)] = 1.0 / self.noise.joint_sigma_rad();
        }
        row += self.poses.len() * nj;
        if let Some(p) = self.prior {
            for k in 0..self.prior_rows() {
                jac[(row + k, k)] = p.weight[k];
            }
        }
        Some(jac)
    }

    /// [`ImageFit::arrow_normal_equations`].
    fn normal_equations(
        &self,
        x: &DVector<f64>,
        _residuals: &DVector<f64>,
    ) -> Option<(NormalMatrix, DVector<f64>)> {
        let (a, g) = self.arrow_normal_equations(x)?;
        Some((a.into(), g))
    }
}
