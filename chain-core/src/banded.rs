//! Banded matrices of the chain: the tridiagonal tangent stiffness (every spring couples two
//! neighbouring rotors, paper Eq. `eq:prestress8`) and the bidiagonal compatibility matrix.
//!
//! Fixed-size forms carry their sizes in the type: `N` rotors and `M = N - 1` springs (stable Rust
//! cannot write `N - 1` in a type, so the macro writes both numbers out), and their float type `T`:
//! `f64` unless the chain was declared with `float = f32`.

use nalgebra::SMatrix;

use crate::real::Real;

/// A symmetric tridiagonal `N x N` matrix: `diag[i] = K[i][i]`, `off[i] = K[i][i+1] = K[i+1][i]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tridiagonal<const N: usize, const M: usize, T = f64> {
    /// The diagonal: entry `(i, i)` in `diag[i]`.
    pub diag: [T; N],
    /// The off-diagonal: entry `(p, p + 1)` = `(p + 1, p)` in `off[p]`.
    pub off: [T; M],
}

/// The bidiagonal `M x N` compatibility matrix `C[p][i] = dl_p / d(r_i theta_i)` (paper
/// Introduction and Appendix D, whose `n_p` are its entries): row `p` has `left[p]` in column `p` and `right[p]` in column `p + 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bidiagonal<const M: usize, const N: usize, T = f64> {
    /// Entry `(p, p)` of the `(n - 1) x n` matrix in `left[p]`.
    pub left: [T; M],
    /// Entry `(p, p + 1)` in `right[p]`.
    pub right: [T; M],
}

impl<const N: usize, const M: usize, T: Real> Tridiagonal<N, M, T> {
    /// From its bands (no check: any numbers are a valid banded matrix).
    pub fn new(diag: [T; N], off: [T; M]) -> Self {
        const { assert!(M + 1 == N, "a chain of N rotors has N - 1 springs") };
        Self { diag, off }
    }

    /// Entry `(i, j)`; zero outside the band.
    pub fn get(&self, i: usize, j: usize) -> T {
        tridiagonal_entry(&self.diag, &self.off, i, j)
    }

    /// The dense matrix: zeros, then the three bands written in (not an entry-by-entry lookup,
    /// whose branches cost more than the tangent stiffness itself at n = 60).
    pub fn to_dense(&self) -> SMatrix<T, N, N> {
        let mut dense = SMatrix::from_element(T::ZERO);
        for (i, &d) in self.diag.iter().enumerate() {
            dense[(i, i)] = d;
        }
        for (p, &o) in self.off.iter().enumerate() {
            dense[(p, p + 1)] = o;
            dense[(p + 1, p)] = o;
        }
        dense
    }

    /// `K x`.
    pub fn mul_vec(&self, x: &[T; N]) -> [T; N] {
        let mut y = [T::ZERO; N];
        tridiagonal_mul(&self.diag, &self.off, x, &mut y);
        y
    }

    /// `x^T K x`.
    pub fn quadratic_form(&self, x: &[T; N]) -> T {
        self.mul_vec(x).iter().zip(x).fold(T::ZERO, |s, (&a, &b)| s + a * b)
    }
}

impl<const M: usize, const N: usize, T: Real> Bidiagonal<M, N, T> {
    /// From its bands (no check: any numbers are a valid banded matrix).
    pub fn new(left: [T; M], right: [T; M]) -> Self {
        const { assert!(M + 1 == N, "a chain of N rotors has N - 1 springs") };
        Self { left, right }
    }

    /// Entry `(p, i)`; zero outside the band.
    pub fn get(&self, p: usize, i: usize) -> T {
        if p >= M {
            T::ZERO
        } else if i == p {
            self.left[p]
        } else if i == p + 1 {
            self.right[p]
        } else {
            T::ZERO
        }
    }

    /// The dense `M x N` matrix.
    pub fn to_dense(&self) -> SMatrix<T, M, N> {
        SMatrix::from_fn(|p, i| self.get(p, i))
    }
}

/// Entry `(i, j)` of the symmetric tridiagonal matrix with the given bands.
pub fn tridiagonal_entry<T: Real>(diag: &[T], off: &[T], i: usize, j: usize) -> T {
    if i == j {
        diag.get(i).copied().unwrap_or(T::ZERO)
    } else if i + 1 == j {
        off.get(i).copied().unwrap_or(T::ZERO)
    } else if j + 1 == i {
        off.get(j).copied().unwrap_or(T::ZERO)
    } else {
        T::ZERO
    }
}

/// `y = K x` for the symmetric tridiagonal `K` with the given bands.
pub fn tridiagonal_mul<T: Real>(diag: &[T], off: &[T], x: &[T], y: &mut [T]) {
    let n = diag.len();
    for i in 0..n {
        let mut s = diag[i] * x[i];
        if i > 0 {
            s += off[i - 1] * x[i - 1];
        }
        if i + 1 < n {
            s += off[i] * x[i + 1];
        }
        y[i] = s;
    }
}

/// The dense form of a runtime-sized symmetric tridiagonal matrix.
#[cfg(feature = "alloc")]
pub fn tridiagonal_to_dmatrix(diag: &[f64], off: &[f64]) -> nalgebra::DMatrix<f64> {
    let n = diag.len();
    nalgebra::DMatrix::from_fn(n, n, |i, j| tridiagonal_entry(diag, off, i, j))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dense_form_and_product_agree() {
        let t = Tridiagonal::<3, 2>::new([1.0, 2.0, 3.0], [0.5, -1.0]);
        let d = t.to_dense();
        assert_eq!(d, d.transpose());
        let x = [1.0, -2.0, 0.5];
        let y = t.mul_vec(&x);
        let yd = d * nalgebra::Vector3::from(x);
        for i in 0..3 {
            assert!((y[i] - yd[i]).abs() < 1e-15);
        }
        assert_eq!(t.get(0, 2), 0.0);
        assert_eq!(t.get(2, 1), -1.0);
    }
}
