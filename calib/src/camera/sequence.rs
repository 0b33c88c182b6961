//! Sequence-level intrinsics of the paper (method.md §4, paper §§3.2–3.3):
//! the scale ratio `m` and the image centre found by minimising the mean
//! normalised radial-alignment residual over all images (alternating
//! coordinate/pattern search), then per-image stage 2 and averaged `fx, k`.

use nalgebra::{Point2, Vector2};

use super::error::CameraError;
use super::model::Intrinsics;
use super::observations::ImageSize;
use super::tsai::{
    alignment_residual_rms, board_angle_deg, calibrate_view, centre_points, stage1, Stage2Form,
    TsaiView,
};

/// First pattern-search step for the centre, as a fraction of the shorter image side.
const CENTRE_STEP_FRACTION: f64 = 0.02;
/// Stop the centre search below this step (px) in paper mode.
pub const CENTRE_STEP_MIN_PX: f64 = 1e-3;
/// ... and when it only starts the refinement, which finds the centre itself.
pub const CENTRE_STEP_MIN_PX_START: f64 = 0.5;
/// First and last pattern-search steps of the scale ratio.
const SCALE_STEP: f64 = 0.01;
pub const SCALE_STEP_MIN: f64 = 1e-6;
pub const SCALE_STEP_MIN_START: f64 = 1e-3;
/// Plausible range of `m` (pixel aspect).
const SCALE_RATIO_RANGE: (f64, f64) = (0.5, 2.0);
/// Views whose board is closer than this to fronto-parallel do not enter
/// the stage-2 averages: Tz and fx are inseparable there (method.md §3).
pub const STAGE2_MIN_ANGLE_DEG: f64 = 10.0;
/// Evaluation budget of the search.
const MAX_EVALUATIONS: usize = 2000;

#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PaperOptions {
    pub stage2: Stage2Form,
    pub search_centre: bool,
    pub search_scale_ratio: bool,
    /// Start of the centre search; the image's middle if `None`.
    pub initial_centre: Option<[f64; 2]>,
    pub initial_scale_ratio: f64,
    /// Search resolution of the centre (px) and of `m`.
    pub centre_tolerance_px: f64,
    pub scale_tolerance: f64,
}

impl Default for PaperOptions {
    fn default() -> Self {
        Self {
            stage2: Stage2Form::BothAxes,
            search_centre: true,
            search_scale_ratio: true,
            initial_centre: None,
            initial_scale_ratio: 1.0,
            centre_tolerance_px: CENTRE_STEP_MIN_PX,
            scale_tolerance: SCALE_STEP_MIN,
        }
    }
}

/// The paper's sequence calibration.
#[derive(Debug, Clone, PartialEq)]
pub struct PaperCalibration {
    pub scale_ratio: f64,
    pub cx: f64,
    pub cy: f64,
    /// Mean of the per-image focal lengths (x pixels).
    pub fx: f64,
    /// Mean of the per-image Tsai `k` (px^-2, distorted -> undistorted).
    pub k: f64,
    /// Per-image Tsai results; `None` for views too close to fronto-parallel
    /// (below [`STAGE2_MIN_ANGLE_DEG`]) or where stage 2 failed, which are
    /// left out of the averages.
    pub views: Vec<Option<TsaiView>>,
    /// Mean normalised radial-alignment residual at the solution (px).
    pub alignment_residual_px: f64,
    /// The same camera in Brown–Conrady form: `k1 = -k fy^2` (first order).
    pub intrinsics: Intrinsics,
}

/// Board `(x, y)` with pixels, per view.
pub type PlanarView = Vec<(Vector2<f64>, Point2<f64>)>;

fn mean_alignment_residual(views: &[PlanarView], cx: f64, cy: f64, m: f64) -> f64 {
    let mut sum = 0.0;
    for v in views {
        match alignment_residual_rms(&centre_points(v, cx, cy), m) {
            Some(r) => sum += r,
            None => return f64::INFINITY,
        }
    }
    sum / views.len() as f64
}

/// Pattern search over `(cx, cy, m)`: try +-step along each free
/// coordinate, keep improvements, halve steps when none helps.
fn search(
    views: &[PlanarView],
    size: ImageSize,
    options: &PaperOptions,
    start: [f64; 3],
) -> ([f64; 3], f64) {
    let mut x = start;
    let mut best = mean_alignment_residual(views, x[0], x[1], x[2]);
    let side = size.width.min(size.height) as f64;
    let mut steps = [
        side * CENTRE_STEP_FRACTION,
        side * CENTRE_STEP_FRACTION,
        SCALE_STEP,
    ];
    let min_steps = [
        options.centre_tolerance_px,
        options.centre_tolerance_px,
        options.scale_tolerance,
    ];
    let free = [
        options.search_centre,
        options.search_centre,
        options.search_scale_ratio,
    ];
    let bounds = [
        (0.0, size.width as f64),
        (0.0, size.height as f64),
        SCALE_RATIO_RANGE,
    ];
    let mut evaluations = 0;
    while evaluations < MAX_EVALUATIONS && (0..3).any(|i| free[i] && steps[i] >= min_steps[i]) {
        let mut improved = false;
        for i in (0..3).filter(|&i| free[i] && steps[i] >= min_steps[i]) {
            for sign in [1.0, -1.0] {
                let mut trial = x;
                trial[i] = (x[i] + sign * steps[i]).clamp(bounds[i].0, bounds[i].1);
                let value = mean_alignment_residual(views, trial[0], trial[1], trial[2]);
                evaluations += 1;
                if value < best {
                    best = value;
                    x = trial;
                    improved = true;
                    break;
                }
            }
        }
        if !improved {
            for s in &mut steps {
                *s /= 2.0;
            }
        }
    }
    (x, best)
}

/// Paper mode over a sequence (method.md §3–4).
pub fn paper_sequence(
    views: &[PlanarView],
    size: ImageSize,
    options: &PaperOptions,
) -> Result<PaperCalibration, CameraError> {
    paper_sequence_searching(views, views, size, options)
}

/// [`paper_sequence`] with the `(cx, cy, m)` search run on `search_views`
/// (the same views with fewer dots, say, when the result only starts the
/// joint refinement) and stage 2 on all of `views`.
pub fn paper_sequence_searching(
    views: &[PlanarView],
    search_views: &[PlanarView],
    size: ImageSize,
    options: &PaperOptions,
) -> Result<PaperCalibration, CameraError> {
    if views.is_empty() || search_views.is_empty() {
        return Err(CameraError::TooFewImages {
            usable: 0,
            required: 1,
        });
    }
    if !(options.initial_scale_ratio > 0.0 && options.initial_scale_ratio.is_finite()) {
        return Err(CameraError::InvalidOption {
            field: "initial_scale_ratio",
            reason: "must be positive".into(),
        });
    }
    let [cx0, cy0] = options.initial_centre.unwrap_or([
        (size.width as f64 - 1.0) / 2.0,
        (size.height as f64 - 1.0) / 2.0,
    ]);
    let ([cx, cy, m], residual) = search(
        search_views,
        size,
        options,
        [cx0, cy0, options.initial_scale_ratio],
    );
    let mut tsai = Vec::with_capacity(views.len());
    let mut max_angle: f64 = 0.0;
    for (i, v) in views.iter().enumerate() {
        let points = centre_points(v, cx, cy);
        let angle = stage1(&points, m).map_or(0.0, |s| board_angle_deg(&s.rotation));
        max_angle = max_angle.max(angle);
        let result = (angle >= STAGE2_MIN_ANGLE_DEG)
            .then(|| calibrate_view(i, &points, m, options.stage2).ok())
            .flatten();
        tsai.push(result);
    }
    let used: Vec<&TsaiView> = tsai.iter().flatten().collect();
    if used.is_empty() {
        return Err(CameraError::AllFrontoParallel {
            max_angle_deg: max_angle,
        });
    }
    let n = used.len() as f64;
    let fx = used.iter().map(|t| t.fx).sum::<f64>() / n;
    let k = used.iter().map(|t| t.k).sum::<f64>() / n;
    let fy = m * fx;
    let mut intrinsics = Intrinsics::pinhole(fx, fy, cx, cy);
    intrinsics.k1 = -k * fy * fy;
    Ok(PaperCalibration {
        scale_ratio: m,
        cx,
        cy,
        fx,
        k,
        views: tsai,
        alignment_residual_px: residual,
        intrinsics,
    })
}
