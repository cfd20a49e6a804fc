//! Selected eigenpairs: eigenvalues by bisection ([`bisection`](super::bisection)), eigenvectors
//! by inverse iteration, as in LAPACK's `dstein` (Peters & Wilkinson, *The calculation of
//! specified eigenvectors by inverse iteration*, Handbook for Automatic Computation II/18, 1971;
//! Jessup & Ipsen, *SIAM J. Sci. Stat. Comput.* 13, 1992; Golub & Van Loan, *Matrix
//! Computations*, 4th ed., Sec. 8.2; Parlett, *The Symmetric Eigenvalue Problem*, Ch. 4).
//!
//! For an eigenvalue estimate `lambda` accurate to a few `eps ||T||`, one or two solves
//! `(T - lambda I) v_{k+1} = v_k` from a random start give a vector with a residual
//! `||T v - lambda v||` of a few `eps ||T||`. The solves use the pivoted LU factors of
//! [`solve`](mod@super::solve), with pivots below `eps ||T||` raised to `+-eps ||T||` (the matrix
//! is singular to working precision at an eigenvalue). Iteration stops one solve after the
//! residual first falls below `64 eps ||T|| sqrt(n)`: rounding errors grow like `sqrt(n)`, and
//! the factor leaves room for the last vectors of a tight cluster, which inherit the errors of
//! the earlier ones (LAPACK's test is looser still, about `n^1.5 eps ||T||`).
//!
//! **Clusters.** Residuals alone do not make the vectors of close eigenvalues orthogonal.
//! Eigenvalues closer than `1e-3 ||T||` to their neighbour form a cluster (`dstein`'s rule), and
//! each new vector is orthogonalised against the cluster's earlier vectors by modified
//! Gram-Schmidt after every solve, and once more at the end ("twice is enough"). Equal shifts
//! inside a cluster are moved `10 eps |lambda|` apart, as in `dstein`; the step is relative so
//! that a numerically degenerate cluster at zero (the chain's near-zero modes, decoupled
//! blocks) keeps its shifts on its eigenvalues. There the solves amplify the whole degenerate
//! subspace, and the different random starts, orthogonalised, span it. Vectors of different
//! clusters are orthogonal to about `(r_i + r_j) / gap`, at most `1e3` times the residuals
//! relative to `||T||` (in practice about `1e-14`).
//!
//! Cost: bisection O(n (hi - lo)), then O(n) per solve, 1 to 3 solves per vector, plus
//! O(n c) per vector for a cluster of `c`: O(n k) for `k` eigenpairs in small clusters.

use alloc::vec::Vec;

use super::bands::{self, Scaled};
use super::bisection::{Accuracy, bisect};
use super::error::{Input, LinalgError};
use super::ql::eigenpairs_with;
use super::solve::TridiagonalLu;
use super::sturm::Sturm;
use crate::math;

/// An eigenvalue and its unit eigenvector (entry of largest magnitude positive).
#[derive(Clone, Debug, PartialEq)]
pub struct Eigenpair {
    /// The eigenvalue.
    pub value: f64,
    /// Its eigenvector, unit length.
    pub vector: Vec<f64>,
}

/// The `k` smallest eigenvalues of the symmetric tridiagonal matrix (`diag`, `off`), ascending,
/// with orthonormal eigenvectors. O(n k) for well separated or small clusters.
pub fn lowest_eigenpairs(diag: &[f64], off: &[f64], k: usize) -> Result<Vec<Eigenpair>, LinalgError> {
    eigenpairs_in_index_range(diag, off, 0, k)
}

/// Eigenpairs `lo..hi` (0-based, ascending: `lo = 0` is the smallest eigenvalue), with
/// orthonormal eigenvectors. All of them (`0..n`) come from the QL iteration
/// ([`eigenpairs`](super::eigenpairs), O(n^3)) as LAPACK's `dstevx` does; a part of the spectrum
/// from bisection and inverse iteration.
pub fn eigenpairs_in_index_range(
    diag: &[f64],
    off: &[f64],
    lo: usize,
    hi: usize,
) -> Result<Vec<Eigenpair>, LinalgError> {
    eigenpairs_in_index_range_with(diag, off, lo, hi, &mut || false)
}

/// [`eigenpairs_in_index_range`] with a stop question, asked at every QL iteration, before each
/// eigenvalue's bisection and before each inverse iteration (each O(n), O(n^2) for a QL
/// iteration with vectors): a yes ends the call with [`LinalgError::Stopped`] (Python's Ctrl-C
/// stops `Chain.modes` this way).
pub fn eigenpairs_in_index_range_with(
    diag: &[f64],
    off: &[f64],
    lo: usize,
    hi: usize,
    stop: &mut dyn FnMut() -> bool,
) -> Result<Vec<Eigenpair>, LinalgError> {
    bands::check_bands(diag, off)?;
    let n = diag.len();
    bands::check_range(lo, hi, n)?;
    // The whole spectrum: QL (should it ever not converge, bisection and inverse iteration).
    if n > 0 && lo == 0 && hi == n {
        match eigenpairs_with(diag, off, stop) {
            Ok((values, vectors)) => {
                let columns = vectors.as_slice().chunks_exact(n);
                return Ok(values
                    .into_iter()
                    .zip(columns)
                    .map(|(value, v)| Eigenpair { value, vector: v.to_vec() })
                    .collect());
            }
            Err(LinalgError::NoConvergence { .. }) => {}
            Err(other) => return Err(other),
        }
    }
    let sturm = Sturm::new(diag, off);
    let values = bisect(&sturm, lo, hi, Accuracy::Absolute, stop)?;
    inverse_iteration(&sturm.matrix, &values, lo, stop)
}

/// The `k` eigenpairs whose eigenvalues are nearest `sigma`, ascending by eigenvalue, with
/// orthonormal eigenvectors: a Sturm count at `sigma` says where they lie in the spectrum.
pub fn eigenpairs_near(
    diag: &[f64],
    off: &[f64],
    sigma: f64,
    k: usize,
) -> Result<Vec<Eigenpair>, LinalgError> {
    bands::check_bands(diag, off)?;
    bands::check_finite(Input::Shift, &[sigma])?;
    let n = diag.len();
    bands::check_range(0, k, n)?;
    let sturm = Sturm::new(diag, off);
    // Beyond the Gershgorin interval the order of distances is that from its nearer end.
    let x = (sigma * sturm.matrix.scale).clamp(sturm.bounds.0, sturm.bounds.1);
    let below = sturm.count(x);
    let lo = below.saturating_sub(k);
    let values = bisect(&sturm, lo, (below + k).min(n), Accuracy::Absolute, &mut || false)?;
    // The k nearest form a run around the first eigenvalue at or above x.
    let (mut a, mut b) = (below - lo, below - lo);
    while b - a < k {
        if b == values.len() || (a > 0 && (x - values[a - 1]).abs() <= (values[b] - x).abs()) {
            a -= 1;
        } else {
            b += 1;
        }
    }
    inverse_iteration(&sturm.matrix, &values[a..b], lo + a, &mut || false)
}

/// Inverse iteration sweeps before giving up (`dstein` allows 5; one or two suffice in practice).
const MAX_ITERATIONS: usize = 8;

/// Eigenvectors of the scaled matrix `t` for its ascending eigenvalues `values` (scaled), of
/// which the first has index `first` in the spectrum. `stop` is asked before each vector: a yes
/// ends with [`LinalgError::Stopped`].
fn inverse_iteration(
    t: &Scaled,
    values: &[f64],
    first: usize,
    stop: &mut dyn FnMut() -> bool,
) -> Result<Vec<Eigenpair>, LinalgError> {
    let n = t.diag.len();
    let norm = t.norm();
    if norm == 0.0 {
        // The zero matrix: every vector is an eigenvector; take the unit vectors.
        let unit = |i: usize| (0..n).map(|r| if r == i { 1.0 } else { 0.0 }).collect();
        return Ok((first..first + values.len())
            .map(|i| Eigenpair { value: 0.0, vector: unit(i) })
            .collect());
    }
    let cluster_gap = 1e-3 * norm;
    let tolerance = 64.0 * f64::EPSILON * norm * math::sqrt(n as f64);
    let mut random = Random::new();
    // The eigenvectors are the result sized by the caller's count: all allocated fallibly before
    // the first iteration (a request that cannot be met fails at once), the error naming the
    // bytes of all of them.
    let all = crate::allocation::AllocationError {
        bytes: crate::allocation::bytes_of::<f64>(values.len().saturating_mul(n)),
        what: "the eigenvectors",
    };
    let mut vectors: Vec<Vec<f64>> = crate::allocation::try_vec(values.len(), all.what).map_err(|_| all)?;
    let mut unused: Vec<Vec<f64>> = crate::allocation::try_vec(values.len(), all.what).map_err(|_| all)?;
    for _ in 0..values.len() {
        unused.push(crate::allocation::try_filled(n, 0.0, all.what).map_err(|_| all)?);
    }
    let mut cluster_start = 0;
    let mut shift = f64::NEG_INFINITY;
    for (j, &lambda) in values.iter().enumerate() {
        if stop() {
            return Err(LinalgError::Stopped { what: "eigenvectors", done: j, of: values.len() });
        }
        if j > 0 && lambda - values[j - 1] > cluster_gap {
            cluster_start = j;
        }
        shift =
            if j > cluster_start { lambda.max(shift + 10.0 * f64::EPSILON * lambda.abs()) } else { lambda };
        let mut lu = TridiagonalLu::factor(&t.diag, &t.off, shift);
        lu.perturb_small_pivots(f64::EPSILON * norm);
        let cluster = &vectors[cluster_start..j];
        let mut v = unused.pop().ok_or(all)?;
        random.start(&mut v, cluster);
        // Like dstein, iterate once more after the residual first meets the tolerance: the
        // extra solve costs O(n) and takes the residual down to its floor.
        let (mut residual, mut iterations, mut accepted) = (f64::INFINITY, 0, 0);
        while accepted < 2 && iterations < MAX_ITERATIONS {
            iterations += 1;
            lu.solve_in_place(&mut v);
            orthogonalize(&mut v, cluster);
            let size = bands::normalize(&mut v);
            if size > 0.0 && size.is_finite() {
                residual = t.residual(lambda, &v);
            } else {
                // Overflow (many tiny pivots at once) or a start inside the cluster's span.
                random.start(&mut v, cluster);
                residual = f64::INFINITY;
            }
            accepted = if residual <= tolerance { accepted + 1 } else { 0 };
        }
        if residual > tolerance {
            return Err(LinalgError::NoConvergence {
                iterations,
                index: first + j,
                residual: residual / t.scale,
            });
        }
        orthogonalize(&mut v, cluster);
        bands::normalize(&mut v);
        bands::orient(&mut v);
        vectors.push(v);
    }
    Ok(values
        .iter()
        .zip(vectors)
        .map(|(&value, vector)| Eigenpair { value: value / t.scale, vector })
        .collect())
}

/// Modified Gram-Schmidt: removes from `v` its components along the orthonormal `basis`.
fn orthogonalize(v: &mut [f64], basis: &[Vec<f64>]) {
    for q in basis {
        let c = bands::dot(q, v);
        v.iter_mut().zip(q).for_each(|(x, y)| *x -= c * y);
    }
}

/// Deterministic pseudo-random starting vectors (xorshift64*), so results are reproducible.
struct Random(u64);

impl Random {
    fn new() -> Self {
        Self(0x9e37_79b9_7f4a_7c15)
    }

    /// Uniform in `[-1, 1)`.
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let bits = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        bits as f64 / (1u64 << 52) as f64 - 1.0
    }

    /// Fills `v` with a random unit vector orthogonal to `basis`. A random vector lies in the
    /// span of fewer than `n` vectors with probability zero, so one draw suffices; the bound on
    /// the draws only guarantees termination (a last failed draw leaves `v` zero, and the
    /// caller's residual test then reports no convergence).
    fn start(&mut self, v: &mut [f64], basis: &[Vec<f64>]) {
        for _ in 0..64 {
            v.iter_mut().for_each(|x| *x = self.next());
            orthogonalize(v, basis);
            let size = bands::normalize(v);
            if size > 0.0 || v.is_empty() {
                return;
            }
        }
    }
}
