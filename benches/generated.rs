//! Speed of the code `#[rotor_chain]` generates, against the transcendental floor, a careful
//! hand-written loop, and the runtime-sized chain, all in one run so the ratios sit side by side.
//!
//! Run: `cargo bench --bench generated`
//! (results and their reading: `docs/benchmarks.md`).
//!
//! Every benchmark works on the same fixed, non-trivial configuration (`configuration()`); before
//! any timing, `main` checks that the plain loop and the runtime chain compute the same numbers as
//! the generated code (to 1e-9 relative), so the comparisons are between equal work.

mod support;

use divan::{Bencher, black_box};
use rotor_chain::prelude::*;
use rotor_chain::{RuntimeChain, math};
use support::{configuration, transcendental_floor};

// Unrolled explicitly (the default unrolls only n <= 16 since the vectorised loop measured faster).
#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 128)]
struct Chain;

/// Number of rotors.
const N: usize = 60;
/// Number of springs.
const M: usize = N - 1;
/// Lattice spacing (the macro's default).
const A: f64 = 1.0;
/// Rotor length.
const R: f64 = 0.8;
/// Equilibrium angle of the uniform state.
const THETA_BAR: f64 = 0.58;
/// Spring stiffness.
const K: f64 = 1.0e4;

/// Rest length of every spring: the length in the uniform state `theta_i = theta_bar`.
fn rest_length() -> f64 {
    let dy = 2.0 * R * THETA_BAR.cos();
    (A * A + dy * dy).sqrt()
}

// ---------------------------------------------------------------------------------------------
// What a careful user writes by hand: one loop over the springs, each angle's trig computed in
// both springs it belongs to, the harmonic law's derivatives by hand-derived formulas.
// ---------------------------------------------------------------------------------------------

/// One spring's geometry: tip separation `(dx, dy)`, length `l`, and `dl/dtheta` of its two
/// rotors. Tips sit at `(i a + r sin theta_i, +-r cos theta_i)`, alternating sides.
struct Spring {
    s1: f64,
    c1: f64,
    s2: f64,
    c2: f64,
    dx: f64,
    dy: f64,
    l: f64,
    dl1: f64,
    dl2: f64,
}

#[inline(always)]
fn spring(theta1: f64, theta2: f64) -> Spring {
    let (s1, c1) = math::sin_cos(theta1);
    let (s2, c2) = math::sin_cos(theta2);
    let dx = A + R * (s2 - s1);
    let dy = R * (c1 + c2);
    let l = (dx * dx + dy * dy).sqrt();
    let inv_l = 1.0 / l;
    Spring {
        s1,
        c1,
        s2,
        c2,
        dx,
        dy,
        l,
        dl1: -R * (dx * c1 + dy * s1) * inv_l,
        dl2: R * (dx * c2 - dy * s2) * inv_l,
    }
}

/// `dV/dtheta_i` of `V = sum_p k (l_p - l0)^2 / 2`.
#[inline(never)]
fn plain_gradient(theta: &[f64; N], l0: f64) -> [f64; N] {
    let mut g = [0.0; N];
    for p in 0..M {
        let sp = spring(theta[p], theta[p + 1]);
        let t = K * (sp.l - l0);
        g[p] += t * sp.dl1;
        g[p + 1] += t * sp.dl2;
    }
    g
}

/// The tridiagonal `d2V/dtheta_i dtheta_j`: per spring `k (dl_a dl_b + (l - l0) d2l_ab)` with
/// `d2l_ab = (dx_a dx_b + dy_a dy_b + dx dx_ab + dy dy_ab - dl_a dl_b) / l`.
#[inline(never)]
fn plain_tangent_stiffness(theta: &[f64; N], l0: f64) -> Tridiagonal<N, M> {
    let mut diag = [0.0; N];
    let mut off = [0.0; M];
    for p in 0..M {
        let Spring { s1, c1, s2, c2, dx, dy, l, dl1, dl2 } = spring(theta[p], theta[p + 1]);
        let stretch_over_l = (l - l0) / l;
        let d2l11 = R * R + R * (dx * s1 - dy * c1) - dl1 * dl1;
        let d2l22 = R * R - R * (dx * s2 + dy * c2) - dl2 * dl2;
        let d2l12 = R * R * (s1 * s2 - c1 * c2) - dl1 * dl2;
        diag[p] += K * (dl1 * dl1 + stretch_over_l * d2l11);
        diag[p + 1] += K * (dl2 * dl2 + stretch_over_l * d2l22);
        off[p] = K * (dl1 * dl2 + stretch_over_l * d2l12);
    }
    Tridiagonal::new(diag, off)
}

// ---------------------------------------------------------------------------------------------
// Honesty check, run once before any timing.
// ---------------------------------------------------------------------------------------------

/// Panics unless `got` and `want` agree entrywise to `1e-9` relative to the larger magnitude.
fn assert_close(what: &str, got: &[f64], want: &[f64]) {
    assert_eq!(got.len(), want.len(), "{what}: lengths differ");
    for (i, (&g, &w)) in got.iter().zip(want).enumerate() {
        let scale = g.abs().max(w.abs());
        assert!(
            (g - w).abs() <= 1e-9 * scale,
            "{what}[{i}]: {g:e} vs generated {w:e} (relative {:e})",
            (g - w).abs() / scale
        );
    }
}

fn check_agreement() {
    let theta = configuration();
    let chain = Chain;
    let l0 = rest_length();
    assert_close("rest length", &[l0], &[SpringNetwork::rest_length(&chain, 0)]);

    let g = chain.gradient(&theta);
    assert!(g.iter().all(|x| x.abs() > 1.0), "configuration too close to equilibrium");
    let t = chain.tangent_stiffness(&theta);
    let h = chain.hessian(&theta);
    for i in 0..N {
        for j in 0..N {
            assert_eq!(h[(i, j)], t.get(i, j), "hessian({i}, {j}) is the dense stiffness");
        }
    }

    let pg = plain_gradient(&theta, l0);
    assert_close("plain loop gradient", &pg, &g);
    let pt = plain_tangent_stiffness(&theta, l0);
    assert_close("plain loop stiffness diagonal", &pt.diag, &t.diag);
    assert_close("plain loop stiffness off-diagonal", &pt.off, &t.off);

    let rt = runtime_chain();
    let mut rg = [0.0; N];
    rt.gradient_into(&theta, &mut rg);
    assert_close("runtime gradient", &rg, &g);
    let mut rk = [0.0; N + M];
    rt.tangent_stiffness_into(&theta, &mut rk);
    let (rd, ro) = rk.split_at(N);
    assert_close("runtime stiffness diagonal", rd, &t.diag);
    assert_close("runtime stiffness off-diagonal", ro, &t.off);
    assert_close("runtime energy", &[rt.energy(&theta)], &[chain.energy(&theta)]);
}

fn runtime_chain() -> RuntimeChain {
    RuntimeChain::builder(N, R, K, THETA_BAR).build().unwrap()
}

/// Every benchmark takes 200 samples of 400 calls each (so a sample lasts 0.3 to 0.8 ms and no
/// benchmark's numbers depend on divan's calibration of its sample size); `--sample-count` and
/// `--sample-size` on the command line override these.
fn main() {
    check_agreement();
    divan::Divan::default().sample_count(200).sample_size(400).config_with_args().main();
}

// ---------------------------------------------------------------------------------------------
// Benchmarks.
// ---------------------------------------------------------------------------------------------

#[divan::bench]
fn floor(bencher: Bencher) {
    let theta = configuration();
    bencher.bench_local(|| transcendental_floor(black_box(&theta)));
}

#[divan::bench]
fn generated_energy(bencher: Bencher) {
    let (chain, theta) = (Chain, configuration());
    bencher.bench_local(|| black_box(&chain).energy(black_box(&theta)));
}

#[divan::bench]
fn generated_gradient(bencher: Bencher) {
    let (chain, theta) = (Chain, configuration());
    bencher.bench_local(|| black_box(&chain).gradient(black_box(&theta)));
}

#[divan::bench]
fn generated_tangent_stiffness(bencher: Bencher) {
    let (chain, theta) = (Chain, configuration());
    bencher.bench_local(|| black_box(&chain).tangent_stiffness(black_box(&theta)));
}

#[divan::bench]
fn generated_hessian(bencher: Bencher) {
    let (chain, theta) = (Chain, configuration());
    bencher.bench_local(|| black_box(&chain).hessian(black_box(&theta)));
}

/// The dense-matrix part of `generated_hessian` alone: `Tridiagonal::to_dense` of a ready
/// tangent stiffness (zero a 60 x 60 matrix, write the three bands, return it).
#[divan::bench]
fn generated_hessian_to_dense_part(bencher: Bencher) {
    let t = Chain.tangent_stiffness(&configuration());
    bencher.bench_local(|| black_box(&t).to_dense());
}

#[divan::bench]
fn plain_loop_gradient(bencher: Bencher) {
    let (theta, l0) = (configuration(), rest_length());
    bencher.bench_local(|| plain_gradient(black_box(&theta), black_box(l0)));
}

#[divan::bench]
fn plain_loop_tangent_stiffness(bencher: Bencher) {
    let (theta, l0) = (configuration(), rest_length());
    bencher.bench_local(|| plain_tangent_stiffness(black_box(&theta), black_box(l0)));
}

#[divan::bench]
fn runtime_gradient(bencher: Bencher) {
    let (chain, theta) = (runtime_chain(), configuration());
    let mut out = [0.0; N];
    bencher.bench_local(|| {
        black_box(&chain).gradient_into(black_box(&theta), &mut out);
        black_box(&out);
    });
}

#[divan::bench]
fn runtime_tangent_stiffness(bencher: Bencher) {
    let (chain, theta) = (runtime_chain(), configuration());
    let mut values = [0.0; N + M];
    bencher.bench_local(|| {
        black_box(&chain).tangent_stiffness_into(black_box(&theta), &mut values);
        black_box(&values);
    });
}
