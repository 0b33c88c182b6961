//! The normal matrix `J^T J` of a least-squares problem as the solver holds
//! it (method.md §6): dense for small problems, or block-arrowhead
//! ([`ArrowMatrix`]) for the bundle-style ones whose tail grows with the
//! number of images, so that memory stays linear in the campaign size.

use nalgebra::{DMatrix, DVector};

use crate::arrow::ArrowMatrix;
use crate::covariance::covariance_from_normal;

/// A symmetric positive semi-definite normal matrix.
#[derive(Debug, Clone, PartialEq)]
pub enum NormalMatrix {
    Dense(DMatrix<f64>),
    Arrow(ArrowMatrix),
}

impl From<DMatrix<f64>> for NormalMatrix {
    fn from(a: DMatrix<f64>) -> Self {
        Self::Dense(a)
    }
}

impl From<ArrowMatrix> for NormalMatrix {
    fn from(a: ArrowMatrix) -> Self {
        Self::Arrow(a)
    }
}

impl NormalMatrix {
    pub fn dim(&self) -> usize {
        match self {
            Self::Dense(a) => a.nrows(),
            Self::Arrow(a) => a.dim(),
        }
    }

    pub fn diagonal(&self) -> DVector<f64> {
        match self {
            Self::Dense(a) => a.diagonal(),
            Self::Arrow(a) => a.diagonal(),
        }
    }

    /// `A <- D^-1 A D^-1` with `D = diag(scale)`.
    pub fn scale_symmetric(&mut self, scale: &DVector<f64>) {
        match self {
            Self::Dense(a) => {
                let n = a.nrows();
                for i in 0..n {
                    for j in 0..n {
                        a[(i, j)] /= scale[i] * scale[j];
                    }
                }
            }
            Self::Arrow(a) => a.scale_symmetric(scale),
        }
    }

    /// `A <- A + mu I`.
    pub fn add_to_diagonal(&mut self, mu: f64) {
        match self {
            Self::Dense(a) => {
                for j in 0..a.nrows() {
                    a[(j, j)] += mu;
                }
            }
            Self::Arrow(a) => a.add_to_diagonal(mu),
        }
    }

    /// `A v`.
    pub fn mul_vector(&self, v: &DVector<f64>) -> DVector<f64> {
        match self {
            Self::Dense(a) => a * v,
            Self::Arrow(a) => a.mul_vector(v),
        }
    }

    pub fn is_finite(&self) -> bool {
        match self {
            Self::Dense(a) => a.iter().all(|v| v.is_finite()),
            Self::Arrow(a) => a.is_finite(),
        }
    }

    /// The dense matrix (a copy; for an arrowhead, `O(n^2)` memory: block
    /// problems take what they need from [`ArrowMatrix::invert`]).
    pub fn to_dense(&self) -> DMatrix<f64> {
        match self {
            Self::Dense(a) => a.clone(),
            Self::Arrow(a) => a.to_dense(),
        }
    }

    /// `variance * A^+` over every parameter ([`covariance_from_normal`]).
    /// Whole, so for an arrowhead it is dense (`O(n^2)`); the head's
    /// covariance alone comes from [`ArrowMatrix::invert`].
    pub fn covariance(&self, variance: f64) -> DMatrix<f64> {
        match self {
            Self::Dense(a) => covariance_from_normal(a, variance),
            Self::Arrow(a) => covariance_from_normal(&a.to_dense(), variance),
        }
    }
}
