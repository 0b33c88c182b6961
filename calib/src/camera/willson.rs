//! Tsai's own camera model as in Reg Willson's reference implementation
//! (release 3.0b3; shared/data/tsai/README.md): focal length `f` in mm, one
//! radial coefficient `kappa1` defined distorted -> undistorted, horizontal
//! scale `sx`, sensor pitch `dpx, dpy`, Euler angles `(Rx, Ry, Rz)`;
//! projection inverts the distortion cubic in closed form (Cardan). The full
//! non-linear optimisation minimises the undistorted sensor-plane error over
//! all extrinsics, `f, kappa1, Cx, Cy` (and `sx` for non-coplanar data),
//! started from Tsai's linear stages (method.md §3).

use nalgebra::{DMatrix, DVector, Matrix3, Point2, Point3, Vector2, Vector3};

use super::error::CameraError;
use super::tsai::{stage1, CentredPoint};
use crate::geometry::orthonormalize;
use crate::solver::{solve, LeastSquaresProblem, LmOptions};

/// Fewest points for Tsai's full optimisation (Willson FAQ §3.1).
pub const MIN_POINTS_FULL_OPTIMISATION: usize = 11;
/// |zw| above this (mm) makes the data non-coplanar.
const COPLANAR_TOLERANCE_MM: f64 = 1e-9;
/// Tight stopping rules: the published figures are printed to 6-9 digits.
const TIGHT_TOLERANCE: f64 = 1e-16;
const MAX_ITERATIONS: usize = 1000;

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

fn rotation_from_euler(a: f64, b: f64, g: f64) -> Matrix3<f64> {
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

fn euler_from_rotation(r: &Matrix3<f64>) -> (f64, f64, f64) {
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

fn stats(e: &[f64]) -> ErrorStats {
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

/// Parameter vector: `[Rx, Ry, Rz, Tx, Ty, Tz, kappa1, f, Cx, Cy (, sx)]`.
struct FullOptimisation<'a> {
    points: &'a [TsaiPoint],
    sensor: TsaiSensor,
    /// `None`: sx is free (non-coplanar); `Some(sx)`: fixed.
    fixed_sx: Option<f64>,
}

impl FullOptimisation<'_> {
    fn decode(&self, x: &DVector<f64>) -> TsaiModel {
        TsaiModel {
            rx: x[0],
            ry: x[1],
            rz: x[2],
            tx: x[3],
            ty: x[4],
            tz: x[5],
            kappa1: x[6],
            f_mm: x[7],
            cx: x[8],
            cy: x[9],
            sx: self.fixed_sx.unwrap_or_else(|| x[10]),
        }
    }

    fn encode(&self, m: &TsaiModel) -> DVector<f64> {
        let mut v = vec![
            m.rx, m.ry, m.rz, m.tx, m.ty, m.tz, m.kappa1, m.f_mm, m.cx, m.cy,
        ];
        if self.fixed_sx.is_none() {
            v.push(m.sx);
        }
        DVector::from_vec(v)
    }
}

impl LeastSquaresProblem for FullOptimisation<'_> {
    /// Undistorted sensor-plane error (mm), both components, per point.
    fn residuals(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
        let m = self.decode(x);
        let mut r = DVector::zeros(2 * self.points.len());
        for (i, p) in self.points.iter().enumerate() {
            let u1 = m.undistorted_sensor(&p.world)?;
            let d = m.distorted_sensor(&self.sensor, &p.image);
            let u2 = d * (1.0 + m.kappa1 * d.norm_squared());
            r[2 * i] = u1.x - u2.x;
            r[2 * i + 1] = u1.y - u2.y;
        }
        Some(r)
    }
}

/// Tsai's linear start (stage 1 for coplanar or non-coplanar data, then
/// stage 2), with the image centre at `centre` and `kappa1 = 0`.
fn linear_start(
    points: &[TsaiPoint],
    sensor: &TsaiSensor,
    centre: Point2<f64>,
    coplanar: bool,
) -> Option<TsaiModel> {
    let probe = TsaiModel {
        f_mm: 1.0,
        kappa1: 0.0,
        cx: centre.x,
        cy: centre.y,
        sx: 1.0,
        tx: 0.0,
        ty: 0.0,
        tz: 0.0,
        rx: 0.0,
        ry: 0.0,
        rz: 0.0,
    };
    let sensor_pts: Vec<Vector2<f64>> = points
        .iter()
        .map(|p| probe.distorted_sensor(sensor, &p.image))
        .collect();
    let (rotation, tx, ty, sx) = if coplanar {
        let centred: Vec<CentredPoint> = points
            .iter()
            .zip(&sensor_pts)
            .map(|(p, d)| CentredPoint {
                world: p.world.xy().coords,
                image: *d,
            })
            .collect();
        let s1 = stage1(&centred, 1.0)?;
        (s1.rotation, s1.tx, s1.ty, 1.0)
    } else {
        noncoplanar_stage1(points, &sensor_pts)?
    };
    // Stage 2 (Tsai's y rows, distortion-free): f y - Yd Tz = Yd w.
    let mut a = DMatrix::zeros(points.len(), 2);
    let mut b = DVector::zeros(points.len());
    for (i, (p, d)) in points.iter().zip(&sensor_pts).enumerate() {
        let c = rotation * p.world.coords;
        a[(i, 0)] = c.y + ty;
        a[(i, 1)] = -d.y;
        b[i] = d.y * c.z;
    }
    let sol = a.svd(true, true).solve(&b, 1e-14).ok()?;
    let (f, tz) = (sol[0], sol[1]);
    if !(f > 0.0 && tz > 0.0) {
        return None;
    }
    let (rx, ry, rz) = euler_from_rotation(&rotation);
    Some(TsaiModel {
        f_mm: f,
        kappa1: 0.0,
        cx: centre.x,
        cy: centre.y,
        sx,
        tx,
        ty,
        tz,
        rx,
        ry,
        rz,
    })
}

/// Tsai's non-coplanar stage 1: seven unknowns
/// `(sx r1, sx r2, sx r3, sx Tx, r4, r5, r6) / Ty`.
fn noncoplanar_stage1(
    points: &[TsaiPoint],
    d: &[Vector2<f64>],
) -> Option<(Matrix3<f64>, f64, f64, f64)> {
    let a = DMatrix::from_fn(points.len(), 7, |i, j| {
        let w = points[i].world;
        let (x, y) = (d[i].x, d[i].y);
        [y * w.x, y * w.y, y * w.z, y, -x * w.x, -x * w.y, -x * w.z][j]
    });
    let b = DVector::from_iterator(points.len(), d.iter().map(|v| v.x));
    let u = a.svd(true, true).solve(&b, 1e-14).ok()?;
    let mut ty = 1.0 / (u[4] * u[4] + u[5] * u[5] + u[6] * u[6]).sqrt();
    let far =
        (0..points.len()).max_by(|&i, &j| d[i].norm_squared().total_cmp(&d[j].norm_squared()))?;
    let sx = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt() * ty;
    let w = points[far].world;
    let x = (u[0] * w.x + u[1] * w.y + u[2] * w.z + u[3]) * ty / sx;
    let y = (u[4] * w.x + u[5] * w.y + u[6] * w.z + 1.0) * ty;
    if x.signum() != d[far].x.signum() || y.signum() != d[far].y.signum() {
        ty = -ty;
    }
    let row1 = Vector3::new(u[0], u[1], u[2]) * ty / sx;
    let row2 = Vector3::new(u[4], u[5], u[6]) * ty;
    let r = Matrix3::from_rows(&[
        row1.transpose(),
        row2.transpose(),
        row1.cross(&row2).transpose(),
    ]);
    Some((*orthonormalize(&r).matrix(), u[3] * ty / sx, ty, sx))
}

/// Tsai's calibration with full non-linear optimisation (Willson's
/// `ccal_fo` for coplanar data, `nccal_fo` otherwise; `sx` is fixed at 1 for
/// coplanar data, where it cannot be calibrated).
pub fn calibrate_tsai_full(
    points: &[TsaiPoint],
    sensor: &TsaiSensor,
    initial_centre: Point2<f64>,
) -> Result<TsaiFit, CameraError> {
    if points.len() < MIN_POINTS_FULL_OPTIMISATION {
        return Err(CameraError::TooFewPoints {
            view: 0,
            count: points.len(),
            required: MIN_POINTS_FULL_OPTIMISATION,
        });
    }
    let coplanar = points
        .iter()
        .all(|p| p.world.z.abs() <= COPLANAR_TOLERANCE_MM);
    if super::observations::is_collinear(points.iter().map(|p| Point2::new(p.world.x, p.world.y))) {
        return Err(CameraError::CollinearPoints { view: 0 });
    }
    let start = linear_start(points, sensor, initial_centre, coplanar).ok_or(
        CameraError::DegenerateView {
            view: 0,
            reason: "Tsai's linear stages have no solution".into(),
        },
    )?;
    let problem = FullOptimisation {
        points,
        sensor: *sensor,
        fixed_sx: coplanar.then_some(1.0),
    };
    let options = LmOptions {
        cost_tolerance: TIGHT_TOLERANCE,
        step_tolerance: TIGHT_TOLERANCE,
        gradient_tolerance: TIGHT_TOLERANCE,
        max_iterations: MAX_ITERATIONS,
        ..LmOptions::default()
    };
    let report = solve(&problem, problem.encode(&start), &options)?;
    let sd = report.standard_deviations();
    let mut sd_full = sd.clone();
    if coplanar {
        sd_full = sd_full.push(0.0);
    }
    Ok(TsaiFit {
        model: problem.decode(&report.x),
        std_dev: FullOptimisation {
            fixed_sx: None,
            ..problem
        }
        .decode(&sd_full),
        cost_mm2: report.cost,
    })
}

/// Sum of squared undistorted sensor-plane errors (mm^2) of a model: the
/// objective of the full optimisation.
pub fn full_optimisation_cost(
    model: &TsaiModel,
    points: &[TsaiPoint],
    sensor: &TsaiSensor,
) -> Option<f64> {
    let problem = FullOptimisation {
        points,
        sensor: *sensor,
        fixed_sx: None,
    };
    Some(problem.residuals(&problem.encode(model))?.norm_squared())
}

/// The full optimisation's result.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TsaiFit {
    pub model: TsaiModel,
    /// Standard deviation of each parameter (same fields; 0 where fixed).
    pub std_dev: TsaiModel,
    /// Objective at the solution (mm^2).
    pub cost_mm2: f64,
}

#[cfg(test)]
#[path = "willson_tests.rs"]
mod tests;
