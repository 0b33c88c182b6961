//! Camera pose in the target frame for one image with known intrinsics
//! (method.md §4, paper eqs. 37–39: position `-R^T T`, orientation `R^T`),
//! with its covariance: what the kinematics stage consumes.

use nalgebra::{
    DMatrix, DVector, Isometry3, Matrix3, Matrix6, Point2, Point3, Translation3, UnitQuaternion,
    Vector3, Vector6,
};

use super::error::CameraError;
use super::model::Intrinsics;
use super::observations::validate_points;
use super::projection_jacobian::POSE_PARAMS;
use super::projection_jacobian::{projection_jacobian_at, PoseLinearisation};
use crate::geometry::{orthonormalize, pose_error, pose_from_vector, pose_to_vector};
use crate::solver::{finite_difference_jacobian, solve, LeastSquaresProblem, LmOptions};

/// The camera pose in the target frame for one image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoseEstimate {
    /// The camera's pose in the target frame (`p_target = target_to_camera * p_camera`).
    pub target_to_camera: Isometry3<f64>,
    /// Covariance of `[tx, ty, tz, rx, ry, rz]`: the camera position in the
    /// target frame (mm) and the small-angle orientation error in the
    /// target frame (rad), i.e. the convention of `geometry::pose_error`
    /// (`perturb_left`) applied to `target_to_camera`.
    pub covariance_6x6: Matrix6<f64>,
    /// Reprojection RMS (px, per point: sqrt(mean |r|^2)).
    pub rms_px: f64,
}

/// Residuals `observed - projected` (px) of points under the target pose in
/// the camera frame; `None` if a point is behind the camera.
pub fn reprojection_residuals(
    intrinsics: &Intrinsics,
    camera_to_target: &Isometry3<f64>,
    observations: &[(Point3<f64>, Point2<f64>)],
    out: &mut [f64],
) -> Option<()> {
    for (i, (p, uv)) in observations.iter().enumerate() {
        let q = intrinsics.project(&(camera_to_target * p))?;
        out[2 * i] = uv.x - q.x;
        out[2 * i + 1] = uv.y - q.y;
    }
    Some(())
}

struct PoseProblem<'a> {
    intrinsics: &'a Intrinsics,
    observations: &'a [(Point3<f64>, Point2<f64>)],
}

impl LeastSquaresProblem for PoseProblem<'_> {
    fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
        let pose = pose_from_vector(&Vector6::from_column_slice(x.as_slice()));
        let mut r = DVector::zeros(2 * self.observations.len());
        reprojection_residuals(self.intrinsics, &pose, self.observations, r.as_mut_slice())?;
        Some(r)
    }

    /// Analytic ([`projection_jacobian_at`]): residual = observed -
    /// projected, so the rows are the negated projection derivatives.
    fn jacobian(&self, x: &DVector<f64>) -> Option<DMatrix<f64>> {
        let pose = PoseLinearisation::new(&Vector6::from_column_slice(x.as_slice()));
        let mut jac = DMatrix::zeros(2 * self.observations.len(), POSE_PARAMS);
        for (i, (p, _)) in self.observations.iter().enumerate() {
            let (_, jp) = projection_jacobian_at(self.intrinsics, &pose, p)?;
            for k in 0..2 {
                for j in 0..POSE_PARAMS {
                    jac[(2 * i + k, j)] = -jp[(k, j)];
                }
            }
        }
        Some(jac)
    }
}

/// Closed-form start for a planar target: the homography from board
/// `(x, y)` to undistorted normalised rays, decomposed into `[r1 r2 t]`.
pub fn planar_pose_guess(
    intrinsics: &Intrinsics,
    observations: &[(Point3<f64>, Point2<f64>)],
) -> Option<Isometry3<f64>> {
    let rays: Option<Vec<_>> = observations
        .iter()
        .map(|(_, uv)| intrinsics.pixel_to_ray(uv))
        .collect();
    let rays = rays?;
    // Normalise the board coordinates for conditioning.
    let n = observations.len() as f64;
    let mean = observations
        .iter()
        .fold(Vector3::zeros(), |a, (p, _)| a + p.coords)
        / n;
    let spread = observations
        .iter()
        .map(|(p, _)| (p.coords - mean).xy().norm())
        .sum::<f64>()
        / n;
    if spread <= 0.0 {
        return None;
    }
    let mut a = DMatrix::zeros(2 * observations.len(), 9);
    for (i, ((p, _), ray)) in observations.iter().zip(&rays).enumerate() {
        let (x, y) = ((p.x - mean.x) / spread, (p.y - mean.y) / spread);
        let (u, v) = (ray.x, ray.y);
        let r0 = [x, y, 1.0, 0.0, 0.0, 0.0, -u * x, -u * y, -u];
        let r1 = [0.0, 0.0, 0.0, x, y, 1.0, -v * x, -v * y, -v];
        for j in 0..9 {
            a[(2 * i, j)] = r0[j];
            a[(2 * i + 1, j)] = r1[j];
        }
    }
    let svd = (a.transpose() * &a).symmetric_eigen();
    let k = svd.eigenvalues.imin();
    let h = svd.eigenvectors.column(k);
    let mut hm = Matrix3::new(h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], h[8]);
    // Undo the normalisation: board (x, y) -> ((x - mx)/s, (y - my)/s).
    let norm = Matrix3::new(
        1.0 / spread,
        0.0,
        -mean.x / spread,
        0.0,
        1.0 / spread,
        -mean.y / spread,
        0.0,
        0.0,
        1.0,
    );
    hm *= norm;
    let scale = 2.0 / (hm.column(0).norm() + hm.column(1).norm());
    if !scale.is_finite() {
        return None;
    }
    hm *= scale;
    if hm[(2, 2)] < 0.0 {
        hm = -hm;
    }
    let (c0, c1) = (hm.column(0).into_owned(), hm.column(1).into_owned());
    let r = orthonormalize(&Matrix3::from_columns(&[c0, c1, c0.cross(&c1)]));
    let t = hm.column(2).into_owned();
    Some(Isometry3::from_parts(
        Translation3::from(t),
        UnitQuaternion::from_rotation_matrix(&r),
    ))
}

/// Map from the solver's `camera_to_target` vector to the reported
/// parameters of `target_to_camera` about `reference` (method.md §4).
fn reported_parameters(v: &DVector<f64>, reference: &Isometry3<f64>) -> DVector<f64> {
    let target_to_camera = pose_from_vector(&Vector6::from_column_slice(v.as_slice())).inverse();
    let e = pose_error(&target_to_camera, reference);
    let c = target_to_camera.translation.vector;
    DVector::from_column_slice(&[c.x, c.y, c.z, e[3], e[4], e[5]])
}

/// Camera pose in the target frame for one image with known intrinsics,
/// by Levenberg–Marquardt on the reprojection error, started from
/// `initial_camera_to_target` or, for planar targets, the homography.
pub fn estimate_pose(
    intrinsics: &Intrinsics,
    observations: &[(Point3<f64>, Point2<f64>)],
    initial_camera_to_target: Option<&Isometry3<f64>>,
) -> Result<PoseEstimate, CameraError> {
    validate_points(0, observations)?;
    let start = match initial_camera_to_target {
        Some(p) => *p,
        None => planar_pose_guess(intrinsics, observations).ok_or_else(|| {
            CameraError::DegenerateView {
                view: 0,
                reason: "no homography: rays could not be formed".into(),
            }
        })?,
    };
    let problem = PoseProblem {
        intrinsics,
        observations,
    };
    let x0 = DVector::from_column_slice(pose_to_vector(&start).as_slice());
    let report = solve(&problem, x0, &LmOptions::default())?;
    let covariance_solver = report.covariance();
    let target_to_camera =
        pose_from_vector(&Vector6::from_column_slice(report.x.as_slice())).inverse();
    let map = |v: &DVector<f64>| Some(reported_parameters(v, &target_to_camera));
    let jac = finite_difference_jacobian(map, &report.x).ok_or(CameraError::DegenerateView {
        view: 0,
        reason: "pose covariance could not be propagated".into(),
    })?;
    let cov = &jac * covariance_solver * jac.transpose();
    Ok(PoseEstimate {
        target_to_camera,
        covariance_6x6: Matrix6::from_fn(|i, j| cov[(i, j)]),
        rms_px: (report.cost / observations.len() as f64).sqrt(),
    })
}

#[cfg(test)]
#[path = "pose_tests.rs"]
mod tests;
