//! Parameter covariance of a least-squares fit (method.md §6): the
//! pseudo-inverse of the normal matrix, scaled by the residual variance,
//! with unidentifiable directions cut off rather than made infinite.

use nalgebra::DMatrix;

/// Singular values below this fraction of the largest are treated as zero
/// when inverting `J^T J` for the covariance.
pub const COVARIANCE_RCOND: f64 = 1e-10;

/// `variance * (J^T J)^+`, computed from the SVD of `J` for stability;
/// directions with singular value below [`COVARIANCE_RCOND`] times the
/// largest contribute nothing (they are unidentifiable, not infinitely
/// uncertain: the caller reports them as fixed).
pub fn covariance_from_jacobian(jacobian: &DMatrix<f64>, variance: f64) -> DMatrix<f64> {
    let n = jacobian.ncols();
    let svd = jacobian.clone().svd(false, true);
    let v_t = svd.v_t.expect("v_t requested");
    let s_max = svd.singular_values.max();
    let mut cov = DMatrix::zeros(n, n);
    for (k, &s) in svd.singular_values.iter().enumerate() {
        if s > COVARIANCE_RCOND * s_max && s > 0.0 {
            let v = v_t.row(k).transpose();
            cov += (&v * v.transpose()) * (variance / (s * s));
        }
    }
    cov
}

/// `variance * (J^T J)^+` from the normal matrix `J^T J` itself, for
/// problems that assemble it without the dense Jacobian: the symmetric
/// eigendecomposition with the same cut-off as [`covariance_from_jacobian`]
/// (eigenvalues are squared singular values).
pub fn covariance_from_normal(normal: &DMatrix<f64>, variance: f64) -> DMatrix<f64> {
    let n = normal.ncols();
    let eigen = normal.clone().symmetric_eigen();
    let l_max = eigen.eigenvalues.max();
    let mut cov = DMatrix::zeros(n, n);
    for (k, &l) in eigen.eigenvalues.iter().enumerate() {
        if l > COVARIANCE_RCOND * COVARIANCE_RCOND * l_max && l > 0.0 {
            let v = eigen.eigenvectors.column(k);
            cov += (v * v.transpose()) * (variance / l);
        }
    }
    cov
}
