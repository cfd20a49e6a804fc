//! Test models with known answers, shared by the integration tests.
//!
//! [`Reference`] is an independent statement of the chain's energy: tip positions in Cartesian
//! coordinates (pivot `i` at `(i a, 0)`, tip at `(i a + r_i sin theta_i, (-1)^i r_i cos theta_i)`),
//! Euclidean spring lengths, harmonic springs. It shares no code with the generated chain or the
//! symbolic engine, and is generic over num-dual's `DualNum` so an independent forward-mode
//! autodiff differentiates it.
#![allow(dead_code)]

use num_dual::{Dual64, DualNum, HyperDual64};

/// The chain of the paper's figures: r/a = 0.8, k = 1e4, M = 1 (paper Appendix B).
pub const A: f64 = 1.0;
pub const R: f64 = 0.8;
pub const K: f64 = 1.0e4;

/// A harmonic chain given spring by spring.
#[derive(Clone, Debug)]
pub struct Reference {
    pub a: f64,
    pub r: Vec<f64>,
    pub k: Vec<f64>,
    pub l0: Vec<f64>,
}

impl Reference {
    /// A uniform chain of `n` rotors, rest length from `theta_bar` (paper Sec. III).
    pub fn uniform(n: usize, theta_bar: f64) -> Self {
        let l0 = (A * A + 4.0 * R * R * theta_bar.cos().powi(2)).sqrt();
        Self { a: A, r: vec![R; n], k: vec![K; n - 1], l0: vec![l0; n - 1] }
    }

    pub fn tip<D: DualNum<Primitive = f64> + Copy>(&self, i: usize, theta: D) -> (D, D) {
        let sign = if i.is_multiple_of(2) { 1.0 } else { -1.0 };
        (theta.sin() * self.r[i] + self.a * i as f64, theta.cos() * (sign * self.r[i]))
    }

    pub fn length<D: DualNum<Primitive = f64> + Copy>(&self, p: usize, t1: D, t2: D) -> D {
        let (x1, y1) = self.tip(p, t1);
        let (x2, y2) = self.tip(p + 1, t2);
        ((x2 - x1).powi(2) + (y2 - y1).powi(2)).sqrt()
    }

    pub fn energy<D: DualNum<Primitive = f64> + Copy>(&self, theta: &[D]) -> D {
        let mut e = D::zero();
        for p in 0..theta.len() - 1 {
            let stretch = self.length(p, theta[p], theta[p + 1]) - self.l0[p];
            e += stretch * stretch * (0.5 * self.k[p]);
        }
        e
    }

    /// `dV/dtheta_i` by forward-mode autodiff (num-dual), one seed per rotor.
    pub fn gradient(&self, theta: &[f64]) -> Vec<f64> {
        (0..theta.len())
            .map(|i| {
                let x: Vec<Dual64> = theta
                    .iter()
                    .enumerate()
                    .map(|(j, &t)| Dual64::new(t, if i == j { 1.0 } else { 0.0 }))
                    .collect();
                self.energy(&x).eps
            })
            .collect()
    }

    /// `d2V/dtheta_i dtheta_j` by hyper-dual numbers (exact second derivatives, no step size).
    pub fn hessian_entry(&self, theta: &[f64], i: usize, j: usize) -> f64 {
        let x: Vec<HyperDual64> = theta
            .iter()
            .enumerate()
            .map(|(m, &t)| {
                HyperDual64::new(t, if m == i { 1.0 } else { 0.0 }, if m == j { 1.0 } else { 0.0 }, 0.0)
            })
            .collect();
        self.energy(&x).eps1eps2
    }
}

/// `|x - y| <= tol * max(1, |x|, |y|)`, with a message naming what differs.
#[track_caller]
pub fn assert_close(x: f64, y: f64, tol: f64, what: &str) {
    let scale = 1.0f64.max(x.abs()).max(y.abs());
    assert!(
        (x - y).abs() <= tol * scale,
        "{what}: {x} vs {y} (difference {:e}, tolerance {tol:e} x {scale})",
        (x - y).abs()
    );
}

/// A deterministic configuration near the uniform state with some structure, for `n` rotors.
pub fn wavy(n: usize, theta_bar: f64, seed: u64) -> Vec<f64> {
    let mut random = test_support::random::SplitMix(seed);
    (0..n).map(|i| theta_bar * (0.3 * i as f64).cos() + random.range(-0.1, 0.1)).collect()
}

/// A chain of `n` rotors (`R`, `K` of the paper's figures) and its [`Reference`] twin, with
/// `overrides` as (spring, stiffness factor, rest-length factor).
pub fn chains(
    n: usize,
    theta_bar: f64,
    overrides: &[(usize, f64, f64)],
) -> (rotor_chain::RuntimeChain, Reference) {
    let mut reference = Reference::uniform(n, theta_bar);
    let mut builder = rotor_chain::RuntimeChain::builder(n, R, K, theta_bar);
    for &(p, k, l) in overrides {
        reference.k[p] *= k;
        reference.l0[p] *= l;
        if k != 1.0 {
            builder = builder.spring_constant(p, reference.k[p]);
        }
        if l != 1.0 {
            builder = builder.spring_rest_length(p, reference.l0[p]);
        }
    }
    (builder.build().unwrap(), reference)
}

/// The eigenvalues of the symmetric tridiagonal `(d, o)` below `x`: the negative pivots of the
/// `LDL^T` of `(d, o) - x I` (Sturm), written here independently of the library's.
pub fn count_below(d: &[f64], o: &[f64], x: f64) -> usize {
    let mut pivot = d[0] - x;
    let mut count = usize::from(pivot < 0.0);
    for i in 1..d.len() {
        pivot = d[i] - x - o[i - 1] * o[i - 1] / pivot;
        count += usize::from(pivot < 0.0);
    }
    count
}

/// The infinity norm of the tridiagonal `(d, o)`.
pub fn norm(d: &[f64], o: &[f64]) -> f64 {
    (0..d.len())
        .map(|i| d[i].abs() + if i > 0 { o[i - 1].abs() } else { 0.0 } + o.get(i).map_or(0.0, |x| x.abs()))
        .fold(0.0, f64::max)
}

/// The lowest eigenvalue of `(d, o)` by 200 bisections of the Sturm count.
pub fn lowest(d: &[f64], o: &[f64]) -> f64 {
    let r = norm(d, o);
    let (mut a, mut b) = (-r, r);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if count_below(d, o, m) >= 1 { b = m } else { a = m }
    }
    0.5 * (a + b)
}

/// Solves the tridiagonal `(d, o) x = b` (Thomas algorithm, no pivoting: for the positive
/// definite or far-from-singular blocks the tests use it on).
pub fn solve(d: &[f64], o: &[f64], b: &[f64]) -> Vec<f64> {
    let m = d.len();
    let (mut c, mut y) = (vec![0.0; m], vec![0.0; m]);
    for i in 0..m {
        let den = d[i] - if i > 0 { o[i - 1] * c[i - 1] } else { 0.0 };
        if i + 1 < m {
            c[i] = o[i] / den;
        }
        y[i] = (b[i] - if i > 0 { o[i - 1] * y[i - 1] } else { 0.0 }) / den;
    }
    for i in (0..m.saturating_sub(1)).rev() {
        y[i] -= c[i] * y[i + 1];
    }
    y
}
