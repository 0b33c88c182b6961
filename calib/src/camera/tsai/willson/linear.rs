//! The linear parts of Tsai's method exactly as Willson's `cal_main.c`
//! evaluates them (method.md §3 states the method; this file only fixes the
//! arithmetic): least squares through the normal equations with a
//! full-pivoting Gauss–Jordan inverse, `Ty` from the 2x2 minor (coplanar)
//! or the row norm (non-coplanar), the sign of `Ty` from the image point
//! farthest from the centre, roll–pitch–yaw angles after Paul (1981), and
//! `(f, Tz)` from the y rows. The calibration state is one mutable struct,
//! as Willson's globals are, because his coplanar stages leave rotation and
//! translation as side effects of their last residual evaluation.

use super::model::TsaiPoint;

/// Willson refuses a normal matrix whose determinant is below this.
const MIN_NORMAL_DETERMINANT: f64 = 0.001;
/// Coplanar `Ty`: a 2x2 rotation minor entry below this counts as zero.
const MINOR_EPSILON: f64 = 1e-8;

/// Willson's `cp` and `cc` globals plus his working arrays.
#[derive(Debug, Clone)]
pub(super) struct WillsonState<'a> {
    pub points: &'a [TsaiPoint],
    /// Effective pixel pitch (mm/px): `dx Ncx / Nfx` and `dy`.
    pub dpx: f64,
    pub dpy: f64,
    pub cx: f64,
    pub cy: f64,
    pub sx: f64,
    /// `r1..r9`, row-major.
    pub r: [f64; 9],
    pub rx: f64,
    pub ry: f64,
    pub rz: f64,
    pub tx: f64,
    pub ty: f64,
    pub tz: f64,
    pub f: f64,
    pub kappa1: f64,
    /// Sensor coordinates (mm) of the measured points and their squared radius.
    pub xd: Vec<f64>,
    pub yd: Vec<f64>,
    pub r2: Vec<f64>,
    u: [f64; 7],
}

/// `(1 if a <= 0)`: Willson's `SIGNBIT`, which counts zero as negative.
fn signbit(a: f64) -> bool {
    a <= 0.0
}

/// Least squares `M a = b` (`M` row-major, `cols` wide) as Willson solves
/// it: `a = (M^T M)^-1 M^T b`, products accumulated left to right.
fn solve_system(m: &[f64], cols: usize, b: &[f64]) -> Option<Vec<f64>> {
    let rows = b.len();
    if rows < cols {
        return None;
    }
    let mut mtm = vec![0.0; cols * cols];
    for i in 0..cols {
        for j in 0..cols {
            let mut t = 0.0;
            for k in 0..rows {
                t += m[k * cols + i] * m[k * cols + j];
            }
            mtm[i * cols + j] = t;
        }
    }
    let det = invert_gauss_jordan(&mut mtm, cols);
    if det.is_nan() || det.abs() < MIN_NORMAL_DETERMINANT {
        return None;
    }
    let mut mdag = vec![0.0; cols * rows];
    for i in 0..cols {
        for j in 0..rows {
            let mut t = 0.0;
            for k in 0..cols {
                t += mtm[i * cols + k] * m[j * cols + k];
            }
            mdag[i * rows + j] = t;
        }
    }
    let a: Vec<f64> = (0..cols)
        .map(|i| {
            let mut t = 0.0;
            for k in 0..rows {
                t += mdag[i * rows + k] * b[k];
            }
            t
        })
        .collect();
    a.iter().all(|v| v.is_finite()).then_some(a)
}

/// In-place inverse of the row-major `n x n` matrix by Gauss–Jordan
/// elimination with full pivoting (the classic SSP `MINV` scheme Willson's
/// matrix library uses); returns the determinant (0 when singular).
fn invert_gauss_jordan(a: &mut [f64], n: usize) -> f64 {
    let (mut l, mut mm) = (vec![0usize; n], vec![0usize; n]);
    let mut det = 1.0;
    for k in 0..n {
        l[k] = k;
        mm[k] = k;
        let mut biga = a[k * n + k];
        for i in k..n {
            for j in k..n {
                if a[i * n + j].abs() > biga.abs() {
                    biga = a[i * n + j];
                    l[k] = i;
                    mm[k] = j;
                }
            }
        }
        let i = l[k];
        if i > k {
            for j in 0..n {
                let hold = -a[k * n + j];
                a[k * n + j] = a[i * n + j];
                a[i * n + j] = hold;
            }
        }
        let j = mm[k];
        if j > k {
            for i in 0..n {
                let hold = -a[i * n + k];
                a[i * n + k] = a[i * n + j];
                a[i * n + j] = hold;
            }
        }
        if biga == 0.0 {
            return 0.0;
        }
        for i in (0..n).filter(|&i| i != k) {
            a[i * n + k] /= -biga;
        }
        for i in (0..n).filter(|&i| i != k) {
            let hold = a[i * n + k];
            for j in (0..n).filter(|&j| j != k) {
                a[i * n + j] += hold * a[k * n + j];
            }
        }
        for j in (0..n).filter(|&j| j != k) {
            a[k * n + j] /= biga;
        }
        det *= biga;
        a[k * n + k] = 1.0 / biga;
    }
    for k in (0..n.saturating_sub(1)).rev() {
        let i = l[k];
        if i > k {
            for j in 0..n {
                let hold = a[j * n + k];
                a[j * n + k] = -a[j * n + i];
                a[j * n + i] = hold;
            }
        }
        let j = mm[k];
        if j > k {
            for i in 0..n {
                let hold = a[k * n + i];
                a[k * n + i] = -a[j * n + i];
                a[j * n + i] = hold;
            }
        }
    }
    det
}

impl<'a> WillsonState<'a> {
    pub fn new(points: &'a [TsaiPoint], dpx: f64, dpy: f64, cx: f64, cy: f64) -> Self {
        let n = points.len();
        Self {
            points,
            dpx,
            dpy,
            cx,
            cy,
            sx: 1.0,
            r: [0.0; 9],
            rx: 0.0,
            ry: 0.0,
            rz: 0.0,
            tx: 0.0,
            ty: 0.0,
            tz: 0.0,
            f: 0.0,
            kappa1: 0.0,
            xd: vec![0.0; n],
            yd: vec![0.0; n],
            r2: vec![0.0; n],
            u: [0.0; 7],
        }
    }

    /// Measured pixels to distorted sensor coordinates at the current
    /// `Cx, Cy, sx`.
    pub fn compute_xd_yd_r2(&mut self) {
        for (i, p) in self.points.iter().enumerate() {
            let xd = self.dpx * (p.image.x - self.cx) / self.sx;
            let yd = self.dpy * (p.image.y - self.cy);
            self.xd[i] = xd;
            self.yd[i] = yd;
            self.r2[i] = xd * xd + yd * yd;
        }
    }

    /// Tsai's first linear stage: the 5 (coplanar) or 7 unknowns `U`.
    pub fn compute_u(&mut self, coplanar: bool) -> Option<()> {
        let cols = if coplanar { 5 } else { 7 };
        let mut m = Vec::with_capacity(self.points.len() * cols);
        for (i, p) in self.points.iter().enumerate() {
            let (w, xd, yd) = (p.world, self.xd[i], self.yd[i]);
            if coplanar {
                m.extend_from_slice(&[yd * w.x, yd * w.y, yd, -xd * w.x, -xd * w.y]);
            } else {
                m.extend_from_slice(&[
                    yd * w.x,
                    yd * w.y,
                    yd * w.z,
                    yd,
                    -xd * w.x,
                    -xd * w.y,
                    -xd * w.z,
                ]);
            }
        }
        let a = solve_system(&m, cols, &self.xd)?;
        self.u[..cols].copy_from_slice(&a);
        Some(())
    }

    /// Index of the point farthest from the image centre (first on ties).
    fn far_point(&self) -> usize {
        let (mut far, mut far_distance) = (0, 0.0);
        for (i, &d) in self.r2.iter().enumerate() {
            if d > far_distance {
                far = i;
                far_distance = d;
            }
        }
        far
    }

    /// `Tx, Ty` from `U`, the sign of `Ty` from the far point.
    pub fn compute_tx_ty(&mut self, coplanar: bool) -> Option<()> {
        let u = self.u;
        let ty_squared = if coplanar {
            let (r1p, r2p, r4p, r5p) = (u[0], u[1], u[3], u[4]);
            let small = |v: f64| v.abs() < MINOR_EPSILON;
            if small(r1p) && small(r2p) {
                1.0 / (r4p * r4p + r5p * r5p)
            } else if small(r4p) && small(r5p) {
                1.0 / (r1p * r1p + r2p * r2p)
            } else if small(r1p) && small(r4p) {
                1.0 / (r2p * r2p + r5p * r5p)
            } else if small(r2p) && small(r5p) {
                1.0 / (r1p * r1p + r4p * r4p)
            } else {
                let sr = r1p * r1p + r2p * r2p + r4p * r4p + r5p * r5p;
                let minor = r1p * r5p - r4p * r2p;
                (sr - (sr * sr - 4.0 * (minor * minor)).sqrt()) / (2.0 * (minor * minor))
            }
        } else {
            1.0 / (u[4] * u[4] + u[5] * u[5] + u[6] * u[6])
        };
        let mut ty = ty_squared.sqrt();
        if !ty.is_finite() || ty == 0.0 {
            return None;
        }
        let k = self.far_point();
        let w = self.points[k].world;
        let (x, y, tx_index) = if coplanar {
            let x = u[0] * ty * w.x + u[1] * ty * w.y + u[2] * ty;
            let y = u[3] * ty * w.x + u[4] * ty * w.y + ty;
            (x, y, 2)
        } else {
            let x = u[0] * ty * w.x + u[1] * ty * w.y + u[2] * ty * w.z + u[3] * ty;
            let y = u[4] * ty * w.x + u[5] * ty * w.y + u[6] * ty * w.z + ty;
            (x, y, 3)
        };
        if signbit(x) != signbit(self.xd[k]) || signbit(y) != signbit(self.yd[k]) {
            ty = -ty;
        }
        self.tx = u[tx_index] * ty;
        self.ty = ty;
        Some(())
    }

    /// Non-coplanar `sx` from the norm of the first rotation row.
    pub fn compute_sx(&mut self) {
        let u = self.u;
        self.sx = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt() * self.ty.abs();
    }

    /// Coplanar rotation: complete the 2x2 minor to an orthonormal matrix.
    pub fn compute_r_coplanar(&mut self) {
        let (u, ty) = (self.u, self.ty);
        let (r1, r2) = (u[0] * ty, u[1] * ty);
        let r3 = (1.0 - r1 * r1 - r2 * r2).max(0.0).sqrt();
        let (r4, r5) = (u[3] * ty, u[4] * ty);
        let mut r6 = (1.0 - r4 * r4 - r5 * r5).max(0.0).sqrt();
        if !signbit(r1 * r4 + r2 * r5) {
            r6 = -r6;
        }
        let r7 = r2 * r6 - r3 * r5;
        let r8 = r3 * r4 - r1 * r6;
        let r9 = r1 * r5 - r2 * r4;
        self.r = [r1, r2, r3, r4, r5, r6, r7, r8, r9];
        self.solve_rpy();
    }

    /// Non-coplanar rotation: angles from the estimated rows, then the
    /// (more orthonormal) matrix of those angles.
    pub fn compute_better_r(&mut self) {
        let (u, ty, sx) = (self.u, self.ty, self.sx);
        let (r1, r2, r3) = (u[0] * ty / sx, u[1] * ty / sx, u[2] * ty / sx);
        let (r4, r5, r6) = (u[4] * ty, u[5] * ty, u[6] * ty);
        let r7 = r2 * r6 - r3 * r5;
        self.rz = r4.atan2(r1);
        let (sg, cg) = (self.rz.sin(), self.rz.cos());
        self.ry = (-r7).atan2(r1 * cg + r4 * sg);
        self.rx = (r3 * sg - r6 * cg).atan2(r5 * cg - r2 * sg);
        self.apply_rpy();
    }

    /// Roll–pitch–yaw angles of `r` (Paul 1981, p. 70).
    pub fn solve_rpy(&mut self) {
        let r = self.r;
        self.rz = r[3].atan2(r[0]);
        let (sg, cg) = (self.rz.sin(), self.rz.cos());
        self.ry = (-r[6]).atan2(r[0] * cg + r[3] * sg);
        self.rx = (r[2] * sg - r[5] * cg).atan2(r[4] * cg - r[1] * sg);
    }

    /// `r` from the angles (README / `cal_tran.c` formula).
    pub fn apply_rpy(&mut self) {
        self.r = rotation_rows(self.rx, self.ry, self.rz);
    }

    /// `(f, Tz)` from the y rows with `kappa1 = 0`; if `f < 0` the other
    /// orthonormal completion is tried once (Willson's handedness check).
    pub fn compute_approximate_f_tz_checked(&mut self) -> Option<()> {
        self.compute_approximate_f_tz()?;
        if self.f < 0.0 {
            for k in [2, 5, 6, 7] {
                self.r[k] = -self.r[k];
            }
            self.solve_rpy();
            self.compute_approximate_f_tz()?;
            if self.f < 0.0 {
                return None;
            }
        }
        Some(())
    }

    fn compute_approximate_f_tz(&mut self) -> Option<()> {
        let r = self.r;
        let mut m = Vec::with_capacity(2 * self.points.len());
        let mut b = Vec::with_capacity(self.points.len());
        for (i, p) in self.points.iter().enumerate() {
            let w = p.world;
            m.push(r[3] * w.x + r[4] * w.y + r[5] * w.z + self.ty);
            m.push(-self.yd[i]);
            b.push((r[6] * w.x + r[7] * w.y + r[8] * w.z) * self.yd[i]);
        }
        let a = solve_system(&m, 2, &b)?;
        self.f = a[0];
        self.tz = a[1];
        self.kappa1 = 0.0;
        Some(())
    }
}

/// `r1..r9` of Willson's Euler angles, in his operation order.
pub(super) fn rotation_rows(rx: f64, ry: f64, rz: f64) -> [f64; 9] {
    let (sa, ca) = (rx.sin(), rx.cos());
    let (sb, cb) = (ry.sin(), ry.cos());
    let (sg, cg) = (rz.sin(), rz.cos());
    [
        cb * cg,
        cg * sa * sb - ca * sg,
        sa * sg + ca * cg * sb,
        cb * sg,
        sa * sb * sg + ca * cg,
        ca * sb * sg - cg * sa,
        -sb,
        cb * sa,
        ca * cb,
    ]
}

#[cfg(test)]
#[path = "linear_tests.rs"]
mod tests;
