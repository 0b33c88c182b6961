//! Solving and inverting a block-arrowhead normal matrix
//! ([`ArrowMatrix`]) through the Schur complement of its tail,
//! `S = A_hh - sum_k A_hk A_kk^-1 A_kh`, at the cost of the head's size
//! per tail block instead of the whole system's cube (the
//! bundle-adjustment trick): time and memory grow linearly with the
//! number of tail blocks (images).

use nalgebra::{DMatrix, DVector};

use crate::arrow::ArrowMatrix;
use crate::covariance::covariance_from_normal;

/// The tail blocks' inverses and the Schur complement of an arrowhead.
struct Elimination {
    /// `A_kk^-1` of every tail block.
    inverses: Vec<DMatrix<f64>>,
    /// `A_hk A_kk^-1` of every tail block.
    couplings: Vec<DMatrix<f64>>,
    schur: DMatrix<f64>,
}

/// How a tail block is inverted.
#[derive(Clone, Copy, PartialEq)]
enum BlockInverse {
    /// Cholesky: the block must be positive definite.
    Exact,
    /// Cholesky, or the pseudo-inverse where it fails.
    Pseudo,
}

impl Elimination {
    /// `None` when a tail block is not positive definite and `how` is
    /// [`BlockInverse::Exact`].
    fn new(a: &ArrowMatrix, how: BlockInverse) -> Option<Self> {
        let blocks = a.block_count();
        let mut schur = a.head().clone();
        let mut inverses = Vec::with_capacity(blocks);
        let mut couplings = Vec::with_capacity(blocks);
        for k in 0..blocks {
            let block = a.block(k);
            let inverse = match (block.clone().cholesky(), how) {
                (Some(c), _) => c.inverse(),
                (None, BlockInverse::Pseudo) => covariance_from_normal(block, 1.0),
                (None, BlockInverse::Exact) => return None,
            };
            let a_hk = a.coupling(k);
            let coupling = a_hk * &inverse;
            schur -= &coupling * a_hk.transpose();
            inverses.push(inverse);
            couplings.push(coupling);
        }
        Some(Self {
            inverses,
            couplings,
            schur,
        })
    }
}

impl ArrowMatrix {
    /// Solve `A d = g`; `None` when `A` is not positive definite (or `g`
    /// has the wrong length).
    pub fn solve(&self, g: &DVector<f64>) -> Option<DVector<f64>> {
        if g.len() != self.dim() {
            return None;
        }
        let e = Elimination::new(self, BlockInverse::Exact)?;
        let (head, block) = (self.head_len(), self.block_len());
        let mut rhs = g.rows(0, head).into_owned();
        for (k, coupling) in e.couplings.iter().enumerate() {
            rhs -= coupling * g.rows(self.block_start(k), block);
        }
        let d_head = if head > 0 {
            e.schur.cholesky()?.solve(&rhs)
        } else {
            DVector::zeros(0)
        };
        let mut d = DVector::zeros(g.len());
        d.rows_mut(0, head).copy_from(&d_head);
        for (k, inverse) in e.inverses.iter().enumerate() {
            let b0 = self.block_start(k);
            let a_kh_d = self.coupling(k).tr_mul(&d_head);
            let d_k = inverse * (g.rows(b0, block) - a_kh_d);
            d.rows_mut(b0, block).copy_from(&d_k);
        }
        Some(d)
    }

    /// The Schur complement of the tail, `S = A_hh - sum_k A_hk A_kk^-1 A_kh`:
    /// for a normal matrix, the head's information with every tail block
    /// marginalised (the Fisher information of the head when the tail are
    /// nuisance unknowns); `None` when a tail block is not positive definite.
    pub fn schur_complement(&self) -> Option<DMatrix<f64>> {
        Elimination::new(self, BlockInverse::Exact).map(|e| e.schur)
    }

    /// The parts of `A^-1` a covariance needs (see [`ArrowInverse`]);
    /// `None` when `A` is not positive definite.
    pub fn invert(&self) -> Option<ArrowInverse> {
        let e = Elimination::new(self, BlockInverse::Exact)?;
        let head = if self.head_len() > 0 {
            e.schur.clone().cholesky()?.inverse()
        } else {
            DMatrix::zeros(0, 0)
        };
        Some(self.inverse_parts(&e, head))
    }

    /// As [`Self::invert`] for a matrix that may be singular: `S^+` (the
    /// pseudo-inverse of the Schur complement, with
    /// [`crate::covariance::COVARIANCE_RCOND`]'s cut-off) in place of
    /// `S^-1`, and likewise for a tail block that is not positive definite,
    /// so an unidentifiable combination of parameters contributes nothing
    /// instead of failing. When `A` is regular this is [`Self::invert`]
    /// within round-off.
    pub fn pseudo_invert(&self) -> ArrowInverse {
        let e = Elimination::new(self, BlockInverse::Pseudo)
            .expect("pseudo-inverted blocks always eliminate");
        let head = if self.head_len() > 0 {
            covariance_from_normal(&e.schur, 1.0)
        } else {
            DMatrix::zeros(0, 0)
        };
        self.inverse_parts(&e, head)
    }

    fn inverse_parts(&self, e: &Elimination, head_inverse: DMatrix<f64>) -> ArrowInverse {
        let block = self.block_len();
        let mut tail_diagonal = DVector::zeros(self.dim() - self.head_len());
        for (k, (inverse, coupling)) in e.inverses.iter().zip(&e.couplings).enumerate() {
            let full = inverse + coupling.transpose() * &head_inverse * coupling;
            tail_diagonal
                .rows_mut(k * block, block)
                .copy_from(&full.diagonal());
        }
        ArrowInverse {
            head: head_inverse,
            tail_diagonal,
        }
    }
}

/// The parts of `A^-1` a covariance needs: the head block and the diagonal
/// of the tail.
#[derive(Debug, Clone)]
pub struct ArrowInverse {
    /// `(A^-1)_hh = S^-1`: the head's covariance with every tail block
    /// marginalised (unit variance).
    pub head: DMatrix<f64>,
    /// Diagonal of `(A^-1)_kk = A_kk^-1 + (A_hk A_kk^-1)^T S^-1 (A_hk A_kk^-1)`.
    pub tail_diagonal: DVector<f64>,
}

/// Solve `A d = g` for a dense positive definite `a` of arrowhead shape
/// (first `head` rows dense, the tail block-diagonal in `block`-sized
/// blocks), for problems small enough to assemble it densely; `None` when
/// it is not positive definite or not so shaped.
pub fn schur_solve(
    a: &DMatrix<f64>,
    g: &DVector<f64>,
    head: usize,
    block: usize,
) -> Option<DVector<f64>> {
    ArrowMatrix::from_dense(a, head, block)?.solve(g)
}

#[cfg(test)]
#[path = "schur_tests.rs"]
mod tests;
