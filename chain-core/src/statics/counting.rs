//! Maxwell-Calladine counting (paper Sec. VII-A; Kane and Lubensky 2014).
//!
//! The compatibility matrix `C` (`(n - 1) x n`, `C[p][i] = dl_p / d(r_i theta_i)`) maps rotor
//! displacements to spring extensions. Its null space holds the **zero modes** (displacements that
//! stretch no spring) and the null space of `C^T` the **states of self-stress** (tensions in
//! equilibrium with no load). With `rank C = rho`, there are `n - rho` zero modes and
//! `(n - 1) - rho` self-stresses, so `N_zero - N_selfstress = n - (n - 1) = 1` on every
//! configuration, whatever its geometry.
//!
//! The rank comes from the singular values of `C` (a dense SVD; `C` is small next to the O(n^3)
//! it costs only for chains of thousands of rotors) with the tolerance
//! `max(n, n - 1) * epsilon * sigma_max` (the usual numerical-rank rule). The vectors of both null
//! spaces are singular vectors of `C` with a row of zeros appended (square, so that its
//! decomposition holds all `n` right vectors; nalgebra's decomposition with vectors is less
//! accurate in its singular values, 1e-5 to 3e-3 seen, so the values come from a decomposition
//! without vectors): the `n - rank` right vectors that `C` maps nearest to zero are the zero
//! modes, and the `n - rank` left ones that `C^T` maps nearest to zero span the self-stresses and
//! the appended row's axis, which is taken out. Eigenvectors of `C^T C` would be cheaper but
//! cannot tell apart singular values below `sqrt(epsilon) sigma_max`: a singular value of 3e-14,
//! just above the rank tolerance, left a "zero mode" with `|C z| = 3e-14`, a mix of the null
//! vector and its neighbour (found by a mirror-symmetry audit; the singular vectors give
//! `|C z| ~ epsilon sigma_max`). The **tensional modes** are eigenvectors of the tridiagonal
//! `C C^T`.

use alloc::vec;
use alloc::vec::Vec;

use nalgebra::DMatrix;

use super::error::StaticsError;
use super::validate;
use crate::linalg;
use crate::model::ChainModel;

/// The outcome of the counting at one configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Counting {
    /// Rotors (degrees of freedom).
    pub rotors: usize,
    /// Springs (constraints).
    pub springs: usize,
    /// Singular values of `C`, descending.
    pub singular_values: Vec<f64>,
    /// Singular values at or below this count as zero.
    pub tolerance: f64,
    /// Rank of the compatibility matrix.
    pub rank: usize,
    /// Orthonormal basis of the zero modes (rotor displacements `r_i dtheta_i`).
    pub zero_modes: Vec<Vec<f64>>,
    /// Orthonormal basis of the states of self-stress (spring tensions).
    pub self_stresses: Vec<Vec<f64>>,
}

impl Counting {
    /// `N_zero - N_selfstress`, which must equal `n - (n - 1) = 1`.
    pub fn index(&self) -> isize {
        self.zero_modes.len() as isize - self.self_stresses.len() as isize
    }
}

/// A tensional mode: an eigenvector of `C C^T` (spring tensions), with its eigenvalue.
#[derive(Clone, Debug, PartialEq)]
pub struct TensionalMode {
    /// Its eigenvalue.
    pub eigenvalue: f64,
    /// Spring tensions, one per spring.
    pub tensions: Vec<f64>,
}

/// The bands of `C` at `theta`.
pub fn compatibility<M: ChainModel + ?Sized>(model: &M, theta: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let m = model.spring_count();
    let (mut left, mut right) = (vec![0.0; m], vec![0.0; m]);
    model.compatibility_into(theta, &mut left, &mut right);
    (left, right)
}

/// The bands of `C` at `theta`, checked: `theta` one finite angle per rotor, and every entry of
/// `C` finite (a model whose parameters make a spring of zero length gives NaN).
fn checked_compatibility<M: ChainModel + ?Sized>(
    model: &M,
    theta: &[f64],
) -> Result<(Vec<f64>, Vec<f64>), StaticsError> {
    validate::angles(model, theta)?;
    let (left, right) = compatibility(model, theta);
    validate::finite("the compatibility matrix's diagonal", &left)?;
    validate::finite("the compatibility matrix's superdiagonal", &right)?;
    Ok((left, right))
}

/// Maxwell-Calladine counting at `theta`; `tolerance` overrides the numerical-rank rule.
///
/// # Errors
/// `theta` not one finite angle per rotor, a compatibility matrix that is not finite, a
/// `tolerance` that is not finite and `>= 0`, or a failed SVD or eigensolver (each iteration
/// bounded).
pub fn maxwell_calladine<M: ChainModel + ?Sized>(
    model: &M,
    theta: &[f64],
    tolerance: Option<f64>,
) -> Result<Counting, StaticsError> {
    if let Some(t) = tolerance {
        validate::non_negative("tolerance", t)?;
    }
    let (n, m) = (model.rotor_count(), model.spring_count());
    let (left, right) = checked_compatibility(model, theta)?;
    validate::at_most("rotors x springs of the dense SVD", n.saturating_mul(m), super::MAX_DENSE_VALUES)?;
    let c = DMatrix::from_fn(m, n, |p, i| {
        if i == p {
            left[p]
        } else if i == p + 1 {
            right[p]
        } else {
            0.0
        }
    });
    // nalgebra's `singular_values()` iterates without a bound; LAPACK's `dbdsqr` allows
    // 6 n^2 sweeps, which is what this gives.
    let budget = 6 * n.max(m) * n.max(m);
    let failed = || StaticsError::NoConvergence {
        method: "SVD of the compatibility matrix",
        iterations: budget,
        residual: f64::NAN,
        tolerance: f64::EPSILON,
    };
    // The singular values alone: nalgebra's SVD of a non-square matrix is accurate only without
    // vectors (with them, 1e-5 off on a 59 x 60 `C` whose values agree to 3e-15 otherwise; the
    // same family as nalgebra issues #983 and #1211). A test compares them with the eigenvalues
    // of the tridiagonal `C C^T`.
    let values = c.clone().try_svd(false, false, f64::EPSILON, budget).ok_or_else(failed)?;
    let mut singular_values: Vec<f64> = values.singular_values.iter().copied().collect();
    singular_values.sort_by(|a, b| b.total_cmp(a));
    let sigma_max = singular_values.first().copied().unwrap_or(0.0);
    let tolerance = tolerance.unwrap_or(n.max(m) as f64 * f64::EPSILON * sigma_max);
    let rank = singular_values.iter().filter(|&&s| s > tolerance).count();
    // The vectors: `C` with a row of zeros appended, square, whose decomposition holds all `n`
    // right vectors. On the right, `n - rank` of them span the null space of `C` (the zero
    // modes); on the left, the self-stresses `[s; 0]` and the appended row's `e_n`.
    let square = c.resize(n, n, 0.0);
    let full = square.try_svd(true, true, f64::EPSILON, budget).ok_or_else(failed)?;
    let (u, v_t) = (full.u.as_ref().ok_or_else(failed)?, full.v_t.as_ref().ok_or_else(failed)?);
    // Which vectors span the null spaces is read from what `C` does to them (`|C v|`, and
    // `|C^T u|` on the left, whose appended axis `e_n` gives 0), not from the singular values
    // this decomposition pairs them with: with vectors, nalgebra's values can be off (3e-3 seen
    // on the square `C` of a 41-rotor chain, which is why the values above come from the
    // vector-free decomposition).
    let right_residual =
        |v: &[f64]| -> f64 { (0..m).map(|p| left[p] * v[p] + right[p] * v[p + 1]).map(|x| x * x).sum() };
    let left_residual = |u: &[f64]| -> f64 {
        (0..n)
            .map(|i| {
                let below = if i < m { left[i] * u[i] } else { 0.0 };
                let above = if i > 0 { right[i - 1] * u[i - 1] } else { 0.0 };
                (below + above) * (below + above)
            })
            .sum()
    };
    let rows: Vec<Vec<f64>> = (0..n).map(|j| v_t.row(j).iter().copied().collect()).collect();
    let columns: Vec<Vec<f64>> = (0..n).map(|j| u.column(j).iter().copied().collect()).collect();
    let zero_modes = least(&rows, n - rank, right_residual).into_iter().map(oriented).collect();
    let stresses_and_axis = least(&columns, n - rank, left_residual);
    let self_stresses = without_last_axis(&stresses_and_axis).into_iter().map(oriented).collect();
    Ok(Counting { rotors: n, springs: m, singular_values, tolerance, rank, zero_modes, self_stresses })
}

/// An orthonormal basis of the vectors of `span(basis)` (orthonormal, each of length `n`, the
/// span holding the last axis `e_n`) that are orthogonal to `e_n`, with that last entry dropped:
/// one vector fewer. The combination along `e_n` is `x = h / |h|`, `h` the basis vectors' last
/// entries; the Householder reflection `H` that takes `x` to a multiple of `e_1` has its other
/// columns orthogonal to `x`, and those combinations of the basis are the answer.
fn without_last_axis(basis: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let q = basis.len();
    if q < 2 {
        return Vec::new();
    }
    let n = basis[0].len();
    let h: Vec<f64> = basis.iter().map(|b| b[n - 1]).collect();
    let size = crate::math::sqrt(h.iter().map(|x| x * x).sum());
    // v = x + sign(x_1) e_1 (no cancellation); H = I - 2 v v^T / (v^T v).
    let mut v: Vec<f64> = if size > 0.0 { h.iter().map(|x| x / size).collect() } else { vec![0.0; q] };
    v[0] += if v[0] < 0.0 { -1.0 } else { 1.0 };
    let vv: f64 = v.iter().map(|x| x * x).sum();
    (1..q)
        .map(|j| {
            // Column j of H, then the combination of the basis, without its last entry.
            let column: Vec<f64> =
                (0..q).map(|k| if k == j { 1.0 } else { 0.0 } - 2.0 * v[k] * v[j] / vv).collect();
            let mut s: Vec<f64> =
                (0..n - 1).map(|i| basis.iter().zip(&column).map(|(b, c)| b[i] * c).sum()).collect();
            let norm = crate::math::sqrt(s.iter().map(|x| x * x).sum());
            s.iter_mut().for_each(|x| *x /= norm);
            s
        })
        .collect()
}

/// The `count` vectors with the smallest `residual`, ascending.
fn least(vectors: &[Vec<f64>], count: usize, residual: impl Fn(&[f64]) -> f64) -> Vec<Vec<f64>> {
    let mut scored: Vec<(f64, &Vec<f64>)> = vectors.iter().map(|v| (residual(v), v)).collect();
    scored.sort_by(|a, b| a.0.total_cmp(&b.0));
    scored.into_iter().take(count).map(|(_, v)| v.clone()).collect()
}

/// `v` with the sign that makes its largest entry (the first, on a tie) positive: a singular
/// vector's sign is arbitrary, and this gives one answer for one subspace of dimension 1.
fn oriented(mut v: Vec<f64>) -> Vec<f64> {
    let largest = v.iter().copied().fold(0.0f64, |best, x| if x.abs() > best.abs() { x } else { best });
    if largest < 0.0 {
        v.iter_mut().for_each(|x| *x = -*x);
    }
    v
}

/// `C C^T` as a tridiagonal matrix.
fn cct(left: &[f64], right: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let m = left.len();
    let diag = (0..m).map(|p| left[p] * left[p] + right[p] * right[p]).collect();
    let off = (0..m.saturating_sub(1)).map(|p| right[p] * left[p + 1]).collect();
    (diag, off)
}

/// The `count` softest tensional modes at `theta` (eigenvectors of `C C^T`, ascending).
pub fn tensional_modes<M: ChainModel + ?Sized>(
    model: &M,
    theta: &[f64],
    count: usize,
) -> Result<Vec<TensionalMode>, StaticsError> {
    let (left, right) = checked_compatibility(model, theta)?;
    let (diag, off) = cct(&left, &right);
    Ok(linalg::lowest_eigenpairs(&diag, &off, count.min(left.len()))?
        .into_iter()
        .map(|p| TensionalMode { eigenvalue: p.value, tensions: p.vector })
        .collect())
}
