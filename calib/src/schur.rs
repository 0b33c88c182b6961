//! Block-arrowhead normal matrices: a dense head (intrinsics, kinematics)
//! coupled to many small independent tail blocks (one per image: its pose,
//! or its joint corrections). Such systems are solved and inverted through
//! the Schur complement of the tail,
//! `S = A_hh - sum_k A_hk A_kk^-1 A_kh`, at the cost of the head's size
//! instead of the whole system's (the bundle-adjustment trick).

use nalgebra::{DMatrix, DVector};

/// The tail blocks' inverses and the Schur complement of a normal matrix.
struct Elimination {
    block: usize,
    /// `A_kk^-1` of every tail block.
    inverses: Vec<DMatrix<f64>>,
    /// `A_hk A_kk^-1` of every tail block.
    couplings: Vec<DMatrix<f64>>,
    schur: DMatrix<f64>,
}

impl Elimination {
    /// `None` unless `a` is square with a tail of whole `block`s, each
    /// positive definite.
    fn new(a: &DMatrix<f64>, head: usize, block: usize) -> Option<Self> {
        let n = a.nrows();
        if a.ncols() != n || head > n || block == 0 || !(n - head).is_multiple_of(block) {
            return None;
        }
        let blocks = (n - head) / block;
        let mut schur = a.view((0, 0), (head, head)).into_owned();
        let mut inverses = Vec::with_capacity(blocks);
        let mut couplings = Vec::with_capacity(blocks);
        for k in 0..blocks {
            let b0 = head + k * block;
            let inverse = a
                .view((b0, b0), (block, block))
                .into_owned()
                .cholesky()?
                .inverse();
            let a_hk = a.view((0, b0), (head, block));
            let coupling = a_hk * &inverse;
            schur -= &coupling * a_hk.transpose();
            inverses.push(inverse);
            couplings.push(coupling);
        }
        Some(Self {
            block,
            inverses,
            couplings,
            schur,
        })
    }
}

/// Solve `A d = g` for a positive definite block-arrowhead `A` whose first
/// `head` rows are dense and whose tail is block-diagonal in `block`-sized
/// blocks; `None` when it is not positive definite (or not so shaped).
pub fn schur_solve(
    a: &DMatrix<f64>,
    g: &DVector<f64>,
    head: usize,
    block: usize,
) -> Option<DVector<f64>> {
    let e = Elimination::new(a, head, block)?;
    let mut rhs = g.rows(0, head).into_owned();
    for (k, coupling) in e.couplings.iter().enumerate() {
        rhs -= coupling * g.rows(head + k * block, block);
    }
    let d_head = if head > 0 {
        e.schur.clone().cholesky()?.solve(&rhs)
    } else {
        DVector::zeros(0)
    };
    let mut d = DVector::zeros(g.len());
    d.rows_mut(0, head).copy_from(&d_head);
    for (k, inverse) in e.inverses.iter().enumerate() {
        let b0 = head + k * block;
        let a_kh = a.view((b0, 0), (block, head));
        let d_k = inverse * (g.rows(b0, block) - a_kh * &d_head);
        d.rows_mut(b0, block).copy_from(&d_k);
    }
    Some(d)
}

/// The parts of `A^-1` a covariance needs: the head block and the diagonal
/// of the tail.
#[derive(Debug, Clone)]
pub struct ArrowInverse {
    /// `(A^-1)_hh = S^-1`.
    pub head: DMatrix<f64>,
    /// Diagonal of `(A^-1)_kk = A_kk^-1 + (A_hk A_kk^-1)^T S^-1 (A_hk A_kk^-1)`.
    pub tail_diagonal: DVector<f64>,
}

/// Invert a block-arrowhead `A` (see [`schur_solve`]) in the parts a
/// covariance needs; `None` when it is not positive definite.
pub fn schur_invert(a: &DMatrix<f64>, head: usize, block: usize) -> Option<ArrowInverse> {
    let e = Elimination::new(a, head, block)?;
    let head_inverse = if head > 0 {
        e.schur.clone().cholesky()?.inverse()
    } else {
        DMatrix::zeros(0, 0)
    };
    let mut tail_diagonal = DVector::zeros(a.nrows() - head);
    for (k, (inverse, coupling)) in e.inverses.iter().zip(&e.couplings).enumerate() {
        let full = inverse + coupling.transpose() * &head_inverse * coupling;
        tail_diagonal
            .rows_mut(k * e.block, e.block)
            .copy_from(&full.diagonal());
    }
    Some(ArrowInverse {
        head: head_inverse,
        tail_diagonal,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A random positive definite arrowhead: `J^T J` of a block-sparse `J`.
    fn arrowhead(head: usize, block: usize, blocks: usize) -> DMatrix<f64> {
        let n = head + block * blocks;
        let rows_per_block = 3 * (head + block);
        let mut j = DMatrix::zeros(rows_per_block * blocks, n);
        let mut seed = 1u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 33) as f64 / (1u64 << 31) as f64) - 0.5
        };
        for k in 0..blocks {
            for r in 0..rows_per_block {
                let row = k * rows_per_block + r;
                for c in 0..head {
                    j[(row, c)] = next();
                }
                for c in 0..block {
                    j[(row, head + k * block + c)] = next();
                }
            }
        }
        j.transpose() * j
    }

    #[test]
    fn arrow_solve_and_inverse_match_the_dense_ones() {
        for (head, block, blocks) in [(5, 6, 7), (0, 3, 4), (8, 2, 1)] {
            let a = arrowhead(head, block, blocks);
            let g = DVector::from_fn(a.nrows(), |i, _| (i as f64 * 0.37).sin());
            let dense = a.clone().cholesky().unwrap();
            let d = schur_solve(&a, &g, head, block).unwrap();
            assert!((&d - dense.solve(&g)).amax() < 1e-9 * (1.0 + d.amax()));
            let inv = dense.inverse();
            let parts = schur_invert(&a, head, block).unwrap();
            assert!((&parts.head - inv.view((0, 0), (head, head))).amax() < 1e-9 * inv.amax());
            let tail = inv.diagonal().rows(head, a.nrows() - head).into_owned();
            assert!((&parts.tail_diagonal - tail).amax() < 1e-9 * inv.amax());
        }
    }

    #[test]
    fn misshapen_or_indefinite_systems_are_refused() {
        let a = arrowhead(2, 3, 2);
        let g = DVector::zeros(a.nrows());
        assert!(schur_solve(&a, &g, 3, 3).is_none(), "tail not whole blocks");
        assert!(schur_solve(&a, &g, 2, 0).is_none());
        assert!(schur_invert(&(-a), 2, 3).is_none());
    }
}
