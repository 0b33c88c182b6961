//! The stage campaign's calibration (issue 18): a free camera calibration
//! starts it (intrinsics, poses, the dot-centre bias correction and outlier
//! rejection of method.md §4), the stage bundle ([`super::bundle`]) fits
//! the intrinsics with the stage's translations as constraints, every
//! image's camera position is then measured on its own with those
//! intrinsics (how the camera measures a robot), and each sequence is
//! assessed the paper's way ([`super::assessment`]).

use std::collections::HashSet;

use nalgebra::{Isometry3, Point2, Point3, Rotation3, UnitQuaternion, Vector3};

use super::assessment::{assess_sequence, average_rotation_errors, SequenceAccuracy};
use super::bundle::{BundleView, SequenceFit, SequenceStart, StageBundle};
use super::layout::{average_rotation, fit_stage_axes, group_sequences};
use super::offset::{sequence_offset_sd_mm, BundleSolution, OffsetView};
use super::{StageError, StageView};
use crate::camera::calibrate::{calibrate, CalibrationOptions, CameraCalibration};
use crate::camera::model::{Intrinsics, IntrinsicsStdDev};
use crate::camera::observations::{ImageSize, ViewObservations};
use crate::camera::pose::{estimate_pose, PoseEstimate};
use crate::camera::refine::IntrinsicsBlock;
use crate::camera::CameraError;
use crate::covariance::covariance_from_jacobian;
use crate::geometry::bounding_box;
use crate::solver::{solve, LeastSquaresProblem, LmOptions, SolverError};

/// One image's result.
#[derive(Debug, Clone, PartialEq)]
pub struct StageViewResult {
    pub sequence: u32,
    /// The camera pose measured from this image alone with the stage
    /// bundle's intrinsics (`target_to_camera`, with its covariance).
    pub pose: PoseEstimate,
    /// The bundle's pose of this image (sequence origin + stage translation).
    pub constrained_target_to_camera: Isometry3<f64>,
    /// The image's position error by the paper's average-rotation method
    /// (target frame, mm; [`super::assessment::average_rotation_errors`]).
    pub average_rotation_error_mm: Vector3<f64>,
}

/// A fitted sequence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StageSequence {
    pub sequence: u32,
    pub fit: SequenceFit,
}

#[derive(Debug, Clone, PartialEq)]
pub struct StageCalibration {
    pub image_size: ImageSize,
    /// The stage bundle's intrinsics.
    pub intrinsics: Intrinsics,
    pub std_dev: Option<IntrinsicsStdDev>,
    /// RMS reprojection error of the stage bundle (px, per dot).
    pub rms_px: f64,
    /// The free calibration that started the bundle (no stage constraint).
    pub start: CameraCalibration,
    pub sequences: Vec<StageSequence>,
    /// In the order of the input views.
    pub views: Vec<StageViewResult>,
    /// Per sequence, ascending.
    pub accuracy: Vec<SequenceAccuracy>,
}

/// Calibrates the camera of a stage campaign and assesses it.
pub fn calibrate_stage(
    views: &[StageView],
    options: &CalibrationOptions,
) -> Result<StageCalibration, StageError> {
    let layout = group_sequences(views)?;
    let observations: Vec<ViewObservations> =
        views.iter().map(|v| v.observations.clone()).collect();
    let start = calibrate(&observations, options)?;
    let used = used_observations(&observations, &start);
    let starts: Vec<SequenceStart> = layout
        .iter()
        .map(|seq| {
            let poses: Vec<Isometry3<f64>> = seq
                .views
                .iter()
                .map(|&v| start.views[v].pose.target_to_camera)
                .collect();
            sequence_start(
                &poses,
                &seq.views
                    .iter()
                    .map(|&v| views[v].stage_position_mm)
                    .collect::<Vec<_>>(),
            )
        })
        .collect();
    let mut bundle_views = vec![None; views.len()];
    for (s, seq) in layout.iter().enumerate() {
        for &v in &seq.views {
            bundle_views[v] = Some(BundleView {
                sequence: s,
                stage_position_mm: views[v].stage_position_mm,
                observations: used[v].clone(),
            });
        }
    }
    let bundle_views: Vec<BundleView> = bundle_views.into_iter().flatten().collect();
    let block = match options.fixed_intrinsics {
        Some(i) => IntrinsicsBlock::Fixed(i),
        None => IntrinsicsBlock::Free {
            with_k3: options.estimate_k3,
        },
    };
    let bundle = StageBundle {
        views: &bundle_views,
        start: &starts,
        block,
    };
    let report = solve(
        &bundle,
        bundle.encode(&start.intrinsics),
        &LmOptions::default(),
    )?;
    let intrinsics = bundle.intrinsics(&report.x);
    let dots: usize = bundle_views.iter().map(|v| v.observations.len()).sum();
    // The offsets' σ needs the Jacobian and (JᵀJ)⁺ themselves
    // (`super::offset`); the covariance is the latter scaled.
    let jacobian = match &report.jacobian {
        Some(j) => j.clone(),
        None => bundle.jacobian(&report.x).ok_or(SolverError::NonFinite)?,
    };
    let normal_inverse = covariance_from_jacobian(&jacobian, 1.0);
    let covariance = &normal_inverse * report.residual_variance();
    let std_dev = (!block.is_empty()).then(|| {
        let n = block.len();
        let block_covariance = covariance.view((0, 0), (n, n)).into_owned();
        IntrinsicsStdDev::from_covariance(&block_covariance, &intrinsics)
    });
    let sequences: Vec<StageSequence> = layout
        .iter()
        .enumerate()
        .map(|(s, seq)| StageSequence {
            sequence: seq.sequence,
            fit: bundle.sequence(&report.x, s),
        })
        .collect();
    let results = measure_views(views, &bundle_views, &sequences, &intrinsics)?;
    let centre = board_centre(&observations);
    let mut results = results;
    let mut accuracy = layout
        .iter()
        .map(|seq| {
            let measured: Vec<Isometry3<f64>> = seq
                .views
                .iter()
                .map(|&v| results[v].pose.target_to_camera.inverse())
                .collect();
            for (&v, e) in seq.views.iter().zip(average_rotation_errors(&measured)) {
                results[v].average_rotation_error_mm = e;
            }
            let stage: Vec<Vector3<f64>> = seq
                .views
                .iter()
                .map(|&v| views[v].stage_position_mm)
                .collect();
            assess_sequence(seq.sequence, &measured, &stage, &centre)
        })
        .collect::<Vec<SequenceAccuracy>>();
    let offset_views: Vec<OffsetView> = bundle_views
        .iter()
        .zip(&results)
        .map(|(bv, r)| OffsetView {
            sequence: bv.sequence,
            observations: &bv.observations,
            target_to_camera: r.pose.target_to_camera,
        })
        .collect();
    let offsets = sequence_offset_sd_mm(
        &BundleSolution {
            jacobian: &jacobian,
            residuals: &report.residuals,
            normal_inverse: &normal_inverse,
            intrinsics: block.len(),
        },
        &intrinsics,
        &offset_views,
        layout.len(),
    )?;
    for (acc, sd) in accuracy.iter_mut().zip(offsets) {
        acc.offset_sd_mm = sd.into();
    }
    Ok(StageCalibration {
        image_size: start.image_size,
        intrinsics,
        std_dev,
        rms_px: (report.cost / dots.max(1) as f64).sqrt(),
        start,
        sequences,
        views: results,
        accuracy,
    })
}

/// The bias-corrected dots the free calibration kept, per view.
fn used_observations(
    observations: &[ViewObservations],
    start: &CameraCalibration,
) -> Vec<Vec<(Point3<f64>, Point2<f64>)>> {
    let dropped: HashSet<(usize, u32, u32)> = start
        .outliers
        .iter()
        .map(|o| (o.view, o.row, o.col))
        .collect();
    observations
        .iter()
        .zip(&start.views)
        .enumerate()
        .map(|(v, (obs, fit))| {
            obs.dots
                .iter()
                .zip(&fit.corrected_pixels)
                .filter(|(d, _)| !dropped.contains(&(v, d.row, d.col)))
                .map(|(d, px)| (d.target_mm, *px))
                .collect()
        })
        .collect()
}

/// The bundle's start for one sequence: the average of the free poses'
/// orientations and the Kabsch fit of their positions to the stage's.
fn sequence_start(target_to_camera: &[Isometry3<f64>], stage_mm: &[Vector3<f64>]) -> SequenceStart {
    let rotations: Vec<Rotation3<f64>> = target_to_camera
        .iter()
        .map(|p| p.rotation.to_rotation_matrix())
        .collect();
    let camera_mm: Vec<Vector3<f64>> = target_to_camera
        .iter()
        .map(|p| p.translation.vector)
        .collect();
    let (stage_axes, origin_mm) = fit_stage_axes(stage_mm, &camera_mm);
    SequenceStart {
        target_to_camera_rotation: UnitQuaternion::from_rotation_matrix(&average_rotation(
            &rotations,
        )),
        target_to_stage_rotation: UnitQuaternion::from_rotation_matrix(&stage_axes),
        origin_mm,
    }
}

/// Each image's own camera pose with the bundle's intrinsics, started at
/// the bundle's constrained pose (`bundle_views[v]` is view `v`'s).
fn measure_views(
    views: &[StageView],
    bundle_views: &[BundleView],
    sequences: &[StageSequence],
    intrinsics: &Intrinsics,
) -> Result<Vec<StageViewResult>, StageError> {
    views
        .iter()
        .zip(bundle_views)
        .enumerate()
        .map(|(v, (view, bv))| {
            let constrained = sequences[bv.sequence]
                .fit
                .target_to_camera(&bv.stage_position_mm);
            let pose = estimate_pose(intrinsics, &bv.observations, Some(&constrained.inverse()))
                .map_err(|e| match e {
                    CameraError::DegenerateView { reason, .. } => {
                        CameraError::DegenerateView { view: v, reason }
                    }
                    other => other,
                })?;
            Ok(StageViewResult {
                sequence: view.sequence,
                pose,
                constrained_target_to_camera: constrained,
                average_rotation_error_mm: Vector3::zeros(),
            })
        })
        .collect()
}

/// The middle of the board's seen dots (target frame): the point whose
/// distance Fig. 5 plots against.
fn board_centre(observations: &[ViewObservations]) -> Point3<f64> {
    let points = observations
        .iter()
        .flat_map(|v| v.dots.iter().map(|d| d.target_mm));
    let (lo, hi) = bounding_box(points);
    Point3::from(0.5 * (lo + hi))
}
