//! The stage bundle: intrinsics and, per sequence, one camera orientation,
//! one origin and the stage's axes, fitted to every image's dots at once
//! (issue 18). Image `i` of sequence `s` has the camera pose
//! `target_to_camera_i = (o_s + S_s t_i, R_s)`: the stage only translates
//! (one `R_s` per sequence) and reads `t_i` exactly, so the translations
//! between images are constraints, not unknowns. That is the paper's CMM
//! reference built into the fit (method.md §4 **beyond**: it tuned `fx` by
//! hand against the CMM's travel).
//!
//! Parameter vector: the intrinsics block `[fx, m, cx, cy, k1, k2, p1, p2]`
//! ([`IntrinsicsBlock`]), then per sequence `[o (mm), dR, dS]` where the
//! rotations are `R_s = R0_s exp(dR)`, `S_s = S0_s exp(dS)` about the
//! closed-form start (a local parameterisation: no rotation-vector
//! singularity whatever the board's roll).

use nalgebra::{DVector, Isometry3, Point2, Point3, Translation3, UnitQuaternion, Vector3};

use crate::camera::model::Intrinsics;
use crate::camera::pose::reprojection_residuals;
use crate::camera::refine::IntrinsicsBlock;
use crate::geometry::rotation_from_vector;
use crate::solver::LeastSquaresProblem;

/// Unknowns per sequence: origin, camera rotation correction, stage-axes
/// rotation correction.
pub const SEQUENCE_PARAMS: usize = 9;

/// One image in the bundle.
#[derive(Debug, Clone, PartialEq)]
pub struct BundleView {
    /// Index of its sequence in [`StageBundle::start`].
    pub sequence: usize,
    pub stage_position_mm: Vector3<f64>,
    /// `(board point mm, bias-corrected pixel)` of the dots in use.
    pub observations: Vec<(Point3<f64>, Point2<f64>)>,
}

/// A sequence's start: camera orientation in the target frame and the
/// stage's axes in the target frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SequenceStart {
    pub target_to_camera_rotation: UnitQuaternion<f64>,
    pub target_to_stage_rotation: UnitQuaternion<f64>,
    pub origin_mm: Vector3<f64>,
}

/// A sequence as fitted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SequenceFit {
    pub target_to_camera_rotation: UnitQuaternion<f64>,
    pub target_to_stage_rotation: UnitQuaternion<f64>,
    /// The camera position at stage reading zero (target frame, mm).
    pub origin_mm: Vector3<f64>,
}

impl SequenceFit {
    /// The camera pose in the target frame at stage reading `t`.
    pub fn target_to_camera(&self, stage_position_mm: &Vector3<f64>) -> Isometry3<f64> {
        Isometry3::from_parts(
            Translation3::from(self.origin_mm + self.target_to_stage_rotation * stage_position_mm),
            self.target_to_camera_rotation,
        )
    }
}

pub struct StageBundle<'a> {
    pub views: &'a [BundleView],
    pub start: &'a [SequenceStart],
    pub block: IntrinsicsBlock,
}

impl StageBundle<'_> {
    pub fn encode(&self, intrinsics: &Intrinsics) -> DVector<f64> {
        let mut x = self.block.encode(intrinsics);
        for s in self.start {
            x.extend_from_slice(s.origin_mm.as_slice());
            x.extend_from_slice(&[0.0; 6]);
        }
        DVector::from_vec(x)
    }

    pub fn intrinsics(&self, x: &DVector<f64>) -> Intrinsics {
        self.block.decode(&x.as_slice()[..self.block.len()])
    }

    pub fn sequence(&self, x: &DVector<f64>, s: usize) -> SequenceFit {
        let o = self.block.len() + SEQUENCE_PARAMS * s;
        let v = |k: usize| Vector3::new(x[o + k], x[o + k + 1], x[o + k + 2]);
        let start = &self.start[s];
        SequenceFit {
            origin_mm: v(0),
            target_to_camera_rotation: start.target_to_camera_rotation
                * rotation_from_vector(&v(3)),
            target_to_stage_rotation: start.target_to_stage_rotation * rotation_from_vector(&v(6)),
        }
    }
}

impl LeastSquaresProblem for StageBundle<'_> {
    fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
        let intrinsics = self.intrinsics(x);
        let fits: Vec<SequenceFit> = (0..self.start.len()).map(|s| self.sequence(x, s)).collect();
        let rows: usize = self.views.iter().map(|v| 2 * v.observations.len()).sum();
        let mut r = DVector::zeros(rows);
        let mut at = 0;
        for view in self.views {
            let camera_to_target = fits[view.sequence]
                .target_to_camera(&view.stage_position_mm)
                .inverse();
            let n = 2 * view.observations.len();
            reprojection_residuals(
                &intrinsics,
                &camera_to_target,
                &view.observations,
                &mut r.as_mut_slice()[at..at + n],
            )?;
            at += n;
        }
        Some(r)
    }
}
