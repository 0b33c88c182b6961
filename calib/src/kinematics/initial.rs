//! Starting values for the identification (method.md §6): the world-to-base
//! transform from the measured positions by a least-squares rigid
//! registration (Kabsch/Horn), given nominal kinematics and a tool guess;
//! with full measured poses (a 6-DoF probe), the tool's frame as well.

use nalgebra::{Matrix3, Matrix3x6, Matrix6, Translation3, UnitQuaternion, Vector3, Vector6};

use super::identify::{IdentifyError, Measurement, Observed};
use super::params::{CalibratedModel, Instrument};
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

/// Rounds of the alternating frame estimate in [`initial_frames_from_poses`]:
/// each round halves the error of a start a few degrees off; three reach
/// the fit's basin from any tool rotation.
const FRAME_ROUNDS: usize = 3;

/// `world_to_base` and the full `flange_to_tool` from measured full poses
/// (a 6-DoF tracker probe, method.md §6), given nominal kinematics: the
/// tool's orientation is whatever the probe was mounted at, so unlike a
/// camera's hand–eye guess it cannot be assumed near identity. Starts from
/// the positions' registration ([`initial_world_to_base`], with
/// `model.flange_to_tool`'s point), then alternates the chordal mean of the
/// tool rotation (`R_tool = mean_i (R_wb R_bf_i)^T R_i`) and of the base
/// rotation (`R_wb = mean_i R_i R_tool^T R_bf_i^T`), and solves both
/// translations in one linear least squares
/// (`p_i = R_wb (R_bf_i t_tool + p_bf_i) + t_wb`). Every measurement must be
/// a full pose.
pub fn initial_frames_from_poses(
    model: &CalibratedModel,
    data: &[Measurement],
) -> Result<(Pose, Pose), IdentifyError> {
    let measured: Vec<Pose> = data
        .iter()
        .enumerate()
        .map(|(pose, m)| match &m.observed {
            Observed::Pose { world_to_tool, .. } => Ok(*world_to_tool),
            Observed::Position { .. } => Err(IdentifyError::WrongMeasurement {
                pose,
                instrument: Instrument::Camera,
                expected: "full-pose",
            }),
        })
        .collect::<Result<_, _>>()?;
    let mut world_to_base = initial_world_to_base(model, data)?;
    let flanges: Vec<Pose> = data
        .iter()
        .enumerate()
        .map(|(pose, m)| {
            model
                .robot
                .base_to_flange(&m.joints_rad)
                .map_err(|source| IdentifyError::Pose { pose, source })
        })
        .collect::<Result<_, _>>()?;
    let mut tool_rotation = model.flange_to_tool.rotation;
    for _ in 0..FRAME_ROUNDS {
        let mut sum = Matrix3::zeros();
        for (f, m) in flanges.iter().zip(&measured) {
            sum += ((world_to_base.rotation * f.rotation).inverse() * m.rotation)
                .to_rotation_matrix()
                .into_inner();
        }
        tool_rotation = UnitQuaternion::from_rotation_matrix(&orthonormalize(&sum));
        let mut sum = Matrix3::zeros();
        for (f, m) in flanges.iter().zip(&measured) {
            sum += (m.rotation * tool_rotation.inverse() * f.rotation.inverse())
                .to_rotation_matrix()
                .into_inner();
        }
        world_to_base.rotation = UnitQuaternion::from_rotation_matrix(&orthonormalize(&sum));
    }
    // Translations: [R_wb R_bf_i | I] [t_tool; t_wb] = p_i - R_wb p_bf_i.
    let mut normal = Matrix6::zeros();
    let mut rhs = Vector6::zeros();
    for (f, m) in flanges.iter().zip(&measured) {
        let a = world_to_base.rotation.to_rotation_matrix().into_inner()
            * f.rotation.to_rotation_matrix().into_inner();
        let mut row = Matrix3x6::zeros();
        row.fixed_view_mut::<3, 3>(0, 0).copy_from(&a);
        row.fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&Matrix3::identity());
        let b = m.translation.vector - world_to_base.rotation * f.translation.vector;
        normal += row.transpose() * row;
        rhs += row.transpose() * b;
    }
    let solution = normal.cholesky().ok_or(IdentifyError::NoPoses)?.solve(&rhs);
    let tool_mm = Vector3::new(solution[0], solution[1], solution[2]);
    world_to_base.translation = Translation3::new(solution[3], solution[4], solution[5]);
    Ok((
        world_to_base,
        Pose::from_parts(Translation3::from(tool_mm), tool_rotation),
    ))
}

#[cfg(test)]
#[path = "initial_tests.rs"]
mod tests;
