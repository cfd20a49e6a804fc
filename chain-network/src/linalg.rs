//! The decompositions the analyses use, over faer, and the one rank rule.
//!
//! **Rank rule** (issue 33): the rank of a matrix is the number of its singular values above
//! [`RANK_TOLERANCE`] times the largest. A periodic patch's compatibility matrix is unitarily
//! block-diagonal in the Bloch basis, so its singular values are exactly those of the blocks
//! `Q(k)` and the same rule applies with the largest over all blocks.

use crate::error::NetworkError;
use dyn_stack::{MemBuffer, MemStack};
use faer::diag::Diag;
use faer::linalg::evd::{self, ComputeEigenvectors};
use faer::linalg::svd::{self, ComputeSvdVectors};
use faer::traits::ComplexField;
use faer::traits::ext::ComplexFieldExt;
use faer::{Mat, MatRef, Par};

/// Singular values at most this fraction of the largest count as zero.
pub const RANK_TOLERANCE: f64 = 1e-9;

/// Threads for the one large decomposition of a free patch (the machine's two cores).
pub const MAX_THREADS: usize = 2;

/// The largest dense matrix (rows x cols) decomposed: 2.5e8 entries, 2 GB of `f64`, ~20 GB of
/// workspace-free headroom on the 24 GiB machines this runs on.
pub const MAX_DENSE_ENTRIES: usize = 250_000_000;

/// The rank of a matrix with singular values `s` under the rank rule, with `largest` the
/// largest singular value of the whole matrix (for a block of a block-diagonal matrix, the
/// largest over all blocks).
pub fn rank(s: &[f64], largest: f64) -> usize {
    s.iter().filter(|&&x| x > RANK_TOLERANCE * largest).count()
}

/// The parallelism of a decomposition of `entries` entries: sequential when small.
pub(crate) fn parallelism(entries: usize) -> Par {
    if entries >= 1 << 16 { Par::rayon(MAX_THREADS) } else { Par::Seq }
}

fn check_size(what: &'static str, rows: usize, cols: usize) -> Result<(), NetworkError> {
    if rows.saturating_mul(cols) > MAX_DENSE_ENTRIES {
        Err(NetworkError::TooLarge { what, rows, cols, limit: MAX_DENSE_ENTRIES })
    } else {
        Ok(())
    }
}

/// The singular values of `a`, largest first (no vectors).
pub fn singular_values<T: ComplexField<Real = f64>>(
    what: &'static str,
    a: MatRef<'_, T>,
) -> Result<Vec<f64>, NetworkError> {
    let (m, n) = a.shape();
    check_size(what, m, n)?;
    let size = m.min(n);
    if size == 0 {
        return Ok(Vec::new());
    }
    let par = parallelism(m * n);
    let mut s = Diag::<T>::zeros(size);
    let scratch =
        svd::svd_scratch::<T>(m, n, ComputeSvdVectors::No, ComputeSvdVectors::No, par, Default::default());
    let mut mem = MemBuffer::new(scratch);
    svd::svd(a, s.as_mut(), None, None, par, MemStack::new(&mut mem), Default::default()).map_err(|_| {
        NetworkError::NoConvergence { what, decomposition: "singular value decomposition", rows: m, cols: n }
    })?;
    Ok(s.column_vector().iter().map(|x| x.real()).collect())
}

/// A full singular value decomposition `a = U S V^H`: `s` largest first, `u` square (rows),
/// `v` square (columns).
pub struct FullSvd<T> {
    /// Singular values, largest first (`min(rows, cols)` of them).
    pub s: Vec<f64>,
    /// Left singular vectors, `rows x rows`.
    pub u: Mat<T>,
    /// Right singular vectors, `cols x cols`.
    pub v: Mat<T>,
}

/// The full singular value decomposition of `a`.
pub fn full_svd<T: ComplexField<Real = f64>>(
    what: &'static str,
    a: MatRef<'_, T>,
) -> Result<FullSvd<T>, NetworkError> {
    let (m, n) = a.shape();
    check_size(what, m.max(n), m.max(n))?;
    let size = m.min(n);
    let mut u = Mat::<T>::zeros(m, m);
    let mut v = Mat::<T>::zeros(n, n);
    if size == 0 {
        u.as_mut().diagonal_mut().fill(T::one_impl());
        v.as_mut().diagonal_mut().fill(T::one_impl());
        return Ok(FullSvd { s: Vec::new(), u, v });
    }
    let par = parallelism(m * n);
    let mut s = Diag::<T>::zeros(size);
    let scratch = svd::svd_scratch::<T>(
        m,
        n,
        ComputeSvdVectors::Full,
        ComputeSvdVectors::Full,
        par,
        Default::default(),
    );
    let mut mem = MemBuffer::new(scratch);
    svd::svd(
        a,
        s.as_mut(),
        Some(u.as_mut()),
        Some(v.as_mut()),
        par,
        MemStack::new(&mut mem),
        Default::default(),
    )
    .map_err(|_| NetworkError::NoConvergence {
        what,
        decomposition: "singular value decomposition",
        rows: m,
        cols: n,
    })?;
    Ok(FullSvd { s: s.column_vector().iter().map(|x| x.real()).collect(), u, v })
}

impl<T: ComplexField<Real = f64>> FullSvd<T> {
    /// The right null space under the rank rule with largest singular value `largest`: the
    /// columns of `V` beyond the rank (`cols - rank` of them).
    pub fn right_null(&self, largest: f64) -> Mat<T> {
        let r = rank(&self.s, largest);
        self.v.subcols(r, self.v.ncols() - r).to_owned()
    }

    /// The left null space: the columns of `U` beyond the rank.
    pub fn left_null(&self, largest: f64) -> Mat<T> {
        let r = rank(&self.s, largest);
        self.u.subcols(r, self.u.ncols() - r).to_owned()
    }
}

/// Eigenvalues (ascending) and eigenvectors of the Hermitian matrix `a`.
pub fn hermitian_eigen<T: ComplexField<Real = f64>>(
    what: &'static str,
    a: MatRef<'_, T>,
) -> Result<(Vec<f64>, Mat<T>), NetworkError> {
    let n = a.nrows();
    check_size(what, n, n)?;
    let mut s = Diag::<T>::zeros(n);
    let mut u = Mat::<T>::zeros(n, n);
    if n == 0 {
        return Ok((Vec::new(), u));
    }
    let par = parallelism(n * n);
    let scratch = evd::self_adjoint_evd_scratch::<T>(n, ComputeEigenvectors::Yes, par, Default::default());
    let mut mem = MemBuffer::new(scratch);
    evd::self_adjoint_evd(a, s.as_mut(), Some(u.as_mut()), par, MemStack::new(&mut mem), Default::default())
        .map_err(|_| NetworkError::NoConvergence {
            what,
            decomposition: "Hermitian eigendecomposition",
            rows: n,
            cols: n,
        })?;
    Ok((s.column_vector().iter().map(|x| x.real()).collect(), u))
}

/// Eigenvalues (ascending) of the Hermitian matrix `a`.
pub fn hermitian_eigenvalues<T: ComplexField<Real = f64>>(
    what: &'static str,
    a: MatRef<'_, T>,
) -> Result<Vec<f64>, NetworkError> {
    let n = a.nrows();
    check_size(what, n, n)?;
    if n == 0 {
        return Ok(Vec::new());
    }
    let par = parallelism(n * n);
    let mut s = Diag::<T>::zeros(n);
    let scratch = evd::self_adjoint_evd_scratch::<T>(n, ComputeEigenvectors::No, par, Default::default());
    let mut mem = MemBuffer::new(scratch);
    evd::self_adjoint_evd(a, s.as_mut(), None, par, MemStack::new(&mut mem), Default::default()).map_err(
        |_| NetworkError::NoConvergence {
            what,
            decomposition: "Hermitian eigendecomposition",
            rows: n,
            cols: n,
        },
    )?;
    Ok(s.column_vector().iter().map(|x| x.real()).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::c64;

    #[test]
    fn singular_values_of_a_known_matrix() {
        // diag(3, 2, 0) rotated on both sides has singular values 3, 2, 0.
        let a = Mat::<f64>::from_fn(3, 3, |i, j| if i == j { [3.0, 2.0, 0.0][i] } else { 0.0 });
        let c = (0.3f64).cos();
        let s = (0.3f64).sin();
        let r = Mat::<f64>::from_fn(3, 3, |i, j| match (i, j) {
            (0, 0) | (1, 1) => c,
            (0, 1) => -s,
            (1, 0) => s,
            (2, 2) => 1.0,
            _ => 0.0,
        });
        let m = &r * &a * r.transpose();
        let sv = singular_values("test", m.as_ref()).unwrap();
        assert!((sv[0] - 3.0).abs() < 1e-14 && (sv[1] - 2.0).abs() < 1e-14 && sv[2] < 1e-14, "{sv:?}");
        assert_eq!(rank(&sv, sv[0]), 2);
        let full = full_svd("test", m.as_ref()).unwrap();
        let null = full.right_null(full.s[0]);
        assert_eq!(null.ncols(), 1);
        let image = &m * &null;
        assert!(image.norm_l2() < 1e-14);
    }

    #[test]
    fn complex_and_wide_matrices() {
        // [[1, i, 0]] has one singular value sqrt 2 and a two-dimensional null space.
        let a =
            Mat::<c64>::from_fn(1, 3, |_, j| [c64::new(1.0, 0.0), c64::new(0.0, 1.0), c64::new(0.0, 0.0)][j]);
        let full = full_svd("test", a.as_ref()).unwrap();
        assert!((full.s[0] - 2f64.sqrt()).abs() < 1e-15);
        let null = full.right_null(full.s[0]);
        assert_eq!(null.ncols(), 2);
        assert!((&a * &null).norm_l2() < 1e-15);
        assert_eq!(full.left_null(full.s[0]).ncols(), 0);
    }
}
