//! Speed of the network model (issue 36), side by side in one run: the fused energy and gradient
//! per bond on a periodic kagome patch against the chain's per-spring cost (`RuntimeChain`, its
//! vectorised kernels, as many springs), and a Verlet step on the 256 x 256 kagome patch (393 216
//! degrees of freedom) per degree of freedom; the polynomial law's kernels (13-15 arguments) on the
//! same patch with its coefficients shared by every bond (constants of the runs) and with each
//! bond's own (per-bond arrays). `cargo bench -p rotor-chain-network --bench motion`;
//! results, the CPU and the dispatch level in docs/benchmarks.md. One thread.

use chain_core::integrate::{Phase, Verlet};
use chain_core::{Potential, RuntimeChain, SpringNetwork};
use chain_network::cell::ready;
use chain_network::patch::{Boundary, Patch};
use chain_network::{NetworkModel, Polynomial};
use divan::counter::ItemsCount;
use divan::{Bencher, black_box};

fn main() {
    println!("dispatch level: {:?}", chain_core::simd::level());
    divan::main();
}

/// A periodic kagome patch of `n x n` cells, every joint moved a little off the reference.
fn kagome(n: usize) -> (NetworkModel, Vec<f64>) {
    let cell = ready::kagome();
    let patch = Patch::new(&cell, [n, n], Boundary::Periodic).unwrap();
    let model = NetworkModel::builder(&patch).build().unwrap();
    let x = model.reference().iter().enumerate().map(|(i, x)| x + 0.01 * (i as f64 * 0.37).sin()).collect();
    (model, x)
}

/// Fused energy and gradient of a 64 x 64 periodic kagome patch (24 576 bonds), per bond.
#[divan::bench]
fn network_energy_gradient_per_bond(bencher: Bencher) {
    let (model, x) = kagome(64);
    let mut g = vec![0.0; x.len()];
    bencher
        .counter(ItemsCount::new(model.spring_count()))
        .bench_local(|| model.energy_and_gradient_into(black_box(&x), &mut g));
}

/// A periodic kagome patch of `n x n` cells with the polynomial law: one law for every bond
/// (`per_bond` false) or each spring its own coefficients, at the start of [`kagome`].
fn kagome_polynomial(n: usize, per_bond: bool) -> (NetworkModel, Vec<f64>) {
    let cell = ready::kagome();
    let patch = Patch::new(&cell, [n, n], Boundary::Periodic).unwrap();
    let law = |p: usize| {
        let c3 = if per_bond { -0.5 + 0.1 * (p as f64 * 0.61).sin() } else { -0.5 };
        Polynomial::new(&[1.0, c3, 0.25, 0.0, 0.1]).unwrap()
    };
    let mut builder = NetworkModel::builder(&patch).law(law(0));
    for p in (0..patch.bonds().len()).filter(|_| per_bond) {
        builder = builder.spring_law(p, law(p));
    }
    let model = builder.build().unwrap();
    let x = model.reference().iter().enumerate().map(|(i, x)| x + 0.01 * (i as f64 * 0.37).sin()).collect();
    (model, x)
}

/// The polynomial law's fused energy and gradient on the 64 x 64 patch, its coefficients shared by
/// every bond (constants of every run), per bond.
#[divan::bench]
fn network_polynomial_shared_per_bond(bencher: Bencher) {
    let (model, x) = kagome_polynomial(64, false);
    let mut g = vec![0.0; x.len()];
    bencher
        .counter(ItemsCount::new(model.spring_count()))
        .bench_local(|| model.energy_and_gradient_into(black_box(&x), &mut g));
}

/// The polynomial law with each bond's own coefficients (per-bond arrays of the runs), per bond.
#[divan::bench]
fn network_polynomial_own_per_bond(bencher: Bencher) {
    let (model, x) = kagome_polynomial(64, true);
    let mut g = vec![0.0; x.len()];
    bencher
        .counter(ItemsCount::new(model.spring_count()))
        .bench_local(|| model.energy_and_gradient_into(black_box(&x), &mut g));
}

/// The chain's fused energy and gradient with as many springs (24 576), per spring.
#[divan::bench]
fn chain_energy_gradient_per_spring(bencher: Bencher) {
    let n = 24_577;
    let chain = RuntimeChain::builder(n, 0.8, 1.0e4, 0.58).build().unwrap();
    let theta: Vec<f64> = (0..n).map(|i| 0.58 + 0.01 * (i as f64 * 0.37).sin()).collect();
    let mut g = vec![0.0; n];
    bencher
        .counter(ItemsCount::new(n - 1))
        .bench_local(|| chain.energy_and_gradient_into(black_box(&theta), &mut g));
}

/// One velocity-Verlet step (one gradient) on the 256 x 256 periodic kagome patch, per degree of
/// freedom.
#[divan::bench(sample_count = 20)]
fn verlet_step_kagome_256(bencher: Bencher) {
    let (model, x) = kagome(256);
    let n = x.len();
    let mut stepper = Verlet::new(&model, Phase { time: 0.0, theta: x, omega: vec![0.0; n] }, 0.01).unwrap();
    bencher.counter(ItemsCount::new(n)).bench_local(|| stepper.step(&model).unwrap());
}
