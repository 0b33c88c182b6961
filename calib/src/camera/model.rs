//! Camera intrinsics: pinhole plus Brown–Conrady distortion on normalised
//! coordinates (method.md §2 **beyond**; OpenCV's convention, so users can
//! compare). Pixel (u, v): the centre of the pixel in column j, row i is (j, i).

use nalgebra::{Matrix2, Point2, Point3, Vector2};
use serde::{Deserialize, Serialize};

/// Points closer than this to the camera plane (mm) are not projected.
pub const MIN_DEPTH_MM: f64 = 1e-6;
/// Newton iterations of the distortion inversion.
const UNDISTORT_MAX_ITERATIONS: usize = 30;
/// Convergence of the distortion inversion, in normalised units (~1e-9 px).
const UNDISTORT_TOLERANCE: f64 = 1e-14;

/// Intrinsics in pixels: `u = fx * xd + cx`, `v = fy * yd + cy`, where
/// `(xd, yd)` is the distorted image of the normalised point `(x/z, y/z)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Intrinsics {
    pub fx: f64,
    pub fy: f64,
    pub cx: f64,
    pub cy: f64,
    pub k1: f64,
    pub k2: f64,
    pub p1: f64,
    pub p2: f64,
    #[serde(default)]
    pub k3: f64,
}

impl Intrinsics {
    /// A distortion-free pinhole.
    pub fn pinhole(fx: f64, fy: f64, cx: f64, cy: f64) -> Self {
        Self {
            fx,
            fy,
            cx,
            cy,
            k1: 0.0,
            k2: 0.0,
            p1: 0.0,
            p2: 0.0,
            k3: 0.0,
        }
    }

    /// Scale ratio `m = fy / fx` (method.md §2).
    pub fn scale_ratio(&self) -> f64 {
        self.fy / self.fx
    }

    /// Brown–Conrady distortion of a normalised point.
    pub fn distort(&self, n: &Vector2<f64>) -> Vector2<f64> {
        let (x, y) = (n.x, n.y);
        let r2 = x * x + y * y;
        let radial = 1.0 + r2 * (self.k1 + r2 * (self.k2 + r2 * self.k3));
        Vector2::new(
            x * radial + 2.0 * self.p1 * x * y + self.p2 * (r2 + 2.0 * x * x),
            y * radial + self.p1 * (r2 + 2.0 * y * y) + 2.0 * self.p2 * x * y,
        )
    }

    /// Jacobian of [`Self::distort`] with respect to the normalised point.
    pub fn distort_jacobian(&self, n: &Vector2<f64>) -> Matrix2<f64> {
        let (x, y) = (n.x, n.y);
        let r2 = x * x + y * y;
        let radial = 1.0 + r2 * (self.k1 + r2 * (self.k2 + r2 * self.k3));
        // d radial / d r2
        let d_radial = self.k1 + r2 * (2.0 * self.k2 + 3.0 * r2 * self.k3);
        Matrix2::new(
            radial + 2.0 * x * x * d_radial + 2.0 * self.p1 * y + 6.0 * self.p2 * x,
            2.0 * x * y * d_radial + 2.0 * self.p1 * x + 2.0 * self.p2 * y,
            2.0 * x * y * d_radial + 2.0 * self.p1 * x + 2.0 * self.p2 * y,
            radial + 2.0 * y * y * d_radial + 6.0 * self.p1 * y + 2.0 * self.p2 * x,
        )
    }

    /// Inverse of [`Self::distort`] by Newton's method; `None` where it does
    /// not converge (far outside the calibrated field).
    pub fn undistort(&self, d: &Vector2<f64>) -> Option<Vector2<f64>> {
        let mut n = *d;
        for _ in 0..UNDISTORT_MAX_ITERATIONS {
            let err = self.distort(&n) - d;
            if err.norm() < UNDISTORT_TOLERANCE {
                return Some(n);
            }
            let step = self.distort_jacobian(&n).try_inverse()? * err;
            n -= step;
            if !n.iter().all(|v| v.is_finite()) {
                return None;
            }
        }
        ((self.distort(&n) - d).norm() < UNDISTORT_TOLERANCE.sqrt()).then_some(n)
    }

    /// Normalised (distorted) coordinates to pixels.
    pub fn normalized_to_pixel(&self, d: &Vector2<f64>) -> Point2<f64> {
        Point2::new(self.fx * d.x + self.cx, self.fy * d.y + self.cy)
    }

    /// Pixels to distorted normalised coordinates.
    pub fn pixel_to_distorted(&self, uv: &Point2<f64>) -> Vector2<f64> {
        Vector2::new((uv.x - self.cx) / self.fx, (uv.y - self.cy) / self.fy)
    }

    /// Project a point given in the camera frame (mm); `None` behind the camera.
    pub fn project(&self, p_camera: &Point3<f64>) -> Option<Point2<f64>> {
        if p_camera.z <= MIN_DEPTH_MM {
            return None;
        }
        let n = Vector2::new(p_camera.x / p_camera.z, p_camera.y / p_camera.z);
        Some(self.normalized_to_pixel(&self.distort(&n)))
    }

    /// The undistorted normalised ray `(x/z, y/z)` seen at a pixel.
    pub fn pixel_to_ray(&self, uv: &Point2<f64>) -> Option<Vector2<f64>> {
        self.undistort(&self.pixel_to_distorted(uv))
    }
}

/// Standard deviations of the intrinsics (from `sigma^2 (J^T J)^-1`).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct IntrinsicsStdDev {
    pub fx: f64,
    pub fy: f64,
    pub scale_ratio: f64,
    pub cx: f64,
    pub cy: f64,
    pub k1: f64,
    pub k2: f64,
    pub p1: f64,
    pub p2: f64,
    pub k3: f64,
}

impl IntrinsicsStdDev {
    /// From the covariance of an intrinsics block `[fx, m, cx, cy, k1, k2,
    /// p1, p2, (k3)]` (px, the refinement's layout; absent entries give 0).
    /// `fy = m fx`: first-order propagation with the fx–m covariance.
    pub fn from_covariance(covariance: &nalgebra::DMatrix<f64>, intrinsics: &Intrinsics) -> Self {
        let n = covariance.nrows().min(covariance.ncols());
        let sd = |i: usize| {
            if i < n {
                covariance[(i, i)].max(0.0).sqrt()
            } else {
                0.0
            }
        };
        let (fx, m) = (intrinsics.fx, intrinsics.scale_ratio());
        let var_fy = if n > 1 {
            m * m * covariance[(0, 0)]
                + fx * fx * covariance[(1, 1)]
                + 2.0 * m * fx * covariance[(0, 1)]
        } else {
            0.0
        };
        Self {
            fx: sd(0),
            fy: var_fy.max(0.0).sqrt(),
            scale_ratio: sd(1),
            cx: sd(2),
            cy: sd(3),
            k1: sd(4),
            k2: sd(5),
            p1: sd(6),
            p2: sd(7),
            k3: sd(8),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Intrinsics {
        Intrinsics {
            fx: 2000.0,
            fy: 1965.0,
            cx: 640.5,
            cy: 511.0,
            k1: -0.12,
            k2: 0.08,
            p1: 4e-4,
            p2: -3e-4,
            k3: 0.0,
        }
    }

    #[test]
    fn undistort_inverts_distort_over_the_field() {
        let cam = camera();
        for i in -10..=10 {
            for j in -10..=10 {
                let n = Vector2::new(i as f64 * 0.035, j as f64 * 0.028);
                let back = cam.undistort(&cam.distort(&n)).unwrap();
                assert!((back - n).norm() < 1e-12, "{n} -> {back}");
            }
        }
    }

    #[test]
    fn distort_jacobian_matches_finite_differences() {
        let cam = camera();
        let n = Vector2::new(0.21, -0.17);
        let h = 1e-7;
        let analytic = cam.distort_jacobian(&n);
        for k in 0..2 {
            let mut dn = Vector2::zeros();
            dn[k] = h;
            let numeric = (cam.distort(&(n + dn)) - cam.distort(&(n - dn))) / (2.0 * h);
            assert!((analytic.column(k) - numeric).norm() < 1e-7);
        }
    }

    #[test]
    fn project_then_ray_is_the_identity() {
        let cam = camera();
        let p = Point3::new(120.0, -80.0, 800.0);
        let uv = cam.project(&p).unwrap();
        let ray = cam.pixel_to_ray(&uv).unwrap();
        assert!((ray - Vector2::new(p.x / p.z, p.y / p.z)).norm() < 1e-12);
        assert!(cam.project(&Point3::new(0.0, 0.0, -5.0)).is_none());
    }
}
