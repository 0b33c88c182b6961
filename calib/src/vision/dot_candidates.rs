//! Dot candidates of the circle-board detector: blobs of the locally
//! thresholded image that are shaped like a dot, each refined to a
//! sub-pixel ellipse, and the ones dropped on the way (kept so a failure
//! can say why: too small, too blurred).

use nalgebra::Vector2;

use super::blobs::{find_blobs, Blob};
use super::circle_board::CircleBoard;
use super::ellipse::{refine_dot, Rejection};
use super::image::GrayImage;
use super::threshold::{auto_window_radius, local_threshold};

/// Dots below this area are too small for a sub-pixel centre.
pub const MIN_DOT_AREA_PX: f64 = 12.0;
/// More dot-like blobs than this is clutter or noise, not a board.
pub const MAX_CANDIDATES: usize = 5000;
/// Area ratio slack between lattice neighbours beyond the marker's own ratio.
pub const SIZE_RATIO_SLACK: f64 = 2.0;
/// Blobs below this area are noise.
const MIN_BLOB_AREA_PX: f64 = 3.0;
/// Accepted thresholded-area / moment-ellipse-area range (convexity proxy).
const MIN_FILL_RATIO: f64 = 0.8;
const MAX_FILL_RATIO: f64 = 1.25;
/// Smallest accepted minor/major axis ratio (60 degree tilt gives ~0.5).
const MIN_AXIS_RATIO: f64 = 0.15;
/// Pixel step of the grey-range sampling.
const RANGE_SAMPLE_STEP: usize = 7;

/// Grey range between the 1st and 99th percentile of a pixel sample.
pub(super) fn grey_range(img: &GrayImage) -> f32 {
    let mut hist = [0usize; 256];
    let mut n = 0usize;
    for v in img.data.iter().step_by(RANGE_SAMPLE_STEP) {
        hist[v.clamp(0.0, 255.0) as usize] += 1;
        n += 1;
    }
    let pct = |f: f64| {
        let goal = (f * n as f64) as usize;
        let mut acc = 0usize;
        hist.iter()
            .position(|&h| {
                acc += h;
                acc > goal
            })
            .unwrap_or(255) as f32
    };
    pct(0.99) - pct(0.01)
}

/// Dot-like blobs and why others were dropped.
pub(super) struct CandidateSet {
    pub blobs: Vec<Blob>,
    pub dots: Vec<super::ellipse::RefinedDot>,
    /// Centres and areas of dot-like blobs too small to refine.
    pub too_small: Vec<(Vector2<f64>, f64)>,
    /// Centres and areas of dot-like blobs rejected for contrast or edges.
    pub unsharp: Vec<(Vector2<f64>, f64)>,
}

/// Dot candidates of `img` for `board`; `threshold_radius_px` is the local
/// threshold's window (`None`: chosen from the image size).
pub(super) fn candidates(
    img: &GrayImage,
    board: &CircleBoard,
    threshold_radius_px: Option<usize>,
) -> CandidateSet {
    let radius = threshold_radius_px.unwrap_or_else(|| auto_window_radius(img.width, img.height));
    let thr = local_threshold(img, radius);
    let max_area = (img.width * img.height) as f64 / board.dot_count() as f64;
    let mut set = CandidateSet {
        blobs: Vec::new(),
        dots: Vec::new(),
        too_small: Vec::new(),
        unsharp: Vec::new(),
    };
    for b in find_blobs(img, &thr, MIN_BLOB_AREA_PX) {
        if b.area > max_area || b.touches_border(img.width, img.height) {
            continue;
        }
        let fill = b.area / b.moment_ellipse_area().max(f64::MIN_POSITIVE);
        let (major, minor) = b.moment_semi_axes();
        if !(MIN_FILL_RATIO..=MAX_FILL_RATIO).contains(&fill) || minor < MIN_AXIS_RATIO * major {
            continue;
        }
        if b.area < MIN_DOT_AREA_PX {
            set.too_small.push((Vector2::new(b.cx, b.cy), b.area));
            continue;
        }
        match refine_dot(img, &b) {
            Ok(d) => {
                set.blobs.push(b);
                set.dots.push(d);
            }
            Err(Rejection::NotAnEllipse) => {}
            Err(_) => set.unsharp.push((Vector2::new(b.cx, b.cy), b.area)),
        }
    }
    set
}
