use super::*;

/// Agreement of the blockwise and the dense computations, relative to the
/// largest entry compared.
const TOL: f64 = 1e-9;

/// A deterministic pseudo-random stream in `[-0.5, 0.5)`.
fn stream(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 33) as f64 / (1u64 << 31) as f64) - 0.5
    }
}

/// A random block-sparse Jacobian: every row touches the head and one
/// tail block.
fn jacobian(head: usize, block: usize, blocks: usize) -> DMatrix<f64> {
    let n = head + block * blocks;
    let rows_per_block = 3 * (head + block);
    let mut j = DMatrix::zeros(rows_per_block * blocks, n);
    let mut next = stream(1);
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
    j
}

/// A random positive definite arrowhead `J^T J` (dense).
fn arrowhead(head: usize, block: usize, blocks: usize) -> DMatrix<f64> {
    let j = jacobian(head, block, blocks);
    j.transpose() * j
}

#[test]
fn block_solve_and_inverse_match_the_dense_ones() {
    for (head, block, blocks) in [(5, 6, 7), (0, 3, 4), (8, 2, 1), (9, 6, 40)] {
        let a = arrowhead(head, block, blocks);
        let arrow = ArrowMatrix::from_dense(&a, head, block).unwrap();
        assert_eq!(arrow.to_dense(), a, "round trip");
        let g = DVector::from_fn(a.nrows(), |i, _| (i as f64 * 0.37).sin());
        let dense = a.clone().cholesky().unwrap();
        let d = arrow.solve(&g).unwrap();
        assert!((&d - dense.solve(&g)).amax() < TOL * (1.0 + d.amax()));
        assert_eq!(schur_solve(&a, &g, head, block).unwrap(), d);
        let inv = dense.inverse();
        let tail = inv.diagonal().rows(head, a.nrows() - head).into_owned();
        for parts in [arrow.invert().unwrap(), arrow.pseudo_invert()] {
            assert!((&parts.head - inv.view((0, 0), (head, head))).amax() < TOL * inv.amax());
            assert!((&parts.tail_diagonal - tail.clone()).amax() < TOL * inv.amax());
        }
    }
}

#[test]
fn block_arithmetic_matches_the_dense_matrix() {
    let (head, block, blocks) = (7, 6, 5);
    let a = arrowhead(head, block, blocks);
    let mut arrow = ArrowMatrix::from_dense(&a, head, block).unwrap();
    assert_eq!(arrow.dim(), a.nrows());
    assert_eq!(arrow.diagonal(), a.diagonal());
    let v = DVector::from_fn(a.nrows(), |i, _| (i as f64 * 1.3).cos());
    assert!((arrow.mul_vector(&v) - &a * &v).amax() < TOL * (&a * &v).amax());
    let scale = DVector::from_fn(a.nrows(), |i, _| 1.0 + i as f64);
    let mut dense = a.clone();
    for i in 0..a.nrows() {
        for j in 0..a.ncols() {
            dense[(i, j)] /= scale[i] * scale[j];
        }
        dense[(i, i)] += 0.25;
    }
    arrow.scale_symmetric(&scale);
    arrow.add_to_diagonal(0.25);
    assert_eq!(arrow.to_dense(), dense);
    assert!(arrow.is_finite());
    arrow.block_mut(2)[(0, 0)] = f64::NAN;
    assert!(!arrow.is_finite());
}

#[test]
fn misshapen_or_indefinite_systems_are_refused() {
    let a = arrowhead(2, 3, 2);
    assert!(
        ArrowMatrix::from_dense(&a, 3, 3).is_none(),
        "tail not whole blocks"
    );
    assert!(ArrowMatrix::from_dense(&a, 2, 0).is_none());
    assert!(ArrowMatrix::from_dense(&a.columns(0, 5).into_owned(), 2, 3).is_none());
    let arrow = ArrowMatrix::from_dense(&a, 2, 3).unwrap();
    assert!(arrow.solve(&DVector::zeros(a.nrows() + 1)).is_none());
    let negative = ArrowMatrix::from_dense(&(-a), 2, 3).unwrap();
    assert!(negative.invert().is_none());
    // Nothing of a negative definite matrix is a covariance.
    assert_eq!(negative.pseudo_invert().head.amax(), 0.0);
    assert!(negative.solve(&DVector::zeros(8)).is_none());
}
