//! Sub-pixel X-junction (chessboard corner) refinement shared by the
//! chessboard and ChArUco detectors (issue 14).
//!
//! Two stages, both exact for an ideal X-junction seen under any blur:
//! 1. the saddle of a weighted quadratic fitted to the smoothed grey levels
//!    around the guess, re-centred until it stops moving (wide capture
//!    range: the blurred junction is a saddle of the intensity);
//! 2. the point-symmetry fit: an X-junction is point-symmetric about its
//!    centre (`I(c + p) = I(c - p)`, kept by any symmetric blur and, locally,
//!    by perspective), so the corner is the `c` minimising
//!    `sum w(p) (I(c + p) - I(c - p) - 2 g·p)^2` over the window, with `g` a
//!    local illumination gradient (uneven light breaks the symmetry by an
//!    odd linear term). Gauss–Newton on `(c, g)`; every pixel of the window
//!    contributes, not only the edge pixels `cornerSubPix` weighs, which is
//!    why it is less sensitive to noise and blur.

use nalgebra::{Matrix2, Matrix4, Matrix6, Vector2, Vector4, Vector6};

use crate::vision::image::GreyLevels;

/// Pre-smoothing sigma of the quadratic fit as a fraction of the half window
/// (a sharp X-junction is not a quadratic; its blurred version is, near the
/// centre).
const SMOOTH_SIGMA_FRACTION: f64 = 0.5;
/// Fit weight sigma of the quadratic as a fraction of the half window.
const WEIGHT_SIGMA_FRACTION: f64 = 0.6;
/// Least smoothing sigma, pixels.
const MIN_SMOOTH_SIGMA_PX: f64 = 1.0;
/// Re-centring passes of the quadratic fit.
const QUADRATIC_PASSES: usize = 3;
/// A step below this ends an iteration, pixels.
const CONVERGED_PX: f64 = 1e-3;
/// Gaussian kernel half-width in sigmas.
const KERNEL_SIGMAS: f64 = 3.0;
/// Gauss–Newton iterations of the symmetry fit.
const SYMMETRY_ITERATIONS: usize = 8;
/// Weight sigma of the symmetry fit as a fraction of the half window.
const SYMMETRY_WEIGHT_FRACTION: f64 = 0.75;
/// Largest single Gauss–Newton step, pixels (a larger one means the fit
/// left the junction's basin).
const MAX_STEP_PX: f64 = 2.0;
/// Half windows from this size (pixels) start the symmetry fit on every
/// `COARSE_STRIDE`-th row and column of point pairs...
const COARSE_MIN_HALF_WINDOW_PX: f64 = 6.0;
const COARSE_STRIDE: isize = 2;
/// ...until a step is below this, pixels (then all pairs to
/// `SYMMETRY_CONVERGED_PX`).
const COARSE_CONVERGED_PX: f64 = 0.02;
/// The symmetry fit stops after a step below this, pixels: Gauss–Newton
/// near its fixed point leaves a small fraction of its last step. The
/// full-window stage starts at the coarse stage's fixed point, so its first
/// step usually ends it; the rendered benches' RMS is the same as with
/// 5e-3 to four digits (BENCHMARKS.md, "Detection").
const SYMMETRY_CONVERGED_PX: f64 = 0.02;
/// Smallest half window the fits accept, pixels.
pub const MIN_HALF_WINDOW_PX: f64 = 1.5;

fn gaussian_kernel(sigma: f64) -> Vec<f64> {
    let r = (KERNEL_SIGMAS * sigma).ceil() as isize;
    let k: Vec<f64> = (-r..=r)
        .map(|x| (-((x * x) as f64) / (2.0 * sigma * sigma)).exp())
        .collect();
    let s: f64 = k.iter().sum();
    k.into_iter().map(|v| v / s).collect()
}

/// One quadratic fit centred on pixel `(cx, cy)`: the saddle's offset from
/// it, or `None` when the fitted surface has no saddle (no corner there).
fn quadratic_once<I: GreyLevels>(img: &I, cx: isize, cy: isize, half: f64) -> Option<Vector2<f64>> {
    let r = half.ceil() as isize;
    let kernel = gaussian_kernel((SMOOTH_SIGMA_FRACTION * half).max(MIN_SMOOTH_SIGMA_PX));
    let kr = (kernel.len() / 2) as isize;
    let (x0, y0) = (cx - r - kr, cy - r - kr);
    let side = (2 * (r + kr) + 1) as usize;
    let (width, height) = (img.width(), img.height());
    if x0 < 0 || y0 < 0 || x0 as usize + side > width || y0 as usize + side > height {
        return None;
    }
    // Separable blur of the patch (rows, then columns inside the fit window).
    let inner = (2 * r + 1) as usize;
    let mut rows = vec![0.0f64; side * inner];
    for y in 0..side {
        let line = (y0 as usize + y) * width + x0 as usize;
        for x in 0..inner {
            rows[y * inner + x] = kernel
                .iter()
                .enumerate()
                .map(|(k, w)| w * img.level(line + x + k) as f64)
                .sum();
        }
    }
    let sw = WEIGHT_SIGMA_FRACTION * half;
    let (mut ata, mut atb) = (Matrix6::<f64>::zeros(), Vector6::<f64>::zeros());
    for y in 0..inner {
        for x in 0..inner {
            let v: f64 = kernel
                .iter()
                .enumerate()
                .map(|(k, w)| w * rows[(y + k) * inner + x])
                .sum();
            let (dx, dy) = (x as f64 - r as f64, y as f64 - r as f64);
            let w = (-(dx * dx + dy * dy) / (2.0 * sw * sw)).exp();
            let a = Vector6::new(dx * dx, dx * dy, dy * dy, dx, dy, 1.0);
            ata += w * a * a.transpose();
            atb += w * v * a;
        }
    }
    let c = ata.cholesky()?.solve(&atb);
    let hess = Matrix2::new(2.0 * c[0], c[1], c[1], 2.0 * c[2]);
    if hess.determinant() >= 0.0 {
        return None; // an extremum, not a saddle
    }
    Some(-(hess.try_inverse()? * Vector2::new(c[3], c[4])))
}

/// The saddle of the fitted quadratic, re-centred; `None` if there is no
/// saddle or it lies farther than `half` from the guess.
pub fn quadratic_saddle<I: GreyLevels>(img: &I, guess_px: [f64; 2], half: f64) -> Option<[f64; 2]> {
    let guess = Vector2::new(guess_px[0], guess_px[1]);
    let mut p = guess;
    for _ in 0..QUADRATIC_PASSES {
        let (cx, cy) = (p.x.round() as isize, p.y.round() as isize);
        let q = Vector2::new(cx as f64, cy as f64) + quadratic_once(img, cx, cy, half)?;
        let moved = (q - p).norm();
        p = q;
        if (p - guess).norm() > half {
            return None;
        }
        if moved < CONVERGED_PX {
            break;
        }
    }
    Some([p.x, p.y])
}

/// Bilinear grey level and its gradient at fractions `(fx, fy)` inside the
/// pixel square whose top-left pixel has index `i` (in bounds: checked by
/// the caller once per window). f32: the levels are 8-bit, and the fit's
/// sums of a few hundred terms keep ~1e-5 relative precision, far below
/// its noise (about 1e-3 of the corner error).
#[inline]
fn sample_at<I: GreyLevels>(img: &I, i: usize, width: usize, fx: f32, fy: f32) -> (f32, f32, f32) {
    let a = img.level(i);
    let b = img.level(i + 1);
    let c = img.level(i + width);
    let d = img.level(i + width + 1);
    let top = a + (b - a) * fx;
    let bottom = c + (d - c) * fx;
    let v = top + (bottom - top) * fy;
    let gx = (b - a) + ((d - c) - (b - a)) * fy;
    let gy = bottom - top;
    (v, gx, gy)
}

/// The point pairs of a symmetry fit: offsets `(dx, dy)` of the upper
/// half-plane plus the positive x axis within `half` (each pair once),
/// with their Gaussian weights (separable: one `exp` per row and column).
fn pair_offsets(half: f64) -> Vec<(f64, f64, f64)> {
    let r = half.floor() as isize;
    let sw = SYMMETRY_WEIGHT_FRACTION * half;
    let along: Vec<f64> = (0..=r)
        .map(|d| (-((d * d) as f64) / (2.0 * sw * sw)).exp())
        .collect();
    let mut out = Vec::with_capacity(((r + 1) * (2 * r + 1)) as usize);
    for dy in 0..=r {
        for dx in -r..=r {
            if (dy > 0 || dx > 0) && ((dx * dx + dy * dy) as f64) <= half * half {
                let w = along[dx.unsigned_abs()] * along[dy as usize];
                out.push((dx as f64, dy as f64, w));
            }
        }
    }
    out
}

/// The pairs of `offsets` on every `COARSE_STRIDE`-th row and column.
fn coarse_offsets(offsets: &[(f64, f64, f64)]) -> Vec<(f64, f64, f64)> {
    let on = |d: f64| (d as isize).rem_euclid(COARSE_STRIDE) == 0;
    offsets
        .iter()
        .copied()
        .filter(|&(dx, dy, _)| on(dx) && on(dy))
        .collect()
}

/// One Gauss–Newton step of the symmetry fit over `offsets` at centre `c`
/// and illumination gradient `g`: the change of `(c, g)`, or `None` when a
/// sample leaves the image or the normal equations are singular. The
/// Jacobian row is `(∇a − ∇b, −2 d)`: its `g` block `4 Σ w d dᵀ` does not
/// depend on `c`, so `dd` holds it (computed once per window).
fn symmetry_step<I: GreyLevels>(
    img: &I,
    offsets: &[(f64, f64, f64)],
    dd: &Matrix2<f64>,
    c: Vector2<f64>,
    g: Vector2<f64>,
) -> Option<Vector4<f64>> {
    // Integer offsets: every sample `c ± d` has the bilinear fractions of
    // `c` itself, and the window's extreme offsets `(±r, 0)`, `(0, ±r)`
    // bound all samples, so one check covers the window.
    let r = offsets
        .iter()
        .fold(0.0f64, |m, o| m.max(o.0.abs()).max(o.1.abs())) as usize;
    let (floor_x, floor_y) = (c.x.floor(), c.y.floor());
    let (width, height) = (img.width(), img.height());
    if !(floor_x >= r as f64 && floor_y >= r as f64)
        || floor_x as usize + r + 1 >= width
        || floor_y as usize + r + 1 >= height
    {
        return None;
    }
    let centre = floor_y as usize * width + floor_x as usize;
    let (fx, fy) = ((c.x - floor_x) as f32, (c.y - floor_y) as f32);
    let (gx, gy) = (g.x as f32, g.y as f32);
    let (mut uxx, mut uxy, mut uyy) = (0.0f32, 0.0f32, 0.0f32);
    let (mut bxx, mut bxy, mut byx, mut byy) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
    let (mut rx, mut ry, mut rgx, mut rgy) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
    for &(dx, dy, w) in offsets {
        let shift = dy as isize * width as isize + dx as isize;
        let (dx, dy, w) = (dx as f32, dy as f32, w as f32);
        let (a, ax, ay) = sample_at(img, centre.wrapping_add_signed(shift), width, fx, fy);
        let (b, bx, by) = sample_at(img, centre.wrapping_add_signed(-shift), width, fx, fy);
        let res = w * (a - b - 2.0 * (gx * dx + gy * dy));
        let (ux, uy) = (ax - bx, ay - by);
        let (wux, wuy) = (w * ux, w * uy);
        uxx += wux * ux;
        uxy += wux * uy;
        uyy += wuy * uy;
        bxx += wux * dx;
        bxy += wux * dy;
        byx += wuy * dx;
        byy += wuy * dy;
        rx += res * ux;
        ry += res * uy;
        rgx += res * dx;
        rgy += res * dy;
    }
    let [uxx, uxy, uyy, bxx, bxy, byx, byy, rx, ry, rgx, rgy] =
        [uxx, uxy, uyy, bxx, bxy, byx, byy, rx, ry, rgx, rgy].map(f64::from);
    let jtj = Matrix4::new(
        uxx,
        uxy,
        -2.0 * bxx,
        -2.0 * bxy,
        uxy,
        uyy,
        -2.0 * byx,
        -2.0 * byy,
        -2.0 * bxx,
        -2.0 * byx,
        dd[(0, 0)],
        dd[(0, 1)],
        -2.0 * bxy,
        -2.0 * byy,
        dd[(1, 0)],
        dd[(1, 1)],
    );
    let jtr = Vector4::new(rx, ry, -2.0 * rgx, -2.0 * rgy);
    Some(jtj.cholesky()?.solve(&(-jtr)))
}

/// `4 Σ w d dᵀ` over `offsets`: the symmetry fit's constant `g` block.
fn gradient_block(offsets: &[(f64, f64, f64)]) -> Matrix2<f64> {
    offsets.iter().fold(Matrix2::zeros(), |m, &(dx, dy, w)| {
        m + 4.0 * w * Matrix2::new(dx * dx, dx * dy, dx * dy, dy * dy)
    })
}

/// Gauss–Newton on the point-symmetry residual from `start`: the centre,
/// and whether the last step was below `SYMMETRY_CONVERGED_PX` (a start far off a
/// sharp junction runs out of iterations first). Wide windows first
/// iterate on every `COARSE_STRIDE`-th row and column of pairs until the
/// step is below `COARSE_CONVERGED_PX` (a quarter of the cost per step),
/// then on all pairs to convergence: the fixed point is the full fit's.
fn symmetry_fit<I: GreyLevels>(
    img: &I,
    start: Vector2<f64>,
    half: f64,
) -> Option<(Vector2<f64>, bool)> {
    let mut c = start;
    let mut g = Vector2::zeros();
    let offsets = pair_offsets(half);
    let mut stages = Vec::with_capacity(2);
    if half >= COARSE_MIN_HALF_WINDOW_PX {
        stages.push((coarse_offsets(&offsets), COARSE_CONVERGED_PX));
    }
    stages.push((offsets, SYMMETRY_CONVERGED_PX));
    let last = stages.len() - 1;
    for (stage, (offsets, converged)) in stages.iter().enumerate() {
        let dd = gradient_block(offsets);
        for _ in 0..SYMMETRY_ITERATIONS {
            let step = symmetry_step(img, offsets, &dd, c, g)?;
            let dc = Vector2::new(step[0], step[1]);
            if !dc.norm().is_finite() || dc.norm() > MAX_STEP_PX {
                return None;
            }
            c += dc;
            g += Vector2::new(step[2], step[3]);
            if dc.norm() < *converged {
                if stage == last {
                    return Some((c, true));
                }
                break;
            }
        }
    }
    Some((c, false))
}

/// The X-junction near `guess_px` within `half_window_px` (the window must
/// hold the four squares' edges and nothing else), or `None` when there is
/// no junction or the fit leaves the window.
pub fn refine_saddle<I: GreyLevels>(
    img: &I,
    guess_px: [f64; 2],
    half_window_px: f64,
) -> Option<[f64; 2]> {
    if half_window_px.is_nan() || half_window_px < MIN_HALF_WINDOW_PX {
        return None;
    }
    let guess = Vector2::new(guess_px[0], guess_px[1]);
    // The quadratic's saddle is the better start; where it is none (heavy
    // blur, a window clipped by the image) start from the guess.
    let start =
        quadratic_saddle(img, guess_px, half_window_px).map_or(guess, |q| Vector2::new(q[0], q[1]));
    let (p, _) = symmetry_fit(img, start, half_window_px)?;
    ((p - guess).norm() <= half_window_px).then_some([p.x, p.y])
}

/// [`refine_saddle`] for a guess already within a pixel or so of the
/// junction (a detector's candidate): the point-symmetry fit straight from
/// the guess, which lands where `refine_saddle` does at a fraction of its
/// cost (the quadratic's smoothing dominates it); the full two-stage fit
/// where that fails.
pub fn refine_saddle_near<I: GreyLevels>(
    img: &I,
    guess_px: [f64; 2],
    half_window_px: f64,
) -> Option<[f64; 2]> {
    if half_window_px.is_nan() || half_window_px < MIN_HALF_WINDOW_PX {
        return None;
    }
    let guess = Vector2::new(guess_px[0], guess_px[1]);
    match symmetry_fit(img, guess, half_window_px) {
        Some((p, true)) if (p - guess).norm() <= half_window_px => Some([p.x, p.y]),
        _ => refine_saddle(img, guess_px, half_window_px),
    }
}

#[cfg(test)]
#[path = "saddle_tests.rs"]
mod tests;
