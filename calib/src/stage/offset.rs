//! The part of a sequence's error no stage method sees: the offset common
//! to all its images. The stage's readings fix the camera's travel, not
//! where the board sits on the stage, so the average-rotation method and
//! the stage-referenced table (`super::assessment`) both fit it away. Its
//! size is predicted, not measured, by linear propagation (method.md
//! §"Uncertainty") of every dot's pixel error `e` to the offset:
//!
//! `offset_s = L_s e`, `L_s = D_s - Ḡ_s W_θ`, where
//! - `D_s e` is the mean over the sequence's images of what each image's
//!   own pose fit makes of its dots' errors (`T_v (A_vᵀA_v)⁻¹A_vᵀ e_v`,
//!   `A_v` the projection's derivative by the pose, `T_v` the camera
//!   position's by the pose vector);
//! - `W_θ e = δθ` is the bundle's intrinsics error (`-(JᵀJ)⁺Jᵀ`, rows of
//!   the intrinsics), and `Ḡ_s` the mean over the sequence of
//!   `T_v (A_vᵀA_v)⁻¹A_vᵀ K_v` (`K_v` the projection's derivative by the
//!   intrinsics): how much every image's position moves with them.
//!
//! Session 10 kept only `Ḡ_s Σ_θ Ḡ_sᵀ`, with the white covariance
//! `Σ_θ = σ² (JᵀJ)⁺` (and took `Ḡ_s` by re-measuring every image once per
//! intrinsic parameter). On rendered campaigns of 8 varied layouts the true
//! offsets were 1.88x that σ (RMS of offset / σ per axis) on 9- and on
//! 25-image sequences. Session 11 measured why (BENCHMARKS "Stage
//! accuracy"): the dot errors of rendered images are partly shared
//! by a sequence's images (`super::noise`), so the white `Σ_θ` is 1.4-1.5x
//! too small; the images' own pose noise averaged over the sequence
//! (`D_s`) was left out, and it does not average down as `1/n` either
//! (2.1x (9 images) to 3.2x (25) its independent σ); and it is correlated
//! with the intrinsics' part (the same dots fitted the intrinsics).
//! `Σ_s = L_s Σ_e L_sᵀ`, `Σ_e` from [`DotErrorModel`], holds all three:
//! 1.18 (9 images) and 1.00 (25). The derivatives are analytic: no image
//! is re-measured (75 images: 5-10 ms against 64-86 ms).

use std::collections::HashMap;

use nalgebra::{DMatrix, DVector, Isometry3, Matrix3, Point2, Point3, Vector3, Vector6};

use super::noise::DotErrorModel;
use super::StageError;
use crate::camera::model::Intrinsics;
use crate::camera::projection_jacobian::{projection_jacobian_at, PoseLinearisation, POSE_PARAMS};
use crate::camera::CameraError;
use crate::geometry::{pose_from_vector, pose_to_vector};
use crate::solver::finite_difference_jacobian;

/// One image as its sequence's offset sees it.
#[derive(Debug, Clone, Copy)]
pub struct OffsetView<'a> {
    /// Index of its sequence (`0..sequences`).
    pub sequence: usize,
    /// The dots in use, in the bundle's row order (two rows a dot).
    pub observations: &'a [(Point3<f64>, Point2<f64>)],
    /// The camera's pose measured from this image alone.
    pub target_to_camera: Isometry3<f64>,
}

/// The stage bundle at its solution: residuals `observed - projected`,
/// their Jacobian, and `(JᵀJ)⁺`; the first `intrinsics` parameters are
/// the intrinsics. Rows are the views' dots in [`OffsetView`] order.
pub struct BundleSolution<'a> {
    pub jacobian: &'a DMatrix<f64>,
    pub residuals: &'a DVector<f64>,
    pub normal_inverse: &'a DMatrix<f64>,
    pub intrinsics: usize,
}

/// The linear maps from the dots' pixel errors to each sequence's offset.
pub struct OffsetMaps {
    /// `D_s` (3 x rows), per sequence.
    direct: Vec<DMatrix<f64>>,
    /// `Ḡ_s` (3 x intrinsics), per sequence.
    through_intrinsics: Vec<DMatrix<f64>>,
}

impl OffsetMaps {
    /// Linearises every image's pose fit at its measured pose.
    pub fn new(
        intrinsics: &Intrinsics,
        intrinsic_params: usize,
        views: &[OffsetView],
        sequences: usize,
    ) -> Result<Self, StageError> {
        let rows: usize = views.iter().map(|v| 2 * v.observations.len()).sum();
        let mut direct = vec![DMatrix::zeros(3, rows); sequences];
        let mut through_intrinsics = vec![DMatrix::zeros(3, intrinsic_params); sequences];
        let mut count = vec![0usize; sequences];
        views.iter().for_each(|v| count[v.sequence] += 1);
        let mut at = 0;
        for (index, view) in views.iter().enumerate() {
            let n = 2 * view.observations.len();
            let (a, k) = pose_fit_derivatives(intrinsics, intrinsic_params, view).ok_or(
                CameraError::DegenerateView {
                    view: index,
                    reason: "a dot is behind the camera at the measured pose".into(),
                },
            )?;
            let degenerate = || CameraError::DegenerateView {
                view: index,
                reason: "the pose fit's normal matrix is singular".into(),
            };
            let normal_inverse = a.tr_mul(&a).try_inverse().ok_or_else(degenerate)?;
            let position = position_by_pose(&view.target_to_camera).ok_or_else(degenerate)?;
            let weight = 1.0 / count[view.sequence] as f64;
            // T_v (AᵀA)⁻¹Aᵀ: the camera position's change per pixel error.
            let p = (&position * normal_inverse * a.transpose()) * weight;
            let s = view.sequence;
            direct[s].columns_mut(at, n).copy_from(&p);
            through_intrinsics[s] += &p * k;
            at += n;
        }
        Ok(Self {
            direct,
            through_intrinsics,
        })
    }

    /// `Ḡ_s Σ_θ Ḡ_sᵀ`: the offset's covariance from the intrinsics' alone
    /// (session 10's figure, analytic).
    pub fn intrinsics_covariance(
        &self,
        s: usize,
        intrinsics_covariance: &DMatrix<f64>,
    ) -> Matrix3<f64> {
        let g = &self.through_intrinsics[s];
        let c = g * intrinsics_covariance * g.transpose();
        Matrix3::from_fn(|i, j| c[(i, j)])
    }

    /// `L_s = D_s - Ḡ_s W_θ`, per sequence.
    fn total(&self, bundle: &BundleSolution) -> Vec<DMatrix<f64>> {
        let n = bundle.intrinsics;
        // W_θ = -(JᵀJ)⁺_{θ,:} Jᵀ.
        let w = -(bundle.normal_inverse.rows(0, n) * bundle.jacobian.transpose());
        self.direct
            .iter()
            .zip(&self.through_intrinsics)
            .map(|(d, g)| d - g * &w)
            .collect()
    }
}

/// σ of each sequence's common offset, per target axis (mm): `L_s Σ_e L_sᵀ`
/// with the dot error model fitted to the bundle's residuals.
pub fn sequence_offset_sd_mm(
    bundle: &BundleSolution,
    intrinsics: &Intrinsics,
    views: &[OffsetView],
    sequences: usize,
) -> Result<Vec<Vector3<f64>>, StageError> {
    let maps = OffsetMaps::new(intrinsics, bundle.intrinsics, views, sequences)?;
    let (group, groups) = dot_groups(views);
    let model = DotErrorModel::estimate(
        bundle.residuals.as_slice(),
        &group,
        groups,
        bundle.jacobian.ncols(),
    );
    Ok(maps
        .total(bundle)
        .iter()
        .map(|l| {
            let mut shared = DMatrix::zeros(3, groups);
            for (i, &g) in group.iter().enumerate() {
                let mut column = shared.column_mut(g);
                column += l.column(i);
            }
            let weighted = DMatrix::from_fn(3, groups, |i, g| shared[(i, g)] * model.shared_sq[g]);
            let sigma = model.independent_var * l * l.transpose() + weighted * shared.transpose();
            Vector3::from_fn(|i, _| sigma[(i, i)].max(0.0).sqrt())
        })
        .collect())
}

/// Per residual row, its group (sequence, dot, pixel axis); and the count.
fn dot_groups(views: &[OffsetView]) -> (Vec<usize>, usize) {
    let mut ids: HashMap<(usize, [u64; 3]), usize> = HashMap::new();
    let mut group = Vec::new();
    for view in views {
        for (p, _) in view.observations {
            let key = (view.sequence, [p.x, p.y, p.z].map(f64::to_bits));
            let next = ids.len();
            let id = *ids.entry(key).or_insert(next);
            group.extend([2 * id, 2 * id + 1]);
        }
    }
    (group, 2 * ids.len())
}

/// `A_v` (rows x 6, by the `camera_to_target` pose vector) and `K_v`
/// (rows x intrinsics) of the projection at the measured pose.
fn pose_fit_derivatives(
    intrinsics: &Intrinsics,
    intrinsic_params: usize,
    view: &OffsetView,
) -> Option<(DMatrix<f64>, DMatrix<f64>)> {
    let pose = PoseLinearisation::new(&pose_to_vector(&view.target_to_camera.inverse()));
    let rows = 2 * view.observations.len();
    let mut a = DMatrix::zeros(rows, POSE_PARAMS);
    let mut k = DMatrix::zeros(rows, intrinsic_params);
    for (i, (p, _)) in view.observations.iter().enumerate() {
        let (ji, jp) = projection_jacobian_at(intrinsics, &pose, p)?;
        for r in 0..2 {
            for c in 0..POSE_PARAMS {
                a[(2 * i + r, c)] = jp[(r, c)];
            }
            for c in 0..intrinsic_params {
                k[(2 * i + r, c)] = ji[(r, c)];
            }
        }
    }
    Some((a, k))
}

/// `T_v`: the camera position in the target frame by the
/// `camera_to_target` pose vector (3 x 6).
fn position_by_pose(target_to_camera: &Isometry3<f64>) -> Option<DMatrix<f64>> {
    let x = DVector::from_column_slice(pose_to_vector(&target_to_camera.inverse()).as_slice());
    let position = |v: &DVector<f64>| {
        let c = pose_from_vector(&Vector6::from_column_slice(v.as_slice()))
            .inverse()
            .translation
            .vector;
        Some(DVector::from_column_slice(c.as_slice()))
    };
    finite_difference_jacobian(position, &x)
}

#[cfg(test)]
#[path = "offset_tests.rs"]
mod tests;
