//! The eigenpairs of a sparse symmetric `A` nearest a value, or at the bottom of the spectrum, by
//! shift-invert block subspace iteration with Rayleigh-Ritz, checked by an inertia count.
//!
//! With the factorization of `A - sigma I` ([`lblt`](super::lblt)) the block `X` (`p` orthonormal columns) is
//! replaced by an orthonormal basis of `(A - sigma I)^{-1} X`, and `A` is diagonalised within it
//! (Rayleigh-Ritz): eigenvalue `lambda_j` converges at the rate
//! `|lambda_j - sigma| / |lambda_{p+1} - sigma|` per iteration, so the eigenvalues nearest `sigma`
//! come first, whatever their multiplicity up to `p` (Saad, *Numerical Methods for Large
//! Eigenvalue Problems*, ch. 5).
//!
//! Why a block method and not (thick-restart) Lanczos, faer's `partial_self_adjoint_eigen`: a
//! single-vector Krylov method sees one vector of each eigenspace and finds further copies of a
//! repeated eigenvalue only through rounding, while a lattice's spectrum is full of them (a periodic
//! square patch's zero eigenvalue has multiplicity `2N`); faer's implementation also refuses a
//! subspace as large as the matrix by panicking.
//!
//! **Stopping.** Every wanted pair's residual `||A v - lambda v||_inf <= `[`RESIDUAL_TOLERANCE`]`
//! ||A||_inf`, within [`MAX_ITERATIONS`] iterations, else [`LinalgError::NoConvergence`] with the
//! worst residual. **Completeness.** The number of eigenvalues that lie strictly inside the found
//! set's range (by an inertia count of [`lblt`](super::lblt), Sylvester's law) must equal the number found there, else
//! [`LinalgError::Missed`]: a skipped eigenvalue cannot go unnoticed.

use alloc::vec;
use alloc::vec::Vec;

use nalgebra::DMatrix;

use super::Upper;
use super::lblt::{Lblt, try_vec};
use crate::linalg::{Eigenpair, LinalgError};
use crate::math;

/// At most this many block iterations. Why 300: the worst rate the shifts below leave for a
/// wanted pair is `|lambda_k - sigma| / |lambda_{p+1} - sigma|` with `p >= 2k`, in practice below
/// 0.9 for a lattice's lowest modes, which converge in under 300 iterations from a random start
/// (`0.9^300 = 2e-14`); each iteration costs `p` solves with the factors.
pub const MAX_ITERATIONS: usize = 300;

/// The residual `||A v - lambda v||_inf / ||A||_inf` every returned pair meets: `1e-11`, far above
/// the rounding floor of a residual (`~ eps` times the few entries of a row) and far below any
/// eigenvalue the analyses resolve (`statics::classify` calls a few `n eps ||A||` zero).
pub const RESIDUAL_TOLERANCE: f64 = 1e-11;

/// What to compute.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Target {
    /// The `k` smallest eigenvalues.
    Lowest,
    /// The `k` eigenvalues nearest this value.
    Near(f64),
}

/// How far below the target the factorization is shifted, relative to `||A||`: far enough above
/// the rounding of a zero eigenvalue (`64 n eps`) that `A - sigma I` is safely nonsingular at a
/// zero mode, small enough that the zero modes converge at once (rate `delta / lambda_{p+1}`).
fn offset(n: usize, norm: f64) -> f64 {
    math::sqrt(f64::EPSILON).max(128.0 * n as f64 * f64::EPSILON) * norm
}

/// The `k` eigenpairs of `A` (`||A||_inf = norm > 0`) nearest the target, ascending, each vector of
/// unit length with its entry of largest magnitude positive.
///
/// # Errors
/// No convergence, a missed eigenvalue, an unstable factorization, or a failed allocation.
pub(crate) fn eigenpairs(
    a: &Upper<'_>,
    norm: f64,
    target: Target,
    k: usize,
) -> Result<Vec<Eigenpair>, LinalgError> {
    eigenpairs_with(a, norm, target, k, 0, &mut || false)
}

/// [`eigenpairs`] with a stop question, asked before each block iteration and within its
/// `O(n p^2)` parts (Gram-Schmidt, Rayleigh-Ritz and the rotations, once per column), so that an
/// answer comes after `O(n p)` work: a yes ends it with [`LinalgError::Stopped`]. After the
/// residuals are met it iterates `polish` more times (within [`MAX_ITERATIONS`]): each divides the
/// pairs' components along the unwanted eigenvectors by about
/// `|lambda_{p+1} - sigma| / |lambda_j - sigma|` again, below what the residual can show
/// (`null_space`'s refinement needs them at the rounding floor).
///
/// # Errors
/// As [`eigenpairs`], and `Stopped`.
pub(crate) fn eigenpairs_with(
    a: &Upper<'_>,
    norm: f64,
    target: Target,
    k: usize,
    mut polish: usize,
    stop: &mut dyn FnMut() -> bool,
) -> Result<Vec<Eigenpair>, LinalgError> {
    let n = a.n;
    if k == 0 {
        return Ok(Vec::new());
    }
    let p = block_size(k, n);
    let delta = offset(n, norm);
    let (_, lblt) = match target {
        Target::Lowest => below_the_spectrum(a, norm, delta)?,
        Target::Near(x) => {
            let lblt = Lblt::new(a, x - delta)?;
            if lblt.inertia().zero == 0 { (x - delta, lblt) } else { (x + delta, Lblt::new(a, x + delta)?) }
        }
    };
    let order = |values: &[f64]| -> Vec<usize> {
        let mut idx: Vec<usize> = (0..values.len()).collect();
        match target {
            Target::Lowest => idx.sort_by(|&i, &j| values[i].total_cmp(&values[j])),
            Target::Near(x) => idx.sort_by(|&i, &j| (values[i] - x).abs().total_cmp(&(values[j] - x).abs())),
        }
        idx
    };
    let mut x = start_block(n, p)?;
    let mut asked = Asked { stop, yes: false };
    orthonormalise(&mut x, n, p, &mut asked);
    let mut ax = try_vec(n * p)?;
    ax.resize(n * p, 0.0);
    let mut rotated = try_vec(n * p)?;
    rotated.resize(n * p, 0.0);
    let mut worst = (0, f64::INFINITY);
    for iteration in 0..MAX_ITERATIONS {
        let stopped =
            LinalgError::Stopped { what: "subspace iterations", done: iteration, of: MAX_ITERATIONS };
        if asked.now() {
            return Err(stopped);
        }
        lblt.solve_in_place(&mut x, p)?;
        orthonormalise(&mut x, n, p, &mut asked);
        for j in 0..p {
            a.mul_vec_shifted(0.0, &x[j * n..(j + 1) * n], &mut ax[j * n..(j + 1) * n]);
        }
        let (values, w) = rayleigh_ritz(&x, &ax, n, p, &mut asked);
        rotate(&mut x, &w, n, p, &mut rotated, &mut asked);
        rotate(&mut ax, &w, n, p, &mut rotated, &mut asked);
        if asked.yes {
            return Err(stopped);
        }
        let wanted: Vec<usize> = order(&values).into_iter().take(k).collect();
        worst = (0, 0.0);
        for &j in &wanted {
            let r =
                (0..n).fold(0.0f64, |m, i| m.max((ax[j * n + i] - values[j] * x[j * n + i]).abs())) / norm;
            if r.is_nan() || r > worst.1 {
                worst = (j, r);
            }
        }
        if worst.1 <= RESIDUAL_TOLERANCE && polish > 0 {
            polish -= 1;
        } else if worst.1 <= RESIDUAL_TOLERANCE {
            let mut pairs: Vec<Eigenpair> = wanted
                .iter()
                .map(|&j| Eigenpair { value: values[j], vector: signed(&x[j * n..(j + 1) * n]) })
                .collect();
            pairs.sort_by(|a, b| a.value.total_cmp(&b.value));
            check_complete(a, norm, target, &pairs)?;
            return Ok(pairs);
        }
    }
    Err(LinalgError::NoConvergence { iterations: MAX_ITERATIONS, index: worst.0, residual: worst.1 })
}

/// The block size: twice the wanted count and at least 8 more (the convergence rate is set by the
/// first unwanted eigenvalue `p + 1`), at most `n`.
pub(crate) fn block_size(k: usize, n: usize) -> usize {
    (2 * k).max(k + 8).min(n)
}

/// A shift below every eigenvalue, its factorization's inertia all positive: `-delta`, then four
/// times further down until it is (Gershgorin: `-||A||_inf - delta` always is).
fn below_the_spectrum(a: &Upper<'_>, norm: f64, delta: f64) -> Result<(f64, Lblt), LinalgError> {
    let mut sigma = -delta;
    loop {
        if sigma < -norm {
            sigma = -norm - delta;
        }
        let lblt = Lblt::new(a, sigma)?;
        let inertia = lblt.inertia();
        if inertia.negative == 0 && inertia.zero == 0 {
            return Ok((sigma, lblt));
        }
        if sigma <= -norm - delta {
            // Gershgorin's bound leaves no eigenvalue below it: a factorization that says
            // otherwise is not to be trusted.
            return Err(LinalgError::Missed { below: sigma, counted: inertia.negative, found: 0 });
        }
        sigma *= 4.0;
    }
}

/// Inertia counts on the inner part of the found range agree with what was found.
fn check_complete(a: &Upper<'_>, norm: f64, target: Target, pairs: &[Eigenpair]) -> Result<(), LinalgError> {
    // Found eigenvalues carry errors up to ~ the residual tolerance; a margin well above it keeps
    // the ends of the range (and a degenerate cluster there) out of the comparison.
    let margin = 1e3 * RESIDUAL_TOLERANCE * norm;
    let below = |t: f64| -> Result<usize, LinalgError> { Ok(Lblt::new(a, t)?.inertia().negative) };
    let found_in = |lo: f64, hi: f64| pairs.iter().filter(|p| p.value >= lo && p.value < hi).count();
    let (lo, hi, counted) = match target {
        Target::Lowest => {
            let hi = pairs[pairs.len() - 1].value - margin;
            (f64::NEG_INFINITY, hi, below(hi)?)
        }
        Target::Near(x) => {
            let radius = pairs.iter().fold(0.0f64, |m, p| m.max((p.value - x).abs())) - margin;
            if radius <= 0.0 {
                return Ok(());
            }
            let (lo, hi) = (x - radius, x + radius);
            (lo, hi, below(hi)? - below(lo)?)
        }
    };
    let found = found_in(lo, hi);
    if counted != found {
        return Err(LinalgError::Missed { below: hi, counted, found });
    }
    Ok(())
}

/// `p` columns of a fixed pseudo-random start (SplitMix64, the same every call).
pub(crate) fn start_block(n: usize, p: usize) -> Result<Vec<f64>, LinalgError> {
    let mut x = try_vec(n * p)?;
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    for _ in 0..n * p {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        x.push((z >> 11) as f64 / (1u64 << 53) as f64 - 0.5);
    }
    Ok(x)
}

/// The stop question, remembered once it answered yes (the `O(n p^2)` parts ask it per column
/// and give up: their results are then discarded).
struct Asked<'a> {
    stop: &'a mut dyn FnMut() -> bool,
    yes: bool,
}

impl Asked<'_> {
    fn now(&mut self) -> bool {
        self.yes = self.yes || (self.stop)();
        self.yes
    }
}

/// Modified Gram-Schmidt, twice ("twice is enough", Giraud et al. 2005), on the `p` columns of `x`;
/// a column that vanishes against the others is replaced by a coordinate vector made orthogonal
/// to them.
fn orthonormalise(x: &mut [f64], n: usize, p: usize, asked: &mut Asked<'_>) {
    for j in 0..p {
        if asked.now() {
            return;
        }
        project_out_previous(x, n, j);
        project_out_previous(x, n, j);
        if !normalise(&mut x[j * n..(j + 1) * n]) {
            x[j * n..(j + 1) * n]
                .iter_mut()
                .enumerate()
                .for_each(|(i, v)| *v = f64::from(u8::from(i == j % n)));
            project_out_previous(x, n, j);
            normalise(&mut x[j * n..(j + 1) * n]);
        }
    }
}

/// Column `j` of `x` minus its components along columns `0..j`.
fn project_out_previous(x: &mut [f64], n: usize, j: usize) {
    let (done, rest) = x.split_at_mut(j * n);
    let col = &mut rest[..n];
    for q in done.chunks_exact(n) {
        let dot: f64 = q.iter().zip(col.iter()).map(|(a, b)| a * b).sum();
        col.iter_mut().zip(q).for_each(|(c, q)| *c -= dot * q);
    }
}

/// Scales `v` to unit length; `false` if its length is zero or not finite.
fn normalise(v: &mut [f64]) -> bool {
    let norm = math::sqrt(v.iter().map(|v| v * v).sum::<f64>());
    let ok = norm > 0.0 && norm.is_finite();
    if ok {
        v.iter_mut().for_each(|x| *x /= norm);
    }
    ok
}

/// The eigenvalues (ascending) and eigenvectors of `X^T A X` (`p x p`).
fn rayleigh_ritz(
    x: &[f64],
    ax: &[f64],
    n: usize,
    p: usize,
    asked: &mut Asked<'_>,
) -> (Vec<f64>, DMatrix<f64>) {
    let mut h = DMatrix::zeros(p, p);
    for i in 0..p {
        if asked.now() {
            return (vec![0.0; p], DMatrix::identity(p, p));
        }
        for j in 0..=i {
            let v: f64 = x[i * n..(i + 1) * n].iter().zip(&ax[j * n..(j + 1) * n]).map(|(a, b)| a * b).sum();
            let w: f64 = x[j * n..(j + 1) * n].iter().zip(&ax[i * n..(i + 1) * n]).map(|(a, b)| a * b).sum();
            h[(i, j)] = 0.5 * (v + w);
            h[(j, i)] = h[(i, j)];
        }
    }
    let eig = h.symmetric_eigen();
    (eig.eigenvalues.iter().copied().collect(), eig.eigenvectors)
}

/// `X <- X W` for the `n x p` block `x` and the `p x p` matrix `w`, through `out` (`n p` values,
/// allocated once before the iterations).
fn rotate(x: &mut [f64], w: &DMatrix<f64>, n: usize, p: usize, out: &mut [f64], asked: &mut Asked<'_>) {
    out.fill(0.0);
    for j in 0..p {
        if asked.now() {
            return;
        }
        let col = &mut out[j * n..(j + 1) * n];
        for l in 0..p {
            let c = w[(l, j)];
            if c != 0.0 {
                col.iter_mut().zip(&x[l * n..(l + 1) * n]).for_each(|(o, v)| *o += c * v);
            }
        }
    }
    x.copy_from_slice(out);
}

/// The vector with its entry of largest magnitude positive (as the dense and tridiagonal paths).
fn signed(v: &[f64]) -> Vec<f64> {
    let largest = v.iter().fold(0.0f64, |m, &x| if x.abs() > m.abs() { x } else { m });
    if largest < 0.0 { v.iter().map(|x| -x).collect() } else { v.to_vec() }
}
