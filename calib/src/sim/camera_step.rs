//! The precision a camera step reaches on a simulated campaign (method.md
//! §6): the covariance of the intrinsics and the marginal covariance of
//! every camera pose when the intrinsics are calibrated from the same
//! images. It sets the oracle's noise level and the two-step pipeline's
//! weights; the per-image pose itself comes from `camera/pose.rs`.

use nalgebra::{DMatrix, Matrix6, Point3, SMatrix};

use crate::camera::model::Intrinsics;
use crate::geometry::Pose;
use crate::kinematics::projection::project_with_jacobians;

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
    /// Covariance of each pose were the intrinsics known exactly (a PnP
    /// with the true camera).
    pub poses_known_intrinsics: Vec<Matrix6<f64>>,
    /// Per pose, how an intrinsics error moves the pose estimate
    /// (`-A_k^-1 B_k`, linearised): one intrinsics error is shared by every
    /// pose of the bundle, so the poses' errors are correlated.
    pub pose_intrinsics_gain: Vec<SMatrix<f64, 6, 8>>,
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
    let poses_known_intrinsics = blocks.iter().map(|(a_inv, _)| a_inv * var).collect();
    let pose_intrinsics_gain = blocks.iter().map(|(a_inv, b)| -(a_inv * b)).collect();
    Some(CameraStepPrecision {
        intrinsics: s_inv * var,
        poses,
        poses_known_intrinsics,
        pose_intrinsics_gain,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::campaign::{simulate_campaign, CampaignSpec};
    use crate::sim::campaign_io::Board;

    /// The shared-intrinsics decomposition reproduces each pose's marginal:
    /// `known + G C G^T` (what the correlated oracle's draws rely on).
    #[test]
    fn gain_and_known_intrinsics_make_the_marginal() {
        let spec = CampaignSpec::standard("irb2400", 1).unwrap();
        let campaign = simulate_campaign(&spec).unwrap();
        let points = Board::standard().points();
        let bundle: Vec<_> = campaign
            .poses
            .iter()
            .take(20)
            .map(|p| (p.target_to_camera, points.clone()))
            .collect();
        let sigma_px = 0.05;
        let precision =
            camera_step_precision(&campaign.truth.intrinsics, &bundle, sigma_px).unwrap();
        let c = SMatrix::<f64, 8, 8>::from_column_slice(precision.intrinsics.as_slice());
        for k in 0..bundle.len() {
            let g = precision.pose_intrinsics_gain[k];
            let rebuilt = precision.poses_known_intrinsics[k] + g * c * g.transpose();
            let marginal = precision.poses[k];
            assert!(
                (rebuilt - marginal).norm() <= 1e-9 * marginal.norm(),
                "pose {k}: {rebuilt} vs {marginal}"
            );
        }
    }
}
