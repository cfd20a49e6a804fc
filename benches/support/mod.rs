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
