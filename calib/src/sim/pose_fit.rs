//! A minimal per-image pose fit (PnP refinement from a starting pose) and
//! its covariance, for the simulator's oracle and the two-step baseline
//! (method.md §6). The camera helper's `camera/pose.rs` is the production
//! PnP; this one only refines a pose that is already close, which the
//! simulator always has (the nominal prediction).

use nalgebra::{DMatrix, DVector, Matrix6, Point2, Point3, Vector6};

use crate::camera::model::Intrinsics;
use crate::geometry::{perturb_left, Pose};
use crate::kinematics::projection::project_with_jacobians;
use crate::solver::{covariance_from_jacobian, solve, LeastSquaresProblem, LmOptions, SolverError};

/// A refined camera pose with its covariance in the left-perturbation form
/// of [`crate::geometry::pose_error`] (`[dp mm; dr rad]`, target frame).
#[derive(Debug, Clone)]
pub struct PoseFit {
    pub target_to_camera: Pose,
    pub covariance: Matrix6<f64>,
    pub rms_px: f64,
}

struct Pnp<'a> {
    cam: &'a Intrinsics,
    start: Pose,
    points: &'a [(Point3<f64>, Point2<f64>)],
}

impl LeastSquaresProblem for Pnp<'_> {
    fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
        let pose = perturb_left(&self.start, &Vector6::from_column_slice(x.as_slice()));
        let mut r = DVector::zeros(2 * self.points.len());
        for (k, (p, uv)) in self.points.iter().enumerate() {
            let pred = self.cam.project(&(pose.inverse() * p))?;
            r[2 * k] = pred.x - uv.x;
            r[2 * k + 1] = pred.y - uv.y;
        }
        Some(r)
    }

    fn jacobian(&self, x: &DVector<f64>) -> Option<DMatrix<f64>> {
        let pose = perturb_left(&self.start, &Vector6::from_column_slice(x.as_slice()));
        let mut j = DMatrix::zeros(2 * self.points.len(), 6);
        for (k, (p, _)) in self.points.iter().enumerate() {
            let (_, jp, _) = project_with_jacobians(self.cam, &pose, p)?;
            j.view_mut((2 * k, 0), (2, 6)).copy_from(&jp);
        }
        Some(j)
    }
}

/// Refine `start` to the observed pixels; the covariance assumes
/// independent pixel noise of `sigma_px` (or the fit's own residual
/// variance when `sigma_px` is `None`).
pub fn fit_camera_pose(
    cam: &Intrinsics,
    start: &Pose,
    points: &[(Point3<f64>, Point2<f64>)],
    sigma_px: Option<f64>,
) -> Result<PoseFit, SolverError> {
    let problem = Pnp {
        cam,
        start: *start,
        points,
    };
    let report = solve(&problem, DVector::zeros(6), &LmOptions::default())?;
    let pose = perturb_left(start, &Vector6::from_column_slice(report.x.as_slice()));
    let at = Pnp {
        start: pose,
        ..problem
    };
    let jac = at
        .jacobian(&DVector::zeros(6))
        .ok_or(SolverError::NonFinite)?;
    let variance = sigma_px.map_or(report.residual_variance(), |s| s * s);
    let cov = covariance_from_jacobian(&jac, variance);
    Ok(PoseFit {
        target_to_camera: pose,
        covariance: Matrix6::from_column_slice(cov.as_slice()),
        rms_px: (report.cost / report.residuals.len() as f64).sqrt(),
    })
}

/// Precision of a camera step that calibrates the intrinsics from the same
/// images (a bundle over the 8 intrinsics of
/// [`crate::kinematics::projection::INTRINSIC_NAMES`] and every pose, with
/// pixel noise `sigma_px`), evaluated at the true values.
#[derive(Debug, Clone)]
pub struct CameraStepPrecision {
    /// Covariance of the intrinsics (8x8).
    pub intrinsics: DMatrix<f64>,
    /// Marginal covariance of each camera pose (intrinsics uncertainty
    /// included), in the [`crate::geometry::pose_error`] form.
    pub poses: Vec<Matrix6<f64>>,
}

/// Schur-complement evaluation of the bundle's covariance: with per-pose
/// information `A_k`, cross terms `B_k` and intrinsics information `C`,
/// `S = C - sum B_k^T A_k^-1 B_k`, `Cov(intrinsics) = S^-1` and
/// `Cov(pose k) = A_k^-1 + A_k^-1 B_k S^-1 B_k^T A_k^-1`.
pub fn camera_step_precision(
    cam: &Intrinsics,
    poses: &[(Pose, Vec<Point3<f64>>)],
    sigma_px: f64,
) -> Option<CameraStepPrecision> {
    let mut c = DMatrix::<f64>::zeros(8, 8);
    let mut blocks = Vec::with_capacity(poses.len());
    for (pose, points) in poses {
        let mut a = Matrix6::<f64>::zeros();
        let mut b = nalgebra::SMatrix::<f64, 6, 8>::zeros();
        for p in points {
            let (_, jp, jc) = project_with_jacobians(cam, pose, p)?;
            a += jp.transpose() * jp;
            b += jp.transpose() * jc;
            c += DMatrix::from_column_slice(8, 8, (jc.transpose() * jc).as_slice());
        }
        let a_inv = a.try_inverse()?;
        blocks.push((a_inv, b));
    }
    let mut s = c;
    for (a_inv, b) in &blocks {
        s -= DMatrix::from_column_slice(8, 8, (b.transpose() * a_inv * b).as_slice());
    }
    let s_inv = s.try_inverse()?;
    let s_inv_fixed = nalgebra::SMatrix::<f64, 8, 8>::from_column_slice(s_inv.as_slice());
    let var = sigma_px * sigma_px;
    let poses = blocks
        .iter()
        .map(|(a_inv, b)| {
            let g = a_inv * b;
            (a_inv + g * s_inv_fixed * g.transpose()) * var
        })
        .collect();
    Some(CameraStepPrecision {
        intrinsics: s_inv * var,
        poses,
    })
}
