//! Tsai's full non-linear optimisation, converged: Tsai's linear stages
//! (method.md §3, and the seven-unknown non-coplanar stage 1) start one
//! Levenberg–Marquardt (the project's solver, two residuals per point, tight
//! tolerances) over all extrinsics, `f, kappa1, Cx, Cy` (and `sx` for
//! non-coplanar data) minimising the undistorted sensor-plane error, Willson's
//! own objective.
//!
//! This reaches the least-squares minimum, whose cost is lower than that of
//! Willson's published cameras (by 5e-4 relative non-coplanar, 2e-4
//! coplanar): Willson's `ccal_fo` / `nccal_fo` stop early, because MINPACK
//! `lmdif` on one `hypot` residual per point meets `ftol = 1e-5` first. To
//! reproduce his numbers use [`super::stages::calibrate_tsai_willson`]
//! ("Willson mode"); to calibrate, use this.

use nalgebra::{DMatrix, DVector, Matrix3, Point2, Vector2, Vector3};

use super::model::{euler_from_rotation, TsaiModel, TsaiPoint, TsaiSensor};
use crate::camera::error::CameraError;
use crate::camera::observations::is_collinear;
use crate::camera::tsai::{stage1, CentredPoint};
use crate::geometry::orthonormalize;
use crate::solver::{solve, LeastSquaresProblem, LmOptions};

/// Fewest points for Tsai's full optimisation (Willson FAQ §3.1).
pub const MIN_POINTS_FULL_OPTIMISATION: usize = 11;
/// |zw| above this (mm) makes the data non-coplanar.
const COPLANAR_TOLERANCE_MM: f64 = 1e-9;
/// Tight stopping rules: the published figures are printed to 6-9 digits.
const TIGHT_TOLERANCE: f64 = 1e-16;
const MAX_ITERATIONS: usize = 1000;

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

/// All `zw` within [`COPLANAR_TOLERANCE_MM`] of 0: Willson's coplanar
/// routines (`sx` fixed, five linear unknowns).
pub(super) fn is_coplanar(points: &[TsaiPoint]) -> bool {
    points
        .iter()
        .all(|p| p.world.z.abs() <= COPLANAR_TOLERANCE_MM)
}

/// Tsai's calibration with full non-linear optimisation, converged to the
/// least-squares minimum of Willson's objective (the model and stages of
/// his `ccal_fo` for coplanar data, `nccal_fo` otherwise; `sx` is fixed at 1
/// for coplanar data, where it cannot be calibrated). Not his stopping
/// point: see [`super::stages::calibrate_tsai_willson`].
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
    let coplanar = is_coplanar(points);
    if is_collinear(points.iter().map(|p| Point2::new(p.world.x, p.world.y))) {
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
