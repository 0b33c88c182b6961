//! Sub-pixel dot outline and ellipse fit (method.md §1, §4 "beyond").
//!
//! The outline is the iso-contour half-way between the dot's own interior and
//! surrounding background levels, sampled where it crosses pixel rows and
//! columns (linear interpolation between neighbouring pixels). A conic is
//! fitted to those points by linear least squares with the Euclidean-invariant
//! constraint `A + C = 1`. Uneven illumination (vignetting, a lamp's falloff)
//! tilts the grey levels across a dot; with a blurred edge that moves the
//! half-level contour towards the darker side on both flanks, shifting the
//! centre by ~`sigma_blur * radius * gradient` (0.005 px on a 20 px dot at a
//! 1280x1024 sensor's edge with 25 % corner vignetting — as large as the
//! centre's random noise, and the same in every image). The illumination is
//! therefore fitted as a plane over the background ring and divided out
//! (it multiplies the dot's and the board's reflectance alike) before the
//! contour is traced. The fitted ellipse is exposed per dot: its centre
//! is the image of the dot's centre only up to the perspective bias, which
//! `bias.rs` (or the camera model) corrects.

use nalgebra::{Matrix2, Matrix3, Matrix5, Vector2, Vector3, Vector5};
use serde::{Deserialize, Serialize};

use super::blobs::Blob;
use super::image::GrayImage;

/// Samples inside this normalised radius give the dot's interior level.
const INNER_RADIUS: f64 = 0.4;
/// Samples between these normalised radii give the background level.
const RING_INNER_RADIUS: f64 = 1.6;
const RING_OUTER_RADIUS: f64 = 2.2;
/// Edge crossings are searched between these normalised radii.
const EDGE_MIN_RADIUS: f64 = 0.5;
const EDGE_MAX_RADIUS: f64 = 1.5;
/// Fewer edge points than this cannot give a trustworthy ellipse.
pub const MIN_EDGE_POINTS: usize = 12;
/// Smallest accepted interior-to-background contrast, grey levels.
pub const MIN_CONTRAST_GREY: f32 = 12.0;
/// Largest accepted RMS distance of edge points from the fitted ellipse:
/// this many pixels, or this fraction of the semi-minor axis for large dots
/// (real edges of big dots carry print, paper and interlace texture).
pub const MAX_FIT_RESIDUAL_PX: f64 = 0.6;
pub const MAX_FIT_RESIDUAL_FRACTION: f64 = 0.03;
/// Smallest relative illumination the gradient correction divides by (a
/// wild plane fit must not blow the levels up).
const MIN_SHADE: f64 = 0.5;
/// Number of fit passes (each re-centres the edge annulus on the last fit).
const FIT_PASSES: usize = 2;

/// An ellipse in pixel coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Ellipse {
    pub cx: f64,
    pub cy: f64,
    pub semi_major_px: f64,
    pub semi_minor_px: f64,
    /// Angle of the major axis from +u towards +v, radians.
    pub angle_rad: f64,
}

impl Ellipse {
    /// Squared normalised radius of a point (1 on the ellipse).
    pub fn normalised_radius_sq(&self, x: f64, y: f64) -> f64 {
        let (s, c) = self.angle_rad.sin_cos();
        let (dx, dy) = (x - self.cx, y - self.cy);
        let u = c * dx + s * dy;
        let v = -s * dx + c * dy;
        (u / self.semi_major_px).powi(2) + (v / self.semi_minor_px).powi(2)
    }

    /// Coefficients `(a, b, c)` with normalised radius squared
    /// `a dx^2 + b dx dy + c dy^2` about the centre (for tight loops).
    pub fn quadratic_form(&self) -> (f64, f64, f64) {
        let (s, c) = self.angle_rad.sin_cos();
        let (ia, ib) = (self.semi_major_px.powi(-2), self.semi_minor_px.powi(-2));
        (
            c * c * ia + s * s * ib,
            2.0 * s * c * (ia - ib),
            s * s * ia + c * c * ib,
        )
    }

    /// Ellipse with the second moments of a blob (a filled ellipse has
    /// covariance `diag(a^2, b^2) / 4`).
    pub fn from_blob(b: &Blob) -> Self {
        let (a, bb) = b.moment_semi_axes();
        let angle = 0.5 * (2.0 * b.mxy).atan2(b.mxx - b.myy);
        Self {
            cx: b.cx,
            cy: b.cy,
            semi_major_px: a.max(0.5),
            semi_minor_px: bb.max(0.5),
            angle_rad: angle,
        }
    }
}

/// Per-dot quality figures (issue 3: area, axes, contrast, residual).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DotQuality {
    /// Thresholded pixel count.
    pub area_px: f64,
    /// Background minus interior grey level.
    pub contrast_grey: f64,
    /// RMS distance of the edge points from the fitted ellipse, px.
    pub fit_residual_px: f64,
    /// Thresholded area over moment-ellipse area (1 for a filled convex ellipse).
    pub fill_ratio: f64,
    /// Number of sub-pixel edge points used.
    pub edge_points: usize,
    /// Contrast over the steepest edge slope: ~2.5 sigma of a Gaussian blur, px.
    pub edge_width_px: f64,
}

/// A dot refined to sub-pixel precision.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefinedDot {
    pub ellipse: Ellipse,
    pub quality: DotQuality,
}

/// Why a blob was not accepted as a dot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rejection {
    LowContrast,
    TooFewEdgePoints,
    NotAnEllipse,
    PoorFit,
}

fn median(v: &mut [f32]) -> Option<f32> {
    if v.is_empty() {
        return None;
    }
    let mid = v.len() / 2;
    let (_, m, _) = v.select_nth_unstable_by(mid, |a, b| a.total_cmp(b));
    Some(*m)
}

/// Refines one blob: local levels, sub-pixel edge points, conic fit.
pub fn refine_dot(img: &GrayImage, blob: &Blob) -> Result<RefinedDot, Rejection> {
    let mut ell = Ellipse::from_blob(blob);
    let margin = (RING_OUTER_RADIUS - 1.0) * ell.semi_major_px + 2.0;
    let x0 = (blob.x_min as f64 - margin).floor().max(0.0) as usize;
    let y0 = (blob.y_min as f64 - margin).floor().max(0.0) as usize;
    let x1 = ((blob.x_max as f64 + margin).ceil() as usize).min(img.width - 1);
    let y1 = ((blob.y_max as f64 + margin).ceil() as usize).min(img.height - 1);

    let (mut inner, mut ring, mut ring_at) = (Vec::new(), Vec::new(), Vec::new());
    let (qa, qb, qc) = ell.quadratic_form();
    for y in y0..=y1 {
        let dy = y as f64 - ell.cy;
        for x in x0..=x1 {
            let dx = x as f64 - ell.cx;
            let q = qa * dx * dx + qb * dx * dy + qc * dy * dy;
            if q < INNER_RADIUS * INNER_RADIUS {
                inner.push(img.at(x, y));
            } else if q > RING_INNER_RADIUS.powi(2) && q < RING_OUTER_RADIUS.powi(2) {
                ring.push(img.at(x, y));
                ring_at.push((dx, dy, img.at(x, y)));
            }
        }
    }
    let fg = match median(&mut inner) {
        Some(v) => v,
        None => img.at(blob.cx.round() as usize, blob.cy.round() as usize),
    };
    let bg = median(&mut ring).ok_or(Rejection::LowContrast)?;
    let contrast = bg - fg;
    if contrast < MIN_CONTRAST_GREY {
        return Err(Rejection::LowContrast);
    }
    let mid = 0.5 * (bg + fg);
    // Grey levels with the illumination's tilt across the dot divided out.
    let (gx, gy) = illumination_gradient(&ring_at);
    let (ox, oy) = (ell.cx, ell.cy);
    let level = |x: usize, y: usize| {
        let shade = 1.0 + gx * (x as f64 - ox) + gy * (y as f64 - oy);
        (img.at(x, y) as f64 / shade.max(MIN_SHADE)) as f32
    };

    let mut points: Vec<Vector2<f64>> = Vec::new();
    let mut fit = None;
    let mut max_slope = 0.0f32;
    for _ in 0..FIT_PASSES {
        points.clear();
        max_slope = 0.0;
        let (qmin, qmax) = (EDGE_MIN_RADIUS.powi(2), EDGE_MAX_RADIUS.powi(2));
        let (qa, qb, qc) = ell.quadratic_form();
        let q_at = |x: f64, y: f64| {
            let (dx, dy) = (x - ell.cx, y - ell.cy);
            qa * dx * dx + qb * dx * dy + qc * dy * dy
        };
        for y in y0..=y1 {
            for x in x0..=x1 {
                let a = level(x, y);
                if x < x1 {
                    let b = level(x + 1, y);
                    if (a - mid) * (b - mid) < 0.0 {
                        let q = q_at(x as f64 + 0.5, y as f64);
                        if q > qmin && q < qmax {
                            let t = ((mid - a) / (b - a)) as f64;
                            points.push(Vector2::new(x as f64 + t, y as f64));
                            max_slope = max_slope.max((b - a).abs());
                        }
                    }
                }
                if y < y1 {
                    let b = level(x, y + 1);
                    if (a - mid) * (b - mid) < 0.0 {
                        let q = q_at(x as f64, y as f64 + 0.5);
                        if q > qmin && q < qmax {
                            let t = ((mid - a) / (b - a)) as f64;
                            points.push(Vector2::new(x as f64, y as f64 + t));
                            max_slope = max_slope.max((b - a).abs());
                        }
                    }
                }
            }
        }
        if points.len() < MIN_EDGE_POINTS {
            return Err(Rejection::TooFewEdgePoints);
        }
        let (e, residual) = fit_ellipse(&points, &ell).ok_or(Rejection::NotAnEllipse)?;
        ell = e;
        fit = Some(residual);
    }
    let residual = fit.ok_or(Rejection::NotAnEllipse)?;
    if residual > MAX_FIT_RESIDUAL_PX.max(MAX_FIT_RESIDUAL_FRACTION * ell.semi_minor_px) {
        return Err(Rejection::PoorFit);
    }
    Ok(RefinedDot {
        ellipse: ell,
        quality: DotQuality {
            area_px: blob.area,
            contrast_grey: contrast as f64,
            fit_residual_px: residual,
            fill_ratio: blob.area / blob.moment_ellipse_area().max(f64::MIN_POSITIVE),
            edge_points: points.len(),
            edge_width_px: (contrast / max_slope.max(f32::MIN_POSITIVE)) as f64,
        },
    })
}

/// Relative illumination gradient `(d/dx, d/dy) ln(grey)` per pixel at the
/// dot centre: a plane `b0 + bx dx + by dy` fitted to the background ring's
/// `(dx, dy, grey)` samples, as `(bx, by) / b0`; zero if the ring cannot
/// carry a plane.
fn illumination_gradient(ring: &[(f64, f64, f32)]) -> (f64, f64) {
    let (mut ata, mut atb) = (Matrix3::<f64>::zeros(), Vector3::<f64>::zeros());
    for &(dx, dy, v) in ring {
        let row = Vector3::new(1.0, dx, dy);
        ata += row * row.transpose();
        atb += row * v as f64;
    }
    match ata.cholesky().map(|c| c.solve(&atb)) {
        Some(b) if b[0] > 0.0 && b.iter().all(|v| v.is_finite()) => (b[1] / b[0], b[2] / b[0]),
        _ => (0.0, 0.0),
    }
}

/// An axis angle in `(-pi/2, pi/2]` (an ellipse axis has no sign).
fn wrap_half_turn(a: f64) -> f64 {
    use std::f64::consts::{FRAC_PI_2, PI};
    if a > FRAC_PI_2 {
        a - PI
    } else if a <= -FRAC_PI_2 {
        a + PI
    } else {
        a
    }
}

/// Least-squares conic through `points` (normalised about `guess`), returned
/// as an ellipse with the RMS geometric residual, or `None` if the conic is
/// not a real ellipse.
pub fn fit_ellipse(points: &[Vector2<f64>], guess: &Ellipse) -> Option<(Ellipse, f64)> {
    let scale = (guess.semi_major_px * guess.semi_minor_px).sqrt().max(0.5);
    let (ox, oy) = (guess.cx, guess.cy);
    // A u^2 + B uv + C v^2 + D u + E v + F = 0 with C = 1 - A:
    // A (u^2 - v^2) + B uv + D u + E v + F = -v^2.
    let mut ata = Matrix5::<f64>::zeros();
    let mut atb = Vector5::<f64>::zeros();
    for p in points {
        let (u, v) = ((p.x - ox) / scale, (p.y - oy) / scale);
        let row = Vector5::new(u * u - v * v, u * v, u, v, 1.0);
        ata += row * row.transpose();
        atb += row * (-v * v);
    }
    let sol = ata.cholesky()?.solve(&atb);
    let (a, b, d, e, f) = (sol[0], sol[1], sol[2], sol[3], sol[4]);
    let c = 1.0 - a;
    let m = Matrix2::new(a, 0.5 * b, 0.5 * b, c);
    if m.determinant() <= 0.0 {
        return None;
    }
    let centre = m.try_inverse()? * Vector2::new(-0.5 * d, -0.5 * e);
    let f0 = f + 0.5 * (d * centre.x + e * centre.y);
    let eig = m.symmetric_eigen();
    let (l0, l1) = (eig.eigenvalues[0], eig.eigenvalues[1]);
    if !(f0 < 0.0 && l0 > 0.0 && l1 > 0.0) {
        return None;
    }
    let (ax0, ax1) = ((-f0 / l0).sqrt(), (-f0 / l1).sqrt());
    let (major_idx, semi_major, semi_minor) = if ax0 >= ax1 {
        (0, ax0, ax1)
    } else {
        (1, ax1, ax0)
    };
    let dir = eig.eigenvectors.column(major_idx);
    let ell = Ellipse {
        cx: ox + scale * centre.x,
        cy: oy + scale * centre.y,
        semi_major_px: scale * semi_major,
        semi_minor_px: scale * semi_minor,
        angle_rad: wrap_half_turn(dir[1].atan2(dir[0])),
    };
    // Geometric residual ~ |Q(p)| / |grad Q(p)| (first-order distance).
    let mut sum_sq = 0.0;
    for p in points {
        let (u, v) = ((p.x - ox) / scale, (p.y - oy) / scale);
        let q = a * u * u + b * u * v + c * v * v + d * u + e * v + f;
        let gu = 2.0 * a * u + b * v + d;
        let gv = b * u + 2.0 * c * v + e;
        let g = (gu * gu + gv * gv).sqrt().max(1e-12);
        sum_sq += (q / g).powi(2);
    }
    let residual = scale * (sum_sq / points.len() as f64).sqrt();
    ell.cx.is_finite().then_some((ell, residual))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conic_fit_recovers_an_exact_ellipse() {
        let truth = Ellipse {
            cx: 40.3,
            cy: 22.7,
            semi_major_px: 9.0,
            semi_minor_px: 4.5,
            angle_rad: 0.6,
        };
        let (s, c) = truth.angle_rad.sin_cos();
        let pts: Vec<_> = (0..40)
            .map(|k| {
                let t = k as f64 * std::f64::consts::TAU / 40.0;
                let (u, v) = (truth.semi_major_px * t.cos(), truth.semi_minor_px * t.sin());
                Vector2::new(truth.cx + c * u - s * v, truth.cy + s * u + c * v)
            })
            .collect();
        let guess = Ellipse {
            cx: 41.0,
            cy: 22.0,
            ..truth
        };
        let (e, res) = fit_ellipse(&pts, &guess).unwrap();
        assert!((e.cx - truth.cx).abs() < 1e-9 && (e.cy - truth.cy).abs() < 1e-9);
        assert!((e.semi_major_px - 9.0).abs() < 1e-9 && (e.semi_minor_px - 4.5).abs() < 1e-9);
        assert!((e.angle_rad - 0.6).abs() < 1e-9 && res < 1e-9);
    }

    #[test]
    fn collinear_points_are_not_an_ellipse() {
        let pts: Vec<_> = (0..20)
            .map(|k| Vector2::new(k as f64, 2.0 * k as f64))
            .collect();
        let guess = Ellipse {
            cx: 10.0,
            cy: 20.0,
            semi_major_px: 5.0,
            semi_minor_px: 5.0,
            angle_rad: 0.0,
        };
        assert!(fit_ellipse(&pts, &guess).is_none());
    }
}
