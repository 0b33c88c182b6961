//! Block-arrowhead storage of a symmetric normal matrix (method.md §4
//! **beyond**, §6): a dense head (the shared parameters: intrinsics,
//! kinematics, hand–eye, board) coupled to many small tail blocks that are
//! independent of each other (one per image: its pose, or its joint
//! corrections),
//!
//! ```text
//!     [ A_hh  A_h1  A_h2  ...  ]
//! A = [ A_1h  A_11   0    ...  ]
//!     [ A_2h   0    A_22  ...  ]
//!     [ ...                    ]
//! ```
//!
//! Only `A_hh`, every `A_hk` and every `A_kk` are kept: memory grows
//! linearly with the number of images (`h b + b^2` numbers per image) where
//! the dense matrix grows with its square (about 290 MB at 1,000 camera
//! poses). [`crate::schur`] solves and inverts it by blocks.

use nalgebra::{DMatrix, DVector};

/// A symmetric block-arrowhead matrix of `head + block * blocks` rows.
#[derive(Debug, Clone, PartialEq)]
pub struct ArrowMatrix {
    head: DMatrix<f64>,
    /// `A_hk` (`head x block`) of every tail block.
    couplings: Vec<DMatrix<f64>>,
    /// `A_kk` (`block x block`) of every tail block.
    blocks: Vec<DMatrix<f64>>,
    block: usize,
}

impl ArrowMatrix {
    /// The zero matrix with a `head`-sized head and `blocks` tail blocks of
    /// `block` rows each.
    pub fn zeros(head: usize, block: usize, blocks: usize) -> Self {
        Self {
            head: DMatrix::zeros(head, head),
            couplings: vec![DMatrix::zeros(head, block); blocks],
            blocks: vec![DMatrix::zeros(block, block); blocks],
            block,
        }
    }

    /// The arrowhead parts of a dense symmetric `a` (entries between two
    /// different tail blocks are ignored); `None` unless `a` is square with
    /// a tail of whole, non-empty `block`s.
    pub fn from_dense(a: &DMatrix<f64>, head: usize, block: usize) -> Option<Self> {
        let n = a.nrows();
        if a.ncols() != n || head > n || block == 0 || !(n - head).is_multiple_of(block) {
            return None;
        }
        let count = (n - head) / block;
        let start = |k: usize| head + k * block;
        Some(Self {
            head: a.view((0, 0), (head, head)).into_owned(),
            couplings: (0..count)
                .map(|k| a.view((0, start(k)), (head, block)).into_owned())
                .collect(),
            blocks: (0..count)
                .map(|k| a.view((start(k), start(k)), (block, block)).into_owned())
                .collect(),
            block,
        })
    }

    /// The dense matrix (for tests and small problems only: it is what
    /// this type exists to avoid).
    pub fn to_dense(&self) -> DMatrix<f64> {
        let h = self.head_len();
        let mut a = DMatrix::zeros(self.dim(), self.dim());
        a.view_mut((0, 0), (h, h)).copy_from(&self.head);
        for k in 0..self.blocks.len() {
            let s = self.block_start(k);
            a.view_mut((0, s), (h, self.block))
                .copy_from(&self.couplings[k]);
            a.view_mut((s, 0), (self.block, h))
                .copy_from(&self.couplings[k].transpose());
            a.view_mut((s, s), (self.block, self.block))
                .copy_from(&self.blocks[k]);
        }
        a
    }

    /// Rows (and columns) of the whole matrix.
    pub fn dim(&self) -> usize {
        self.head_len() + self.block * self.blocks.len()
    }

    pub fn head_len(&self) -> usize {
        self.head.nrows()
    }

    /// Rows of one tail block.
    pub fn block_len(&self) -> usize {
        self.block
    }

    /// Number of tail blocks.
    pub fn block_count(&self) -> usize {
        self.blocks.len()
    }

    /// First row of tail block `k` in the whole matrix.
    pub fn block_start(&self, k: usize) -> usize {
        self.head_len() + k * self.block
    }

    /// `A_hh`.
    pub fn head(&self) -> &DMatrix<f64> {
        &self.head
    }

    pub fn head_mut(&mut self) -> &mut DMatrix<f64> {
        &mut self.head
    }

    /// `A_hk` of tail block `k`.
    pub fn coupling(&self, k: usize) -> &DMatrix<f64> {
        &self.couplings[k]
    }

    pub fn coupling_mut(&mut self, k: usize) -> &mut DMatrix<f64> {
        &mut self.couplings[k]
    }

    /// `A_kk` of tail block `k`.
    pub fn block(&self, k: usize) -> &DMatrix<f64> {
        &self.blocks[k]
    }

    pub fn block_mut(&mut self, k: usize) -> &mut DMatrix<f64> {
        &mut self.blocks[k]
    }

    pub fn diagonal(&self) -> DVector<f64> {
        let mut d = DVector::zeros(self.dim());
        d.rows_mut(0, self.head_len())
            .copy_from(&self.head.diagonal());
        for (k, b) in self.blocks.iter().enumerate() {
            d.rows_mut(self.block_start(k), self.block)
                .copy_from(&b.diagonal());
        }
        d
    }

    /// `A <- D^-1 A D^-1` with `D = diag(scale)` (the solver's column
    /// scaling).
    pub fn scale_symmetric(&mut self, scale: &DVector<f64>) {
        let scale = scale.as_slice();
        let head = &scale[..self.head_len()];
        divide(&mut self.head, head, head);
        for k in 0..self.blocks.len() {
            let s = self.block_start(k);
            let tail = &scale[s..s + self.block];
            divide(&mut self.couplings[k], head, tail);
            divide(&mut self.blocks[k], tail, tail);
        }
    }

    /// `A <- A + mu I`.
    pub fn add_to_diagonal(&mut self, mu: f64) {
        for m in std::iter::once(&mut self.head).chain(&mut self.blocks) {
            for j in 0..m.nrows() {
                m[(j, j)] += mu;
            }
        }
    }

    /// `A v`.
    pub fn mul_vector(&self, v: &DVector<f64>) -> DVector<f64> {
        let h = self.head_len();
        let v_head = v.rows(0, h);
        let mut out = DVector::zeros(self.dim());
        let mut out_head = &self.head * v_head;
        for k in 0..self.blocks.len() {
            let s = self.block_start(k);
            let v_k = v.rows(s, self.block);
            out_head += &self.couplings[k] * v_k;
            let out_k = self.couplings[k].tr_mul(&v_head) + &self.blocks[k] * v_k;
            out.rows_mut(s, self.block).copy_from(&out_k);
        }
        out.rows_mut(0, h).copy_from(&out_head);
        out
    }

    /// Every stored entry is finite.
    pub fn is_finite(&self) -> bool {
        std::iter::once(&self.head)
            .chain(&self.couplings)
            .chain(&self.blocks)
            .all(|m| m.iter().all(|v| v.is_finite()))
    }
}

/// `m[(i, j)] /= rows[i] * cols[j]`.
fn divide(m: &mut DMatrix<f64>, rows: &[f64], cols: &[f64]) {
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            m[(i, j)] /= rows[i] * cols[j];
        }
    }
}
