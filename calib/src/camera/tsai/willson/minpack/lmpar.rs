//! MINPACK's `qrfac`, `lmpar` and `qrsolv` (public domain, Argonne 1980),
//! re-implemented from the algorithm for [`super::lmdif::lmdif`].
//! Matrices are column-major with leading dimension `ld` (Fortran layout);
//! the loop and operation order of MINPACK is kept because Willson's
//! published camera depends on where `lmdif` stops.

use super::norm::{enorm, DWARF, EPSMCH};

/// `lmpar` accepts `|D x| - delta` within this fraction of `delta`.
const PAR_TOLERANCE: f64 = 0.1;
/// Lower bound of the LM parameter as a fraction of its upper bound.
const P001: f64 = 0.001;
/// Iterations of `lmpar`'s safeguarded Newton search.
const MAX_PAR_ITERATIONS: usize = 10;
/// `qrfac` recomputes a column norm when its downdate lost this much.
const P05: f64 = 0.05;

/// Householder QR with column pivoting of the `m x n` matrix `a`: on return
/// the strict upper triangle of `a` holds R (its diagonal is `rdiag`), the
/// lower trapezoid the Householder vectors; `acnorm` holds the column norms
/// of the input, `ipvt` the permutation.
pub(super) fn qrfac(
    m: usize,
    n: usize,
    a: &mut [f64],
    ipvt: &mut [usize],
    rdiag: &mut [f64],
    acnorm: &mut [f64],
    wa: &mut [f64],
) {
    for j in 0..n {
        acnorm[j] = enorm(&a[j * m..(j + 1) * m]);
        rdiag[j] = acnorm[j];
        wa[j] = rdiag[j];
        ipvt[j] = j;
    }
    for j in 0..m.min(n) {
        let mut kmax = j;
        for k in j..n {
            if rdiag[k] > rdiag[kmax] {
                kmax = k;
            }
        }
        if kmax != j {
            for i in 0..m {
                a.swap(i + j * m, i + kmax * m);
            }
            rdiag[kmax] = rdiag[j];
            wa[kmax] = wa[j];
            ipvt.swap(j, kmax);
        }
        let mut ajnorm = enorm(&a[j + j * m..(j + 1) * m]);
        if ajnorm != 0.0 {
            if a[j + j * m] < 0.0 {
                ajnorm = -ajnorm;
            }
            for i in j..m {
                a[i + j * m] /= ajnorm;
            }
            a[j + j * m] += 1.0;
            for k in j + 1..n {
                let mut sum = 0.0;
                for i in j..m {
                    sum += a[i + j * m] * a[i + k * m];
                }
                let temp = sum / a[j + j * m];
                for i in j..m {
                    a[i + k * m] -= temp * a[i + j * m];
                }
                if rdiag[k] != 0.0 {
                    let t = a[j + k * m] / rdiag[k];
                    rdiag[k] *= (1.0 - t * t).max(0.0).sqrt();
                    let q = rdiag[k] / wa[k];
                    if P05 * (q * q) <= EPSMCH {
                        rdiag[k] = enorm(&a[j + 1 + k * m..(k + 1) * m]);
                        wa[k] = rdiag[k];
                    }
                }
            }
        }
        rdiag[j] = -ajnorm;
    }
}

/// Back-substitute the upper-triangular `r` for its first `nsing` unknowns.
fn solve_upper(r: &[f64], ld: usize, nsing: usize, w: &mut [f64]) {
    for j in (0..nsing).rev() {
        w[j] /= r[j + j * ld];
        let temp = w[j];
        for i in 0..j {
            w[i] -= r[i + j * ld] * temp;
        }
    }
}

/// Moré's Levenberg–Marquardt parameter: `par` such that the solution `x`
/// of `min |A x - b|^2 + par |D x|^2` has `|D x|` within 10% of `delta`
/// (or `par = 0` when the Gauss–Newton step is already inside). `r`, `ipvt`
/// and `qtb` come from [`qrfac`]; `sdiag` returns the diagonal of the
/// factor of the damped system.
#[allow(clippy::too_many_arguments)]
pub(super) fn lmpar(
    n: usize,
    r: &mut [f64],
    ld: usize,
    ipvt: &[usize],
    diag: &[f64],
    qtb: &[f64],
    delta: f64,
    par: &mut f64,
    x: &mut [f64],
    sdiag: &mut [f64],
    wa1: &mut [f64],
    wa2: &mut [f64],
) {
    let mut nsing = n;
    for j in 0..n {
        wa1[j] = qtb[j];
        if r[j + j * ld] == 0.0 && nsing == n {
            nsing = j;
        }
        if nsing < n {
            wa1[j] = 0.0;
        }
    }
    solve_upper(r, ld, nsing, wa1);
    for j in 0..n {
        x[ipvt[j]] = wa1[j];
    }
    let mut iter = 0usize;
    for j in 0..n {
        wa2[j] = diag[j] * x[j];
    }
    let mut dxnorm = enorm(&wa2[..n]);
    let mut fp = dxnorm - delta;
    if fp <= PAR_TOLERANCE * delta {
        *par = 0.0;
        return;
    }
    let mut parl = 0.0f64;
    if nsing >= n {
        for j in 0..n {
            let l = ipvt[j];
            wa1[j] = diag[l] * (wa2[l] / dxnorm);
        }
        for j in 0..n {
            let mut sum = 0.0;
            for i in 0..j {
                sum += r[i + j * ld] * wa1[i];
            }
            wa1[j] = (wa1[j] - sum) / r[j + j * ld];
        }
        let temp = enorm(&wa1[..n]);
        parl = ((fp / delta) / temp) / temp;
    }
    for j in 0..n {
        let mut sum = 0.0;
        for i in 0..=j {
            sum += r[i + j * ld] * qtb[i];
        }
        wa1[j] = sum / diag[ipvt[j]];
    }
    let gnorm = enorm(&wa1[..n]);
    let mut paru = gnorm / delta;
    if paru == 0.0 {
        paru = DWARF / delta.min(PAR_TOLERANCE);
    }
    *par = par.max(parl).min(paru);
    if *par == 0.0 {
        *par = gnorm / dxnorm;
    }
    loop {
        iter += 1;
        if *par == 0.0 {
            *par = DWARF.max(P001 * paru);
        }
        let temp = par.sqrt();
        for j in 0..n {
            wa1[j] = temp * diag[j];
        }
        qrsolv(n, r, ld, ipvt, wa1, qtb, x, sdiag, wa2);
        for j in 0..n {
            wa2[j] = diag[j] * x[j];
        }
        dxnorm = enorm(&wa2[..n]);
        let previous = fp;
        fp = dxnorm - delta;
        if fp.abs() <= PAR_TOLERANCE * delta
            || (parl == 0.0 && fp <= previous && previous < 0.0)
            || iter == MAX_PAR_ITERATIONS
        {
            return;
        }
        for j in 0..n {
            let l = ipvt[j];
            wa1[j] = diag[l] * (wa2[l] / dxnorm);
        }
        for j in 0..n {
            wa1[j] /= sdiag[j];
            let temp = wa1[j];
            for i in j + 1..n {
                wa1[i] -= r[i + j * ld] * temp;
            }
        }
        let temp = enorm(&wa1[..n]);
        let parc = ((fp / delta) / temp) / temp;
        if fp > 0.0 {
            parl = parl.max(*par);
        }
        if fp < 0.0 {
            paru = paru.min(*par);
        }
        *par = parl.max(*par + parc);
    }
}

/// Solve `min |A x - b|^2 + |D x|^2` given the pivoted QR of `A` (upper
/// triangle of `r`) by Givens rotations; the strict lower triangle of `r`
/// receives the transposed factor, `sdiag` its diagonal.
#[allow(clippy::too_many_arguments)]
fn qrsolv(
    n: usize,
    r: &mut [f64],
    ld: usize,
    ipvt: &[usize],
    diag: &[f64],
    qtb: &[f64],
    x: &mut [f64],
    sdiag: &mut [f64],
    wa: &mut [f64],
) {
    for j in 0..n {
        for i in j..n {
            r[i + j * ld] = r[j + i * ld];
        }
        x[j] = r[j + j * ld];
        wa[j] = qtb[j];
    }
    for j in 0..n {
        let l = ipvt[j];
        if diag[l] != 0.0 {
            sdiag[j..n].fill(0.0);
            sdiag[j] = diag[l];
            let mut qtbpj = 0.0;
            for k in j..n {
                if sdiag[k] == 0.0 {
                    continue;
                }
                let rkk = r[k + k * ld];
                let (sin, cos) = if rkk.abs() < sdiag[k].abs() {
                    let cotan = rkk / sdiag[k];
                    let sin = 0.5 / (0.25 + 0.25 * (cotan * cotan)).sqrt();
                    (sin, sin * cotan)
                } else {
                    let tan = sdiag[k] / rkk;
                    let cos = 0.5 / (0.25 + 0.25 * (tan * tan)).sqrt();
                    (cos * tan, cos)
                };
                r[k + k * ld] = cos * rkk + sin * sdiag[k];
                let temp = cos * wa[k] + sin * qtbpj;
                qtbpj = -sin * wa[k] + cos * qtbpj;
                wa[k] = temp;
                for i in k + 1..n {
                    let temp = cos * r[i + k * ld] + sin * sdiag[i];
                    sdiag[i] = -sin * r[i + k * ld] + cos * sdiag[i];
                    r[i + k * ld] = temp;
                }
            }
        }
        sdiag[j] = r[j + j * ld];
        r[j + j * ld] = x[j];
    }
    let mut nsing = n;
    for j in 0..n {
        if sdiag[j] == 0.0 && nsing == n {
            nsing = j;
        }
        if nsing < n {
            wa[j] = 0.0;
        }
    }
    for j in (0..nsing).rev() {
        let mut sum = 0.0;
        for i in j + 1..nsing {
            sum += r[i + j * ld] * wa[i];
        }
        wa[j] = (wa[j] - sum) / sdiag[j];
    }
    for j in 0..n {
        x[ipvt[j]] = wa[j];
    }
}
