//! The information one pose brings to the image-level identification a job
//! runs (method.md §6 **beyond**, `kinematics/image_fit.rs`): every dot's
//! pixel depends on the parameters only through the 6-D camera pose and the
//! 8 intrinsics, so a pose's information `J_k^T J_k` over all its dots has
//! rank at most 14 and is kept as a low-rank factor `G_k` (`J_k^T J_k =
//! G_k^T G_k`), which makes the selection's determinant updates cheap.
//!
//! Parameters are in scaled units (divided by [`Columns::scale`]) so that
//! the prior and the condition number compare like with like.

use nalgebra::{DMatrix, SMatrix};

use super::error::PlanError;
use super::request::{PlanPurpose, PlanRequest};
use crate::kinematics::identifiability::structural_redundancies_among;
use crate::kinematics::jacobian::tool_pose_jacobian;
use crate::kinematics::projection::{project_with_jacobians, INTRINSIC_NAMES};
use crate::kinematics::{CalibratedModel, Instrument, ParamKind, ParamLayout};

/// Scale of a length parameter (mm) and of an angle (rad, 1 mm at 1 m):
/// the prior standard deviations the greedy selection starts from.
pub const LENGTH_SCALE_MM: f64 = 1.0;
pub const ANGLE_SCALE_RAD: f64 = 1e-3;
/// Scales of the focal lengths and principal point (px) and of the
/// distortion coefficients.
pub const PIXEL_SCALE_PX: f64 = 1.0;
pub const DISTORTION_SCALE: f64 = 1e-3;
/// Intrinsics that are pixels (fx, fy, cx, cy); the rest are distortion.
const PIXEL_INTRINSICS: usize = 4;

/// The unknowns of the identification the plan is for.
#[derive(Debug, Clone, PartialEq)]
pub struct Columns {
    pub layout: ParamLayout,
    /// Layout indices identified.
    pub free: Vec<usize>,
    /// Intrinsics identified with them (0 or 8).
    pub intrinsics: usize,
    /// Scale of every column (free ones, then intrinsics).
    pub scale: Vec<f64>,
    pub names: Vec<String>,
}

impl Columns {
    pub fn len(&self) -> usize {
        self.free.len() + self.intrinsics
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The columns of `request`: a calibration identifies everything not
    /// structurally redundant (and the intrinsics unless held); a quick
    /// check the joint zeros and the base, the rest known.
    pub fn of(request: &PlanRequest, model: &CalibratedModel) -> Result<Self, PlanError> {
        let layout = ParamLayout::new(&model.robot, Instrument::Camera);
        let quick = request.purpose == PlanPurpose::QuickCheck;
        let estimated: Vec<usize> = (0..layout.len())
            .filter(|&i| {
                !quick
                    || matches!(
                        layout.params[i].kind,
                        ParamKind::JointOffset | ParamKind::Base(_)
                    )
            })
            .collect();
        // Redundant among the estimated ones only: with the hand–eye known,
        // a quick check sees the last joint's zero drift.
        let structural = structural_redundancies_among(&layout, model, &estimated)
            .map_err(|e| PlanError::Model(e.to_string()))?;
        let free: Vec<usize> = estimated
            .into_iter()
            .filter(|i| !structural.contains(i))
            .collect();
        let intrinsics = if quick || request.hold_intrinsics {
            0
        } else {
            INTRINSIC_NAMES.len()
        };
        let mut scale: Vec<f64> = free
            .iter()
            .map(|&i| {
                if layout.is_angle(i) {
                    ANGLE_SCALE_RAD
                } else {
                    LENGTH_SCALE_MM
                }
            })
            .collect();
        scale.extend((0..intrinsics).map(|k| {
            if k < PIXEL_INTRINSICS {
                PIXEL_SCALE_PX
            } else {
                DISTORTION_SCALE
            }
        }));
        let mut names: Vec<String> = free
            .iter()
            .map(|&i| layout.params[i].name.clone())
            .collect();
        names.extend(INTRINSIC_NAMES[..intrinsics].iter().map(|s| s.to_string()));
        Ok(Self {
            layout,
            free,
            intrinsics,
            scale,
            names,
        })
    }
}

/// `G` with `J^T J = G^T G` for the image of every board point at joints
/// `q` (whitened by `sigma_px`, scaled columns); `None` if a point falls
/// behind the camera or the pose cannot be evaluated.
pub fn pose_factor(
    request: &PlanRequest,
    model: &CalibratedModel,
    columns: &Columns,
    q: &[f64],
) -> Option<DMatrix<f64>> {
    let (t2c, jt) = tool_pose_jacobian(&columns.layout, model, q).ok()?;
    let mut h = SMatrix::<f64, 14, 14>::zeros();
    for p in &request.board_points {
        let (_, jp, jc) = project_with_jacobians(&request.intrinsics, &t2c, p)?;
        let mut row = SMatrix::<f64, 2, 14>::zeros();
        row.fixed_view_mut::<2, 6>(0, 0).copy_from(&jp);
        row.fixed_view_mut::<2, 8>(0, 6).copy_from(&jc);
        h += row.transpose() * row;
    }
    let ni = columns.intrinsics;
    let m = 6 + ni;
    let h = DMatrix::from_fn(m, m, |r, c| h[(r, c)]) / (request.sigma_px * request.sigma_px);
    // B maps the scaled parameters to (pose perturbation, intrinsics).
    let nf = columns.free.len();
    let mut b = DMatrix::zeros(m, columns.len());
    for (c, &i) in columns.free.iter().enumerate() {
        for r in 0..6 {
            b[(r, c)] = jt[(r, i)] * columns.scale[c];
        }
    }
    for k in 0..ni {
        b[(6 + k, nf + k)] = columns.scale[nf + k];
    }
    // h = V D V^T, G = D^1/2 V^T B.
    let eig = h.symmetric_eigen();
    let root = DMatrix::from_fn(m, m, |r, c| {
        eig.eigenvalues[r].max(0.0).sqrt() * eig.eigenvectors[(c, r)]
    });
    Some(root * b)
}
