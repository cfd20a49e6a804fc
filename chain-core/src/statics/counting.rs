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
//! `max(n, n - 1) * epsilon * sigma_max` (the usual numerical-rank rule); the vectors of both null
//! spaces and the **tensional modes** are eigenvectors of the tridiagonal matrices `C^T C` and
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
    let svd = c.try_svd(false, false, f64::EPSILON, budget).ok_or(StaticsError::NoConvergence {
        method: "SVD of the compatibility matrix",
        iterations: budget,
        residual: f64::NAN,
        tolerance: f64::EPSILON,
    })?;
    let mut singular_values: Vec<f64> = svd.singular_values.iter().copied().collect();
    singular_values.sort_by(|a, b| b.total_cmp(a));
    let sigma_max = singular_values.first().copied().unwrap_or(0.0);
    let tolerance = tolerance.unwrap_or(n.max(m) as f64 * f64::EPSILON * sigma_max);
    let rank = singular_values.iter().filter(|&&s| s > tolerance).count();
    // C^T C (n x n) and C C^T (m x m) are tridiagonal.
    let ctc_diag: Vec<f64> = (0..n)
        .map(|i| if i < m { left[i] * left[i] } else { 0.0 } + if i > 0 { right[i - 1] * right[i - 1] } else { 0.0 })
        .collect();
    let ctc_off: Vec<f64> = (0..n - 1).map(|i| left[i] * right[i]).collect();
    let zero_modes =
        linalg::lowest_eigenpairs(&ctc_diag, &ctc_off, n - rank)?.into_iter().map(|p| p.vector).collect();
    let (cct_diag, cct_off) = cct(&left, &right);
    let self_stresses = if m > rank {
        linalg::lowest_eigenpairs(&cct_diag, &cct_off, m - rank)?.into_iter().map(|p| p.vector).collect()
    } else {
        Vec::new()
    };
    Ok(Counting { rotors: n, springs: m, singular_values, tolerance, rank, zero_modes, self_stresses })
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
