//! The part of a sequence's error no stage method sees: the offset common
//! to all its images. The stage's readings fix the camera's travel, not
//! where the board sits on the stage, so the average-rotation method and
//! the stage-referenced table (`super::assessment`) both fit it away. Its
//! size follows from the intrinsics' uncertainty: an error in the focal
//! length or the principal point moves every image's measured camera
//! position alike. Propagated linearly (method.md §"Uncertainty",
//! `Σ_offset = J Σ_intrinsics Jᵀ`), with `J` the derivative of the
//! sequence's mean camera position by each intrinsic parameter, taken by
//! re-measuring every image with the parameter moved by one σ.

use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

use super::StageError;

/// σ of each sequence's common offset, per target axis (mm).
///
/// - `x`, `covariance`: the bundle's solution and covariance; its first
///   `intrinsics` entries are the intrinsic parameters.
/// - `positions(x')`: every view's measured camera position (target frame,
///   mm) with the intrinsics of `x'`.
/// - `sequences`: the views of each sequence.
///
/// A parameter with no variance (held) adds nothing.
pub fn sequence_offset_sd_mm(
    x: &DVector<f64>,
    covariance: &DMatrix<f64>,
    intrinsics: usize,
    positions: impl Fn(&DVector<f64>) -> Result<Vec<Vector3<f64>>, StageError>,
    sequences: &[Vec<usize>],
) -> Result<Vec<Vector3<f64>>, StageError> {
    let mean_of = |p: &[Vector3<f64>], views: &[usize]| {
        views.iter().map(|&v| p[v]).sum::<Vector3<f64>>() / views.len().max(1) as f64
    };
    let base = positions(x)?;
    let base_means: Vec<Vector3<f64>> = sequences.iter().map(|s| mean_of(&base, s)).collect();
    // Per sequence, the offset's change for a one-σ step of each parameter.
    let mut steps: Vec<Vec<Vector3<f64>>> = vec![Vec::new(); sequences.len()];
    let mut sds = Vec::new();
    for j in 0..intrinsics.min(x.len()) {
        let sd = covariance[(j, j)].max(0.0).sqrt();
        if sd == 0.0 || !sd.is_finite() {
            continue;
        }
        let mut moved = x.clone();
        moved[j] += sd;
        let p = positions(&moved)?;
        for (s, views) in sequences.iter().enumerate() {
            steps[s].push(mean_of(&p, views) - base_means[s]);
        }
        sds.push((j, sd));
    }
    // Σ = Σ_jk (Δ_j/σ_j) C_jk (Δ_k/σ_k)ᵀ.
    Ok(steps
        .iter()
        .map(|deltas| {
            let mut sigma = Matrix3::zeros();
            for (a, (j, sd_j)) in sds.iter().enumerate() {
                for (b, (k, sd_k)) in sds.iter().enumerate() {
                    let c = covariance[(*j, *k)] / (sd_j * sd_k);
                    sigma += deltas[a] * deltas[b].transpose() * c;
                }
            }
            Vector3::from_fn(|i, _| sigma[(i, i)].max(0.0).sqrt())
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A linear measurement `p_v = A_v x` gives `σ = sqrt(diag(Ā C Āᵀ))`
    /// exactly, `Ā` the sequence's mean of `A_v`.
    #[test]
    fn a_linear_measurement_propagates_exactly() {
        let a = [
            Matrix3::new(1.0, 0.5, 0.0, 0.0, 2.0, 0.0, 0.3, 0.0, 1.0),
            Matrix3::new(3.0, 0.5, 0.0, 0.0, 0.0, 1.0, 0.3, 0.2, 1.0),
        ];
        let x = DVector::from_vec(vec![0.4, -0.2, 1.0, 7.0]);
        let l = DMatrix::from_row_slice(3, 3, &[1.0, 0.0, 0.0, 0.5, 2.0, 0.0, -0.3, 0.1, 0.7]);
        let c3 = &l * l.transpose();
        let mut covariance = DMatrix::zeros(4, 4);
        covariance.view_mut((0, 0), (3, 3)).copy_from(&c3);
        covariance[(3, 3)] = 100.0;
        let positions = |x: &DVector<f64>| {
            let v = Vector3::new(x[0], x[1], x[2]);
            Ok(a.iter().map(|m| m * v).collect())
        };
        let sd = sequence_offset_sd_mm(&x, &covariance, 3, positions, &[vec![0, 1]]).unwrap();
        let mean = (a[0] + a[1]) / 2.0;
        let c = Matrix3::from_iterator(c3.iter().copied());
        let expected = mean * c * mean.transpose();
        for i in 0..3 {
            assert!((sd[0][i] - expected[(i, i)].sqrt()).abs() < 1e-9, "{sd:?}");
        }
    }
}
