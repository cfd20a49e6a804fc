//! Shared by the benchmarks: the configuration every n = 60 benchmark uses, and the scalar
//! transcendental floor all ratios are taken to.
#![allow(dead_code)]

use rotor_chain::math;

/// Number of rotors of the floor.
pub const N: usize = 60;
const THETA_BAR: f64 = 0.58;

/// `theta_i = theta_bar cos(0.3 i)` plus a small deterministic perturbation: every spring is
/// stretched or compressed by a different amount, so no term of the gradient or Hessian vanishes.
pub fn configuration() -> [f64; N] {
    core::array::from_fn(|i| {
        let x = i as f64;
        THETA_BAR * (0.3 * x).cos() + 0.01 * (1.7 * x + 0.2).sin()
    })
}

/// The configuration of [`configuration`] continued to `n` rotors.
pub fn angles(n: usize) -> Vec<f64> {
    (0..n).map(|i| THETA_BAR * (0.3 * i as f64).cos() + 0.01 * (1.7 * i as f64 + 0.2).sin()).collect()
}

/// Configurations in a batch benchmark.
pub const BATCH: usize = 1024;

/// `BATCH` configurations of `N` rotors back to back, each a different perturbation of the same
/// shape.
pub fn batch_angles() -> Vec<f64> {
    (0..BATCH * N)
        .map(|i| THETA_BAR * (0.3 * (i % N) as f64).cos() + 0.05 * (0.013 * i as f64).sin())
        .collect()
}

/// `N` `sin_cos` and `N - 1` `sqrt` of data-dependent arguments (each sqrt takes the trig of two
/// neighbouring angles, as a spring length does), summed so none can be dropped.
#[inline(never)]
pub fn transcendental_floor(theta: &[f64; N]) -> f64 {
    let (mut s1, mut c1) = math::sin_cos(theta[0]);
    let mut total = s1 + c1;
    for &next in &theta[1..] {
        let (s2, c2) = math::sin_cos(next);
        total += s2 + c2 + f64::sqrt(2.0 + s1 * c2 - c1 * s2);
        (s1, c1) = (s2, c2);
    }
    total
}
