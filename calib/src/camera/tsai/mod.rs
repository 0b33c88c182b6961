//! Tsai's radial-alignment calibration of one image of coplanar points
//! (method.md §3): stage 1 (rotation and Tx, Ty from the radial-alignment
//! constraint, distortion-free) and stage 2 (Tz, fx, k; the paper's eq. 32
//! with both image axes, or Tsai's original y-only rows).
//!
//! Image coordinates are relative to the image centre; the x coordinate is
//! scaled by `m = fy / fx` before the alignment (`X' = m X`). The functions
//! work in any unit (pixels here, millimetres for Willson's model).

use nalgebra::{
    DMatrix, DVector, Isometry3, Matrix3, Point2, Translation3, UnitQuaternion, Vector2,
};

use super::error::CameraError;
use crate::geometry::orthonormalize;

/// Willson's reference implementation, replayed only to reproduce his
/// published cameras: compiled for tests, or with the `willson` feature.
#[cfg(any(test, feature = "willson"))]
pub mod willson;

/// Fewest points for stage 1 (five unknowns).
pub const STAGE1_MIN_POINTS: usize = 5;
/// `|D|` below this fraction of `S` means the 2x2 block is rank one and
/// Tsai's row/column rule gives `Ty` (method.md §3).
const RANK_ONE_RATIO: f64 = 1e-12;

/// Which rows stage 2 uses (method.md §3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum Stage2Form {
    /// The paper's eq. 32: x and y rows.
    #[default]
    BothAxes,
    /// Tsai's original: y rows only.
    YOnly,
}

/// One coplanar correspondence: board point `(xw, yw)` (z = 0) and image
/// point `(X, Y)` relative to the image centre, x not yet scaled by m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CentredPoint {
    pub world: Vector2<f64>,
    pub image: Vector2<f64>,
}

/// Stage-1 result: the rotation and `Tx, Ty` (units of the world points).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stage1 {
    pub rotation: Matrix3<f64>,
    pub tx: f64,
    pub ty: f64,
}

/// One image's Tsai calibration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TsaiView {
    /// `P_c = R P_w + T` (the target's pose in the camera frame).
    pub camera_to_target: Isometry3<f64>,
    /// Focal length in x-pixel units (or mm for sensor-unit input).
    pub fx: f64,
    /// Tsai's radial coefficient `k` (distorted -> undistorted, per unit^2
    /// of y-units), method.md §2.
    pub k: f64,
    /// Angle between board and image plane.
    pub board_angle_deg: f64,
}

/// Centre the pixels of `(xw, yw)`-`(u, v)` pairs on `(cx, cy)`.
pub fn centre_points(pairs: &[(Vector2<f64>, Point2<f64>)], cx: f64, cy: f64) -> Vec<CentredPoint> {
    pairs
        .iter()
        .map(|(w, p)| CentredPoint {
            world: *w,
            image: Vector2::new(p.x - cx, p.y - cy),
        })
        .collect()
}

/// Least-squares solution of the stage-1 system in `v = (r1, r2, Tx, r4, r5) / Ty`.
fn solve_alignment(points: &[CentredPoint], m: f64) -> Option<[f64; 5]> {
    if points.len() < STAGE1_MIN_POINTS {
        return None;
    }
    // Normal equations (5x5): this runs thousands of times in the sequence
    // searches of method.md §4.
    let mut ata = nalgebra::Matrix5::<f64>::zeros();
    let mut atb = nalgebra::Vector5::<f64>::zeros();
    for p in points {
        let (xw, yw) = (p.world.x, p.world.y);
        let (xs, y) = (m * p.image.x, p.image.y);
        let row = nalgebra::Vector5::new(y * xw, y * yw, y, -xs * xw, -xs * yw);
        ata += row * row.transpose();
        atb += row * xs;
    }
    let v = ata.cholesky()?.solve(&atb);
    v.iter()
        .all(|x| x.is_finite())
        .then(|| [v[0], v[1], v[2], v[3], v[4]])
}

/// RMS distance (image units) of the points from the radial lines predicted
/// by the stage-1 fit: the normalised radial-alignment residual of
/// method.md §4, comparable across images.
pub fn alignment_residual_rms(points: &[CentredPoint], m: f64) -> Option<f64> {
    let v = solve_alignment(points, m)?;
    let mut sum = 0.0;
    for p in points {
        let (xw, yw) = (p.world.x, p.world.y);
        let x = v[0] * xw + v[1] * yw + v[2];
        let y = v[3] * xw + v[4] * yw + 1.0;
        // Distance in the pixel plane (not the m-scaled one) from the radial
        // line of direction (x / m, y), so that trial values of m compare.
        let xp = x / m;
        // Plain sqrt, not hypot: no overflow risk at these magnitudes and
        // this runs for every point in every evaluation of the searches.
        let norm = (xp * xp + y * y).sqrt();
        if norm == 0.0 {
            return None;
        }
        let d = (p.image.x * y - p.image.y * xp) / norm;
        sum += d * d;
    }
    Some((sum / points.len() as f64).sqrt())
}

/// Stage 1 (method.md §3).
pub fn stage1(points: &[CentredPoint], m: f64) -> Option<Stage1> {
    let [v1, v2, v3, v4, v5] = solve_alignment(points, m)?;
    let s = v1 * v1 + v2 * v2 + v4 * v4 + v5 * v5;
    let d = v1 * v5 - v2 * v4;
    let ty2 = if d.abs() > RANK_ONE_RATIO * s {
        (s - (s * s - 4.0 * d * d).max(0.0).sqrt()) / (2.0 * d * d)
    } else {
        let rows = [
            v1 * v1 + v2 * v2,
            v4 * v4 + v5 * v5,
            v1 * v1 + v4 * v4,
            v2 * v2 + v5 * v5,
        ];
        1.0 / rows.iter().cloned().fold(0.0, f64::max)
    };
    if !(ty2.is_finite() && ty2 > 0.0) {
        return None;
    }
    // Sign of Ty from the point farthest from the centre.
    let far = points
        .iter()
        .max_by(|a, b| a.image.norm_squared().total_cmp(&b.image.norm_squared()))?;
    let mut ty = ty2.sqrt();
    let xy = |ty: f64| {
        (
            (v1 * far.world.x + v2 * far.world.y + v3) * ty,
            (v4 * far.world.x + v5 * far.world.y + 1.0) * ty,
        )
    };
    let (x, y) = xy(ty);
    if x.signum() != (m * far.image.x).signum() || y.signum() != far.image.y.signum() {
        ty = -ty;
    }
    let (r1, r2, tx, r4, r5) = (v1 * ty, v2 * ty, v3 * ty, v4 * ty, v5 * ty);
    let r3 = (1.0 - r1 * r1 - r2 * r2).max(0.0).sqrt();
    let r6 = -(r1 * r4 + r2 * r5).signum() * (1.0 - r4 * r4 - r5 * r5).max(0.0).sqrt();
    let row1 = nalgebra::Vector3::new(r1, r2, r3);
    let row2 = nalgebra::Vector3::new(r4, r5, r6);
    let row3 = row1.cross(&row2);
    let raw = Matrix3::from_rows(&[row1.transpose(), row2.transpose(), row3.transpose()]);
    let rotation = *orthonormalize(&raw).matrix();
    Some(Stage1 { rotation, tx, ty })
}

/// Stage 2: `(Tz, fx, k)` from the paper's eq. 32 (linearised distortion).
pub fn stage2(
    points: &[CentredPoint],
    m: f64,
    s1: &Stage1,
    form: Stage2Form,
) -> Option<(f64, f64, f64)> {
    let r = &s1.rotation;
    let rows_per_point = match form {
        Stage2Form::BothAxes => 2,
        Stage2Form::YOnly => 1,
    };
    let n = points.len() * rows_per_point;
    if n < 3 {
        return None;
    }
    let mut a = DMatrix::zeros(n, 3);
    let mut b = DVector::zeros(n);
    for (i, p) in points.iter().enumerate() {
        let (xw, yw) = (p.world.x, p.world.y);
        let x = r[(0, 0)] * xw + r[(0, 1)] * yw + s1.tx;
        let y = r[(1, 0)] * xw + r[(1, 1)] * yw + s1.ty;
        let w = r[(2, 0)] * xw + r[(2, 1)] * yw;
        let (big_x, big_y) = (p.image.x, p.image.y);
        let r2 = (m * big_x).powi(2) + big_y * big_y;
        let mut row = i * rows_per_point;
        if form == Stage2Form::BothAxes {
            a.set_row(row, &nalgebra::RowVector3::new(-big_x, x, -x * r2));
            b[row] = big_x * w;
            row += 1;
        }
        a.set_row(row, &nalgebra::RowVector3::new(-big_y, m * y, -m * y * r2));
        b[row] = big_y * w;
    }
    let sol = a.svd(true, true).solve(&b, 1e-14).ok()?;
    let (tz, fx, kfx) = (sol[0], sol[1], sol[2]);
    (tz.is_finite() && fx.is_finite() && fx != 0.0).then(|| (tz, fx, kfx / fx))
}

/// Angle between the board plane and the image plane, from the rotation.
pub fn board_angle_deg(rotation: &Matrix3<f64>) -> f64 {
    rotation[(2, 2)].abs().min(1.0).acos().to_degrees()
}

/// Both stages on one image: if stage 2 gives `fx < 0` the mirror rotation
/// is taken (negate r3, r6, r7, r8) and stage 2 redone (method.md §3).
pub fn calibrate_view(
    view: usize,
    points: &[CentredPoint],
    m: f64,
    form: Stage2Form,
) -> Result<TsaiView, CameraError> {
    let degenerate = |reason: &str| CameraError::DegenerateView {
        view,
        reason: reason.to_string(),
    };
    let mut s1 = stage1(points, m).ok_or_else(|| degenerate("Tsai stage 1 has no solution"))?;
    let (mut tz, mut fx, mut k) =
        stage2(points, m, &s1, form).ok_or_else(|| degenerate("Tsai stage 2 has no solution"))?;
    if fx < 0.0 {
        let flip = Matrix3::from_diagonal(&nalgebra::Vector3::new(1.0, 1.0, -1.0));
        s1.rotation = flip * s1.rotation * flip;
        (tz, fx, k) = stage2(points, m, &s1, form)
            .ok_or_else(|| degenerate("Tsai stage 2 has no solution"))?;
    }
    if fx <= 0.0 || tz <= 0.0 {
        return Err(degenerate(
            "Tsai stage 2 gives a negative focal length or depth",
        ));
    }
    let rotation = UnitQuaternion::from_matrix(&s1.rotation);
    Ok(TsaiView {
        camera_to_target: Isometry3::from_parts(Translation3::new(s1.tx, s1.ty, tz), rotation),
        fx,
        k,
        board_angle_deg: board_angle_deg(&s1.rotation),
    })
}

#[cfg(test)]
#[path = "tsai_tests.rs"]
mod tests;
