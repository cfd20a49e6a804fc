//! Vibrational modes about an equilibrium (paper Sec. IV, Figs. `fig:mode-config`, `fig:w-th`).
//!
//! Small oscillations obey `K v = omega^2 I v` with `K` the tangent stiffness and `I` the
//! inertias (`diag(M r_i^2)` for a chain). [`normal_modes`] solves it for any model with a
//! tangent stiffness ([`Stiffness`]); [`modes`] adds, for a rotor chain, where each mode lives.
//! Scaling by `I^{-1/2}` keeps the problem symmetric (tridiagonal for a chain), so the lowest
//! modes of a long chain come from bisection and inverse iteration in O(n) each; the whole
//! spectrum comes from the implicit QL iteration, O(n^2) for the values and O(n^3) with the
//! vectors ([`SymmetricMatrix`]).
//!
//! **Kinds of mode**, by where the mode lives: a mode concentrated near a domain wall is its
//! *translation* mode (the one most parallel to the wall's displacement `dtheta/dx`) or a *shape*
//! mode; a mode concentrated within a few sites of a free end is an *edge* mode; anything spread
//! over the chain is *extended* (a phonon). Near-zero eigenvalues come in near-degenerate clusters
//! (the antikink's translation and the two edge modes of its domains, for wide antikinks), inside
//! which the eigensolver's vectors are arbitrary mixtures; such a cluster is first rotated to the
//! basis that diagonalises the position operator, which separates modes living in different
//! places.

use alloc::vec;
use alloc::vec::Vec;

use nalgebra::DMatrix;

use super::error::StaticsError;
use super::validate;
use super::walls::domain_walls;
use crate::allocation::{self, AllocationError};
use crate::linalg::{self, LinalgError, SymmetricMatrix};
use crate::math;
use crate::model::{ChainModel, Stiffness};
use crate::validate::{Fields, Validate};

/// Where a mode lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ModeKind {
    /// At a domain wall, along the wall's own displacement.
    Translation,
    /// At a domain wall, deforming it.
    Shape,
    /// At the left (`0`) or right (`n - 1`) end of the chain.
    Edge {
        /// `true` at rotor 0, `false` at rotor `n - 1`.
        left: bool,
    },
    /// Spread over the chain.
    Extended,
    /// Not labelled: [`normal_modes`] of a model that is not a rotor chain has no walls or ends
    /// to place a mode by (its position and participation say where it lives).
    Unlabelled,
}

/// One vibrational mode.
#[derive(Clone, Debug, PartialEq)]
pub struct Mode {
    /// Eigenvalue `omega^2` of `I^{-1/2} K I^{-1/2}` (for equal rotors, `lambda(K) / (M r^2)`).
    pub omega_squared: f64,
    /// The signed frequency [`signed_frequency`]`(omega^2)`: `sqrt(omega^2)` for a stable
    /// direction, `-sqrt(-omega^2)` for an unstable one (`omega^2 < 0`, the imaginary frequency
    /// `i sqrt(-omega^2)` written with a minus sign), so an unstable direction never reads as a
    /// zero mode.
    pub frequency: f64,
    /// The angular displacement pattern `v` (`K v = omega^2 I v`), normalised so `sum_i I_i v_i^2 = 1`.
    pub shape: Vec<f64>,
    /// Mean position `sum_i i w_i` of the weights `w_i = I_i v_i^2`.
    pub position: f64,
    /// Participation number `1 / sum_i w_i^2`: how many rotors take part.
    pub participation: f64,
    /// Where the mode lives (translation, shape, edge, extended).
    pub kind: ModeKind,
}

/// Settings of [`modes`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModeOptions {
    /// How many of the lowest modes to compute. Default `Some(12)`: O(n) each by bisection and
    /// inverse iteration. `None` asks for all `n` modes, which takes the dense QL route
    /// (O(n^2) memory and O(n^3) time for the vectors): fine for hundreds of rotors, not for 1e5.
    /// `Some` count between 0 (no mode) and [`MAX_DENSE_VALUES`](super::MAX_DENSE_VALUES)
    /// (2^26): the modes' vectors hold `count x n` values, bounded by that at the call, so no
    /// chain gives more modes (a count above a chain's degrees of freedom gives them all).
    pub count: Option<usize>,
    /// Eigenvalues closer than `cluster * ||K||` are treated as one degenerate cluster.
    pub cluster: f64,
    /// A mode is localised when fewer than `localised_fraction * n` rotors take part, and fewer
    /// than `localised_widths` wall widths.
    pub localised_fraction: f64,
    /// See [`ModeOptions::localised_fraction`].
    pub localised_widths: f64,
    /// A localised mode within `reach` wall widths (at least 4 rotors) of an end or of a wall
    /// belongs to it. The width is the continuum `w = a^2 / (2 r sin theta_bar)` (App. E) in sites,
    /// `w / a` ([`wall_width`](super::walls::wall_width)).
    pub reach: f64,
    /// Analyse with the end rotors held (the boundary condition of
    /// [`super::antikink::Ends::Held`]): the held rotors' shape entries are zero. Default `false`.
    pub hold_ends: bool,
}

impl Default for ModeOptions {
    fn default() -> Self {
        Self {
            count: Some(12),
            cluster: 1e-9,
            localised_fraction: 0.5,
            localised_widths: 6.0,
            reach: 3.0,
            hold_ends: false,
        }
    }
}

impl Validate for ModeOptions {
    type Error = StaticsError;

    /// `cluster`, `localised_widths` and `reach` finite and `>= 0`, `localised_fraction` in
    /// `[0, 1]`, `count` (`None`: all) between 0 and
    /// [`MAX_DENSE_VALUES`](super::MAX_DENSE_VALUES) (`Some(0)` asks for no mode; more than the
    /// chain's degrees of freedom gives them all, within the size bound of [`modes`]).
    fn validate(&self) -> Result<(), StaticsError> {
        // No `..`: a field added here does not compile until it is checked.
        let Self { count, cluster, localised_fraction, localised_widths, reach, hold_ends: _ } = *self;
        let fields = Fields("ModeOptions");
        if let Some(count) = count {
            fields.count_in(
                "count",
                count as u64,
                0,
                super::MAX_DENSE_VALUES as u64,
                "between 0 and MAX_DENSE_VALUES = 67108864 (the modes' vectors hold count x n values)",
            )?;
        }
        fields.non_negative("cluster", cluster)?;
        fields.rule(
            "localised_fraction",
            localised_fraction,
            (0.0..=1.0).contains(&localised_fraction),
            "in [0, 1] (a fraction of the rotors)",
        )?;
        fields.non_negative("localised_widths", localised_widths)?;
        fields.non_negative("reach", reach)?;
        Ok(())
    }
}

/// The lowest modes of `model` about `theta` ([`ModeOptions::count`] of them), ascending in `omega^2`.
///
/// # Errors
/// `theta` not one finite angle per rotor, a setting out of range, a tangent stiffness or inertia
/// that is not finite at `theta` (the model's parameters), or a failed eigensolver.
/// # Example
///
/// ```
/// use rotor_chain::RuntimeChain;
/// use rotor_chain::statics::modes::{ModeKind, ModeOptions, modes};
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let chain = RuntimeChain::builder(40, 0.8, 1.0e4, 0.58).build()?;
/// let uniform = vec![0.58; 40];
/// let all = modes(&chain, &uniform, &ModeOptions { count: None, ..ModeOptions::default() })?;
/// assert_eq!(all.len(), 40);
/// // The uniform chain's one zero mode is its mechanism (paper Sec. II); the phonon band above
/// // it starts at omega(0) = 87.8 / t for this chain (guide::statics §9).
/// assert!(all[0].frequency < 1e-3 && all[1].frequency > 50.0);
/// assert!(all.windows(2).all(|w| w[0].omega_squared <= w[1].omega_squared));
/// # let _ = ModeKind::Extended;
/// # Ok(())
/// # }
/// ```
pub fn modes<M: ChainModel + ?Sized>(
    model: &M,
    theta: &[f64],
    options: &ModeOptions,
) -> Result<Vec<Mode>, StaticsError> {
    modes_with(model, theta, options, &mut || false)
}

/// [`modes`] with a stop question, asked inside the eigensolver's loops (every QL iteration,
/// each bisected eigenvalue, each inverse iteration) of a chain's tridiagonal problem: a yes ends
/// the call with [`LinalgError::Stopped`] (Python's Ctrl-C
/// stops `Chain.modes` this way).
///
/// # Errors
/// As [`modes`], and `Stopped` when `stop` answered yes.
pub fn modes_with<M: ChainModel + ?Sized>(
    model: &M,
    theta: &[f64],
    options: &ModeOptions,
    stop: &mut dyn FnMut() -> bool,
) -> Result<Vec<Mode>, StaticsError> {
    let mut result = normal_modes_with(model, theta, options, stop)?;
    label_kinds(model, theta, options, &mut result);
    Ok(result)
}

/// The lowest modes of any model with a tangent stiffness about `x` ([`ModeOptions::count`] of
/// them), ascending in `omega^2`, their kinds [`ModeKind::Unlabelled`] ([`modes`] labels a
/// chain's). [`ModeOptions::hold_ends`] holds the first and the last degree of freedom.
///
/// # Errors
/// As [`modes`].
pub fn normal_modes<M: Stiffness + ?Sized>(
    model: &M,
    x: &[f64],
    options: &ModeOptions,
) -> Result<Vec<Mode>, StaticsError> {
    normal_modes_with(model, x, options, &mut || false)
}

/// [`normal_modes`] with a stop question ([`modes_with`]); a sparse stiffness (a network's)
/// takes the dense decomposition, bounded by [`MAX_DENSE_VALUES`](super::MAX_DENSE_VALUES), and
/// asks it once before it starts.
///
/// # Errors
/// As [`modes`], and `Stopped` when `stop` answered yes.
pub fn normal_modes_with<M: Stiffness + ?Sized>(
    model: &M,
    x: &[f64],
    options: &ModeOptions,
    stop: &mut dyn FnMut() -> bool,
) -> Result<Vec<Mode>, StaticsError> {
    validate::angles(model, x)?;
    options.validate()?;
    let n = model.dof_count();
    let k = SymmetricMatrix::tangent_stiffness(model, x)?;
    k.check_finite()?;
    let inertia: Vec<f64> = (0..n).map(|i| model.inertia(i)).collect();
    if let Some(index) = inertia.iter().position(|&x| !(x.is_finite() && x > 0.0)) {
        return Err(StaticsError::InvalidValue {
            what: "a rotor's moment of inertia",
            value: inertia[index],
            expected: "a finite number > 0 (check the model's mass and rotor lengths)",
        });
    }
    let root: Vec<f64> = inertia.iter().map(|&x| math::sqrt(x)).collect();
    // The moving degrees of freedom: all, or all but the held ends.
    let range = super::equilibrium::moving(n, options.hold_ends);
    let scaled = k.principal(range.clone()).mass_scaled(&inertia[range.clone()]);
    let count = options.count.unwrap_or(n).min(scaled.dim());
    validate::at_most("modes x rotors", count.saturating_mul(n), super::MAX_DENSE_VALUES)?;
    let pairs = match scaled.bands() {
        Some((diag, off)) => linalg::eigenpairs_in_index_range_with(diag, off, 0, count, stop)?,
        None if stop() => return Err(LinalgError::Stopped { what: "eigenpairs", done: 0, of: count }.into()),
        None => scaled.lowest_eigenpairs(count)?,
    };
    let mut values: Vec<f64> = pairs.iter().map(|p| p.value).collect();
    // The vectors and shapes are the result sized by the caller's count: allocated fallibly (a
    // pair's vector already has its `n` entries when no end is held, and is reused).
    let all = AllocationError {
        bytes: allocation::bytes_of::<f64>(count.saturating_mul(n)),
        what: "the modes' vectors",
    };
    let mut vectors: Vec<Vec<f64>> =
        allocation::try_vec(pairs.len(), all.what).map_err(|_| LinalgError::from(all))?;
    for p in pairs {
        if p.vector.len() == n {
            vectors.push(p.vector);
        } else {
            let mut full = allocation::try_filled(n, 0.0, all.what).map_err(|_| LinalgError::from(all))?;
            full[range.clone()].copy_from_slice(&p.vector);
            vectors.push(full);
        }
    }
    let scaled_norm = scaled.inf_norm().max(f64::MIN_POSITIVE);
    localise_clusters(&mut values, &mut vectors, options.cluster * scaled_norm);
    Ok(values
        .iter()
        .zip(vectors)
        .map(|(&value, mut shape)| {
            // u is orthonormal in the scaled problem; v = I^{-1/2} u has sum I v^2 = 1. The
            // weights u_i^2 are summed as they are read (no second vector of n).
            let (mut position, mut squares) = (0.0, 0.0);
            for (i, x) in shape.iter().enumerate() {
                let w = x * x;
                position += i as f64 * w;
                squares += w * w;
            }
            let participation = 1.0 / squares;
            shape.iter_mut().zip(&root).for_each(|(x, r)| *x /= r);
            Mode {
                omega_squared: value,
                frequency: signed_frequency(value),
                shape,
                position,
                participation,
                kind: ModeKind::Unlabelled,
            }
        })
        .collect())
}

/// The signed frequency of an eigenvalue `omega^2`: `sign(omega^2) sqrt(|omega^2|)`.
///
/// A negative `omega^2` (an unstable direction, such as the translation of an antikink on its
/// Peierls-Nabarro saddle) has the imaginary frequency `i sqrt(-omega^2)`: its small oscillations
/// grow as `exp(sqrt(-omega^2) t)`. Written with a minus sign it keeps its size and says that it is
/// unstable, where `sqrt(max(omega^2, 0))` would show it as a zero mode. Every frequency the
/// library returns, prints or plots is this one ([`Mode::frequency`], Python `Modes.frequencies`,
/// the paper's figures).
pub fn signed_frequency(omega_squared: f64) -> f64 {
    math::sqrt(omega_squared.abs()).copysign(omega_squared)
}

/// Labels the kinds of a chain's modes (the module doc): edges first, then walls; at each wall the
/// mode most parallel to `dtheta/dx` translates it; the rest extended.
fn label_kinds<M: ChainModel + ?Sized>(model: &M, theta: &[f64], options: &ModeOptions, result: &mut [Mode]) {
    let n = model.rotor_count();
    let inertia: Vec<f64> = (0..n).map(|i| model.inertia(i)).collect();
    result.iter_mut().for_each(|m| m.kind = ModeKind::Extended);
    let walls = domain_walls(theta);
    // The displacement of each wall, dtheta/dx, by central differences of the profile.
    let slope: Vec<f64> = (0..n)
        .map(|i| {
            let (l, r) = (theta[i.saturating_sub(1)], theta[(i + 1).min(n - 1)]);
            (r - l) / ((i + 1).min(n - 1) - i.saturating_sub(1)) as f64
        })
        .collect();
    // Kinds: edges first, then walls; at each wall the mode most parallel to dtheta/dx translates it.
    // In sites, as the positions it is compared with.
    let width = super::walls::wall_width(model);
    let reach = (options.reach * width).max(4.0);
    let max_participation =
        (options.localised_fraction * n as f64).min(options.localised_widths * width + 4.0);
    // Where the weight is: within `reach` of the left end, the right end, or a wall. (A mean
    // position would put a mode living at both ends in the middle.)
    let weight_in = |m: &Mode, near: &dyn Fn(f64) -> bool| -> f64 {
        m.shape
            .iter()
            .zip(&inertia)
            .enumerate()
            .filter(|(i, _)| near(*i as f64))
            .map(|(_, (v, i))| i * v * v)
            .sum()
    };
    let last = (n - 1) as f64;
    for m in result.iter_mut().filter(|m| m.participation < max_participation) {
        let left = weight_in(m, &|x| x < reach);
        let right = weight_in(m, &|x| x > last - reach);
        let at_wall = weight_in(m, &|x| walls.iter().any(|w| (w.position - x).abs() < reach));
        if left + right > 0.5 && left + right >= at_wall {
            m.kind = ModeKind::Edge { left: left >= right };
        } else if at_wall > 0.5 {
            m.kind = ModeKind::Shape;
        }
    }
    for wall in &walls {
        let overlap = |m: &Mode| {
            let dot: f64 = m.shape.iter().zip(&slope).zip(&inertia).map(|((v, s), i)| v * s * i).sum();
            dot.abs()
        };
        let best = result
            .iter_mut()
            .filter(|m| m.kind == ModeKind::Shape && (m.position - wall.position).abs() < reach)
            .max_by(|a, b| overlap(a).total_cmp(&overlap(b)));
        if let Some(m) = best {
            m.kind = ModeKind::Translation;
        }
    }
}

/// Rotates every cluster of eigenvalues closer than `tolerance` to the basis in which the
/// position operator `diag(i)` is diagonal: within a degenerate subspace any basis is an
/// eigenbasis, and this one puts each vector where it lives.
fn localise_clusters(values: &mut [f64], vectors: &mut [Vec<f64>], tolerance: f64) {
    let mut start = 0;
    while start < values.len() {
        let mut end = start + 1;
        while end < values.len() && values[end] - values[end - 1] <= tolerance {
            end += 1;
        }
        let size = end - start;
        if size > 1 {
            let block = &vectors[start..end];
            let x = DMatrix::<f64>::from_fn(size, size, |a, b| {
                block[a].iter().zip(&block[b]).enumerate().map(|(i, (u, v))| i as f64 * u * v).sum::<f64>()
            });
            let eig = x.symmetric_eigen();
            let n = block[0].len();
            let rotated: Vec<Vec<f64>> = (0..size)
                .map(|c| {
                    let mut v = vec![0.0; n];
                    for (a, basis) in block.iter().enumerate() {
                        let w = eig.eigenvectors[(a, c)];
                        for (vi, bi) in v.iter_mut().zip(basis) {
                            *vi += w * bi;
                        }
                    }
                    v
                })
                .collect();
            // Rayleigh quotients are all equal within the tolerance; keep the values sorted.
            for (slot, v) in vectors[start..end].iter_mut().zip(rotated) {
                *slot = v;
            }
        }
        start = end;
    }
}
