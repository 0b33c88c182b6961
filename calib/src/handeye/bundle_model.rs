//! The unknowns of the flange-pose bundle (method.md §4 **beyond**, §6)
//! and which of them a fit refines: every board point of every image is
//! predicted through
//! `target_to_camera_k = target_to_base * base_to_flange_k * flange_to_camera`
//! with the unknowns `[intrinsics (free subset of
//! kinematics::projection::INTRINSIC_NAMES); target_to_base (6);
//! flange_to_camera (6); board scale (optional, 1)]`, then (with flange
//! weights) one 6-D correction per flange pose.

use nalgebra::{Point2, Point3, Vector6};

use crate::camera::model::Intrinsics;
use crate::geometry::Pose;
use crate::kinematics::projection::INTRINSIC_NAMES;

/// Number of intrinsics the bundle can refine (k3 stays at its start).
pub const BUNDLE_INTRINSICS: usize = INTRINSIC_NAMES.len();
/// Indices (into [`INTRINSIC_NAMES`]) of the pinhole part.
pub const PINHOLE_INTRINSICS: [usize; 4] = [0, 1, 2, 3];
/// Unknowns of one rigid transform.
pub(super) const POSE_PARAMS: usize = 6;

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
