//! Linear algebra on the chain's banded matrices (symmetric tridiagonal): spectra, lowest modes,
//! Sturm counts and solves in O(n) to O(n^2), where a dense decomposition would cost O(n^3).
//!
//! A symmetric tridiagonal matrix `T` is given by two slices: `diag` (length `n`) and `off`
//! (length `n - 1`, `off[i] = T[i][i+1] = T[i+1][i]`), as in [`Tridiagonal`](crate::Tridiagonal).
//! One algorithm per file:
//!
//! | file | algorithm | cost |
//! |---|---|---|
//! | [`sturm`] | [`count_below`]: Sturm count, the inertia of `T - x I` (the Morse index at `x = 0`) | O(n) |
//! | [`bisection`] | [`eigenvalues_in_index_range`]: bisection on Sturm counts | O(n) per eigenvalue |
//! | [`ql`] | [`eigenvalues`], [`eigenpairs`]: implicit QL with Wilkinson shifts | O(n^2), O(n^3) with vectors |
//! | [`inverse_iteration`] | [`lowest_eigenpairs`], [`eigenpairs_near`]: bisection, then inverse iteration with re-orthogonalised clusters | O(n) per eigenpair |
//! | [`solve`](mod@solve) | [`solve`](fn@solve), [`solve_shifted`]: Gaussian elimination with partial pivoting | O(n) |
//!
//! Every function checks its input (except the hot [`count_below`], which has the checked
//! [`try_count_below`]) and reports a [`LinalgError`] carrying the numbers instead of panicking
//! or returning NaN. Internally each algorithm works on the matrix scaled by a power of two
//! (exact), so the units of the stiffness do not matter. Eigenvalues are accurate to a few
//! `eps ||T||` (`||T||` the largest absolute row sum) and eigenvectors have residuals
//! `||T v - lambda v||` of the same order, which is what backward-stable methods promise.

mod bands;
pub mod bisection;
pub mod error;
pub mod inverse_iteration;
pub mod ql;
pub mod solve;
pub mod sturm;

pub use bisection::eigenvalues_in_index_range;
pub use error::{Input, LinalgError};
pub use inverse_iteration::{Eigenpair, eigenpairs_in_index_range, eigenpairs_near, lowest_eigenpairs};
pub use ql::{eigenpairs, eigenvalues, eigenvalues_ql};
pub use solve::{solve, solve_shifted};
pub use sturm::{count_below, try_count_below};
