//! MINPACK's `lmdif` (Moré, Garbow and Hillstrom, Argonne 1980; public
//! domain), re-implemented from the published algorithm so that Willson's
//! staged Tsai calibration ([`super::super::stages`]) takes the very steps
//! his 1995 binary took: forward-difference Jacobian with step
//! `sqrt(max(epsfcn, eps)) |x_j|`, column-pivoted Householder QR,
//! Moré's trust-region Levenberg–Marquardt parameter, and the
//! `ftol`/`xtol`/`gtol`/`maxfev` stopping rules (method.md §6 describes the
//! project's own solver, `crate::solver`, which this does not replace).
//!
//! Willson stops at a relative change of the sum of squares of 1e-5, well
//! short of the minimum in the f–Tz valley, so the published camera is a
//! property of this exact iteration: a different LM (damping schedule,
//! Jacobian, residual layout) converges elsewhere. The operation order of
//! the Fortran is kept wherever it changes rounding.

use super::lmpar::{lmpar, qrfac};
use super::norm::{enorm, EPSMCH};

/// A step is taken when the actual reduction is at least this fraction of
/// the predicted one.
const ACCEPT_RATIO: f64 = 1e-4;
const P1: f64 = 0.1;
const P5: f64 = 0.5;
const P25: f64 = 0.25;
const P75: f64 = 0.75;

/// `lmdif`'s tunables (mode 1: variables scaled by the Jacobian's column
/// norms; `nprint = 0`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LmdifOptions {
    /// Relative reduction of the sum of squares at which to stop.
    pub ftol: f64,
    /// Relative step size at which to stop.
    pub xtol: f64,
    /// Cosine between residual and Jacobian columns at which to stop.
    pub gtol: f64,
    /// Function evaluations allowed (Jacobian columns count).
    pub maxfev: usize,
    /// Assumed relative error of the function values (sets the FD step).
    pub epsfcn: f64,
    /// Initial trust radius as a multiple of `|D x|`.
    pub factor: f64,
}

/// How `lmdif` ended (`info` 1–8 as documented in MINPACK).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LmdifReport {
    pub info: u8,
    pub nfev: usize,
}

/// Why `lmdif` could not run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LmdifFailure {
    /// `m < n`, `n = 0` or a non-positive tolerance/limit (`info = 0`).
    BadInput,
    /// The residual function refused a point (`iflag < 0`).
    UserAbort,
}

/// Forward-difference Jacobian into column-major `fjac` (`m` rows).
fn fdjac2<F>(fcn: &mut F, x: &mut [f64], fvec: &[f64], fjac: &mut [f64], epsfcn: f64) -> bool
where
    F: FnMut(&[f64], &mut [f64]) -> bool,
{
    let m = fvec.len();
    let eps = epsfcn.max(EPSMCH).sqrt();
    let mut wa = vec![0.0; m];
    for j in 0..x.len() {
        let temp = x[j];
        let mut h = eps * temp.abs();
        if h == 0.0 {
            h = eps;
        }
        x[j] = temp + h;
        let ok = fcn(x, &mut wa);
        x[j] = temp;
        if !ok {
            return false;
        }
        for i in 0..m {
            fjac[i + j * m] = (wa[i] - fvec[i]) / h;
        }
    }
    true
}

/// Minimise `sum fvec_i(x)^2` from `x` (updated in place). `fcn(x, fvec)`
/// fills the `m` residuals and returns `false` to abort.
pub fn lmdif<F>(
    mut fcn: F,
    m: usize,
    x: &mut [f64],
    opt: &LmdifOptions,
) -> Result<LmdifReport, LmdifFailure>
where
    F: FnMut(&[f64], &mut [f64]) -> bool,
{
    let n = x.len();
    if n == 0 || m < n || opt.ftol < 0.0 || opt.xtol < 0.0 || opt.gtol < 0.0 {
        return Err(LmdifFailure::BadInput);
    }
    if opt.maxfev == 0 || opt.factor <= 0.0 {
        return Err(LmdifFailure::BadInput);
    }
    let mut fvec = vec![0.0; m];
    let mut fjac = vec![0.0; m * n];
    let (mut diag, mut qtf) = (vec![0.0; n], vec![0.0; n]);
    let (mut wa1, mut wa2, mut wa3) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut wa4 = vec![0.0; m];
    let mut ipvt = vec![0usize; n];

    if !fcn(x, &mut fvec) {
        return Err(LmdifFailure::UserAbort);
    }
    let mut nfev = 1;
    let mut fnorm = enorm(&fvec);
    let (mut par, mut iter) = (0.0f64, 1usize);
    let (mut delta, mut xnorm) = (0.0f64, 0.0f64);
    loop {
        // Outer loop: Jacobian, its QR, and the scaled gradient.
        if !fdjac2(&mut fcn, x, &fvec, &mut fjac, opt.epsfcn) {
            return Err(LmdifFailure::UserAbort);
        }
        nfev += n;
        qrfac(m, n, &mut fjac, &mut ipvt, &mut wa1, &mut wa2, &mut wa3);
        if iter == 1 {
            for j in 0..n {
                diag[j] = if wa2[j] == 0.0 { 1.0 } else { wa2[j] };
                wa3[j] = diag[j] * x[j];
            }
            xnorm = enorm(&wa3);
            delta = opt.factor * xnorm;
            if delta == 0.0 {
                delta = opt.factor;
            }
        }
        wa4.copy_from_slice(&fvec);
        for j in 0..n {
            let ajj = fjac[j + j * m];
            if ajj != 0.0 {
                let mut sum = 0.0;
                for i in j..m {
                    sum += fjac[i + j * m] * wa4[i];
                }
                let temp = -sum / ajj;
                for i in j..m {
                    wa4[i] += fjac[i + j * m] * temp;
                }
            }
            fjac[j + j * m] = wa1[j];
            qtf[j] = wa4[j];
        }
        let mut gnorm = 0.0f64;
        if fnorm != 0.0 {
            for j in 0..n {
                let l = ipvt[j];
                if wa2[l] != 0.0 {
                    let mut sum = 0.0;
                    for i in 0..=j {
                        sum += fjac[i + j * m] * (qtf[i] / fnorm);
                    }
                    gnorm = gnorm.max((sum / wa2[l]).abs());
                }
            }
        }
        if gnorm <= opt.gtol {
            return Ok(LmdifReport { info: 4, nfev });
        }
        for j in 0..n {
            diag[j] = diag[j].max(wa2[j]);
        }
        loop {
            // Inner loop: trial steps until one reduces the sum of squares.
            lmpar(
                n, &mut fjac, m, &ipvt, &diag, &qtf, delta, &mut par, &mut wa1, &mut wa2, &mut wa3,
                &mut wa4,
            );
            for j in 0..n {
                wa1[j] = -wa1[j];
                wa2[j] = x[j] + wa1[j];
                wa3[j] = diag[j] * wa1[j];
            }
            let pnorm = enorm(&wa3);
            if iter == 1 {
                delta = delta.min(pnorm);
            }
            if !fcn(&wa2, &mut wa4) {
                return Err(LmdifFailure::UserAbort);
            }
            nfev += 1;
            let fnorm1 = enorm(&wa4);
            let mut actred = -1.0;
            if P1 * fnorm1 < fnorm {
                let r = fnorm1 / fnorm;
                actred = 1.0 - r * r;
            }
            for j in 0..n {
                wa3[j] = 0.0;
                let temp = wa1[ipvt[j]];
                for i in 0..=j {
                    wa3[i] += fjac[i + j * m] * temp;
                }
            }
            let temp1 = enorm(&wa3) / fnorm;
            let temp2 = par.sqrt() * pnorm / fnorm;
            let prered = temp1 * temp1 + temp2 * temp2 / P5;
            let dirder = -(temp1 * temp1 + temp2 * temp2);
            let ratio = if prered != 0.0 { actred / prered } else { 0.0 };
            if ratio <= P25 {
                let mut temp = if actred >= 0.0 {
                    P5
                } else {
                    P5 * dirder / (dirder + P5 * actred)
                };
                if P1 * fnorm1 >= fnorm || temp < P1 {
                    temp = P1;
                }
                delta = temp * delta.min(pnorm / P1);
                par /= temp;
            } else if par == 0.0 || ratio >= P75 {
                delta = pnorm / P5;
                par *= P5;
            }
            if ratio >= ACCEPT_RATIO {
                for j in 0..n {
                    x[j] = wa2[j];
                    wa2[j] = diag[j] * x[j];
                }
                fvec.copy_from_slice(&wa4);
                xnorm = enorm(&wa2);
                fnorm = fnorm1;
                iter += 1;
            }
            let small_reduction =
                actred.abs() <= opt.ftol && prered <= opt.ftol && P5 * ratio <= 1.0;
            let small_step = delta <= opt.xtol * xnorm;
            match (small_reduction, small_step) {
                (true, true) => return Ok(LmdifReport { info: 3, nfev }),
                (true, false) => return Ok(LmdifReport { info: 1, nfev }),
                (false, true) => return Ok(LmdifReport { info: 2, nfev }),
                (false, false) => {}
            }
            let info = if gnorm <= EPSMCH {
                8
            } else if delta <= EPSMCH * xnorm {
                7
            } else if actred.abs() <= EPSMCH && prered <= EPSMCH && P5 * ratio <= 1.0 {
                6
            } else if nfev >= opt.maxfev {
                5
            } else {
                0
            };
            if info != 0 {
                return Ok(LmdifReport { info, nfev });
            }
            if ratio >= ACCEPT_RATIO {
                break;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rosenbrock as residuals `(10 (x2 - x1^2), 1 - x1)`: lmdif from
    /// MINPACK's standard start (-1.2, 1) reaches the minimum (1, 1).
    #[test]
    fn lmdif_solves_rosenbrock() {
        let mut x = [-1.2, 1.0];
        let opt = LmdifOptions {
            ftol: 1e-12,
            xtol: 1e-12,
            gtol: 0.0,
            maxfev: 2000,
            epsfcn: 0.0,
            factor: 100.0,
        };
        let rep = lmdif(
            |x, f| {
                f[0] = 10.0 * (x[1] - x[0] * x[0]);
                f[1] = 1.0 - x[0];
                true
            },
            2,
            &mut x,
            &opt,
        )
        .unwrap();
        assert!((1..=4).contains(&rep.info), "info {}", rep.info);
        assert!(
            (x[0] - 1.0).abs() < 1e-9 && (x[1] - 1.0).abs() < 1e-9,
            "{x:?}"
        );
    }

    #[test]
    fn enorm_is_the_euclidean_norm_across_scales() {
        assert_eq!(enorm(&[3.0, 4.0]), 5.0);
        let tiny = enorm(&[3e-25, 4e-25]);
        assert!((tiny / 5e-25 - 1.0).abs() < 1e-15);
        let huge = enorm(&[3e200, 4e200]);
        assert!((huge / 5e200 - 1.0).abs() < 1e-15);
        assert_eq!(enorm(&[]), 0.0);
    }

    #[test]
    fn lmdif_refuses_more_unknowns_than_residuals() {
        let mut x = [1.0, 2.0];
        let opt = LmdifOptions {
            ftol: 1e-5,
            xtol: 1e-7,
            gtol: 0.0,
            maxfev: 100,
            epsfcn: 1e-16,
            factor: 100.0,
        };
        assert_eq!(
            lmdif(|_, _| true, 1, &mut x, &opt),
            Err(LmdifFailure::BadInput)
        );
    }
}
