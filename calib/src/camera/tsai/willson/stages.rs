//! "Willson mode": Tsai's calibration with full optimisation replayed stage
//! by stage as Reg Willson's release 3.0b3 runs it (`ccal_fo`, `nccal_fo`;
//! calib/tests/data/tsai/README.md), to reproduce his published cameras.
//!
//! Every non-linear stage is MINPACK `lmdif` (`willson_minpack.rs`)
//! with Willson's settings (`ftol = 1e-5`, `xtol = 1e-7`, `gtol = 0`,
//! `maxfev = 1000 n`, `epsfcn = 1e-16`, `factor = 100`, mode 1) on **one
//! residual per point**: the length `hypot(Xu1 - Xu2, Yu1 - Yu2)` of the
//! undistorted sensor-plane error (mm), where `Xu1 = f xc / zc` and `Xu2 =
//! Xd (1 + kappa1 rd^2)`. The Jacobian of that length is rank one per point,
//! so Gauss–Newton converges slowly and `ftol` stops it short of the minimum
//! of the same cost: the published cameras are *not* least-squares minima.
//! [`super::fit::calibrate_tsai_full`] keeps the converged minimum
//! (two residuals per point, project LM); use it for calibration, and this
//! mode to check the implementation against Willson's numbers.
//!
//! Stages (non-coplanar): Tsai's linear stage at the initial centre with
//! `sx` estimated → `lmdif(f, Tz, kappa1)` (= `nccal`) → `lmdif` over all
//! but `Cx, Cy` → `lmdif` over all eleven. Coplanar (`sx = 1`): linear stage
//! → `lmdif(f, Tz, kappa1)` (= `ccal`) → `lmdif(f, Tz, kappa1, Cx, Cy)`
//! redoing the linear stage inside the residual, first on the distorted and
//! then on the undistorted sensor points → all but `Cx, Cy` → all ten. The
//! two five-parameter stages leave `R, Tx, Ty` as computed by their *last*
//! residual evaluation, which may be a rejected trial point; the mutable
//! `WillsonState` reproduces that.
//!
//! Agreement with the published runs (tests in `willson_stages_tests.rs`):
//! non-coplanar, every parameter within 4e-8 relative of `ncc_cpcc.dat` and
//! all error statistics to their printed digits; coplanar, Tz/f to its
//! printed digits and every parameter within 5.3e-7 relative. The rest is
//! not reachable: `lmdif` stops where rounding noise in its
//! forward-difference Jacobian leads it, so one-ulp changes of the data
//! move the result by about as much (the published numbers lie within 1.1
//! such spreads of ours); the last digits belong to the 1995 machine's
//! `hypot`, `sin` and `cos`.

use nalgebra::Point2;

use super::fit::{is_coplanar, MIN_POINTS_FULL_OPTIMISATION};
use super::linear::{rotation_rows, WillsonState};
pub use super::minpack::LmdifReport;
use super::minpack::{lmdif, LmdifFailure, LmdifOptions};
use super::model::{TsaiModel, TsaiPoint, TsaiSensor};
use crate::camera::error::CameraError;
use crate::camera::observations::is_collinear;

/// Willson's `lmdif` settings (`cal_main.h`).
const FTOL: f64 = 1e-5;
const XTOL: f64 = 1e-7;
const GTOL: f64 = 0.0;
const MAXFEV_PER_PARAMETER: usize = 1000;
const EPSFCN: f64 = 1e-16;
const FACTOR: f64 = 100.0;

/// One `lmdif` run of the sequence.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WillsonStage {
    pub name: &'static str,
    pub report: LmdifReport,
}

/// Result of Willson mode.
#[derive(Debug, Clone, PartialEq)]
pub struct WillsonCalibration {
    /// After the linear stage and `lmdif(f, Tz, kappa1)`: Willson's `ccal`
    /// / `nccal` (`Cx, Cy` at the initial guess).
    pub three_parameter: TsaiModel,
    /// After the whole sequence: `ccal_fo` / `nccal_fo`.
    pub model: TsaiModel,
    pub stages: Vec<WillsonStage>,
}

/// Tsai calibration with full optimisation exactly as Willson's 3.0b3
/// runs it, from the initial image centre `initial_centre` (px; Willson
/// uses (258, 204) for the Photometrics Star I). Coplanar data (all
/// `zw = 0`) keep `sx = 1`.
pub fn calibrate_tsai_willson(
    points: &[TsaiPoint],
    sensor: &TsaiSensor,
    initial_centre: Point2<f64>,
) -> Result<WillsonCalibration, CameraError> {
    if points.len() < MIN_POINTS_FULL_OPTIMISATION {
        return Err(CameraError::TooFewPoints {
            view: 0,
            count: points.len(),
            required: MIN_POINTS_FULL_OPTIMISATION,
        });
    }
    let finite = |p: &TsaiPoint| {
        p.world
            .coords
            .iter()
            .chain(&p.image.coords)
            .all(|v| v.is_finite())
    };
    if !points.iter().all(finite) || !initial_centre.coords.iter().all(|v| v.is_finite()) {
        return Err(CameraError::NonFinite { view: 0 });
    }
    if is_collinear(points.iter().map(|p| Point2::new(p.world.x, p.world.y))) {
        return Err(CameraError::CollinearPoints { view: 0 });
    }
    let dpx = sensor.dx * sensor.ncx / sensor.nfx;
    let mut s = WillsonState::new(points, dpx, sensor.dpy, initial_centre.x, initial_centre.y);
    let coplanar = is_coplanar(points);
    let mut stages = Vec::new();
    let degenerate = |stage: &str| CameraError::DegenerateView {
        view: 0,
        reason: format!("Willson stage `{stage}`: Tsai's linear equations have no solution"),
    };

    // Tsai's linear stage (`cc_`/`ncc_three_parm_optimization`).
    s.compute_xd_yd_r2();
    s.compute_u(coplanar).ok_or_else(|| degenerate("linear"))?;
    s.compute_tx_ty(coplanar)
        .ok_or_else(|| degenerate("linear"))?;
    if coplanar {
        s.compute_r_coplanar();
    } else {
        s.compute_sx();
        s.compute_xd_yd_r2();
        s.compute_better_r();
    }
    s.compute_approximate_f_tz_checked()
        .ok_or_else(|| degenerate("linear"))?;
    let mut x = vec![s.f, s.tz, s.kappa1];
    stages.push(run("f_tz_kappa1", &mut x, points.len(), |p, e| {
        three_parameter_error(&s, p, e)
    })?);
    (s.f, s.tz, s.kappa1) = (x[0], x[1], x[2]);
    let three_parameter = model_of(&s);

    if coplanar {
        for (name, early) in [
            ("centre_late_distortion", false),
            ("centre_early_distortion", true),
        ] {
            let mut x = vec![s.f, s.tz, s.kappa1, s.cx, s.cy];
            stages.push(run(name, &mut x, points.len(), |p, e| {
                centre_error(&mut s, early, p, e)
            })?);
            (s.f, s.tz, s.kappa1, s.cx, s.cy) = (x[0], x[1], x[2], x[3], x[4]);
        }
    }
    // All but the image centre, then everything (`*_nic_`, `*_full_`).
    for free_centre in [false, true] {
        let mut x = vec![s.rx, s.ry, s.rz, s.tx, s.ty, s.tz, s.kappa1, s.f];
        if !coplanar {
            x.push(s.sx);
        }
        if free_centre {
            x.extend([s.cx, s.cy]);
        }
        let name = if free_centre {
            "full"
        } else {
            "all_but_centre"
        };
        let fixed = (s.sx, s.cx, s.cy);
        stages.push(run(name, &mut x, points.len(), |p, e| {
            let sx = if coplanar { fixed.0 } else { p[8] };
            let (cx, cy) = if free_centre {
                (p[p.len() - 2], p[p.len() - 1])
            } else {
                (fixed.1, fixed.2)
            };
            model_error(&s, p, sx, cx, cy, e)
        })?);
        (s.rx, s.ry, s.rz, s.tx, s.ty, s.tz, s.kappa1, s.f) =
            (x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7]);
        s.apply_rpy();
        if !coplanar {
            s.sx = x[8];
        }
        if free_centre {
            (s.cx, s.cy) = (x[x.len() - 2], x[x.len() - 1]);
        }
    }
    Ok(WillsonCalibration {
        three_parameter,
        model: model_of(&s),
        stages,
    })
}

fn run<F>(name: &'static str, x: &mut [f64], m: usize, fcn: F) -> Result<WillsonStage, CameraError>
where
    F: FnMut(&[f64], &mut [f64]) -> bool,
{
    let options = LmdifOptions {
        ftol: FTOL,
        xtol: XTOL,
        gtol: GTOL,
        maxfev: MAXFEV_PER_PARAMETER * x.len(),
        epsfcn: EPSFCN,
        factor: FACTOR,
    };
    match lmdif(fcn, m, x, &options) {
        Ok(report) => Ok(WillsonStage { name, report }),
        Err(failure) => Err(CameraError::DegenerateView {
            view: 0,
            reason: match failure {
                LmdifFailure::BadInput => format!("Willson stage `{name}`: too few points"),
                LmdifFailure::UserAbort => {
                    format!("Willson stage `{name}`: the camera model became undefined")
                }
            },
        }),
    }
}

fn model_of(s: &WillsonState) -> TsaiModel {
    TsaiModel {
        f_mm: s.f,
        kappa1: s.kappa1,
        cx: s.cx,
        cy: s.cy,
        sx: s.sx,
        tx: s.tx,
        ty: s.ty,
        tz: s.tz,
        rx: s.rx,
        ry: s.ry,
        rz: s.rz,
    }
}

/// `hypot` of the undistorted sensor-plane error of point `i` for the
/// camera-frame point `(xc, yc, zc)` and undistorted measurement `(xu, yu)`.
fn point_error(f: f64, c: [f64; 3], xu: f64, yu: f64) -> f64 {
    (f * c[0] / c[2] - xu).hypot(f * c[1] / c[2] - yu)
}

fn camera_point(r: &[f64; 9], t: [f64; 3], p: &TsaiPoint) -> [f64; 3] {
    let w = p.world;
    [
        r[0] * w.x + r[1] * w.y + r[2] * w.z + t[0],
        r[3] * w.x + r[4] * w.y + r[5] * w.z + t[1],
        r[6] * w.x + r[7] * w.y + r[8] * w.z + t[2],
    ]
}

/// `(f, Tz, kappa1)` with `R, Tx, Ty` and the sensor points of the state.
fn three_parameter_error(s: &WillsonState, p: &[f64], err: &mut [f64]) -> bool {
    let (f, tz, kappa1) = (p[0], p[1], p[2]);
    for (i, pt) in s.points.iter().enumerate() {
        let c = camera_point(&s.r, [s.tx, s.ty, tz], pt);
        let k = 1.0 + kappa1 * s.r2[i];
        err[i] = point_error(f, c, s.xd[i] * k, s.yd[i] * k);
    }
    err.iter().all(|e| e.is_finite())
}

/// `(f, Tz, kappa1, Cx, Cy)`: the linear stage is redone inside the
/// residual at the trial centre, on the distorted sensor points (`early =
/// false`) or on the points undistorted with the trial `kappa1` (`early`).
fn centre_error(s: &mut WillsonState, early: bool, p: &[f64], err: &mut [f64]) -> bool {
    let (f, tz, kappa1) = (p[0], p[1], p[2]);
    if early {
        s.kappa1 = kappa1;
    }
    (s.cx, s.cy) = (p[3], p[4]);
    s.compute_xd_yd_r2();
    if early {
        for i in 0..s.points.len() {
            let k = 1.0 + s.kappa1 * (s.xd[i] * s.xd[i] + s.yd[i] * s.yd[i]);
            let (xu, yu) = (s.xd[i] * k, s.yd[i] * k);
            (s.xd[i], s.yd[i], s.r2[i]) = (xu, yu, xu * xu + yu * yu);
        }
    }
    let linear = s.compute_u(true).is_some() && s.compute_tx_ty(true).is_some() && {
        s.compute_r_coplanar();
        s.compute_approximate_f_tz_checked().is_some()
    };
    if !linear {
        return false;
    }
    for (i, pt) in s.points.iter().enumerate() {
        let c = camera_point(&s.r, [s.tx, s.ty, tz], pt);
        let k = if early { 1.0 } else { 1.0 + kappa1 * s.r2[i] };
        err[i] = point_error(f, c, s.xd[i] * k, s.yd[i] * k);
    }
    err.iter().all(|e| e.is_finite())
}

/// `[Rx, Ry, Rz, Tx, Ty, Tz, kappa1, f, ..]` with the given `sx, Cx, Cy`.
fn model_error(s: &WillsonState, p: &[f64], sx: f64, cx: f64, cy: f64, err: &mut [f64]) -> bool {
    let r = rotation_rows(p[0], p[1], p[2]);
    let (kappa1, f) = (p[6], p[7]);
    for (i, pt) in s.points.iter().enumerate() {
        let c = camera_point(&r, [p[3], p[4], p[5]], pt);
        let xd = s.dpx * (pt.image.x - cx) / sx;
        let yd = s.dpy * (pt.image.y - cy);
        let k = 1.0 + kappa1 * (xd * xd + yd * yd);
        err[i] = point_error(f, c, xd * k, yd * k);
    }
    err.iter().all(|e| e.is_finite())
}

#[cfg(test)]
#[path = "stages_tests.rs"]
mod tests;
