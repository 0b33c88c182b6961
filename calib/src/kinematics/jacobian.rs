//! The identification Jacobian (method.md §6): derivative of the predicted
//! `world_to_tool(q)` with respect to every entry of the parameter vector
//! ([`ParamLayout`]), analytic.
//!
//! Every parameter moves the chain by an elementary motion in a known frame:
//! `dtheta_i` a rotation about `z_{i-1}`, `d_i` a translation along it,
//! `a_i` a translation along the common normal `x`, `alpha_i` a rotation about
//! it, Hayati's `beta_i` a rotation about `y_i`. A rotation with unit axis `w`
//! through point `c` moves the tool position by `w x (p - c)` and its
//! orientation by `w` (both in the world frame), which is exactly the
//! left-perturbation form of [`crate::geometry::pose_error`]. Checked against
//! central finite differences in the tests.

use nalgebra::{DMatrix, Vector3};

use super::model::{Convention, KinematicsError};
use super::params::{CalibratedModel, Instrument, ParamLayout, BASE_PARAMS, PARAMS_PER_JOINT};
use crate::geometry::Pose;

/// Predicted `world_to_tool` at joints `q_rad` and its 6 x n Jacobian, rows
/// `[dp (mm); dr (rad)]` in the world frame, with respect to `x` at `x = 0`
/// around `model` (see [`ParamLayout::apply`]).
pub fn tool_pose_jacobian(
    layout: &ParamLayout,
    model: &CalibratedModel,
    q_rad: &[f64],
) -> Result<(Pose, DMatrix<f64>), KinematicsError> {
    let tool = model.world_to_tool(q_rad)?;
    let p_end = tool.translation.vector;
    let mut jac = DMatrix::zeros(6, layout.len());
    let mut set_rotation = |col: usize, w: Vector3<f64>, c: Vector3<f64>| {
        let dp = w.cross(&(p_end - c));
        jac.fixed_view_mut::<3, 1>(0, col).copy_from(&dp);
        jac.fixed_view_mut::<3, 1>(3, col).copy_from(&w);
    };
    let mut frame = model.world_to_base;
    let mut translations: Vec<(usize, Vector3<f64>)> = Vec::new();
    for (i, (joint, &q)) in model.robot.joints.iter().zip(q_rad).enumerate() {
        let o = i * PARAMS_PER_JOINT;
        let z_prev = frame.rotation * Vector3::z();
        set_rotation(o, z_prev, frame.translation.vector);
        // Frame after Rz(theta) (and Tz(d) for DH): its x is the common normal.
        let theta = nalgebra::UnitQuaternion::from_axis_angle(
            &Vector3::z_axis(),
            q + joint.theta_offset_rad,
        );
        let rot_after_theta = frame.rotation * theta;
        let x_axis = rot_after_theta * Vector3::x();
        translations.push((o + 1, x_axis));
        if joint.convention == Convention::Dh {
            translations.push((o + 2, z_prev));
        }
        let next = frame * joint.link_transform(q);
        // Rx(alpha) acts at the end of the common normal: the link's origin.
        set_rotation(o + 3, x_axis, next.translation.vector);
        if joint.convention == Convention::Hayati {
            set_rotation(o + 2, next.rotation * Vector3::y(), next.translation.vector);
        }
        frame = next;
    }
    for (col, u) in translations {
        jac.fixed_view_mut::<3, 1>(0, col).copy_from(&u);
    }
    let b = layout.base_start();
    let base_origin = model.world_to_base.translation.vector;
    for k in 0..3 {
        jac[(k, b + k)] = 1.0;
        let w = Vector3::ith(k, 1.0);
        let dp = w.cross(&(p_end - base_origin));
        jac.fixed_view_mut::<3, 1>(0, b + 3 + k).copy_from(&dp);
        jac.fixed_view_mut::<3, 1>(3, b + 3 + k).copy_from(&w);
    }
    // `frame` is now world_to_flange; the tool is perturbed on the left in
    // the flange frame: translation moves the point, rotation only turns it.
    let t = b + BASE_PARAMS;
    for k in 0..layout.instrument.tool_params().min(3) {
        let u = frame.rotation * Vector3::ith(k, 1.0);
        jac.fixed_view_mut::<3, 1>(0, t + k).copy_from(&u);
    }
    if layout.instrument == Instrument::Camera {
        for k in 0..3 {
            let w = frame.rotation * Vector3::ith(k, 1.0);
            jac.fixed_view_mut::<3, 1>(3, t + 3 + k).copy_from(&w);
        }
    }
    Ok((tool, jac))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{pose_error, pose_from_xyz_rpy_deg};
    use crate::kinematics::presets;
    use nalgebra::DVector;

    const STEP: f64 = 1e-6;

    fn check(instrument: Instrument, robot: crate::kinematics::RobotModel) {
        let model = CalibratedModel {
            robot,
            world_to_base: pose_from_xyz_rpy_deg([100.0, -800.0, 300.0], [10.0, -20.0, 170.0])
                .unwrap(),
            flange_to_tool: pose_from_xyz_rpy_deg([30.0, -20.0, 110.0], [5.0, 3.0, 80.0]).unwrap(),
        };
        let layout = ParamLayout::new(&model.robot, instrument);
        // Evaluate away from x = 0 too: the Jacobian at the applied model.
        let x0 = DVector::from_fn(layout.len(), |i, _| 2e-3 * ((i * 7 % 5) as f64 - 2.0));
        let model = layout.apply(&model, &x0);
        for q in [
            [0.3, -0.4, 0.2, 1.1, -0.7, 2.0],
            [-1.2, 0.5, -0.3, -2.0, 1.0, -0.4],
        ] {
            let (pose, jac) = tool_pose_jacobian(&layout, &model, &q).unwrap();
            for j in 0..layout.len() {
                let mut e = DVector::zeros(layout.len());
                e[j] = STEP;
                let plus = layout.apply(&model, &e).world_to_tool(&q).unwrap();
                e[j] = -STEP;
                let minus = layout.apply(&model, &e).world_to_tool(&q).unwrap();
                let fd = (pose_error(&plus, &pose) - pose_error(&minus, &pose)) / (2.0 * STEP);
                let col = jac.column(j);
                let rows = instrument.rows();
                let diff = (fd.rows(0, rows) - col.rows(0, rows)).amax();
                assert!(
                    diff < 1e-5 * (1.0 + fd.amax()),
                    "{} column {j}: analytic {} vs fd {}",
                    layout.names()[j],
                    col.transpose(),
                    fd.transpose()
                );
            }
        }
    }

    #[test]
    fn analytic_jacobian_matches_finite_differences() {
        check(Instrument::Camera, presets::irb2400());
        check(Instrument::Camera, presets::puma560());
        check(Instrument::Tracker, presets::puma560());
        check(Instrument::Tracker, presets::ur5());
        check(Instrument::Camera, presets::ur10());
    }
}
