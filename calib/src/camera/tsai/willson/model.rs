//! Tsai's own camera model as in Reg Willson's reference implementation
//! (release 3.0b3; calib/tests/data/tsai/README.md): focal length `f` in mm, one
//! radial coefficient `kappa1` defined distorted -> undistorted, horizontal
//! scale `sx`, sensor pitch `dpx, dpy`, Euler angles `(Rx, Ry, Rz)`;
//! projection inverts the distortion cubic in closed form (Cardan). The full
//! non-linear optimisation minimises the undistorted sensor-plane error over
//! all extrinsics, `f, kappa1, Cx, Cy` (and `sx` for non-coplanar data),
//! started from Tsai's linear stages (method.md §3). Two solvers of it:
//! [`calibrate_tsai_full`] converges to the least-squares minimum (use it to
//! calibrate); [`calibrate_tsai_willson`] replays Willson's staged MINPACK
//! run and stops where he stopped (use it to reproduce his published
//! cameras, which lie short of that minimum).

use nalgebra::{Matrix3, Point2, Point3, Vector2, Vector3};

use crate::camera::error::CameraError;

/// Fixed sensor constants (`Ncx Nfx dx dy dpx dpy` in Willson's files).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TsaiSensor {
    pub ncx: f64,
    pub nfx: f64,
    pub dx: f64,
    pub dy: f64,
    pub dpx: f64,
    pub dpy: f64,
}

impl TsaiSensor {
    /// Willson's "Photometrics Star I": 576 elements of 0.023 mm.
    pub fn photometrics_star_i() -> Self {
        Self {
            ncx: 576.0,
            nfx: 576.0,
            dx: 0.023,
            dy: 0.023,
            dpx: 0.023,
            dpy: 0.023,
        }
    }
}

/// Tsai's calibrated camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TsaiModel {
    pub f_mm: f64,
    /// 1/mm^2, distorted -> undistorted: `Xu = Xd (1 + kappa1 (Xd^2 + Yd^2))`.
    pub kappa1: f64,
    pub cx: f64,
    pub cy: f64,
    pub sx: f64,
    pub tx: f64,
    pub ty: f64,
    pub tz: f64,
    /// Radians; `R` as in Willson's `cal_tran.c` (see [`TsaiModel::rotation`]).
    pub rx: f64,
    pub ry: f64,
    pub rz: f64,
}

/// One correspondence of Willson's data files: `xw yw zw Xf Yf`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TsaiPoint {
    pub world: Point3<f64>,
    pub image: Point2<f64>,
}

/// Per-point error statistics as Willson prints them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorStats {
    pub mean: f64,
    /// Sample standard deviation (n - 1).
    pub std_dev: f64,
    pub max: f64,
    pub sse: f64,
}

/// Parse Willson's `*_cd.dat` text (five numbers a line).
pub fn parse_points(text: &str) -> Result<Vec<TsaiPoint>, CameraError> {
    let mut points = Vec::new();
    for (line_no, line) in text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
    {
        let v: Vec<f64> = line
            .split_whitespace()
            .map(str::parse)
            .collect::<Result<_, _>>()
            .map_err(|_| CameraError::InvalidOption {
                field: "tsai_data",
                reason: format!("line {}: not a number", line_no + 1),
            })?;
        if v.len() != 5 || !v.iter().all(|x| x.is_finite()) {
            return Err(CameraError::InvalidOption {
                field: "tsai_data",
                reason: format!("line {}: expected 5 finite numbers", line_no + 1),
            });
        }
        points.push(TsaiPoint {
            world: Point3::new(v[0], v[1], v[2]),
            image: Point2::new(v[3], v[4]),
        });
    }
    Ok(points)
}

impl TsaiModel {
    /// `r1 = cb cg, r2 = cg sa sb - ca sg, ...` (Willson, `cal_tran.c`).
    pub fn rotation(&self) -> Matrix3<f64> {
        rotation_from_euler(self.rx, self.ry, self.rz)
    }

    fn camera_point(&self, p: &Point3<f64>) -> Vector3<f64> {
        self.rotation() * p.coords + Vector3::new(self.tx, self.ty, self.tz)
    }

    /// Undistorted sensor coordinates (mm) of a world point.
    pub fn undistorted_sensor(&self, p: &Point3<f64>) -> Option<Vector2<f64>> {
        let c = self.camera_point(p);
        (c.z > 0.0).then(|| Vector2::new(self.f_mm * c.x / c.z, self.f_mm * c.y / c.z))
    }

    /// Measured frame-buffer pixel to distorted sensor coordinates (mm).
    pub fn distorted_sensor(&self, sensor: &TsaiSensor, image: &Point2<f64>) -> Vector2<f64> {
        let dpx = sensor.dx * sensor.ncx / sensor.nfx;
        Vector2::new(
            dpx * (image.x - self.cx) / self.sx,
            sensor.dpy * (image.y - self.cy),
        )
    }

    /// Project a world point to frame-buffer pixels (Cardan inversion).
    pub fn project(&self, sensor: &TsaiSensor, p: &Point3<f64>) -> Option<Point2<f64>> {
        let u = self.undistorted_sensor(p)?;
        let d = undistorted_to_distorted(self.kappa1, &u)?;
        let dpx = sensor.dx * sensor.ncx / sensor.nfx;
        Some(Point2::new(
            d.x * self.sx / dpx + self.cx,
            d.y / sensor.dpy + self.cy,
        ))
    }

    /// Distorted image-plane error statistics (px), as in Willson's logs.
    pub fn distorted_error(&self, sensor: &TsaiSensor, points: &[TsaiPoint]) -> Option<ErrorStats> {
        let e: Option<Vec<f64>> = points
            .iter()
            .map(|p| Some((self.project(sensor, &p.world)? - p.image).norm()))
            .collect();
        Some(stats(&e?))
    }
}

pub(super) fn rotation_from_euler(a: f64, b: f64, g: f64) -> Matrix3<f64> {
    let (sa, ca) = a.sin_cos();
    let (sb, cb) = b.sin_cos();
    let (sg, cg) = g.sin_cos();
    Matrix3::new(
        cb * cg,
        cg * sa * sb - ca * sg,
        sa * sg + ca * cg * sb,
        cb * sg,
        sa * sb * sg + ca * cg,
        ca * sb * sg - cg * sa,
        -sb,
        cb * sa,
        ca * cb,
    )
}

pub(super) fn euler_from_rotation(r: &Matrix3<f64>) -> (f64, f64, f64) {
    let b = (-r[(2, 0)]).clamp(-1.0, 1.0).asin();
    (r[(2, 1)].atan2(r[(2, 2)]), b, r[(1, 0)].atan2(r[(0, 0)]))
}

/// Solve `Ru = Rd (1 + kappa1 Rd^2)` for `Rd` by Cardan's formula, taking
/// the smaller positive root when there are three (as Willson does).
pub fn undistorted_to_distorted(kappa1: f64, u: &Vector2<f64>) -> Option<Vector2<f64>> {
    let ru = u.norm();
    if kappa1 == 0.0 || ru == 0.0 {
        return Some(*u);
    }
    let c = 1.0 / kappa1;
    let d = -c * ru;
    let q = c / 3.0;
    let r = -d / 2.0;
    let disc = q * q * q + r * r;
    let rd = if disc >= 0.0 {
        let s = disc.sqrt();
        (r + s).cbrt() + (r - s).cbrt()
    } else {
        let dd = (-disc).sqrt();
        let s = r.hypot(dd).cbrt();
        let t = dd.atan2(r) / 3.0;
        -s * t.cos() + 3f64.sqrt() * s * t.sin()
    };
    rd.is_finite().then(|| u * (rd / ru))
}

pub(super) fn stats(e: &[f64]) -> ErrorStats {
    let n = e.len() as f64;
    let mean = e.iter().sum::<f64>() / n;
    let sse = e.iter().map(|v| v * v).sum::<f64>();
    let var = e.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    ErrorStats {
        mean,
        std_dev: var.sqrt(),
        max: e.iter().cloned().fold(0.0, f64::max),
        sse,
    }
}

#[cfg(test)]
#[path = "model_tests.rs"]
mod tests;
