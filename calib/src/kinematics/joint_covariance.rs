//! The full covariance of a joint refinement's kinematic parameters
//! (method.md §6 **beyond**): [`super::joint_refine`] reports only their
//! standard deviations; predicted pose uncertainties need the correlations
//! too (a base offset and a link length trade against each other).
//!
//! Recomputed at the refinement's solution from its public result: each
//! pose's 6-D sums over its dots (as in the refinement's normal equations),
//! the pose's joint corrections eliminated by their Schur complement, the
//! intrinsics marginalised by taking the kinematic block of the inverse.
//! Scaled by the same residual variance as the reported standard
//! deviations, so its diagonal reproduces them.

use nalgebra::{DMatrix, Matrix6, SMatrix};

use super::identify_error::IdentifyError;
use super::image_pose::ImagePose;
use super::jacobian::tool_pose_jacobian;
use super::joint_refine::JointRefinement;
use super::params::{CalibratedModel, ParamKind};
use super::projection::{project_with_jacobians, INTRINSIC_NAMES};
use super::uncertainty::embed_covariance;
use crate::covariance::covariance_from_normal;

const INTRINSICS: usize = INTRINSIC_NAMES.len();

/// Layout-sized covariance (internal units, zero where fixed) of
/// `refined`'s kinematic parameters, from the `poses` and `free` layout
/// indices it was refined with; `hold_intrinsics` as given to it.
pub fn joint_refine_covariance(
    refined: &JointRefinement,
    poses: &[ImagePose],
    free: &[usize],
    hold_intrinsics: bool,
) -> Result<DMatrix<f64>, IdentifyError> {
    joint_refine_covariance_sessions(refined, poses, free, hold_intrinsics, &[])
}

/// [`joint_refine_covariance`] of a refinement over several board
/// placements ([`super::regions::joint_refine_regions`]): pose `k` sees the
/// board `refined.session_target_to_base[session_of[k]]` (empty
/// `session_of`: one session). The further sessions' free base values are
/// unknowns of their own, marginalised like the intrinsics, so the
/// kinematic block is neither conditioned on them nor on session 0's.
pub fn joint_refine_covariance_sessions(
    refined: &JointRefinement,
    poses: &[ImagePose],
    free: &[usize],
    hold_intrinsics: bool,
    session_of: &[usize],
) -> Result<DMatrix<f64>, IdentifyError> {
    let mut all = session_covariances(refined, poses, free, hold_intrinsics, session_of)?;
    Ok(all.swap_remove(0))
}

/// [`joint_refine_covariance_sessions`] seen from every session: entry `s`
/// is the layout-sized covariance with the base values of session `s`'s
/// board in the base slots (its own correlations with the kinematics and
/// hand–eye, the other boards marginalised). What `forward`'s σ needs when
/// it works in session `s`'s board frame.
pub fn session_covariances(
    refined: &JointRefinement,
    poses: &[ImagePose],
    free: &[usize],
    hold_intrinsics: bool,
    session_of: &[usize],
) -> Result<Vec<DMatrix<f64>>, IdentifyError> {
    let layout = &refined.layout;
    let ni = if hold_intrinsics { 0 } else { INTRINSICS };
    let base_slots: Vec<usize> = (0..free.len())
        .filter(|&c| matches!(layout.params[free[c]].kind, ParamKind::Base(_)))
        .collect();
    let sessions = refined.session_target_to_base.len().max(1);
    let nf_layout = free.len();
    // The kinematic unknowns: the layout's free values, then each further
    // session's free base values (as in the refinement's own head).
    let nf = nf_layout + base_slots.len() * (sessions - 1);
    let head = nf + ni;
    let sigma_q = refined.joint_sigma_rad;
    let nj = if sigma_q > 0.0 { layout.joints() } else { 0 };
    let s = refined.sigma_px;
    if poses.is_empty() || s <= 0.0 {
        return Err(IdentifyError::NoPoses);
    }
    let offsets = layout.joint_offset_indices();
    let mut reduced = DMatrix::<f64>::zeros(head, head);
    let (mut cost, mut rows) = (0.0, 0usize);
    for (k, pose) in poses.iter().enumerate() {
        let correction = refined.joint_corrections_rad.get(k);
        let q: Vec<f64> = pose
            .joints_rad
            .iter()
            .enumerate()
            .map(|(j, q)| q + correction.and_then(|c| c.get(j)).copied().unwrap_or(0.0))
            .collect();
        let session = session_of.get(k).copied().unwrap_or(0);
        let model = CalibratedModel {
            world_to_base: refined
                .session_target_to_base
                .get(session)
                .copied()
                .unwrap_or(refined.model.world_to_base),
            ..refined.model.clone()
        };
        let (t2c, jt) = tool_pose_jacobian(layout, &model, &q)
            .map_err(|source| IdentifyError::Pose { pose: k, source })?;
        let (mut h_pp, mut h_pc, mut h_cc) = (
            Matrix6::<f64>::zeros(),
            SMatrix::<f64, 6, INTRINSICS>::zeros(),
            SMatrix::<f64, INTRINSICS, INTRINSICS>::zeros(),
        );
        for (p, uv) in &pose.observations {
            let Some((pred, jp, jc)) = project_with_jacobians(&refined.intrinsics, &t2c, p) else {
                continue;
            };
            let (jp, jc) = (jp / s, jc / s);
            h_pp += jp.transpose() * jp;
            h_pc += jp.transpose() * jc;
            h_cc += jc.transpose() * jc;
            cost += ((pred.coords - uv.coords) / s).norm_squared();
            rows += 2;
        }
        let mut t_free = DMatrix::zeros(6, nf);
        for (c, &i) in free.iter().enumerate() {
            t_free.set_column(c, &jt.column(i));
        }
        if session > 0 {
            // This pose's board is its session's: its base columns move there.
            let at = nf_layout + (session - 1) * base_slots.len();
            for (j, &c) in base_slots.iter().enumerate() {
                let column = t_free.column(c).into_owned();
                t_free.set_column(at + j, &column);
                t_free.column_mut(c).fill(0.0);
            }
        }
        let h_pp = DMatrix::from_column_slice(6, 6, h_pp.as_slice());
        let h_pc = DMatrix::from_column_slice(6, INTRINSICS, h_pc.as_slice())
            .columns(0, ni)
            .into_owned();
        let h_cc = DMatrix::from_column_slice(INTRINSICS, INTRINSICS, h_cc.as_slice())
            .view((0, 0), (ni, ni))
            .into_owned();
        // This pose's head block, less its joint corrections' Schur term.
        let mut block = DMatrix::zeros(head, head);
        block
            .view_mut((0, 0), (nf, nf))
            .copy_from(&(t_free.transpose() * &h_pp * &t_free));
        let kc = t_free.transpose() * &h_pc;
        block.view_mut((0, nf), (nf, ni)).copy_from(&kc);
        block.view_mut((nf, 0), (ni, nf)).copy_from(&kc.transpose());
        block.view_mut((nf, nf), (ni, ni)).copy_from(&h_cc);
        if nj > 0 {
            let t_joint = DMatrix::from_fn(6, nj, |r, c| jt[(r, offsets[c])]);
            let hj = &h_pp * &t_joint;
            let mut cross = DMatrix::zeros(head, nj);
            cross
                .view_mut((0, 0), (nf, nj))
                .copy_from(&(t_free.transpose() * &hj));
            cross
                .view_mut((nf, 0), (ni, nj))
                .copy_from(&(h_pc.transpose() * &t_joint));
            let qq = t_joint.transpose() * &hj + DMatrix::identity(nj, nj) / (sigma_q * sigma_q);
            let qq_inv = qq
                .cholesky()
                .ok_or(IdentifyError::BadCovariance { pose: k })?
                .inverse();
            block -= &cross * qq_inv * cross.transpose();
            if let Some(c) = correction {
                cost += c.iter().map(|e| (e / sigma_q).powi(2)).sum::<f64>();
            }
        }
        reduced += block;
    }
    // The kinematic prior's information (a MAP fit): the posterior.
    for (k, w) in refined.prior_weights.iter().enumerate().take(nf_layout) {
        reduced[(k, k)] += w * w;
    }
    let dof = rows.saturating_sub(head).max(1) as f64;
    let head_cov = covariance_from_normal(&reduced, cost / dof);
    Ok((0..sessions)
        .map(|session| {
            // Head index of each layout free value as session `session` sees it.
            let mut at: Vec<usize> = (0..nf_layout).collect();
            if session > 0 {
                let first = nf_layout + (session - 1) * base_slots.len();
                for (j, &c) in base_slots.iter().enumerate() {
                    at[c] = first + j;
                }
            }
            let kinematic = DMatrix::from_fn(nf_layout, nf_layout, |r, c| head_cov[(at[r], at[c])]);
            embed_covariance(layout.len(), free, &kinematic)
        })
        .collect())
}

#[cfg(test)]
#[path = "joint_covariance_tests.rs"]
mod tests;
