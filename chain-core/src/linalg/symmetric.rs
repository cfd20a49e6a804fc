//! A symmetric matrix in the layout of a model's tangent stiffness ([`StiffnessLayout`]), and the
//! algorithms the analyses need on it: norms, the inertia (how many eigenvalues lie below a
//! shift), eigenpairs near a value or at the bottom of the spectrum, and shifted solves.
//!
//! **Three paths, one interface.** A tridiagonal matrix (the rotor chain's, paper Eq.
//! `eq:prestress8`) takes the O(n) algorithms of this module's siblings: Sturm counts, bisection
//! and inverse iteration, Gaussian elimination with partial pivoting. A sparse upper triangle (a
//! spring network's) of at most [`DENSE_LIMIT`] rows ([`DENSE_FACTOR_LIMIT`] for counts and solves)
//! is taken densely: nalgebra's symmetric
//! eigendecomposition (Householder tridiagonalisation and implicit QL) for counts and eigenpairs,
//! LU with partial pivoting for solves. A larger one takes the sparse path ([`super::sparse`]):
//! inertia counts and solves from a sparse `LBL^T` factorization (Sylvester's law of inertia), the
//! eigenpairs by shift-invert subspace iteration on it. [`SymmetricMatrix::with_dense_limit`]
//! moves the crossover (tests force the sparse path on small matrices with it).
//!
//! Why a representation of our own rather than a sparse crate's: the chain's fast path needs the
//! two bands as plain slices for its O(n) algorithms, a network's Hessian is assembled in place
//! into a fixed pattern, and the layout must exist without allocation for `no_std` models (the
//! traits in [`crate::model`]). A compressed-sparse-rows pattern of the upper triangle is the
//! plainest form that fits both and converts to any sparse library's without copying values.

use alloc::vec;
use alloc::vec::Vec;
use core::ops::Range;

use nalgebra::DMatrix;

use super::error::{Input, LinalgError};
use super::sparse::Upper;
use super::sparse::eigen::{self, Target};
use super::sparse::lblt::{self, Lblt};
use super::{Eigenpair, bands};
use crate::model::{Pattern, Stiffness, StiffnessLayout};

/// The most numbers a dense matrix made by the analyses may hold: 2^26 `f64`s (512 MiB). The
/// dense path of a sparse [`SymmetricMatrix`] (an `n x n` matrix), the `n x m` matrix of the
/// counting's decomposition, the `k` vectors of length `n` of the modes. A larger request is a
/// typed error before anything is allocated, not an allocation failure.
pub const MAX_DENSE_VALUES: usize = 1 << 26;

/// The largest sparse [`SymmetricMatrix`] whose eigenpairs are computed densely by default; larger
/// ones take shift-invert subspace iteration. Why 384: the lowest 12 eigenpairs of a 2D lattice's
/// pattern cost 9.2 ms dense and 14.8 ms sparse at 256 rows, 100 ms and 29 ms at 576 (the
/// crossover near 350; `benches/sparse.rs`, docs/network.md §10.5).
pub const DENSE_LIMIT: usize = 384;

/// The largest sparse [`SymmetricMatrix`] whose inertia counts and shifted solves are computed
/// densely by default; larger ones take the sparse `LBL^T`. Why 256: there already the sparse count
/// takes 0.21 ms against the dense eigenvalues' 4.5 ms, the sparse solve 0.25 ms against dense LU's
/// 1.2 ms (same benchmark).
pub const DENSE_FACTOR_LIMIT: usize = 256;

/// Which algorithm family asks whether to take the sparse path.
#[derive(Clone, Copy)]
enum Operation {
    /// Eigenpairs ([`DENSE_LIMIT`]).
    Eigenpairs,
    /// Inertia counts and solves ([`DENSE_FACTOR_LIMIT`]).
    Factor,
}

/// A symmetric `n x n` matrix in one of the layouts of [`StiffnessLayout`], owning its pattern
/// and values.
#[derive(Clone, Debug, PartialEq)]
pub struct SymmetricMatrix {
    n: usize,
    form: Form,
    values: Vec<f64>,
    /// The largest dimension a sparse form is taken densely at: `None` for the defaults
    /// ([`DENSE_LIMIT`], [`DENSE_FACTOR_LIMIT`]), or the one limit of
    /// [`SymmetricMatrix::with_dense_limit`].
    dense_limit: Option<usize>,
}

#[derive(Clone, Debug, PartialEq)]
enum Form {
    /// `values = [diag (n) | off (n - 1)]`.
    Tridiagonal,
    /// The upper triangle by rows; `values` in the pattern's order.
    Upper { row_starts: Vec<usize>, columns: Vec<usize> },
}

impl SymmetricMatrix {
    /// A zero matrix in `model`'s stiffness layout, ready for
    /// [`Stiffness::tangent_stiffness_into`] (fill it with [`SymmetricMatrix::values_mut`]).
    ///
    /// # Errors
    /// A sparse pattern that is not a well-formed upper triangle of a `dof_count() x dof_count()`
    /// matrix ([`LinalgError::Pattern`]).
    pub fn for_model<M: Stiffness + ?Sized>(model: &M) -> Result<Self, LinalgError> {
        let n = model.dof_count();
        match model.stiffness_layout() {
            StiffnessLayout::Tridiagonal => Ok(Self {
                n,
                form: Form::Tridiagonal,
                values: vec![0.0; (2 * n).saturating_sub(1)],
                dense_limit: None,
            }),
            StiffnessLayout::Upper(p) => {
                p.check(true)?;
                if p.rows() != n {
                    return Err(LinalgError::WrongDimension { expected: n, found: p.rows() });
                }
                Ok(Self {
                    n,
                    form: Form::Upper { row_starts: p.row_starts.to_vec(), columns: p.columns.to_vec() },
                    values: vec![0.0; p.entries()],
                    dense_limit: None,
                })
            }
        }
    }

    /// The tangent stiffness of `model` at `x`.
    ///
    /// # Errors
    /// As [`SymmetricMatrix::for_model`].
    ///
    /// # Panics
    /// As [`Stiffness::tangent_stiffness_into`], if `x` does not have one value per degree of
    /// freedom.
    pub fn tangent_stiffness<M: Stiffness + ?Sized>(model: &M, x: &[f64]) -> Result<Self, LinalgError> {
        let mut k = Self::for_model(model)?;
        model.tangent_stiffness_into(x, &mut k.values);
        Ok(k)
    }

    /// The symmetric tridiagonal matrix with these bands.
    ///
    /// # Errors
    /// `off` not one shorter than `diag` ([`LinalgError::DimensionMismatch`]).
    pub fn tridiagonal(diag: &[f64], off: &[f64]) -> Result<Self, LinalgError> {
        if off.len() != diag.len().saturating_sub(1) {
            return Err(LinalgError::DimensionMismatch { diag: diag.len(), off: off.len() });
        }
        let mut values = Vec::with_capacity(diag.len() + off.len());
        values.extend_from_slice(diag);
        values.extend_from_slice(off);
        Ok(Self { n: diag.len(), form: Form::Tridiagonal, values, dense_limit: None })
    }

    /// The symmetric matrix whose upper triangle is `values` in `pattern`.
    ///
    /// # Errors
    /// A malformed pattern, or not one value per entry.
    pub fn upper(pattern: Pattern<'_>, values: Vec<f64>) -> Result<Self, LinalgError> {
        pattern.check(true)?;
        if values.len() != pattern.entries() {
            return Err(LinalgError::RhsMismatch { n: pattern.entries(), rhs: values.len() });
        }
        let form = Form::Upper { row_starts: pattern.row_starts.to_vec(), columns: pattern.columns.to_vec() };
        Ok(Self { n: pattern.rows(), form, values, dense_limit: None })
    }

    /// The same matrix, taken densely up to `limit` rows and by the sparse path beyond (a sparse
    /// form only; a tridiagonal one always takes its banded algorithms). Never beyond
    /// [`MAX_DENSE_VALUES`]: a larger `limit` is capped there.
    #[must_use]
    pub fn with_dense_limit(mut self, limit: usize) -> Self {
        self.dense_limit = Some(limit);
        self
    }

    /// Whether the sparse path serves this matrix's eigenpairs (and so its counts and solves): a
    /// sparse form beyond the dense limit or the dense bound.
    pub fn is_sparse_path(&self) -> bool {
        self.sparse_view(Operation::Eigenpairs).is_some()
    }

    /// The sparse view when the sparse path serves this matrix for `operation`.
    fn sparse_view(&self, operation: Operation) -> Option<Upper<'_>> {
        let limit = self.dense_limit.unwrap_or(match operation {
            Operation::Eigenpairs => DENSE_LIMIT,
            Operation::Factor => DENSE_FACTOR_LIMIT,
        });
        match &self.form {
            Form::Upper { row_starts, columns }
                if self.n > limit || self.n.saturating_mul(self.n) > MAX_DENSE_VALUES =>
            {
                Some(Upper { n: self.n, row_starts, columns, values: &self.values })
            }
            _ => None,
        }
    }

    /// The dimension `n`.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// The values in the layout.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The values in the layout, to fill.
    pub fn values_mut(&mut self) -> &mut [f64] {
        &mut self.values
    }

    /// The diagonal and the superdiagonal of a tridiagonal matrix; `None` for a sparse one.
    pub fn bands(&self) -> Option<(&[f64], &[f64])> {
        match self.form {
            Form::Tridiagonal => Some(self.values.split_at(self.n)),
            Form::Upper { .. } => None,
        }
    }

    /// Entry `(i, j)` (zero where the pattern has none).
    ///
    /// # Panics
    /// If `i` or `j` is not below `n`.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        assert!(i < self.n && j < self.n, "entry ({i}, {j}) of a {0} x {0} matrix", self.n);
        let (i, j) = (i.min(j), i.max(j));
        match &self.form {
            Form::Tridiagonal => match j - i {
                0 => self.values[i],
                1 => self.values[self.n + i],
                _ => 0.0,
            },
            Form::Upper { row_starts, columns } => {
                let row = &columns[row_starts[i]..row_starts[i + 1]];
                row.binary_search(&j).map_or(0.0, |k| self.values[row_starts[i] + k])
            }
        }
    }

    /// Every stored entry as `(i, j, value)` with `i <= j`.
    fn entries(&self) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
        let n = self.n;
        let (tri, upper) = match &self.form {
            Form::Tridiagonal => (Some(()), None),
            Form::Upper { row_starts, columns } => (None, Some((row_starts, columns))),
        };
        let banded = tri.into_iter().flat_map(move |()| {
            (0..n)
                .map(move |i| (i, i, self.values[i]))
                .chain((0..n.saturating_sub(1)).map(move |i| (i, i + 1, self.values[n + i])))
        });
        let sparse = upper.into_iter().flat_map(move |(starts, columns)| {
            (0..n).flat_map(move |i| (starts[i]..starts[i + 1]).map(move |k| (i, columns[k], self.values[k])))
        });
        banded.chain(sparse)
    }

    /// `Ok` if every value is finite, else the first that is not.
    pub fn check_finite(&self) -> Result<(), LinalgError> {
        bands::check_finite(Input::Matrix, &self.values)
    }

    /// `max_i sum_j |K_ij|`, the infinity norm, a bound on every eigenvalue (Gershgorin); NaN if
    /// an entry is NaN.
    pub fn inf_norm(&self) -> f64 {
        let nan_max = |m: f64, r: f64| if m.is_nan() || r.is_nan() { f64::NAN } else { m.max(r) };
        if let Some((diag, off)) = self.bands() {
            // Row i: |d_i| + |e_{i-1}| + |e_i|, without the general path's row buffer (this runs
            // once per Newton solve, relaxation and mode search of a chain).
            let mut left = 0.0;
            let mut norm = 0.0;
            for (i, d) in diag.iter().enumerate() {
                let right = off.get(i).map_or(0.0, |e| e.abs());
                norm = nan_max(norm, d.abs() + left + right);
                left = right;
            }
            return norm;
        }
        let mut rows = vec![0.0; self.n];
        for (i, j, v) in self.entries() {
            rows[i] += v.abs();
            if i != j {
                rows[j] += v.abs();
            }
        }
        rows.into_iter().fold(0.0, nan_max)
    }

    /// `y = K x`.
    ///
    /// # Panics
    /// If `x` or `y` does not have `n` entries.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        assert!(x.len() == self.n && y.len() == self.n, "K x needs vectors of {} entries", self.n);
        y.iter_mut().for_each(|v| *v = 0.0);
        for (i, j, v) in self.entries() {
            y[i] += v * x[j];
            if i != j {
                y[j] += v * x[i];
            }
        }
    }

    /// The principal submatrix on the contiguous rows and columns `keep` (the moving degrees of
    /// freedom when some are held).
    ///
    /// # Panics
    /// If `keep` does not lie within `0..n`.
    pub fn principal(&self, keep: Range<usize>) -> Self {
        assert!(keep.start <= keep.end && keep.end <= self.n, "rows {keep:?} of a {} x {0} matrix", self.n);
        let m = keep.len();
        match &self.form {
            Form::Tridiagonal => {
                let (diag, off) = self.values.split_at(self.n);
                let mut values = diag[keep.clone()].to_vec();
                values.extend_from_slice(&off[keep.start..keep.start + m.saturating_sub(1)]);
                Self { n: m, form: Form::Tridiagonal, values, dense_limit: self.dense_limit }
            }
            Form::Upper { row_starts, columns } => {
                let (mut starts, mut cols, mut values) = (vec![0], Vec::new(), Vec::new());
                for i in keep.clone() {
                    let row = row_starts[i]..row_starts[i + 1];
                    for (&j, &value) in columns[row.clone()].iter().zip(&self.values[row]) {
                        if keep.contains(&j) {
                            cols.push(j - keep.start);
                            values.push(value);
                        }
                    }
                    starts.push(cols.len());
                }
                Self {
                    n: m,
                    form: Form::Upper { row_starts: starts, columns: cols },
                    values,
                    dense_limit: self.dense_limit,
                }
            }
        }
    }

    /// `I^{-1/2} K I^{-1/2}` for the positive diagonal `I` (inertias): entry `(i, i)` divided by
    /// `I_i`, entry `(i, j)` by `sqrt(I_i) sqrt(I_j)`, the symmetric form of the modes' problem
    /// `K v = omega^2 I v`.
    ///
    /// # Panics
    /// If `inertia` does not have `n` entries.
    pub fn mass_scaled(&self, inertia: &[f64]) -> Self {
        assert_eq!(inertia.len(), self.n, "one inertia per row");
        let root: Vec<f64> = inertia.iter().map(|&x| crate::math::sqrt(x)).collect();
        let mut out = self.clone();
        match &self.form {
            Form::Tridiagonal => {
                let (diag, off) = out.values.split_at_mut(self.n);
                diag.iter_mut().zip(inertia).for_each(|(v, m)| *v /= m);
                off.iter_mut().enumerate().for_each(|(i, v)| *v /= root[i] * root[i + 1]);
            }
            Form::Upper { row_starts, columns } => {
                for i in 0..self.n {
                    let row = row_starts[i]..row_starts[i + 1];
                    for (value, &j) in out.values[row.clone()].iter_mut().zip(&columns[row]) {
                        *value /= if i == j { inertia[i] } else { root[i] * root[j] };
                    }
                }
            }
        }
        out
    }

    /// The dense matrix.
    ///
    /// # Errors
    /// More than [`MAX_DENSE_VALUES`] entries ([`LinalgError::TooLarge`]), or memory the allocator
    /// cannot give ([`LinalgError::OutOfMemory`]; nalgebra's decompositions of it then take
    /// workspace of its size, which they allocate themselves).
    pub fn to_dense(&self) -> Result<DMatrix<f64>, LinalgError> {
        let n = self.n;
        if n.saturating_mul(n) > MAX_DENSE_VALUES {
            return Err(LinalgError::TooLarge { n, max: MAX_DENSE_VALUES });
        }
        let mut m = DMatrix::from_vec(n, n, crate::allocation::try_filled(n * n, 0.0, "a dense matrix")?);
        for (i, j, v) in self.entries() {
            m[(i, j)] = v;
            m[(j, i)] = v;
        }
        Ok(m)
    }

    /// How many eigenvalues lie strictly below `x`: a Sturm count on the tridiagonal path, the
    /// dense eigenvalues on the dense one, the inertia of a sparse `LBL^T` of `K - x I` on the
    /// sparse one (exact for a matrix within its backward error, `<= 64 n eps ||K||`, of
    /// `K - x I`: [`super::sparse::lblt`]).
    ///
    /// # Errors
    /// A non-finite entry or shift, a sparse factorization that is unstable or does not fit in
    /// memory.
    pub fn count_below(&self, x: f64) -> Result<usize, LinalgError> {
        if let Some(upper) = self.sparse_view(Operation::Factor) {
            self.check_finite()?;
            bands::check_finite(Input::Shift, &[x])?;
            let inertia = Lblt::new(&upper, x)?.inertia();
            // An exactly zero pivot is an eigenvalue at x, not below it.
            return Ok(inertia.negative);
        }
        match self.bands() {
            Some((diag, off)) => super::try_count_below(diag, off, x),
            None => {
                bands::check_finite(Input::Shift, &[x])?;
                Ok(self.dense_eigenvalues()?.iter().filter(|&&v| v < x).count())
            }
        }
    }

    /// The `k` eigenpairs whose eigenvalues lie nearest `sigma`, ascending, orthonormal.
    ///
    /// # Errors
    /// A non-finite entry or `sigma`, `k > n`, or a sparse matrix too large for the dense path.
    pub fn eigenpairs_near(&self, sigma: f64, k: usize) -> Result<Vec<Eigenpair>, LinalgError> {
        if let Some(pairs) = self.sparse_eigenpairs(Target::Near(sigma), k)? {
            return Ok(pairs);
        }
        match self.bands() {
            Some((diag, off)) => super::eigenpairs_near(diag, off, sigma, k),
            None => {
                bands::check_finite(Input::Shift, &[sigma])?;
                bands::check_range(0, k, self.n)?;
                let mut pairs = self.dense_eigenpairs()?;
                pairs.sort_by(|a, b| (a.value - sigma).abs().total_cmp(&(b.value - sigma).abs()));
                pairs.truncate(k);
                pairs.sort_by(|a, b| a.value.total_cmp(&b.value));
                Ok(pairs)
            }
        }
    }

    /// The `k` smallest eigenpairs, ascending, orthonormal.
    ///
    /// # Errors
    /// As [`SymmetricMatrix::eigenpairs_near`].
    pub fn lowest_eigenpairs(&self, k: usize) -> Result<Vec<Eigenpair>, LinalgError> {
        if let Some(pairs) = self.sparse_eigenpairs(Target::Lowest, k)? {
            return Ok(pairs);
        }
        match self.bands() {
            Some((diag, off)) => super::lowest_eigenpairs(diag, off, k),
            None => {
                bands::check_range(0, k, self.n)?;
                let mut pairs = self.dense_eigenpairs()?;
                pairs.truncate(k);
                Ok(pairs)
            }
        }
    }

    /// Solves `(K - shift I) x = b` (Gaussian elimination with partial pivoting: stable whatever
    /// the inertia).
    ///
    /// # Errors
    /// Non-finite input, a right-hand side of the wrong length, a singular matrix, or a sparse
    /// matrix too large for the dense path.
    pub fn solve_shifted(&self, shift: f64, rhs: &[f64]) -> Result<Vec<f64>, LinalgError> {
        if let Some(upper) = self.sparse_view(Operation::Factor) {
            return self.sparse_solve(&upper, shift, rhs);
        }
        match self.bands() {
            Some((diag, off)) => super::solve_shifted(diag, off, shift, rhs),
            None => {
                self.check_finite()?;
                bands::check_finite(Input::Shift, &[shift])?;
                if rhs.len() != self.n {
                    return Err(LinalgError::RhsMismatch { n: self.n, rhs: rhs.len() });
                }
                bands::check_finite(Input::Rhs, rhs)?;
                let mut a = self.to_dense()?;
                for i in 0..self.n {
                    a[(i, i)] -= shift;
                }
                let lu = a.lu();
                let x = lu.solve(&nalgebra::DVector::from_column_slice(rhs));
                match x {
                    Some(x) if x.iter().all(|v| v.is_finite()) => Ok(x.as_slice().to_vec()),
                    _ => Err(LinalgError::Singular { row: self.n, pivot: 0.0 }),
                }
            }
        }
    }

    /// The sparse path's eigenpairs (`None` when the matrix takes another path, or asks for so
    /// many pairs that the block would exceed half the matrix and the dense path can serve).
    fn sparse_eigenpairs(&self, target: Target, k: usize) -> Result<Option<Vec<Eigenpair>>, LinalgError> {
        let Some(upper) = self.sparse_view(Operation::Eigenpairs) else { return Ok(None) };
        self.check_finite()?;
        if let Target::Near(sigma) = target {
            bands::check_finite(Input::Shift, &[sigma])?;
        }
        bands::check_range(0, k, self.n)?;
        let dense_fits = self.n.saturating_mul(self.n) <= MAX_DENSE_VALUES;
        if 2 * eigen::block_size(k, self.n) > self.n {
            // So many pairs that subspace iteration is no cheaper than the dense decomposition.
            return if dense_fits {
                Ok(None)
            } else {
                Err(LinalgError::TooLarge { n: self.n, max: MAX_DENSE_VALUES })
            };
        }
        let norm = self.inf_norm();
        if norm == 0.0 {
            // The zero matrix: every vector is an eigenvector of eigenvalue 0.
            let unit = |i: usize| (0..self.n).map(|j| f64::from(u8::from(i == j))).collect();
            return Ok(Some((0..k).map(|i| Eigenpair { value: 0.0, vector: unit(i) }).collect()));
        }
        eigen::eigenpairs(&upper, norm, target, k).map(Some)
    }

    /// `(K - shift I) x = b` by the sparse `LBL^T`, with one step of iterative refinement.
    fn sparse_solve(&self, upper: &Upper<'_>, shift: f64, rhs: &[f64]) -> Result<Vec<f64>, LinalgError> {
        self.check_finite()?;
        bands::check_finite(Input::Shift, &[shift])?;
        if rhs.len() != self.n {
            return Err(LinalgError::RhsMismatch { n: self.n, rhs: rhs.len() });
        }
        bands::check_finite(Input::Rhs, rhs)?;
        let factors = Lblt::new(upper, shift)?;
        // An exactly zero pivot, as the dense and banded eliminations: a merely tiny one is left
        // to the backward-error check below (Newton's shifted solves are nearly singular along
        // the near-null directions they project out, and are right to be).
        let inertia = factors.inertia();
        if inertia.zero > 0 {
            let (row, pivot) = inertia.smallest;
            return Err(LinalgError::Singular { row, pivot });
        }
        let mut x = rhs.to_vec();
        factors.solve_in_place(&mut x, 1)?;
        // One refinement step: x += (K - shift I)^{-1} (b - (K - shift I) x).
        let mut r = vec![0.0; self.n];
        upper.mul_vec_shifted(shift, &x, &mut r);
        r.iter_mut().zip(rhs).for_each(|(r, b)| *r = b - *r);
        factors.solve_in_place(&mut r, 1)?;
        x.iter_mut().zip(&r).for_each(|(x, d)| *x += d);
        let eta = lblt::backward_error(upper, shift, factors.norm(), &x, rhs);
        let bound = lblt::MAX_BACKWARD_ERROR_FACTOR * self.n as f64 * f64::EPSILON;
        if eta.is_nan() || eta > bound {
            return Err(LinalgError::Unstable { shift, backward_error: eta, bound });
        }
        Ok(x)
    }

    /// Every eigenvalue of the dense path, ascending.
    fn dense_eigenvalues(&self) -> Result<Vec<f64>, LinalgError> {
        self.check_finite()?;
        let mut values: Vec<f64> = self.to_dense()?.symmetric_eigenvalues().iter().copied().collect();
        values.sort_by(f64::total_cmp);
        Ok(values)
    }

    /// Every eigenpair of the dense path, ascending, each vector's entry of largest magnitude
    /// positive (as the tridiagonal path gives them).
    fn dense_eigenpairs(&self) -> Result<Vec<Eigenpair>, LinalgError> {
        self.check_finite()?;
        let eig = self.to_dense()?.symmetric_eigen();
        let mut pairs: Vec<Eigenpair> = (0..self.n)
            .map(|c| {
                let mut vector: Vec<f64> = eig.eigenvectors.column(c).iter().copied().collect();
                let largest = vector.iter().fold(0.0f64, |m, &v| if v.abs() > m.abs() { v } else { m });
                if largest < 0.0 {
                    vector.iter_mut().for_each(|v| *v = -*v);
                }
                Eigenpair { value: eig.eigenvalues[c], vector }
            })
            .collect();
        pairs.sort_by(|a, b| a.value.total_cmp(&b.value));
        Ok(pairs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A symmetric matrix both ways: as bands and as a sparse upper triangle.
    fn both(diag: &[f64], off: &[f64]) -> (SymmetricMatrix, SymmetricMatrix) {
        let n = diag.len();
        let mut starts = vec![0];
        let (mut columns, mut values) = (Vec::new(), Vec::new());
        for i in 0..n {
            columns.push(i);
            values.push(diag[i]);
            if i + 1 < n {
                columns.push(i + 1);
                values.push(off[i]);
            }
            starts.push(columns.len());
        }
        let pattern = Pattern { columns_count: n, row_starts: &starts, columns: &columns };
        (SymmetricMatrix::tridiagonal(diag, off).unwrap(), SymmetricMatrix::upper(pattern, values).unwrap())
    }

    #[test]
    fn both_paths_agree_on_an_indefinite_matrix() {
        let diag = [2.0, -1.0, 0.5, 3.0, -2.5, 1.0];
        let off = [0.7, -0.3, 1.1, 0.2, -0.9];
        let (t, s) = both(&diag, &off);
        assert_eq!(t.to_dense().unwrap(), s.to_dense().unwrap());
        assert_eq!(t.inf_norm(), s.inf_norm());
        for x in [-3.0, -1.0, 0.0, 0.4, 2.0, 5.0] {
            assert_eq!(t.count_below(x).unwrap(), s.count_below(x).unwrap(), "{x}");
        }
        let (a, b) = (t.eigenpairs_near(0.3, 3).unwrap(), s.eigenpairs_near(0.3, 3).unwrap());
        for (p, q) in a.iter().zip(&b) {
            assert!((p.value - q.value).abs() < 1e-12);
            let dot: f64 = p.vector.iter().zip(&q.vector).map(|(x, y)| x * y).sum();
            assert!((dot.abs() - 1.0).abs() < 1e-10);
        }
        let rhs = [1.0, 2.0, -1.0, 0.5, 0.0, 3.0];
        let (x, y) = (t.solve_shifted(0.25, &rhs).unwrap(), s.solve_shifted(0.25, &rhs).unwrap());
        x.iter().zip(&y).for_each(|(p, q)| assert!((p - q).abs() < 1e-12));
        // The solution satisfies the system (an independent check of both).
        let mut kx = vec![0.0; 6];
        s.mul_vec(&x, &mut kx);
        kx.iter().zip(&x).zip(&rhs).for_each(|((k, x), b)| assert!((k - 0.25 * x - b).abs() < 1e-12));
        let p = s.principal(1..5);
        assert_eq!(p.to_dense().unwrap(), t.principal(1..5).to_dense().unwrap());
        let inertia = [1.0, 2.0, 0.5, 1.5, 3.0, 0.25];
        let (ms, mt) =
            (s.mass_scaled(&inertia).to_dense().unwrap(), t.mass_scaled(&inertia).to_dense().unwrap());
        assert_eq!(ms, mt);
        assert!((ms[(1, 2)] - (-0.3) / (2.0f64 * 0.5).sqrt()).abs() < 1e-15);
        assert_eq!(s.get(2, 3), 1.1);
        assert_eq!(s.get(3, 2), 1.1);
        assert_eq!(s.get(0, 4), 0.0);
    }

    #[test]
    fn a_sparse_matrix_beyond_the_dense_bound_takes_the_sparse_path() {
        // diag(1, 2, ..., n): the counts below x are floor(x - eps) exactly.
        let n = 8193;
        let diag: Vec<f64> = (1..=n).map(|i| i as f64).collect();
        let off = vec![0.0; n - 1];
        let (_, s) = both(&diag, &off);
        assert!(s.is_sparse_path());
        assert_eq!(s.count_below(0.5).unwrap(), 0);
        assert_eq!(s.count_below(100.5).unwrap(), 100);
        assert_eq!(s.count_below(9000.0).unwrap(), n);
        assert!(matches!(s.to_dense(), Err(LinalgError::TooLarge { n: 8193, .. })));
    }
}
