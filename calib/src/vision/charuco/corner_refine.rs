//! Interim sub-pixel refinement of predicted ChArUco corners: a weighted
//! least-squares quadratic fitted to the smoothed grey levels around the
//! prediction, whose saddle point is the corner (method.md §1 style: an
//! X-junction is a saddle of the blurred intensity).
//!
//! The shared chessboard saddle fit (`vision::saddle::refine_saddle`, branch
//! h/chess) replaces this once merged; the signature is the same, so the
//! swap is a one-line change in `detect.rs`.

use nalgebra::{Matrix2, Matrix6, Vector2, Vector6};

use crate::vision::image::GrayImage;

/// Pre-smoothing sigma as a fraction of the half window (a sharp X-junction
/// is not a quadratic; its blurred version is, near the centre).
const SMOOTH_SIGMA_FRACTION: f64 = 0.5;
/// Fit weight sigma as a fraction of the half window.
const WEIGHT_SIGMA_FRACTION: f64 = 0.6;
/// Least smoothing sigma, pixels.
const MIN_SMOOTH_SIGMA_PX: f64 = 1.0;
/// Re-centring passes and the shift that ends them, pixels.
const MAX_PASSES: usize = 2;
const CONVERGED_PX: f64 = 0.005;
/// Gaussian kernel half-width in sigmas.
const KERNEL_SIGMAS: f64 = 3.0;

fn gaussian_kernel(sigma: f64) -> Vec<f64> {
    let r = (KERNEL_SIGMAS * sigma).ceil() as isize;
    let k: Vec<f64> = (-r..=r)
        .map(|x| (-((x * x) as f64) / (2.0 * sigma * sigma)).exp())
        .collect();
    let s: f64 = k.iter().sum();
    k.into_iter().map(|v| v / s).collect()
}

/// One saddle fit centred on pixel `(cx, cy)`: the saddle's offset from it.
fn fit_once(img: &GrayImage, cx: isize, cy: isize, half: f64) -> Option<Vector2<f64>> {
    let r = half.ceil() as isize;
    let kernel = gaussian_kernel((SMOOTH_SIGMA_FRACTION * half).max(MIN_SMOOTH_SIGMA_PX));
    let kr = (kernel.len() / 2) as isize;
    let (x0, y0) = (cx - r - kr, cy - r - kr);
    let side = (2 * (r + kr) + 1) as usize;
    if x0 < 0 || y0 < 0 || x0 as usize + side > img.width || y0 as usize + side > img.height {
        return None;
    }
    // Separable blur of the patch (rows, then columns inside the fit window).
    let inner = (2 * r + 1) as usize;
    let mut rows = vec![0.0f64; side * inner];
    for y in 0..side {
        for x in 0..inner {
            rows[y * inner + x] = kernel
                .iter()
                .enumerate()
                .map(|(k, w)| w * img.at(x0 as usize + x + k, y0 as usize + y) as f64)
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
        return None; // an extremum, not a saddle: no corner here
    }
    Some(-(hess.try_inverse()? * Vector2::new(c[3], c[4])))
}

/// Gradient-orthogonality passes (Förstner; OpenCV's `cornerSubPix`
/// criterion): every edge pixel's gradient is orthogonal to the line from
/// the corner to it, so the corner solves `sum(g g^T)(q - p) = 0`. Exact for
/// straight edges whatever the window, which the quadratic model is not.
const GRADIENT_PASSES: usize = 5;
/// Gradient weight sigma as a fraction of the half window (edges far from
/// the corner fix its position as well as near ones).
const GRADIENT_WEIGHT_SIGMA_FRACTION: f64 = 0.6;

/// One gradient-orthogonality solve around `p` over integer pixels.
fn gradient_step(img: &GrayImage, p: Vector2<f64>, half: f64) -> Option<Vector2<f64>> {
    let r = half.ceil() as isize;
    let (cx, cy) = (p.x.round() as isize, p.y.round() as isize);
    if cx - r < 1
        || cy - r < 1
        || (cx + r + 1) as usize >= img.width
        || (cy + r + 1) as usize >= img.height
    {
        return None;
    }
    let sw = GRADIENT_WEIGHT_SIGMA_FRACTION * half;
    let (mut a, mut b) = (Matrix2::<f64>::zeros(), Vector2::<f64>::zeros());
    for y in cy - r..=cy + r {
        for x in cx - r..=cx + r {
            let (xu, yu) = (x as usize, y as usize);
            // Sobel: differences smoothed across, less noise than central ones.
            let v = |dx: usize, dy: usize| img.at(xu + dx - 1, yu + dy - 1) as f64;
            let gx = (v(2, 0) + 2.0 * v(2, 1) + v(2, 2)) - (v(0, 0) + 2.0 * v(0, 1) + v(0, 2));
            let gy = (v(0, 2) + 2.0 * v(1, 2) + v(2, 2)) - (v(0, 0) + 2.0 * v(1, 0) + v(2, 0));
            let (dx, dy) = (x as f64 - p.x, y as f64 - p.y);
            let w = (-(dx * dx + dy * dy) / (2.0 * sw * sw)).exp();
            let g = Matrix2::new(gx * gx, gx * gy, gx * gy, gy * gy) * w;
            a += g;
            b += g * Vector2::new(x as f64, y as f64);
        }
    }
    Some(a.try_inverse()? * b)
}

/// Saddle point near `guess_px` within `half_window_px`, polished by the
/// gradient criterion, or `None`.
pub fn refine_corner(img: &GrayImage, guess_px: [f64; 2], half_window_px: f64) -> Option<[f64; 2]> {
    // The saddle is the better start; where the quadratic is no saddle
    // (heavy blur, a window clipped by the image) start from the guess.
    let start = refine_saddle_only(img, guess_px, half_window_px).unwrap_or(guess_px);
    let mut p = Vector2::new(start[0], start[1]);
    for _ in 0..GRADIENT_PASSES {
        let q = gradient_step(img, p, half_window_px)?;
        let moved = (q - p).norm();
        p = q;
        if moved < CONVERGED_PX {
            break;
        }
    }
    let guess = Vector2::new(guess_px[0], guess_px[1]);
    ((p - guess).norm() <= half_window_px).then_some([p.x, p.y])
}

/// The saddle of the fitted quadratic alone.
pub fn refine_saddle_only(
    img: &GrayImage,
    guess_px: [f64; 2],
    half_window_px: f64,
) -> Option<[f64; 2]> {
    let mut p = Vector2::new(guess_px[0], guess_px[1]);
    for _ in 0..MAX_PASSES {
        let (cx, cy) = (p.x.round() as isize, p.y.round() as isize);
        let q = Vector2::new(cx as f64, cy as f64) + fit_once(img, cx, cy, half_window_px)?;
        let moved = (q - p).norm();
        p = q;
        if (p - Vector2::new(guess_px[0], guess_px[1])).norm() > half_window_px {
            return None;
        }
        if moved < CONVERGED_PX {
            break;
        }
    }
    Some([p.x, p.y])
}
