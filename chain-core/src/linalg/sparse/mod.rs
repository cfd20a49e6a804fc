//! The sparse path of [`SymmetricMatrix`](super::SymmetricMatrix): a network's tangent stiffness
//! (an upper triangle by rows) without forming the dense matrix, for patches beyond
//! [`MAX_DENSE_VALUES`](super::MAX_DENSE_VALUES) and wherever it is faster below.
//!
//! - [`lblt`]: `A - sigma I = P^T L B L^T P`, faer's supernodal factorization with Bunch-Kaufman
//!   pivoting within supernodes after an approximate minimum degree ordering; its inertia
//!   (Sylvester's law: how many eigenvalues lie below `sigma`) and its solves, every
//!   factorization checked by its backward error.
//! - [`eigen`]: the eigenpairs nearest a value or at the bottom of the spectrum, by shift-invert
//!   block subspace iteration, checked complete by an inertia count.
//! - [`null_space`]: the null spaces of a sparse rectangular matrix (a network's compatibility
//!   matrix): candidates counted by inertia of its Gram matrices, their bases by the subspace
//!   iteration, decided by [`refine`]: the singular values of the matrix itself on their span.
//!
//! Costs for a 2D lattice patch of `n` degrees of freedom with nested-dissection-like fill: the
//! factor holds `O(n log n)` values, a factorization takes `O(n^{3/2})`, a solve `O(n log n)`;
//! compared with the dense `O(n^2)` memory and `O(n^3)` time. Measured crossover and timings:
//! `benches/sparse.rs` and docs/network.md §10.5.

pub mod eigen;
pub mod lblt;
pub mod null_space;
pub mod refine;

/// A symmetric matrix by its upper triangle in compressed rows (the `Upper` layout's arrays).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Upper<'a> {
    pub n: usize,
    pub row_starts: &'a [usize],
    pub columns: &'a [usize],
    pub values: &'a [f64],
}

impl Upper<'_> {
    /// `y = (A - sigma I) x`.
    pub(crate) fn mul_vec_shifted(&self, sigma: f64, x: &[f64], y: &mut [f64]) {
        for (y, x) in y.iter_mut().zip(x) {
            *y = -sigma * x;
        }
        for i in 0..self.n {
            let row = self.row_starts[i]..self.row_starts[i + 1];
            let mut yi = 0.0;
            for (&j, &v) in self.columns[row.clone()].iter().zip(&self.values[row]) {
                yi += v * x[j];
                if j != i {
                    y[j] += v * x[i];
                }
            }
            y[i] += yi;
        }
    }
}
