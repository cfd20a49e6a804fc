//! Per-spring kernels rendered by the symbolic engine (`chain-symbolic`), and the loops that
//! drive them.
//!
//! The kernels are checked in so that `chain-core` needs no build script. They are the same
//! source the `#[rotor_chain]` macro emits for large chains; `tests/kernels_are_current.rs`
//! regenerates them and fails if they differ (run it with `UPDATE_KERNELS=1` to rewrite them
//! after changing the engine).
//!
//! Every kernel function takes `x = [s1, c1, s2, c2, a, r1, r2, k, l0]`: sine and cosine of the
//! two rotor angles, lattice spacing, the two rotor lengths, and the spring's stiffness and rest
//! length. The drivers below compute each angle's `sin_cos` once and hand it to both springs of
//! the rotor; `params(p)` gives `[a, r_p, r_{p+1}, k_p, l0_p]`. The macro's looped code and
//! [`crate::RuntimeChain`] both call them.

use crate::math;

/// The harmonic law `k (l - l0)^2 / 2` (paper Eq. `eq:discretelagrangian`).
#[rustfmt::skip]
pub mod harmonic;

/// The paper's quartic approximation `k (l^2 - l0^2)^2 / (8 l0^2)` (Eq. `eq:discretepotential`).
#[rustfmt::skip]
pub mod quartic;

/// Kernel argument `[s1, c1, s2, c2, a, r1, r2, k, l0]`.
pub type KernelArgs = [f64; 9];

/// Angles whose `sin_cos` is computed in one batch before their springs are visited.
const CHUNK: usize = 64;

/// Calls `f(p, args)` for every spring `p` of the chain with angles `theta`.
///
/// The `sin_cos` of a chunk of angles is computed first, into a small stack buffer, and the springs
/// of the chunk are visited after: a loop without calls lets the spring arithmetic pipeline
/// (measured on a 60-rotor `RuntimeChain`: tangent stiffness 1.61 -> 1.28 us, gradient unchanged
/// at ~1.0 us), and a fixed-size buffer keeps this `no_std` without allocation.
#[inline(always)]
pub fn for_each_spring(
    theta: &[f64],
    params: impl Fn(usize) -> [f64; 5],
    mut f: impl FnMut(usize, KernelArgs),
) {
    let n = theta.len();
    if n < 2 {
        return;
    }
    let (mut sin, mut cos) = ([0.0; CHUNK + 1], [0.0; CHUNK + 1]);
    (sin[0], cos[0]) = math::sin_cos(theta[0]);
    let mut start = 0;
    while start + 1 < n {
        let end = (start + CHUNK).min(n - 1);
        for i in start + 1..=end {
            (sin[i - start], cos[i - start]) = math::sin_cos(theta[i]);
        }
        for p in start..end {
            let k = p - start;
            let [a, r1, r2, kp, l0] = params(p);
            f(p, [sin[k], cos[k], sin[k + 1], cos[k + 1], a, r1, r2, kp, l0]);
        }
        (sin[0], cos[0]) = (sin[end - start], cos[end - start]);
        start = end;
    }
}

/// `sum_p kernel(p)`: the energy.
#[inline(always)]
pub fn sum(theta: &[f64], params: impl Fn(usize) -> [f64; 5], kernel: impl Fn(KernelArgs) -> f64) -> f64 {
    let mut total = 0.0;
    for_each_spring(theta, params, |_, x| total += kernel(x));
    total
}

/// Rotor sums of per-spring pairs: `out[p] += kernel[0]`, `out[p + 1] += kernel[1]` (the gradient).
#[inline(always)]
pub fn assemble_pairs(
    theta: &[f64],
    params: impl Fn(usize) -> [f64; 5],
    out: &mut [f64],
    kernel: impl Fn(KernelArgs) -> [f64; 2],
) {
    assert_eq!(out.len(), theta.len(), "one entry per rotor");
    out.fill(0.0);
    for_each_spring(theta, params, |p, x| {
        let [left, right] = kernel(x);
        out[p] += left;
        out[p + 1] += right;
    });
}

/// Tridiagonal assembly of per-spring 2x2 blocks `[11, 12, 22]` (paper Eq. `eq:prestress8`).
#[inline(always)]
pub fn assemble_blocks(
    theta: &[f64],
    params: impl Fn(usize) -> [f64; 5],
    diag: &mut [f64],
    off: &mut [f64],
    kernel: impl Fn(KernelArgs) -> [f64; 3],
) {
    assert_eq!(diag.len(), theta.len(), "diag has one entry per rotor");
    assert_eq!(off.len() + 1, theta.len(), "off has one entry per spring");
    diag.fill(0.0);
    for_each_spring(theta, params, |p, x| {
        let [b11, b12, b22] = kernel(x);
        diag[p] += b11;
        diag[p + 1] += b22;
        off[p] = b12;
    });
}

/// One value per spring (lengths, tensions).
#[inline(always)]
pub fn per_spring(
    theta: &[f64],
    params: impl Fn(usize) -> [f64; 5],
    out: &mut [f64],
    kernel: impl Fn(KernelArgs) -> f64,
) {
    assert_eq!(out.len() + 1, theta.len(), "one entry per spring");
    for_each_spring(theta, params, |p, x| out[p] = kernel(x));
}

/// Two values per spring (the compatibility matrix's two bands).
#[inline(always)]
pub fn per_spring_pairs(
    theta: &[f64],
    params: impl Fn(usize) -> [f64; 5],
    left: &mut [f64],
    right: &mut [f64],
    kernel: impl Fn(KernelArgs) -> [f64; 2],
) {
    assert_eq!(left.len() + 1, theta.len(), "one entry per spring");
    assert_eq!(right.len() + 1, theta.len(), "one entry per spring");
    for_each_spring(theta, params, |p, x| [left[p], right[p]] = kernel(x));
}
