//! The flange-pose bundle (method.md §4 **beyond**, §6): every board point
//! of every image predicted through
//! `target_to_camera_k = target_to_base * base_to_flange_k * flange_to_camera`
//! with the flange poses held as given, and the unknowns
//! `[intrinsics (free subset of kinematics::projection::INTRINSIC_NAMES);
//! target_to_base (6); flange_to_camera (6); board scale (optional, 1)]`.
//!
//! Both transforms move by [`perturb_left`] (translation added, rotation
//! `exp(dr) R` in the outer frame), the same convention as the kinematic
//! identification, so their covariance is in `geometry::pose_error`'s
//! coordinates. The board scale multiplies the nominal board coordinates: a
//! printed pitch that differs from the configured one is observable because
//! the flange translations are in millimetres. The Jacobian is analytic,
//! reusing [`project_with_jacobians`]; the problem is small and dense
//! (at most 21 unknowns), so the solver's own dense path is used.

use nalgebra::{DMatrix, DVector, Matrix3, Matrix6, Point2, Point3, SMatrix, Vector3, Vector6};

use super::redundancy::components;
pub use super::redundancy::VarianceComponents;
use crate::camera::model::Intrinsics;
use crate::camera::projection_jacobian::so3_left_jacobian;
use crate::covariance::covariance_from_normal;
use crate::geometry::{perturb_left, Pose};
use crate::kinematics::projection::{apply_intrinsics, project_with_jacobians, INTRINSIC_NAMES};
use crate::schur::schur_solve;
use crate::solver::{solve, LeastSquaresProblem, LmOptions, LmReport, SolverError};

/// Number of intrinsics the bundle can refine (k3 stays at its start).
pub const BUNDLE_INTRINSICS: usize = INTRINSIC_NAMES.len();
/// Indices (into [`INTRINSIC_NAMES`]) of the pinhole part.
pub const PINHOLE_INTRINSICS: [usize; 4] = [0, 1, 2, 3];
/// Unknowns of one rigid transform.
const POSE_PARAMS: usize = 6;

/// `(target point mm, observed pixel)` pairs of one image.
pub type Pairs = [(Point3<f64>, Point2<f64>)];

/// The unknowns of the bundle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BundleModel {
    pub intrinsics: Intrinsics,
    /// The robot base in the board frame (`p_target = target_to_base * p_base`).
    pub target_to_base: Pose,
    /// The camera in the flange frame: the hand–eye transform.
    pub flange_to_camera: Pose,
    /// True board coordinates = `board_scale` x the nominal ones.
    pub board_scale: f64,
}

impl BundleModel {
    /// `target_to_camera` of a view with flange pose `base_to_flange`.
    pub fn target_to_camera(&self, base_to_flange: &Pose) -> Pose {
        self.target_to_base * base_to_flange * self.flange_to_camera
    }

    /// Per-point image residuals `predicted - observed` of one view (px),
    /// stacked `[du, dv]`; `None` if a point falls behind the camera.
    pub fn view_residuals(&self, base_to_flange: &Pose, pairs: &Pairs) -> Option<Vec<f64>> {
        let camera_to_target = self.target_to_camera(base_to_flange).inverse();
        let mut out = Vec::with_capacity(2 * pairs.len());
        for (p, uv) in pairs {
            let pred = self
                .intrinsics
                .project(&(camera_to_target * (p * self.board_scale)))?;
            out.push(pred.x - uv.x);
            out.push(pred.y - uv.y);
        }
        Some(out)
    }

    /// RMS reprojection of one view (px, `sqrt(mean |r|^2)` per point);
    /// infinite when a point falls behind the camera.
    pub fn view_rms_px(&self, base_to_flange: &Pose, pairs: &Pairs) -> f64 {
        match self.view_residuals(base_to_flange, pairs) {
            Some(r) if !pairs.is_empty() => {
                (r.iter().map(|v| v * v).sum::<f64>() / pairs.len() as f64).sqrt()
            }
            _ => f64::INFINITY,
        }
    }
}

/// Which unknowns the bundle refines.
#[derive(Debug, Clone, PartialEq)]
pub struct BundleFreedom {
    /// Indices into [`INTRINSIC_NAMES`] of the refined intrinsics.
    pub intrinsics: Vec<usize>,
    /// Refine the board scale (settles a doubtful printed pitch).
    pub board_scale: bool,
    /// Errors in the flange poses (errors-in-variables): each pose gets a
    /// 6-D left correction with a Gaussian prior, whose residual rows are
    /// `weights .* correction` with `weights = sigma_px / sigma_flange`
    /// (`[t mm; r rad]`). `None` holds the flange poses exact.
    pub flange_weights: Option<Vector6<f64>>,
}

/// A converged bundle with its covariance.
#[derive(Debug, Clone)]
pub struct BundleFit {
    pub model: BundleModel,
    pub freedom: BundleFreedom,
    /// Covariance of `[free intrinsics; target_to_base (6); flange_to_camera
    /// (6); board scale?]` at the solution, transforms in the
    /// `pose_error` coordinates (mm, rad), scaled by the residual variance.
    pub covariance: DMatrix<f64>,
    /// Point residual standard deviation per image axis (px).
    pub sigma_px: f64,
    /// RMS reprojection over all used points (px, per point).
    pub rms_px: f64,
    pub points: usize,
    pub iterations: usize,
    /// The fitted flange corrections (zero without `flange_weights`).
    pub flange_corrections: Vec<Vector6<f64>>,
    /// Present with `flange_weights`.
    pub components: Option<VarianceComponents>,
}

impl BundleFit {
    /// Offset of `target_to_base` in [`Self::covariance`].
    pub fn target_to_base_offset(&self) -> usize {
        self.freedom.intrinsics.len()
    }

    /// Offset of `flange_to_camera` in [`Self::covariance`].
    pub fn flange_to_camera_offset(&self) -> usize {
        self.target_to_base_offset() + POSE_PARAMS
    }

    /// Standard deviation of the board scale, if it was refined.
    pub fn board_scale_sigma(&self) -> Option<f64> {
        let i = self.flange_to_camera_offset() + POSE_PARAMS;
        self.freedom
            .board_scale
            .then(|| self.covariance[(i, i)].max(0.0).sqrt())
    }

    /// The 6x6 covariance block starting at `offset`.
    pub fn block6(&self, offset: usize) -> Matrix6<f64> {
        Matrix6::from_fn(|i, j| self.covariance[(offset + i, offset + j)])
    }
}

/// The least-squares problem about a reference model (module doc).
struct Bundle<'a> {
    views: &'a [(Pose, &'a Pairs)],
    reference: BundleModel,
    freedom: &'a BundleFreedom,
}

impl Bundle<'_> {
    fn ni(&self) -> usize {
        self.freedom.intrinsics.len()
    }

    /// Unknowns before the per-pose flange corrections.
    fn head(&self) -> usize {
        self.ni() + 2 * POSE_PARAMS + usize::from(self.freedom.board_scale)
    }

    fn corrections(&self) -> usize {
        match self.freedom.flange_weights {
            Some(_) => POSE_PARAMS * self.views.len(),
            None => 0,
        }
    }

    fn params(&self) -> usize {
        self.head() + self.corrections()
    }

    fn pixel_rows(&self) -> usize {
        2 * self.views.iter().map(|(_, p)| p.len()).sum::<usize>()
    }

    /// Flange pose of view `k` with its correction in `x` applied.
    fn flange(&self, x: &DVector<f64>, k: usize) -> Pose {
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

    fn delta(x: &DVector<f64>, at: usize) -> Vector6<f64> {
        Vector6::from_column_slice(&x.as_slice()[at..at + POSE_PARAMS])
    }

    fn unpack(&self, x: &DVector<f64>) -> BundleModel {
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
/// left perturbation of `target_to_camera` (see [`Bundle::jacobian`]).
fn block(top_left: Matrix3<f64>, top_right: Matrix3<f64>, bottom: Matrix3<f64>) -> Matrix6<f64> {
    let mut m = Matrix6::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&top_left);
    m.fixed_view_mut::<3, 3>(0, 3).copy_from(&top_right);
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(&bottom);
    m
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

    /// Analytic. With `C = T M` (`M = B_k X`), moving `T` by `(dt, dr)`
    /// moves `C` by `dt - [C_t - T_t]x dr` and `dr`; moving `X` by
    /// `(dt, dr)` moves `C` by `A_R dt`, `A_R dr` (`A = T B_k`). Rotation
    /// parameters enter through the SO(3) left Jacobian at their current
    /// value. The board scale moves each target point along itself. A flange
    /// correction `(dt, dr)` moves `C` by `T_R dt - T_R [B_R X_t]x dr` and
    /// `T_R dr`.
    fn jacobian(&self, x: &DVector<f64>) -> Option<DMatrix<f64>> {
        let model = self.unpack(x);
        let ni = self.ni();
        let (ot, ox) = (ni, ni + POSE_PARAMS);
        let rot = |at: usize| so3_left_jacobian(&Vector3::new(x[at + 3], x[at + 4], x[at + 5]));
        let (jl_t, jl_x) = (rot(ot), rot(ox));
        let t_t = model.target_to_base.translation.vector;
        let mut jac = DMatrix::zeros(self.pixel_rows() + self.corrections(), self.params());
        let t_r = model
            .target_to_base
            .rotation
            .to_rotation_matrix()
            .into_inner();
        let x_t = model.flange_to_camera.translation.vector;
        let mut row = 0;
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
                    jac.view_mut((row, k), (2, 1)).copy_from(&jc.column(i));
                }
                let jt: SMatrix<f64, 2, 6> = jp * m_t;
                let jx: SMatrix<f64, 2, 6> = jp * m_x;
                jac.view_mut((row, ot), (2, POSE_PARAMS)).copy_from(&jt);
                jac.view_mut((row, ox), (2, POSE_PARAMS)).copy_from(&jx);
                if self.freedom.board_scale {
                    // d uv / d P_target = -(translation columns of jp).
                    let d = -(jp.fixed_view::<2, 3>(0, 0) * p0.coords);
                    jac.view_mut((row, ox + POSE_PARAMS), (2, 1)).copy_from(&d);
                }
                if let Some(m_b) = &m_b {
                    let jb: SMatrix<f64, 2, 6> = jp * m_b;
                    jac.view_mut((row, ob), (2, POSE_PARAMS)).copy_from(&jb);
                }
                row += 2;
            }
        }
        if let Some(w) = self.freedom.flange_weights {
            let h = self.head();
            for i in 0..self.corrections() {
                jac[(row + i, h + i)] = w[i % POSE_PARAMS];
            }
        }
        Some(jac)
    }

    /// The flange corrections are block-diagonal: eliminate them.
    fn solve_normal(&self, a: &DMatrix<f64>, g: &DVector<f64>) -> Option<DVector<f64>> {
        match self.freedom.flange_weights {
            Some(_) => schur_solve(a, g, self.head(), POSE_PARAMS),
            None => None,
        }
    }
}

/// Fit the bundle to `views` (flange pose, point pairs) from `start`.
pub fn fit_bundle(
    views: &[(Pose, &Pairs)],
    start: &BundleModel,
    freedom: &BundleFreedom,
) -> Result<BundleFit, SolverError> {
    if freedom.intrinsics.iter().any(|&i| i >= BUNDLE_INTRINSICS) {
        return Err(SolverError::Empty);
    }
    let problem = Bundle {
        views,
        reference: *start,
        freedom,
    };
    let n = problem.params();
    let report: LmReport = solve(&problem, DVector::zeros(n), &LmOptions::default())?;
    let model = problem.unpack(&report.x);
    let head = problem.head();
    let flange_corrections: Vec<Vector6<f64>> = (0..problem.corrections() / POSE_PARAMS)
        .map(|k| Bundle::delta(&report.x, head + POSE_PARAMS * k))
        .collect();
    // Re-linearise about the solution (corrected flange poses, zero
    // corrections) so that the covariance is in the transforms' own
    // left-perturbation coordinates.
    let corrected: Vec<(Pose, &Pairs)> = views
        .iter()
        .enumerate()
        .map(|(k, (_, p))| (problem.flange(&report.x, k), *p))
        .collect();
    let at_solution = Bundle {
        views: &corrected,
        reference: model,
        freedom,
    };
    let jac = at_solution
        .jacobian(&DVector::zeros(n))
        .ok_or(SolverError::NonFinite)?;
    let variance = report.residual_variance();
    let pixel_rows = problem.pixel_rows();
    let pixel_ss = report.residuals.rows(0, pixel_rows).norm_squared();
    // The symmetric eigendecomposition of J^T J (n <= 21 + 6 per pose)
    // costs far less than the SVD of the tall J.
    let normal = jac.transpose() * &jac;
    let inverse = covariance_from_normal(&normal, 1.0);
    let full_covariance = &inverse * variance;
    let components = freedom
        .flange_weights
        .map(|_| components(&jac, &inverse, &report.residuals, pixel_rows, head));
    Ok(BundleFit {
        model,
        freedom: freedom.clone(),
        covariance: full_covariance.view((0, 0), (head, head)).into_owned(),
        sigma_px: variance.sqrt(),
        rms_px: (pixel_ss / (pixel_rows / 2) as f64).sqrt(),
        points: pixel_rows / 2,
        iterations: report.iterations,
        flange_corrections,
        components,
    })
}

#[cfg(test)]
#[path = "bundle_tests.rs"]
mod tests;
