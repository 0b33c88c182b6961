//! Joint refinement, the default final stage (method.md §6 **beyond**):
//! kinematics, `target_to_base`, `flange_to_camera` and the camera
//! intrinsics fitted together directly to the raw image points of every
//! pose. With independent pixel noise this is the statistically efficient
//! estimator: no information is lost in a per-image pose and its
//! approximate covariance.
//!
//! Residual per dot: `(project(camera_to_target * P) - observed) / sigma_px`,
//! with `target_to_camera = target_to_base * base_to_flange(q) *
//! flange_to_camera`. The Jacobian is analytic: the projection's derivative
//! with respect to the camera pose ([`project_with_jacobians`]) times the
//! identification Jacobian ([`tool_pose_jacobian`]), plus the intrinsics'.

use nalgebra::{DMatrix, DVector, Point2, Point3};

use super::identify::IdentifyError;
use super::jacobian::tool_pose_jacobian;
use super::params::{CalibratedModel, Instrument, ParamLayout};
use super::projection::{apply_intrinsics, project_with_jacobians, INTRINSIC_NAMES};
use crate::camera::model::Intrinsics;
use crate::solver::{covariance_from_jacobian, solve, LeastSquaresProblem, LmOptions, Termination};

/// One pose of a camera campaign: recorded joints and the detected dots.
#[derive(Debug, Clone, PartialEq)]
pub struct ImagePose {
    pub joints_rad: Vec<f64>,
    /// `(dot centre in the target frame mm, observed pixel)`.
    pub observations: Vec<(Point3<f64>, Point2<f64>)>,
}

#[derive(Debug, Clone)]
pub struct JointRefinement {
    pub model: CalibratedModel,
    pub intrinsics: Intrinsics,
    pub layout: ParamLayout,
    /// Standard deviation of every layout parameter (zero where fixed).
    pub std_devs: DVector<f64>,
    /// Standard deviations of [`INTRINSIC_NAMES`].
    pub intrinsics_std: [f64; 8],
    pub reprojection_rms_px: f64,
    pub iterations: usize,
    pub termination: Termination,
}

struct ImageFit<'a> {
    layout: &'a ParamLayout,
    reference: &'a CalibratedModel,
    intrinsics: &'a Intrinsics,
    free: &'a [usize],
    poses: &'a [ImagePose],
    sigma_px: f64,
}

impl ImageFit<'_> {
    fn unpack(&self, x: &DVector<f64>) -> (CalibratedModel, Intrinsics) {
        let mut full = DVector::zeros(self.layout.len());
        for (k, &i) in self.free.iter().enumerate() {
            full[i] = x[k];
        }
        let cam = apply_intrinsics(self.intrinsics, &x.as_slice()[self.free.len()..]);
        (self.layout.apply(self.reference, &full), cam)
    }

    fn rows(&self) -> usize {
        2 * self
            .poses
            .iter()
            .map(|p| p.observations.len())
            .sum::<usize>()
    }

    fn params(&self) -> usize {
        self.free.len() + INTRINSIC_NAMES.len()
    }
}

impl LeastSquaresProblem for ImageFit<'_> {
    fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
        let (model, cam) = self.unpack(x);
        let mut r = DVector::zeros(self.rows());
        let mut row = 0;
        for pose in self.poses {
            let inv = model.world_to_tool(&pose.joints_rad).ok()?.inverse();
            for (p, uv) in &pose.observations {
                let pred = cam.project(&(inv * p))?;
                r[row] = (pred.x - uv.x) / self.sigma_px;
                r[row + 1] = (pred.y - uv.y) / self.sigma_px;
                row += 2;
            }
        }
        Some(r)
    }

    fn jacobian(&self, x: &DVector<f64>) -> Option<DMatrix<f64>> {
        let (model, cam) = self.unpack(x);
        let nf = self.free.len();
        let mut jac = DMatrix::zeros(self.rows(), self.params());
        let mut row = 0;
        for pose in self.poses {
            let (t2c, jt) = tool_pose_jacobian(self.layout, &model, &pose.joints_rad).ok()?;
            let jt_free = DMatrix::from_fn(6, nf, |r, c| jt[(r, self.free[c])]);
            for (p, _) in &pose.observations {
                let (_, jp, jc) = project_with_jacobians(&cam, &t2c, p)?;
                let kin = DMatrix::from_column_slice(2, 6, jp.as_slice()) * &jt_free;
                jac.view_mut((row, 0), (2, nf)).copy_from(&kin);
                jac.view_mut((row, nf), (2, 8)).copy_from(&jc);
                row += 2;
            }
        }
        jac /= self.sigma_px;
        Some(jac)
    }
}

/// Refine `start` (usually the pose-level identification) and `intrinsics`
/// (the camera step's) on the image points. `free` are the layout indices
/// identified (the identifiability analysis's), `sigma_px` the dot noise.
pub fn joint_refine(
    start: &CalibratedModel,
    intrinsics: &Intrinsics,
    poses: &[ImagePose],
    free: &[usize],
    sigma_px: f64,
) -> Result<JointRefinement, IdentifyError> {
    if poses.is_empty() {
        return Err(IdentifyError::NoPoses);
    }
    for (pose, p) in poses.iter().enumerate() {
        start
            .robot
            .base_to_flange(&p.joints_rad)
            .map_err(|source| IdentifyError::Pose { pose, source })?;
    }
    let layout = ParamLayout::new(&start.robot, Instrument::Camera);
    let problem = ImageFit {
        layout: &layout,
        reference: start,
        intrinsics,
        free,
        poses,
        sigma_px: if sigma_px > 0.0 { sigma_px } else { 1.0 },
    };
    let report = solve(
        &problem,
        DVector::zeros(problem.params()),
        &LmOptions::default(),
    )?;
    let (model, cam) = problem.unpack(&report.x);
    let at = ImageFit {
        reference: &model,
        intrinsics: &cam,
        ..problem
    };
    let zero = DVector::zeros(at.params());
    let jac = at.jacobian(&zero).ok_or(IdentifyError::NoPoses)?;
    let cov = covariance_from_jacobian(&jac, report.residual_variance());
    let mut std_devs = DVector::zeros(layout.len());
    for (k, &i) in free.iter().enumerate() {
        std_devs[i] = cov[(k, k)].max(0.0).sqrt();
    }
    let intrinsics_std =
        std::array::from_fn(|k| cov[(free.len() + k, free.len() + k)].max(0.0).sqrt());
    let rms = (report.cost / report.residuals.len() as f64).sqrt() * at.sigma_px;
    Ok(JointRefinement {
        model,
        intrinsics: cam,
        std_devs,
        intrinsics_std,
        reprojection_rms_px: rms,
        iterations: report.iterations,
        termination: report.termination,
        layout,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::campaign::{simulate_campaign, CampaignSpec};
    use crate::solver::finite_difference_jacobian;

    #[test]
    fn jacobian_matches_finite_differences_and_exact_points_are_fitted() {
        let mut spec = CampaignSpec::standard("puma560", 5).unwrap();
        spec.cal_poses = 25;
        spec.val_poses = 0;
        spec.pixel_sigma_px = 0.0;
        spec.encoder_sigma_deg = 0.0;
        let c = simulate_campaign(&spec).unwrap();
        let truth = c.truth.model().unwrap();
        let poses: Vec<ImagePose> = c
            .poses
            .iter()
            .map(|p| ImagePose {
                joints_rad: p.joints_rad.clone(),
                observations: p.observations(&c.truth.board),
            })
            .collect();
        let layout = ParamLayout::new(&truth.robot, Instrument::Camera);
        let free: Vec<usize> = (0..layout.len())
            .filter(|&i| {
                !["dtheta_1", "d_1", "dtheta_6", "a_6", "d_6", "alpha_6"]
                    .contains(&layout.params[i].name.as_str())
            })
            .collect();
        let fit = ImageFit {
            layout: &layout,
            reference: &truth,
            intrinsics: &c.truth.intrinsics,
            free: &free,
            poses: &poses[..3],
            sigma_px: 0.5,
        };
        let x = DVector::from_fn(
            fit.params(),
            |i, _| if i < free.len() { 1e-4 } else { 1e-3 },
        );
        let analytic = fit.jacobian(&x).unwrap();
        let fd = finite_difference_jacobian(|x| fit.residuals(x), &x).unwrap();
        assert!(
            (&analytic - &fd).amax() < 1e-4 * fd.amax(),
            "{}",
            (&analytic - &fd).amax()
        );
        // Start off the truth (intrinsics and kinematics), recover it.
        let mut cam = c.truth.intrinsics;
        cam.fx *= 1.001;
        cam.cx += 2.0;
        let mut start = truth.clone();
        start.robot.joints[2].a_mm += 0.5;
        let r = joint_refine(&start, &cam, &poses, &free, 0.1).unwrap();
        assert!(r.reprojection_rms_px < 1e-6, "{}", r.reprojection_rms_px);
        assert!((r.intrinsics.fx - c.truth.intrinsics.fx).abs() < 1e-4);
        assert!((r.model.robot.joints[2].a_mm - truth.robot.joints[2].a_mm).abs() < 1e-6);
        assert!(joint_refine(&start, &cam, &[], &free, 0.1).is_err());
    }
}
