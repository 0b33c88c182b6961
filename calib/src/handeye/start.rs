//! Starting values of the flange bundle (method.md §4): per-image PnP and a
//! robust AX = XB (Park–Martin: rotation from the motions' rotation axes,
//! translation by linear least squares), iteratively reweighted so that a
//! few lying poses do not drag it; then every pose's own estimate of the
//! board, `target_to_base_k = target_to_camera_k * flange_to_camera^-1 *
//! base_to_flange_k^-1`, whose consensus (the medoid) reveals the liars.
//! These are starts only: the answer is the bundle on image points.

use nalgebra::{DMatrix, DVector, Matrix3, Point3, Vector3};

use super::error::HandEyeError;
use super::robust::median;
use crate::geometry::{bounding_box, orthonormalize, rotation_vector, Pose};

/// Reweighting rounds of the robust AX = XB.
const IRLS_ROUNDS: usize = 10;
/// Cauchy weight scale, in medians of the pair residuals.
const IRLS_SCALE_MEDIANS: f64 = 2.0;
/// The second singular value of the axis correlation below this fraction
/// of the first: the motions do not fix the rotation.
const MIN_AXIS_SPREAD: f64 = 1e-4;
/// Relative cut-off of the translation's least-squares pseudo-inverse.
const TRANSLATION_RCOND: f64 = 1e-8;
/// Floor of residual scales, so that exact data do not divide by zero.
const TINY: f64 = 1e-12;
/// Up to this many poses every pair of poses gives a motion; beyond, each
/// pose is paired with [`MOTION_PARTNERS`] others spread evenly over the
/// sequence, so that the motions (and the time and memory of the start)
/// grow linearly with the campaign rather than with its square (500,000
/// motions at 1,000 poses).
const ALL_PAIRS_UP_TO: usize = 2 * MOTION_PARTNERS;
const MOTION_PARTNERS: usize = 32;

/// The pose pairs `(i, j)` whose relative motions feed AX = XB: all of them
/// for a small campaign, else each pose with [`MOTION_PARTNERS`] others at
/// sequence offsets from 1 to about `n / 2`, evenly spread (distinct
/// unordered pairs, as an offset `d < n / 2` never meets `n - d`).
fn motion_pairs(n: usize) -> Vec<(usize, usize)> {
    if n <= ALL_PAIRS_UP_TO {
        return (0..n)
            .flat_map(|i| ((i + 1)..n).map(move |j| (i, j)))
            .collect();
    }
    let longest = (n - 1) / 2;
    let mut offsets: Vec<usize> = (0..MOTION_PARTNERS)
        .map(|m| 1 + m * (longest - 1) / (MOTION_PARTNERS - 1))
        .collect();
    offsets.dedup();
    (0..n)
        .flat_map(|i| offsets.iter().map(move |d| (i, (i + d) % n)))
        .collect()
}

fn cauchy_weights(residuals: &[f64]) -> Vec<f64> {
    let scale = (IRLS_SCALE_MEDIANS * median(residuals)).max(TINY);
    residuals
        .iter()
        .map(|e| 1.0 / (1.0 + (e / scale).powi(2)))
        .collect()
}

/// Robust AX = XB: `flange_to_camera` from flange poses `b` and camera
/// poses `c` (`target_to_camera`) of the same images, `c_k = T b_k X`.
pub fn robust_hand_eye(b: &[Pose], c: &[Pose]) -> Result<Pose, HandEyeError> {
    // Motions between pairs of poses ([`motion_pairs`]): A = b_i^-1 b_j,
    // B = c_i^-1 c_j, A X = X B.
    let motions: Vec<(Pose, Pose)> = motion_pairs(b.len())
        .into_iter()
        .map(|(i, j)| (b[i].inverse() * b[j], c[i].inverse() * c[j]))
        .collect();
    if motions.len() < 2 {
        return Err(HandEyeError::DegenerateMotion);
    }
    let axes: Vec<(Vector3<f64>, Vector3<f64>)> = motions
        .iter()
        .map(|(a, bm)| (rotation_vector(&a.rotation), rotation_vector(&bm.rotation)))
        .collect();
    let mut weights = vec![1.0; motions.len()];
    let mut rotation = Matrix3::identity();
    for _ in 0..IRLS_ROUNDS {
        let m = axes
            .iter()
            .zip(&weights)
            .fold(Matrix3::zeros(), |m, ((a, bm), w)| {
                m + *w * a * bm.transpose()
            });
        let s = m.singular_values();
        if s[1] <= MIN_AXIS_SPREAD * s[0].max(TINY) {
            return Err(HandEyeError::DegenerateMotion);
        }
        rotation = orthonormalize(&m).into_inner();
        let e: Vec<f64> = axes
            .iter()
            .map(|(a, bm)| (a - rotation * bm).norm())
            .collect();
        weights = cauchy_weights(&e);
    }
    // (R_A - I) t_X = R_X t_B - t_A, reweighted by its own residuals.
    let mut translation = Vector3::zeros();
    let mut tw = weights.clone();
    for _ in 0..IRLS_ROUNDS {
        let mut lhs = DMatrix::zeros(3 * motions.len(), 3);
        let mut rhs = DVector::zeros(3 * motions.len());
        for (k, ((a, bm), w)) in motions.iter().zip(&tw).enumerate() {
            let ra = a.rotation.to_rotation_matrix().into_inner() - Matrix3::identity();
            let v = rotation * bm.translation.vector - a.translation.vector;
            let sw = w.sqrt();
            lhs.view_mut((3 * k, 0), (3, 3)).copy_from(&(ra * sw));
            rhs.rows_mut(3 * k, 3).copy_from(&(v * sw));
        }
        let svd = lhs.svd(true, true);
        let tol = TRANSLATION_RCOND * svd.singular_values.max();
        let sol = svd
            .solve(&rhs, tol)
            .map_err(|_| HandEyeError::DegenerateMotion)?;
        translation = Vector3::new(sol[0], sol[1], sol[2]);
        let e: Vec<f64> = motions
            .iter()
            .map(|(a, bm)| {
                let ra = a.rotation.to_rotation_matrix().into_inner() - Matrix3::identity();
                (ra * translation - (rotation * bm.translation.vector - a.translation.vector))
                    .norm()
            })
            .collect();
        tw = cauchy_weights(&e)
            .iter()
            .zip(&weights)
            .map(|(a, b)| a * b)
            .collect();
    }
    Ok(Pose::from_parts(
        translation.into(),
        nalgebra::UnitQuaternion::from_rotation_matrix(&orthonormalize(&rotation)),
    ))
}

/// Each pose's own estimate of `target_to_base`.
pub fn board_estimates(b: &[Pose], c: &[Pose], flange_to_camera: &Pose) -> Vec<Pose> {
    let x_inv = flange_to_camera.inverse();
    b.iter()
        .zip(c)
        .map(|(bk, ck)| ck * x_inv * bk.inverse())
        .collect()
}

/// Largest displacement (mm) of the `probe` points of the board, placed in
/// the base frame by two estimates of `target_to_base`.
pub fn board_distance_mm(a: &Pose, b: &Pose, probe: &[Point3<f64>]) -> f64 {
    let (ai, bi) = (a.inverse(), b.inverse());
    probe
        .iter()
        .map(|p| (ai * p - bi * p).norm())
        .fold(0.0, f64::max)
}

/// The consensus of board estimates: the medoid (the estimate with the
/// smallest median distance to the others) and every estimate's distance
/// to it (mm).
pub fn board_consensus(estimates: &[Pose], probe: &[Point3<f64>]) -> Option<(usize, Vec<f64>)> {
    // Row by row (one row of the n x n distance table held at a time).
    let row = |i: usize| -> Vec<f64> {
        estimates
            .iter()
            .map(|e| board_distance_mm(&estimates[i], e, probe))
            .collect()
    };
    let medoid = (0..estimates.len())
        .map(|i| (i, median(&row(i))))
        .min_by(|a, b| a.1.total_cmp(&b.1))?
        .0;
    Some((medoid, row(medoid)))
}

/// The corners of the bounding box of the board points (z = 0 plane):
/// where a wrong board pose shows most.
pub fn board_probe(points: impl Iterator<Item = Point3<f64>>) -> Vec<Point3<f64>> {
    let (lo, hi) = bounding_box(points);
    if !lo.x.is_finite() {
        return vec![Point3::origin()];
    }
    vec![
        Point3::new(lo.x, lo.y, 0.0),
        Point3::new(hi.x, lo.y, 0.0),
        Point3::new(lo.x, hi.y, 0.0),
        Point3::new(hi.x, hi.y, 0.0),
    ]
}
