//! Errors of the linear algebra (tridiagonal, dense and sparse). Each carries the numbers that explain it.

use core::fmt;

use chain_geometry::Short;

/// Which input of a linear-algebra call held a bad number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Input {
    /// The diagonal `diag`.
    Diag,
    /// The off-diagonal `off` (`off[i]` is entry `(i, i + 1)`).
    Off,
    /// The right-hand side of a solve.
    Rhs,
    /// A scalar: the shift of a solve, the point of a Sturm count, or the target of
    /// [`eigenpairs_near`](super::eigenpairs_near).
    Shift,
    /// The matrix's values.
    Matrix,
}

impl fmt::Display for Input {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Input::Diag => "diag",
            Input::Off => "off",
            Input::Rhs => "rhs",
            Input::Shift => "shift",
            Input::Matrix => "the matrix's values",
        })
    }
}

/// A tridiagonal computation that could not be carried out.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LinalgError {
    /// `off` must have one entry fewer than `diag` (none when `diag` has at most one).
    #[error(
        "off has {}, but a matrix with {} needs {expected}",
        chain_geometry::Counted(*off, "value"),
        chain_geometry::Counted(*diag, "diagonal value"),
        expected = .diag.saturating_sub(1)
    )]
    DimensionMismatch {
        /// Length of the diagonal.
        diag: usize,
        /// Length of the off-diagonal (must be one less).
        off: usize,
    },
    /// The right-hand side of a solve must have one entry per row.
    #[error("the right-hand side has {rhs} entries, but the matrix has {n} rows")]
    RhsMismatch {
        /// The matrix size.
        n: usize,
        /// The right-hand side's length.
        rhs: usize,
    },
    /// A NaN or an infinity in the input.
    #[error("{input}[{index}] = {value} is not finite", value = Short(*value))]
    NotFinite {
        /// Which input.
        input: Input,
        /// Which entry.
        index: usize,
        /// The value found.
        value: f64,
    },
    /// Eigenvalues `lo..hi` (0-based, ascending) were asked for, but the matrix has `n`.
    #[error("eigenvalues {lo}..{hi} were asked for, but the matrix has {n}")]
    IndexOutOfRange {
        /// The first index asked for.
        lo: usize,
        /// The last index asked for.
        hi: usize,
        /// The matrix size.
        n: usize,
    },
    /// Gaussian elimination met a zero pivot (0-based `row` of `U`), or the solution overflows:
    /// the matrix is singular to working precision. `pivot` is the smallest pivot of `U`.
    #[error("the matrix is singular to working precision: pivot {pivot:e} in row {row}")]
    Singular {
        /// The row whose pivot vanished.
        row: usize,
        /// The pivot.
        pivot: f64,
    },
    /// An iteration stopped before converging: the QL iteration on eigenvalue `index` (with
    /// `residual` the off-diagonal entry left), or inverse iteration on the eigenvalue of
    /// ascending `index` (with `residual` = `||T v - lambda v||`).
    #[error("no convergence for eigenvalue {index} after {iterations} iterations: residual {residual:e}")]
    NoConvergence {
        /// Iterations used.
        iterations: usize,
        /// Which eigenpair.
        index: usize,
        /// The residual reached (relative, as the message says).
        residual: f64,
    },
    /// A sparse pattern that is not well formed.
    #[error("sparse pattern: {0}")]
    Pattern(#[from] crate::model::PatternError),
    /// A matrix whose pattern does not fit the model's number of degrees of freedom.
    #[error("the pattern has {found} rows, the model {expected} degrees of freedom")]
    WrongDimension {
        /// The model's degrees of freedom.
        expected: usize,
        /// The pattern's rows.
        found: usize,
    },
    /// The caller's stop question (Ctrl-C in Python) answered yes: the computation stopped after
    /// `done` of its `of` steps (eigenvalues, eigenvectors or iterations, as `what` says).
    #[error("stopped on request after {done} of {of} {what}")]
    Stopped {
        /// What the steps are.
        what: &'static str,
        /// Steps finished.
        done: usize,
        /// Steps there were to do (an upper bound for iterations).
        of: usize,
    },
    /// A sparse matrix too large for the dense path (`n x n` numbers above the bound).
    #[error("a {n} x {n} matrix is too large for the dense algorithms: at most {max} numbers")]
    TooLarge {
        /// The dimension.
        n: usize,
        /// [`super::MAX_DENSE_VALUES`], or the sparse factor's bound
        /// [`sparse::lblt::MAX_FACTOR_VALUES`](super::sparse::lblt::MAX_FACTOR_VALUES).
        max: usize,
    },
    /// An allocation sized by the input failed (or its size overflowed).
    #[error("cannot allocate {bytes} bytes for {what}")]
    OutOfMemory {
        /// The bytes asked for (`usize::MAX` when the size itself overflows).
        bytes: usize,
        /// What they were for.
        what: &'static str,
    },
    /// A sparse factorization of `A - shift I` whose backward error is too large to trust its
    /// inertia or its solves (pivot growth the intranode pivoting could not avoid).
    #[error("the factorization of A - {shift:e} I has backward error {backward_error:e} (at most {bound:e})")]
    Unstable {
        /// The shift.
        shift: f64,
        /// The backward error of a test solve with the factors.
        backward_error: f64,
        /// The bound.
        bound: f64,
    },
    /// The sparse eigensolver's result disagrees with an inertia count: `counted` eigenvalues lie
    /// in the inner part of the found range (below `below`), but `found` of the returned ones do.
    #[error(
        "{counted} eigenvalues lie below {below:e} in the found range, but the eigensolver found {found}"
    )]
    Missed {
        /// The end of the range compared.
        below: f64,
        /// Eigenvalues there by Sylvester's law of inertia.
        counted: usize,
        /// Eigenvalues there among those found.
        found: usize,
    },
}

#[cfg(feature = "alloc")]
impl From<crate::allocation::AllocationError> for LinalgError {
    fn from(e: crate::allocation::AllocationError) -> Self {
        LinalgError::OutOfMemory { bytes: e.bytes, what: e.what }
    }
}
