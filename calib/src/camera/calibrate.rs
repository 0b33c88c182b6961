//! The camera-calibration entry point (issue 4): paper mode (Tsai RAC and
//! the sequence searches, method.md §3–4) or refined mode (the default:
//! joint LM from the Tsai start with bias correction and outlier
//! rejection, method.md §4 **beyond**).

use nalgebra::{Isometry3, Point2, Point3, Vector2};
use serde::{Deserialize, Serialize};

use super::error::CameraError;
use super::model::Intrinsics;
pub use super::model::IntrinsicsStdDev;
use super::observations::{validate_views, Correspondences, ImageSize, ViewObservations};
pub use super::options::{CalibrationMode, CalibrationOptions, OUTLIER_SIGMAS};
use super::pose::{estimate_pose, planar_pose_guess, PoseEstimate};
use super::refine_loop::{refine, RefineInput, Refinement};
use super::sequence::{
    paper_sequence, paper_sequence_searching, PaperCalibration, PaperOptions, PlanarView,
    CENTRE_STEP_MIN_PX_START, SCALE_STEP_MIN_START,
};
use super::tsai::board_angle_deg;

/// Fewest images a calibration accepts (issue 4).
pub const MIN_IMAGES: usize = 3;
/// Views with a smaller board-to-image angle get a warning (method.md §3).
pub const WARN_BOARD_ANGLE_DEG: f64 = 20.0;
/// The focal length counts as undetermined (views too close to
/// fronto-parallel) when its standard deviation exceeds this fraction.
pub const FOCAL_UNDETERMINED_REL: f64 = 0.01;
/// ... or when the per-image Tsai focal lengths scatter by more than this
/// (coefficient of variation).
pub const PAPER_FX_SPREAD_MAX: f64 = 0.25;
/// Refined mode: the paper-stage searches that only start the joint LM use
/// at most this many dots per view (whole rows and columns dropped, see
/// [`thin_for_search`]) ...
const START_SEARCH_DOTS_PER_VIEW: usize = 80;
/// ... unless fewer than this would remain.
const START_SEARCH_MIN_DOTS: usize = 16;
/// A dot left out as an outlier.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OutlierDot {
    pub view: usize,
    pub row: u32,
    pub col: u32,
    pub residual_px: f64,
}

/// Per-image results.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewReport {
    /// Target pose in the camera frame (`P_c = R P_w + T`).
    pub camera_to_target: Isometry3<f64>,
    /// Camera pose in the target frame with covariance (intrinsics held fixed).
    pub pose: PoseEstimate,
    pub rms_px: f64,
    pub board_angle_deg: f64,
    pub dots_used: usize,
    /// Bias-corrected observed centres, in the order of the input dots.
    pub corrected_pixels: Vec<Point2<f64>>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct CameraCalibration {
    pub mode: CalibrationMode,
    /// True when only the paper's method ran.
    pub paper_mode: bool,
    pub image_size: ImageSize,
    pub intrinsics: Intrinsics,
    /// `None` in paper mode and with fixed intrinsics.
    pub std_dev: Option<IntrinsicsStdDev>,
    /// RMS reprojection error over all used dots (px, sqrt(mean |r|^2)).
    pub rms_px: f64,
    pub views: Vec<ViewReport>,
    pub outliers: Vec<OutlierDot>,
    pub warnings: Vec<String>,
    pub bias_iterations: usize,
    /// The paper stage (always run: it starts the refinement).
    pub paper: PaperCalibration,
}

/// Calibrate the camera from dot observations of a flat board.
pub fn calibrate(
    views: &[ViewObservations],
    options: &CalibrationOptions,
) -> Result<CameraCalibration, CameraError> {
    let image_size = validate_views(views)?;
    if views.len() < MIN_IMAGES {
        return Err(CameraError::TooFewImages {
            usable: views.len(),
            required: MIN_IMAGES,
        });
    }
    check_options(views.len(), options)?;
    let planar: Vec<PlanarView> = views
        .iter()
        .map(|v| {
            v.dots
                .iter()
                .map(|d| (Vector2::new(d.target_mm.x, d.target_mm.y), d.pixel))
                .collect()
        })
        .collect();
    // In refined mode the searches only start the joint LM: a coarser
    // resolution is enough and saves most of their time.
    let paper_options = match options.mode {
        CalibrationMode::Paper => options.paper,
        CalibrationMode::Refined => PaperOptions {
            centre_tolerance_px: options
                .paper
                .centre_tolerance_px
                .max(CENTRE_STEP_MIN_PX_START),
            scale_tolerance: options.paper.scale_tolerance.max(SCALE_STEP_MIN_START),
            ..options.paper
        },
    };
    let paper = match options.mode {
        CalibrationMode::Paper => paper_sequence(&planar, image_size, &paper_options)?,
        CalibrationMode::Refined => {
            let thinned: Vec<PlanarView> = views.iter().zip(&planar).map(thin_for_search).collect();
            paper_sequence_searching(&planar, &thinned, image_size, &paper_options)?
        }
    };
    // The per-image Tsai spread only judges the paper's own answer. In
    // refined mode the sequence merely starts the joint fit, which has its
    // own test (the fitted focal's standard deviation, below): a spread
    // over a few nearly flat views (RCT's wrist set, docs/decisions/
    // 0033-camera-stage-robustness.md) must not refuse a camera the joint fit determines well.
    if options.mode == CalibrationMode::Paper {
        check_focal_determined_paper(&paper)?;
    }
    let pairs: Vec<Vec<(Point3<f64>, Point2<f64>)>> = views.iter().map(|v| v.pairs()).collect();
    let start = options.fixed_intrinsics.unwrap_or(paper.intrinsics);
    let initial_poses = pairs
        .iter()
        .enumerate()
        .map(|(i, p)| {
            planar_pose_guess(&start, p).ok_or_else(|| CameraError::DegenerateView {
                view: i,
                reason: "no initial pose from the homography".into(),
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let refinement = match options.mode {
        CalibrationMode::Paper => None,
        CalibrationMode::Refined => Some(refine(&RefineInput {
            views: &pairs,
            initial_intrinsics: start,
            initial_poses: &initial_poses,
            options,
        })?),
    };
    if let Some(r) = &refinement {
        if let Some(sd) = r.std_dev {
            if sd.fx.is_nan() || sd.fx > FOCAL_UNDETERMINED_REL * r.intrinsics.fx {
                return Err(CameraError::AllFrontoParallel {
                    max_angle_deg: max_board_angle_deg(&r.camera_to_target),
                });
            }
        }
    }
    finish(views, image_size, options, paper, refinement, &pairs)
}

/// The dots of every `stride`-th row and column, the smallest stride that
/// leaves at most [`START_SEARCH_DOTS_PER_VIEW`] dots (all dots if fewer
/// than [`START_SEARCH_MIN_DOTS`] would remain): the refined mode's start
/// search needs the board's extent, not every dot.
fn thin_for_search((view, planar): (&ViewObservations, &PlanarView)) -> PlanarView {
    let mut stride = 1;
    loop {
        let kept: PlanarView = view
            .dots
            .iter()
            .zip(planar)
            .filter(|(d, _)| d.row % stride == 0 && d.col % stride == 0)
            .map(|(_, p)| *p)
            .collect();
        if kept.len() < START_SEARCH_MIN_DOTS {
            return planar.clone();
        }
        if kept.len() <= START_SEARCH_DOTS_PER_VIEW {
            return kept;
        }
        stride += 1;
    }
}

fn max_board_angle_deg(camera_to_target: &[Isometry3<f64>]) -> f64 {
    camera_to_target
        .iter()
        .map(|p| board_angle_deg(p.rotation.to_rotation_matrix().matrix()))
        .fold(0.0, f64::max)
}

/// Near-fronto-parallel sequences show up as wildly different per-image
/// Tsai focal lengths (stage 2 cannot separate fx and Tz, method.md §3).
fn check_focal_determined_paper(paper: &PaperCalibration) -> Result<(), CameraError> {
    let fx: Vec<f64> = paper.views.iter().flatten().map(|v| v.fx).collect();
    let n = fx.len() as f64;
    let mean = fx.iter().sum::<f64>() / n;
    let spread = (fx.iter().map(|f| (f - mean).powi(2)).sum::<f64>() / n).sqrt() / mean;
    if fx.len() > 1 && spread > PAPER_FX_SPREAD_MAX {
        let max_angle_deg = paper
            .views
            .iter()
            .flatten()
            .map(|v| v.board_angle_deg)
            .fold(0.0, f64::max);
        return Err(CameraError::AllFrontoParallel { max_angle_deg });
    }
    Ok(())
}

fn check_options(n_views: usize, options: &CalibrationOptions) -> Result<(), CameraError> {
    if let Some(d) = options.dot_diameter_mm {
        if !(d > 0.0 && d.is_finite()) {
            return Err(CameraError::InvalidOption {
                field: "dot_diameter_mm",
                reason: "must be positive".into(),
            });
        }
    }
    if options.outlier_sigmas.is_nan() || options.outlier_sigmas <= 0.0 {
        return Err(CameraError::InvalidOption {
            field: "outlier_sigmas",
            reason: "must be positive".into(),
        });
    }
    for r in &options.reference_distances {
        if r.view_a >= n_views || r.view_b >= n_views || r.view_a == r.view_b {
            return Err(CameraError::InvalidOption {
                field: "reference_distances",
                reason: format!(
                    "views {} and {} must be two different views of {n_views}",
                    r.view_a, r.view_b
                ),
            });
        }
        if !(r.sigma_mm > 0.0 && r.distance_mm > 0.0 && r.distance_mm.is_finite()) {
            return Err(CameraError::InvalidOption {
                field: "reference_distances",
                reason: "distance and sigma must be positive".into(),
            });
        }
    }
    Ok(())
}

fn finish(
    views: &[ViewObservations],
    image_size: ImageSize,
    options: &CalibrationOptions,
    paper: PaperCalibration,
    refinement: Option<Refinement>,
    pairs: &[Vec<(Point3<f64>, Point2<f64>)>],
) -> Result<CameraCalibration, CameraError> {
    let intrinsics = refinement
        .as_ref()
        .map_or(paper.intrinsics, |r| r.intrinsics);
    let mut warnings = Vec::new();
    let mut reports = Vec::with_capacity(views.len());
    let (mut sum_sq, mut count) = (0.0, 0usize);
    for (v, obs) in pairs.iter().enumerate() {
        let (used, corrected): (Correspondences, Vec<Point2<f64>>) = match &refinement {
            Some(r) => (r.used_observations(v), r.corrected[v].clone()),
            None => (obs.clone(), obs.iter().map(|(_, p)| *p).collect()),
        };
        let guess = refinement.as_ref().map(|r| r.camera_to_target[v]);
        let pose = estimate_pose(&intrinsics, &used, guess.as_ref()).map_err(|e| match e {
            CameraError::DegenerateView { reason, .. } => {
                CameraError::DegenerateView { view: v, reason }
            }
            other => other,
        })?;
        let camera_to_target = pose.target_to_camera.inverse();
        let angle = board_angle_deg(camera_to_target.rotation.to_rotation_matrix().matrix());
        if angle < WARN_BOARD_ANGLE_DEG {
            warnings.push(format!(
                "view {v}: board-to-image angle {angle:.1} deg is below {WARN_BOARD_ANGLE_DEG} deg; focal length and distance are poorly separated"
            ));
        }
        sum_sq += pose.rms_px.powi(2) * used.len() as f64;
        count += used.len();
        reports.push(ViewReport {
            camera_to_target,
            rms_px: pose.rms_px,
            board_angle_deg: angle,
            dots_used: used.len(),
            corrected_pixels: corrected,
            pose,
        });
    }
    let outliers = refinement.as_ref().map_or_else(Vec::new, |r| {
        r.outliers
            .iter()
            .map(|&(view, index, residual_px)| OutlierDot {
                view,
                row: views[view].dots[index].row,
                col: views[view].dots[index].col,
                residual_px,
            })
            .collect()
    });
    for o in &outliers {
        warnings.push(format!(
            "view {}: dot ({}, {}) dropped as an outlier ({:.3} px)",
            o.view, o.row, o.col, o.residual_px
        ));
    }
    Ok(CameraCalibration {
        mode: options.mode,
        paper_mode: options.mode == CalibrationMode::Paper,
        image_size,
        intrinsics,
        std_dev: refinement.as_ref().and_then(|r| r.std_dev),
        rms_px: (sum_sq / count.max(1) as f64).sqrt(),
        views: reports,
        outliers,
        warnings,
        bias_iterations: refinement.as_ref().map_or(0, |r| r.bias_iterations),
        paper,
    })
}

#[cfg(test)]
#[path = "calibrate_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "cmu_tests.rs"]
mod cmu_tests;
