//! Starting values for the identification (method.md §6): the world-to-base
//! transform from the measured positions by a least-squares rigid
//! registration (Kabsch/Horn), given nominal kinematics and a tool guess.

use nalgebra::{Matrix3, Translation3, UnitQuaternion, Vector3};

use super::identify::{IdentifyError, Measurement};
use super::params::CalibratedModel;
use crate::geometry::{orthonormalize, Pose};

/// Poses needed for a rigid registration (three non-collinear points).
pub const MIN_REGISTRATION_POSES: usize = 3;

/// `world_to_base` minimising the distance between the measured tool
/// positions and those predicted by `model` (its own `world_to_base` is
/// ignored). Needs at least [`MIN_REGISTRATION_POSES`] poses.
pub fn initial_world_to_base(
    model: &CalibratedModel,
    data: &[Measurement],
) -> Result<Pose, IdentifyError> {
    if data.len() < MIN_REGISTRATION_POSES {
        return Err(IdentifyError::NoPoses);
    }
    let mut base_pts = Vec::with_capacity(data.len());
    for (pose, m) in data.iter().enumerate() {
        let p = (model.robot.base_to_flange(&m.joints_rad))
            .map_err(|source| IdentifyError::Pose { pose, source })?
            * model.flange_to_tool;
        base_pts.push(p.translation.vector);
    }
    let world_pts: Vec<Vector3<f64>> = data.iter().map(|m| m.observed.position_mm()).collect();
    let n = data.len() as f64;
    let cb = base_pts.iter().sum::<Vector3<f64>>() / n;
    let cw = world_pts.iter().sum::<Vector3<f64>>() / n;
    let mut h = Matrix3::zeros();
    for (b, w) in base_pts.iter().zip(&world_pts) {
        h += (w - cw) * (b - cb).transpose();
    }
    let r = orthonormalize(&h);
    let q = UnitQuaternion::from_rotation_matrix(&r);
    let t = cw - (q * cb);
    Ok(Pose::from_parts(Translation3::from(t), q))
}
