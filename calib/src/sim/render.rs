//! Target-image renderer: a known camera and board pose to an 8-bit image
//! plus truth (issue 3; method.md §1–2).
//!
//! Rendering is by inverse mapping: every pixel corner is undistorted to a
//! ray and intersected with the board plane (z = 0 of the target frame), so
//! the image is exact for the Brown–Conrady model. Pixels whose footprint
//! crosses a dot or board edge are supersampled (bilinear between the
//! corners' board points); the rest take one value. Then Gaussian blur,
//! vignetting, Gaussian noise and 8-bit quantisation. The truth of a dot is
//! the projection of its 3-D centre, not a blob centroid. One call renders
//! one view, so a campaign generator calls it per pose.

use nalgebra::{Isometry3, Point2, Vector2, Vector3};
use rand::Rng;
use rand_distr::{Distribution, Normal};
use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::camera::model::Intrinsics;
use crate::vision::image::{GrayImage, WHITE_LEVEL};

/// Largest image side the renderer accepts, pixels.
pub const MAX_RENDER_SIDE_PX: usize = 16_384;
/// Largest supersampling factor per axis.
pub const MAX_SUPERSAMPLING: usize = 64;
/// Gaussian kernel half-width in standard deviations.
const BLUR_HALF_WIDTH_SIGMAS: f64 = 3.5;

/// Rendering settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RenderOptions {
    /// Sub-samples per axis on pixels crossing an edge.
    pub supersampling: usize,
    /// Gaussian blur of the optics, pixels (0 = none).
    pub blur_sigma_px: f64,
    /// Additive Gaussian sensor noise, grey levels (0 = none).
    pub noise_sigma_grey: f64,
    /// Relative brightness loss at the image corners (0 = none; 0.3 = corners at 70 %).
    pub vignetting: f64,
    /// Grey level of the light board, the dark dots and the surroundings.
    pub board_grey: f64,
    pub dot_grey: f64,
    pub background_grey: f64,
    /// Board border beyond the outer dot centres, mm.
    pub board_margin_mm: f64,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            supersampling: 16,
            blur_sigma_px: 0.7,
            noise_sigma_grey: 2.0,
            vignetting: 0.25,
            board_grey: 215.0,
            dot_grey: 30.0,
            background_grey: 70.0,
            board_margin_mm: 20.0,
        }
    }
}

/// Ground truth of one dot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TruthDot {
    pub row: usize,
    pub col: usize,
    /// Projection of the dot's 3-D centre, pixels (pixel-centre convention).
    pub x: f64,
    pub y: f64,
    /// Centre projects in front of the camera and inside the image.
    pub visible: bool,
}

/// A rendered view and its truth (row-major dots).
#[derive(Debug, Clone, PartialEq)]
pub struct RenderedView {
    pub image: GrayImage,
    pub truth: Vec<TruthDot>,
}

/// Why a view cannot be rendered.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RenderError {
    #[error("invalid render settings: {0}")]
    InvalidOptions(String),
    #[error(transparent)]
    InvalidTarget(#[from] crate::vision::error::DetectError),
}

/// Board-plane point seen at pixel `(u, v)`, or `None` if the ray misses it.
pub(crate) fn board_point(
    camera: &Intrinsics,
    target_to_camera: &Isometry3<f64>,
    u: f64,
    v: f64,
) -> Option<Vector2<f64>> {
    let n = camera.pixel_to_ray(&Point2::new(u, v))?;
    let origin = target_to_camera.translation.vector;
    let dir = target_to_camera.rotation * Vector3::new(n.x, n.y, 1.0);
    if dir.z.abs() < f64::EPSILON {
        return None;
    }
    let s = -origin.z / dir.z;
    (s > 0.0).then(|| Vector2::new(origin.x + s * dir.x, origin.y + s * dir.y))
}

pub(crate) fn check(opts: &RenderOptions, width: usize, height: usize) -> Result<(), RenderError> {
    let bad = |s: &str| Err(RenderError::InvalidOptions(s.into()));
    if width == 0 || height == 0 || width > MAX_RENDER_SIDE_PX || height > MAX_RENDER_SIDE_PX {
        return bad("width and height must be 1..=16384");
    }
    if opts.supersampling == 0 || opts.supersampling > MAX_SUPERSAMPLING {
        return bad("supersampling must be 1..=64");
    }
    let finite = [
        opts.blur_sigma_px,
        opts.noise_sigma_grey,
        opts.vignetting,
        opts.board_margin_mm,
    ];
    if finite.iter().any(|v| !(v.is_finite() && *v >= 0.0)) || opts.vignetting >= 1.0 {
        return bad("blur, noise, margin must be finite and >= 0; vignetting in [0, 1)");
    }
    Ok(())
}

/// Separable Gaussian blur with clamped borders.
pub(crate) fn gaussian_blur(data: &mut [f32], w: usize, h: usize, sigma: f64) {
    let r = (BLUR_HALF_WIDTH_SIGMAS * sigma).ceil() as isize;
    let mut k: Vec<f32> = (-r..=r)
        .map(|x| (-(x * x) as f64 / (2.0 * sigma * sigma)).exp() as f32)
        .collect();
    let total: f32 = k.iter().sum();
    k.iter_mut().for_each(|v| *v /= total);
    let mut tmp = vec![0.0f32; data.len()];
    let clamp = |x: isize, n: usize| x.clamp(0, n as isize - 1) as usize;
    for y in 0..h {
        let row = &data[y * w..(y + 1) * w];
        for x in 0..w {
            tmp[y * w + x] = k
                .iter()
                .enumerate()
                .map(|(t, kv)| kv * row[clamp(x as isize + t as isize - r, w)])
                .sum();
        }
    }
    for y in 0..h {
        for x in 0..w {
            data[y * w + x] = k
                .iter()
                .enumerate()
                .map(|(t, kv)| kv * tmp[clamp(y as isize + t as isize - r, h) * w + x])
                .sum();
        }
    }
}

/// Vignetting (quadratic fall-off to the corners), noise, 8-bit quantisation.
pub(crate) fn finish<R: Rng + ?Sized>(
    data: &mut [f32],
    w: usize,
    h: usize,
    opts: &RenderOptions,
    rng: &mut R,
) {
    let (cx, cy) = (0.5 * (w as f64 - 1.0), 0.5 * (h as f64 - 1.0));
    let r2_max = (cx * cx + cy * cy).max(f64::MIN_POSITIVE);
    let noise = Normal::new(0.0, opts.noise_sigma_grey).ok();
    for y in 0..h {
        for x in 0..w {
            let r2 = ((x as f64 - cx).powi(2) + (y as f64 - cy).powi(2)) / r2_max;
            let mut v = data[y * w + x] as f64 * (1.0 - opts.vignetting * r2);
            if let Some(n) = noise.filter(|_| opts.noise_sigma_grey > 0.0) {
                v += n.sample(rng);
            }
            data[y * w + x] = v.round().clamp(0.0, WHITE_LEVEL as f64) as f32;
        }
    }
}

#[cfg(test)]
#[path = "render_tests.rs"]
mod tests;
