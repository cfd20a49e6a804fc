//! Linear algebra of the analyses (with `alloc`; the errors always): [`SymmetricMatrix`], a
//! model's tangent stiffness in its layout with the algorithms the analyses need, and beneath it
//! the chain's fast path on banded matrices (symmetric tridiagonal): spectra, lowest modes, Sturm
//! counts and solves in O(n) to O(n^2), where a dense decomposition would cost O(n^3).
//!
//! A symmetric tridiagonal matrix `T` is given by two slices: `diag` (length `n`) and `off`
//! (length `n - 1`, `off[i] = T[i][i+1] = T[i+1][i]`), as in [`Tridiagonal`](crate::Tridiagonal).
//! One algorithm per file:
//!
//! - [`sturm`]: [`count_below`], the Sturm count, from the inertia of `T - x I` (at `x = 0` the
//!   Morse index). O(n).
//! - [`bisection`]: [`eigenvalues_in_index_range`], bisection on Sturm counts. O(n) per
//!   eigenvalue.
//! - [`ql`]: [`eigenvalues`], [`eigenpairs`], the implicit QL iteration with Wilkinson shifts.
//!   O(n^2), and O(n^3) with the eigenvectors.
//! - [`inverse_iteration`]: [`lowest_eigenpairs`], [`eigenpairs_near`],
//!   [`eigenpairs_in_index_range`], bisection and then inverse iteration, re-orthogonalised
//!   within clusters. O(n) per eigenpair outside large clusters.
//!
//! The long computations take a stop question (`..._with`), asked at every QL iteration and
//! before each bisected eigenvalue and each inverse iteration, and end with
//! [`LinalgError::Stopped`] when it answers yes.
//! - `golub_kahan`: a bidiagonal's singular values to relative accuracy and its null spaces,
//!   through the Sturm counts and inverse iteration of its Golub-Kahan tridiagonal. O(n) per
//!   count (the chain's Maxwell-Calladine counting).
//! - [`solve`](mod@solve): [`solve`](fn@solve), [`solve_shifted`], Gaussian elimination with
//!   partial pivoting. O(n).
//!
//! - [`SymmetricMatrix`] (`symmetric.rs`): the tridiagonal path through the functions above, a
//!   sparse upper triangle through dense decompositions up to [`DENSE_LIMIT`] rows and through
//!   [`sparse`] (a sparse `LBL^T` and shift-invert subspace iteration) beyond.
//!
//! What they share (input checks, exact scaling, norms) is in the private `bands.rs`.
//!
//! ```
//! use chain_core::linalg;
//!
//! // The stiffness of a free chain of five unit springs: one zero mode, the uniform rotation.
//! let diag = [1.0, 2.0, 2.0, 2.0, 1.0];
//! let off = [-1.0; 4];
//! assert_eq!(linalg::count_below(&diag, &off, -1e-12), 0); // no negative eigenvalue: stable
//! assert_eq!(linalg::count_below(&diag, &off, 1e-12), 1); // one zero mode
//! let modes = linalg::lowest_eigenpairs(&diag, &off, 2)?;
//! assert!(modes[0].value.abs() < 1e-14);
//! assert!(modes[0].vector.iter().all(|&x| (x - 1.0 / 5f64.sqrt()).abs() < 1e-14));
//! // The others are 2 - 2 cos(j pi / 5).
//! assert!((modes[1].value - (2.0 - 2.0 * (std::f64::consts::PI / 5.0).cos())).abs() < 1e-14);
//! let x = linalg::solve_shifted(&diag, &off, -1.0, &[1.0, 0.0, 0.0, 0.0, -1.0])?;
//! assert!((x[0] + x[4]).abs() < 1e-15);
//! # Ok::<(), linalg::LinalgError>(())
//! ```
//!
//! Every function checks its input (except the hot [`count_below`], which has the checked
//! [`try_count_below`]) and reports a [`LinalgError`] carrying the numbers instead of panicking
//! or returning NaN. Internally each algorithm works on the matrix scaled by a power of two
//! (exact), so the units of the stiffness do not matter. Eigenvalues are accurate to a few
//! `eps ||T||` (`||T||` the largest absolute row sum) and eigenvectors have residuals
//! `||T v - lambda v||` of the same order, which is what backward-stable methods promise.

#[cfg(feature = "alloc")]
mod bands;
#[cfg(feature = "alloc")]
pub mod bisection;
pub mod error;
#[cfg(feature = "alloc")]
pub(crate) mod golub_kahan;
#[cfg(feature = "alloc")]
pub mod inverse_iteration;
#[cfg(feature = "alloc")]
pub mod ql;
#[cfg(feature = "alloc")]
pub mod solve;
#[cfg(feature = "alloc")]
pub mod sparse;
#[cfg(feature = "alloc")]
pub mod sturm;
#[cfg(feature = "alloc")]
mod symmetric;

#[cfg(feature = "alloc")]
pub use bisection::eigenvalues_in_index_range;
pub use error::{Input, LinalgError};
#[cfg(feature = "alloc")]
pub use inverse_iteration::{
    Eigenpair, eigenpairs_in_index_range, eigenpairs_in_index_range_with, eigenpairs_near, lowest_eigenpairs,
};
#[cfg(feature = "alloc")]
pub use ql::{eigenpairs, eigenpairs_with, eigenvalues, eigenvalues_ql};
#[cfg(feature = "alloc")]
pub use solve::{solve, solve_shifted};
#[cfg(feature = "alloc")]
pub use sturm::{count_below, try_count_below};
#[cfg(feature = "alloc")]
pub use symmetric::{DENSE_FACTOR_LIMIT, DENSE_LIMIT, MAX_DENSE_VALUES, SymmetricMatrix};
