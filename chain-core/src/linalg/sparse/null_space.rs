//! The null spaces of a sparse rectangular matrix `C` (`m x n`, by rows): `dim ker C` and
//! `dim ker C^T` by inertia counts of the Gram matrices `C^T C - tau I` and `C C^T - tau I`
//! ([`lblt`](super::lblt), Sylvester's law: the eigenvalues below `tau` are the negative pivots),
//! and bases of both by shift-invert block subspace iteration ([`eigen`]) on the
//! same Gram matrices. A network's Maxwell-Calladine count beyond the dense bound
//! (`statics::counting`) runs here.
//!
//! **Candidates.** `C^T C` is formed in floating point (each entry a sum of at most `m` products,
//! error below `m eps ||C^T C||_inf`), and a factorization is accepted when its backward error is
//! below `64 n eps` ([`MAX_BACKWARD_ERROR_FACTOR`](super::lblt::MAX_BACKWARD_ERROR_FACTOR)): its
//! inertia is exact for a matrix within `(m + 64 n) eps ||C^T C||_inf` of `C^T C`, so by Weyl's
//! inequality (and `||E||_2 <= ||E||_inf` for symmetric `E`) an eigenvalue `sigma^2` is seen within
//! that distance of itself. The candidates are the eigenvalues below
//! `tau = tolerance^2 + `[`ROUNDING_FACTOR`]` max(n, m) eps ||C^T C||_inf`, twice the larger of the
//! two terms' worst case above the square of the tolerance: every singular value at or below the
//! tolerance is a candidate. The Gram matrix alone cannot tell apart singular values below about
//! `sqrt(tau)` (`5e-6 ||C||` at 1000 rows), so it only chooses the candidates.
//!
//! **The count.** The singular values of `C` on the candidates' span are computed from `C` itself
//! ([`refine`]: `C V`, its QR, a small dense SVD; accurate to a few `eps ||C||`), and the dense
//! SVD's rule decides: zero at or below `max(n, m) eps sigma_max` (or the caller's tolerance). The
//! same on `C^T` with the candidates of `C C^T` counts the self-stresses, and the index theorem
//! `dim ker C - dim ker C^T = n - m` checks the two counts against each other (and the candidate
//! counts, `C^T C` and `C C^T` having the same nonzero eigenvalues).
//!
//! **Stopping.** A stop question is asked before each factorization and at every iteration of the
//! subspace iteration, per column of its `O(n p^2)` parts (`eigen::eigenpairs_with`).

use alloc::vec::Vec;

use super::Upper;
use super::eigen::{self, Target};
use super::lblt::{Lblt, try_vec};
use super::refine;
use crate::linalg::{Eigenpair, LinalgError};

/// The threshold's multiple of `max(n, m) eps ||C^T C||_inf` (see the module doc): twice the
/// accepted backward error's factor.
pub const ROUNDING_FACTOR: f64 = 2.0 * super::lblt::MAX_BACKWARD_ERROR_FACTOR;

/// Subspace iterations after the residuals are met: the candidates' components along the other
/// singular vectors (each iteration divides them by the gap's ratio, about `1e-5` on a lattice)
/// reach the rounding floor, so that `C` on their span shows its own small singular values and not
/// those components (two more: `5.6e-13` left on the translations of a twisted kagome, whose dense
/// tolerance is `3.3e-13`, without them; `6e-16` with them).
const POLISH: usize = 2;

/// The candidates take in every singular value below `SPAN_FACTOR sigma_max / max(n, m)` as well
/// as those the Gram matrix cannot resolve: a null vector of the rounded Gram matrix carries a
/// component `~ eps ||C||^2 / sigma^2` along each singular vector of value `sigma` outside the
/// candidates, which `C` maps to `eps ||C||^2 / sigma`; with `sigma` above this bound that is below
/// `max(n, m) eps ||C|| / 64`, a 64th of the dense rule's tolerance. (Without it a square patch
/// whose line modes a disturbance lifted to `1e-2` left its translations at `1e-13`, above the
/// tolerance `1.3e-14`.)
const SPAN_FACTOR: f64 = 64.0;

/// A sparse matrix by rows: each row's `(column, value)` entries, ascending, between
/// `starts[p]..starts[p + 1]`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rows<'a> {
    pub columns: usize,
    pub starts: &'a [usize],
    pub entries: &'a [(usize, f64)],
}

impl Rows<'_> {
    pub(crate) fn rows(&self) -> usize {
        self.starts.len() - 1
    }

    fn row(&self, p: usize) -> &[(usize, f64)] {
        &self.entries[self.starts[p]..self.starts[p + 1]]
    }

    /// `y = M x` (`x` one entry per column, `y` one per row).
    pub(crate) fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        for (p, y) in y.iter_mut().enumerate().take(self.rows()) {
            *y = self.row(p).iter().fold(0.0, |s, &(i, v)| s + v * x[i]);
        }
    }
}

/// A matrix by rows, owned.
struct OwnedRows {
    columns: usize,
    starts: Vec<usize>,
    entries: Vec<(usize, f64)>,
}

impl OwnedRows {
    fn view(&self) -> Rows<'_> {
        Rows { columns: self.columns, starts: &self.starts, entries: &self.entries }
    }
}

/// The transpose, by rows (a counting sort by column, so each row stays ascending).
fn transpose(c: Rows<'_>) -> Result<OwnedRows, LinalgError> {
    let mut starts = try_vec(c.columns + 1)?;
    starts.resize(c.columns + 1, 0);
    for &(j, _) in c.entries {
        starts[j + 1] += 1;
    }
    for j in 0..c.columns {
        starts[j + 1] += starts[j];
    }
    let mut next = starts.clone();
    let mut entries = try_vec(c.entries.len())?;
    entries.resize(c.entries.len(), (0, 0.0));
    for p in 0..c.rows() {
        for &(j, v) in c.row(p) {
            entries[next[j]] = (p, v);
            next[j] += 1;
        }
    }
    Ok(OwnedRows { columns: c.rows(), starts, entries })
}

/// The upper triangle of a symmetric matrix by rows, owned.
struct Gram {
    n: usize,
    row_starts: Vec<usize>,
    columns: Vec<usize>,
    values: Vec<f64>,
}

impl Gram {
    fn upper(&self) -> Upper<'_> {
        Upper { n: self.n, row_starts: &self.row_starts, columns: &self.columns, values: &self.values }
    }

    /// `||G||_inf` (row sums of the full symmetric matrix).
    fn inf_norm(&self) -> f64 {
        let mut rows = alloc::vec![0.0; self.n];
        for i in 0..self.n {
            for k in self.row_starts[i]..self.row_starts[i + 1] {
                let (j, v) = (self.columns[k], self.values[k].abs());
                rows[i] += v;
                if j != i {
                    rows[j] += v;
                }
            }
        }
        rows.into_iter().fold(0.0, f64::max)
    }
}

/// The upper triangle of `M^T M` (`l x l`) from `M` by rows (`k x l`) and its transpose `t`: row
/// `i` is the sum over `M_pi != 0` of `M_pi` times row `p` of `M`, from column `i` on.
fn gram(m: Rows<'_>, t: Rows<'_>) -> Result<Gram, LinalgError> {
    let l = m.columns;
    let mut row_starts = try_vec(l + 1)?;
    row_starts.push(0);
    let (mut columns, mut values) = (Vec::new(), Vec::new());
    let mut sum = try_vec(l)?;
    sum.resize(l, 0.0);
    let mut seen = try_vec(l)?;
    seen.resize(l, false);
    let mut touched: Vec<usize> = Vec::new();
    for i in 0..l {
        for &(p, mpi) in t.row(i) {
            for &(j, mpj) in m.row(p) {
                if j >= i {
                    if !seen[j] {
                        seen[j] = true;
                        touched.push(j);
                    }
                    sum[j] += mpi * mpj;
                }
            }
        }
        touched.sort_unstable();
        let more = touched.len();
        columns.try_reserve(more).map_err(|_| out_of_memory::<usize>(columns.len() + more))?;
        values.try_reserve(more).map_err(|_| out_of_memory::<f64>(values.len() + more))?;
        for &j in &touched {
            columns.push(j);
            values.push(sum[j]);
            sum[j] = 0.0;
            seen[j] = false;
        }
        touched.clear();
        row_starts.push(columns.len());
    }
    Ok(Gram { n: l, row_starts, columns, values })
}

fn out_of_memory<T>(len: usize) -> LinalgError {
    LinalgError::OutOfMemory { bytes: crate::allocation::bytes_of::<T>(len), what: "a Gram matrix" }
}

/// The null spaces of `C`.
#[derive(Clone, Debug)]
pub(crate) struct NullSpaces {
    /// The tolerance on the singular values: at or below it they count as zero.
    pub tolerance: f64,
    /// The largest singular value of `C`, by power iteration ([`refine::largest_singular_value`]:
    /// from below).
    pub sigma_max: f64,
    /// The singular values of `C` on the candidates of its null space (the eigenvectors of `C^T C`
    /// below `tau`), ascending.
    pub right_values: Vec<f64>,
    /// An orthonormal basis of `ker C`: the candidates' combinations with singular values at or
    /// below the tolerance.
    pub zero_modes: Vec<Vec<f64>>,
    /// An orthonormal basis of `ker C^T`.
    pub self_stresses: Vec<Vec<f64>>,
}

/// Counts and bases of the null spaces of `C` and `C^T`, the dense SVD's rule applied to singular
/// values computed on the Gram matrices' candidates ([`refine`]): a singular value counts as zero
/// at or below `tolerance`, by default `max(n, m) eps sigma_max` (`sigma_max` by power iteration,
/// [`refine::largest_singular_value`]). The candidates are the eigenvectors of `C^T C` (and
/// `C C^T`) below `tau = tolerance^2 + `[`ROUNDING_FACTOR`]` max(n, m) eps ||C^T C||_inf` (see the
/// module doc): every singular value at or below the tolerance is among them.
///
/// # Errors
/// A failed allocation, an unstable factorization, a subspace iteration that does not converge or
/// misses an eigenvalue, counts that break the index theorem ([`LinalgError::Missed`]: the left
/// count, then what `n - m` asks), or `Stopped` when `stop` answered yes.
pub(crate) fn null_spaces(
    c: Rows<'_>,
    tolerance: Option<f64>,
    stop: &mut dyn FnMut() -> bool,
) -> Result<NullSpaces, LinalgError> {
    let (m, n) = (c.rows(), c.columns);
    let t = transpose(c)?;
    let ctc = gram(c, t.view())?;
    let norm = ctc.inf_norm();
    if norm == 0.0 {
        // No nonzero entry: every vector is in both null spaces.
        let unit = |len: usize| -> Vec<Vec<f64>> {
            (0..len).map(|i| (0..len).map(|j| f64::from(u8::from(i == j))).collect()).collect()
        };
        return Ok(NullSpaces {
            tolerance: tolerance.unwrap_or(0.0),
            sigma_max: 0.0,
            right_values: alloc::vec![0.0; n],
            zero_modes: unit(n),
            self_stresses: unit(m),
        });
    }
    let side = n.max(m) as f64;
    let sigma_max = refine::largest_singular_value(c, t.view(), stop)?;
    let tolerance = tolerance.unwrap_or(side * f64::EPSILON * sigma_max);
    let tau = (tolerance * tolerance + ROUNDING_FACTOR * side * f64::EPSILON * norm)
        .max((SPAN_FACTOR * sigma_max / side) * (SPAN_FACTOR * sigma_max / side));
    let stopped = |done| LinalgError::Stopped { what: "inertia counts", done, of: 2 };
    if stop() {
        return Err(stopped(0));
    }
    let right = Lblt::new(&ctc.upper(), tau)?.inertia().negative;
    if stop() {
        return Err(stopped(1));
    }
    let cct = gram(t.view(), c)?;
    let left = Lblt::new(&cct.upper(), tau)?.inertia().negative;
    if right as isize - left as isize != n as isize - m as isize {
        return Err(LinalgError::Missed { below: tau, counted: left, found: (right + m).saturating_sub(n) });
    }
    let right_pairs = eigen::eigenpairs_with(&ctc.upper(), norm, Target::Lowest, right, POLISH, stop)?;
    let left_pairs =
        eigen::eigenpairs_with(&cct.upper(), cct.inf_norm(), Target::Lowest, left, POLISH, stop)?;
    // The pairs' eigenvalues and the inertia counts come from different computations: both must
    // put the same number below tau.
    let below = |pairs: &[Eigenpair]| pairs.iter().filter(|p| p.value < tau).count();
    if below(&right_pairs) != right {
        return Err(LinalgError::Missed { below: tau, counted: right, found: below(&right_pairs) });
    }
    if below(&left_pairs) != left {
        return Err(LinalgError::Missed { below: tau, counted: left, found: below(&left_pairs) });
    }
    fn vectors(pairs: &[Eigenpair]) -> Vec<&[f64]> {
        pairs.iter().map(|p| p.vector.as_slice()).collect()
    }
    let zero = refine::on_subspace(c, &vectors(&right_pairs), tolerance)?;
    let stress = refine::on_subspace(t.view(), &vectors(&left_pairs), tolerance)?;
    let (zero_count, stress_count) = (zero.vectors.len(), stress.vectors.len());
    if zero_count as isize - stress_count as isize != n as isize - m as isize {
        return Err(LinalgError::Missed {
            below: tolerance,
            counted: stress_count,
            found: (zero_count + m).saturating_sub(n),
        });
    }
    Ok(NullSpaces {
        tolerance,
        sigma_max,
        right_values: zero.values,
        zero_modes: zero.vectors,
        self_stresses: stress.vectors,
    })
}
