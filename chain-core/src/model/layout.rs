//! How a model lays out the entries of its matrices in the flat slices the capability traits
//! fill: the tangent stiffness ([`Stiffness`](super::Stiffness)), its material part and stress
//! matrix, and the compatibility matrix ([`SpringNetwork`](super::SpringNetwork)).
//!
//! Two forms. The **banded** ones are the rotor chain's fast path (every spring couples two
//! neighbouring rotors, paper Eq. `eq:prestress8`): a symmetric tridiagonal stiffness stored as
//! its diagonal then its superdiagonal, a bidiagonal compatibility matrix stored as its two
//! bands. The **sparse** one fits any spring network: a [`Pattern`] of rows (compressed sparse
//! rows), the values in the pattern's order. A symmetric matrix stores its upper triangle
//! (diagonal included), so every entry is written once.
//!
//! The layout belongs to the model and does not change with the configuration: make the buffer
//! once (`linalg::SymmetricMatrix::for_model` does), fill it at every configuration.

use chain_geometry::Counted;

/// A sparse pattern by rows (compressed sparse rows): row `i` has entries in the columns
/// `columns[row_starts[i]..row_starts[i + 1]]`, strictly ascending, and a matrix with this
/// pattern keeps its values in the same order. `row_starts` has one entry per row and one more
/// (`row_starts[0] = 0`, the last is the number of entries).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pattern<'a> {
    /// The number of columns.
    pub columns_count: usize,
    /// Where each row's entries start in `columns`, and the end of the last row.
    pub row_starts: &'a [usize],
    /// The column of each entry, row after row.
    pub columns: &'a [usize],
}

impl Pattern<'_> {
    /// The number of rows.
    pub fn rows(&self) -> usize {
        self.row_starts.len().saturating_sub(1)
    }

    /// The number of stored entries (and of values).
    pub fn entries(&self) -> usize {
        self.columns.len()
    }

    /// The columns of row `i`.
    ///
    /// # Panics
    /// If `i` is not a row.
    pub fn row(&self, i: usize) -> &[usize] {
        &self.columns[self.row_starts[i]..self.row_starts[i + 1]]
    }

    /// `Ok` if the pattern is well formed: `row_starts` starts at 0, never decreases and ends at
    /// the number of entries; every row's columns are strictly ascending and below
    /// `columns_count`; with `upper`, every entry of a square pattern lies on or above the
    /// diagonal. The error says what is wrong where.
    pub fn check(&self, upper: bool) -> Result<(), PatternError> {
        let starts = self.row_starts;
        if starts.first() != Some(&0) || starts.last() != Some(&self.columns.len()) {
            return Err(PatternError::Bounds {
                first: starts.first().copied(),
                last: starts.last().copied(),
                entries: self.columns.len(),
            });
        }
        for i in 0..self.rows() {
            if starts[i + 1] < starts[i] {
                return Err(PatternError::Decreasing { row: i });
            }
            let row = self.row(i);
            for (k, &c) in row.iter().enumerate() {
                let out_of_range = c >= self.columns_count;
                let unsorted = k > 0 && c <= row[k - 1];
                let below = upper && c < i;
                if out_of_range || unsorted || below {
                    return Err(PatternError::Column {
                        row: i,
                        column: c,
                        columns: self.columns_count,
                        upper,
                    });
                }
            }
        }
        if upper && self.rows() != self.columns_count {
            return Err(PatternError::NotSquare { rows: self.rows(), columns: self.columns_count });
        }
        Ok(())
    }
}

/// A [`Pattern`] that is not well formed (see [`Pattern::check`]).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum PatternError {
    /// `row_starts` does not run from 0 to the number of entries.
    #[error(
        "row_starts must run from 0 to the number of entries ({entries}), but runs from {first:?} to {last:?}"
    )]
    Bounds {
        /// The first row start, if any.
        first: Option<usize>,
        /// The last row start, if any.
        last: Option<usize>,
        /// The number of entries.
        entries: usize,
    },
    /// A row starts before the previous one.
    #[error("row_starts decreases after row {row}")]
    Decreasing {
        /// The row whose end lies before its start.
        row: usize,
    },
    /// A column out of range, out of order, or (`upper`) below the diagonal.
    #[error(
        "row {row} has column {column}: columns must be ascending and below {columns}{}",
        if *upper { ", and on or above the diagonal" } else { "" }
    )]
    Column {
        /// The row.
        row: usize,
        /// The offending column.
        column: usize,
        /// The number of columns.
        columns: usize,
        /// Whether the pattern is a symmetric matrix's upper triangle.
        upper: bool,
    },
    /// A symmetric matrix's pattern that is not square.
    #[error("a symmetric matrix's pattern must be square, this one is {rows} x {columns}")]
    NotSquare {
        /// Rows.
        rows: usize,
        /// Columns.
        columns: usize,
    },
}

/// How the values of a symmetric matrix over the degrees of freedom are laid out: the tangent
/// stiffness, and for a spring network its material part and stress matrix.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum StiffnessLayout<'a> {
    /// Symmetric tridiagonal: the `n` diagonal entries `K[i][i]`, then the `n - 1` entries
    /// `K[i][i + 1]` (`2n - 1` values). The rotor chain's form ([`split_tridiagonal`]).
    Tridiagonal,
    /// Symmetric, its upper triangle (diagonal included) by rows in this pattern.
    Upper(Pattern<'a>),
}

impl StiffnessLayout<'_> {
    /// The number of values of an `n x n` matrix in this layout.
    pub fn values(&self, n: usize) -> usize {
        match self {
            StiffnessLayout::Tridiagonal => (2 * n).saturating_sub(1),
            StiffnessLayout::Upper(p) => p.entries(),
        }
    }
}

/// How the values of the compatibility matrix (one row per spring, one column per degree of
/// freedom) are laid out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum CompatibilityLayout<'a> {
    /// Bidiagonal, `m` springs by `m + 1` degrees of freedom: the `m` entries `C[p][p]`, then the
    /// `m` entries `C[p][p + 1]` (`2m` values). The rotor chain's form ([`split_bidiagonal`]).
    Bidiagonal,
    /// General, by rows (springs) in this pattern.
    Sparse(Pattern<'a>),
}

impl CompatibilityLayout<'_> {
    /// The number of values of a matrix of `m` springs in this layout.
    pub fn values(&self, m: usize) -> usize {
        match self {
            CompatibilityLayout::Bidiagonal => 2 * m,
            CompatibilityLayout::Sparse(p) => p.entries(),
        }
    }
}

/// The two bands of a tridiagonal matrix of `n` rows laid out as [`StiffnessLayout::Tridiagonal`]:
/// `(diag, off)`.
///
/// # Panics
/// If `values` does not hold `2n - 1` numbers (a programming error of the caller: the panic
/// names both counts, at the caller's line).
#[inline(always)]
#[track_caller]
pub fn split_tridiagonal<T>(n: usize, values: &mut [T]) -> (&mut [T], &mut [T]) {
    if n == 0 || values.len() != 2 * n - 1 {
        wrong_values(values.len(), (2 * n).saturating_sub(1), "a tridiagonal matrix", n, "row");
    }
    values.split_at_mut(n)
}

/// [`split_tridiagonal`] for reading.
///
/// # Panics
/// As [`split_tridiagonal`].
#[inline(always)]
#[track_caller]
pub fn tridiagonal_parts<T>(n: usize, values: &[T]) -> (&[T], &[T]) {
    if n == 0 || values.len() != 2 * n - 1 {
        wrong_values(values.len(), (2 * n).saturating_sub(1), "a tridiagonal matrix", n, "row");
    }
    values.split_at(n)
}

/// The two bands `(left, right)` of a bidiagonal matrix of `m` rows laid out as
/// [`CompatibilityLayout::Bidiagonal`].
///
/// # Panics
/// If `values` does not hold `2m` numbers (named, at the caller's line).
#[inline(always)]
#[track_caller]
pub fn split_bidiagonal<T>(m: usize, values: &mut [T]) -> (&mut [T], &mut [T]) {
    if values.len() != 2 * m {
        wrong_values(values.len(), 2 * m, "a bidiagonal matrix", m, "spring");
    }
    values.split_at_mut(m)
}

/// [`split_bidiagonal`] for reading.
///
/// # Panics
/// As [`split_bidiagonal`].
#[inline(always)]
#[track_caller]
pub fn bidiagonal_parts<T>(m: usize, values: &[T]) -> (&[T], &[T]) {
    if values.len() != 2 * m {
        wrong_values(values.len(), 2 * m, "a bidiagonal matrix", m, "spring");
    }
    values.split_at(m)
}

#[cold]
#[inline(never)]
#[track_caller]
fn wrong_values(len: usize, expected: usize, what: &str, rows: usize, unit: &str) -> ! {
    panic!("values has {}, {what} of {} needs {expected}", Counted(len, "value"), Counted(rows, unit))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patterns_are_checked() {
        let ok = Pattern { columns_count: 3, row_starts: &[0, 2, 3, 4], columns: &[0, 1, 1, 2] };
        assert_eq!(ok.check(true), Ok(()));
        assert_eq!(ok.row(0), &[0, 1]);
        let below = Pattern { columns_count: 3, row_starts: &[0, 1, 2, 3], columns: &[0, 0, 2] };
        assert!(matches!(below.check(true), Err(PatternError::Column { row: 1, column: 0, .. })));
        assert_eq!(below.check(false), Ok(()));
        let unsorted = Pattern { columns_count: 3, row_starts: &[0, 2], columns: &[2, 1] };
        assert!(matches!(unsorted.check(false), Err(PatternError::Column { row: 0, column: 1, .. })));
        let bounds = Pattern { columns_count: 3, row_starts: &[0, 3], columns: &[0, 1] };
        assert!(matches!(bounds.check(false), Err(PatternError::Bounds { .. })));
        let wide = Pattern { columns_count: 2, row_starts: &[0, 1], columns: &[5] };
        assert!(matches!(wide.check(false), Err(PatternError::Column { column: 5, .. })));
    }

    #[test]
    fn banded_values_split_into_their_bands() {
        let mut v = [1.0, 2.0, 3.0, 4.0, 5.0];
        let (d, o) = split_tridiagonal(3, &mut v);
        assert_eq!((d.len(), o.len()), (3, 2));
        assert_eq!(StiffnessLayout::Tridiagonal.values(3), 5);
        assert_eq!(CompatibilityLayout::Bidiagonal.values(2), 4);
        let (l, r) = bidiagonal_parts(2, &[1.0, 2.0, 3.0, 4.0]);
        assert_eq!((l, r), (&[1.0, 2.0][..], &[3.0, 4.0][..]));
    }

    #[test]
    #[should_panic(expected = "values has 4 values, a tridiagonal matrix of 3 rows needs 5")]
    fn a_wrong_length_names_both_counts() {
        let mut v = [0.0; 4];
        let _ = split_tridiagonal(3, &mut v);
    }
}
