//! Speed of the vectorised evaluation at every dispatch level, as ratios to the scalar
//! transcendental floor measured in the same run.
//!
//! Run: `cargo bench --bench simd` (results and their reading: `docs/benchmarks.md`).
//!
//! - `floor`: 60 scalar `sin_cos` + 59 `sqrt` (the floor of `benches/generated.rs`);
//! - `vector_floor`: the same transcendental work in lanes: `RuntimeChain::spring_lengths_into`
//!   for 60 rotors (60 `sin_cos`, 59 `sqrt`, and the few products that form their arguments);
//! - `sin_cos_60`: `math::sin_cos_into` of 60 angles;
//! - `runtime_energy_gradient` / `runtime_energy_gradient_stiffness`: the fused `ChainModel`
//!   methods of `RuntimeChain` at n = 60, 1000, 1e5;
//! - `crossover_*`: n = 16 ... 1000, the macro's unrolled scalar gradient against the vectorised
//!   loop (the runtime chain's fused energy + gradient, and the macro's looped gradient, whose
//!   parameters come from a closure), to set the unroll threshold by measurement.
//!
//! Each vector benchmark takes the level as its argument (`scalar`, `avx2`, `avx512`) and is
//! skipped on a machine without it. Before timing, `main` checks that every level's fused
//! outputs equal the separate scalar ones to 1e-12.

mod support;

use divan::{Bencher, black_box};
use rotor_chain::prelude::*;
use rotor_chain::simd::{self, Level};
use rotor_chain::{RuntimeChain, math};
use support::{BATCH, N, angles, batch_angles, configuration, transcendental_floor};

const LEVELS: [&str; 3] = ["scalar", "avx2", "avx512"];

fn level(name: &str) -> Level {
    Level::ALL.into_iter().find(|l| l.name() == name).expect("a level name")
}

/// Runs `bench` with every dispatched call at `name`'s level; nothing on a machine without it.
fn at(name: &str, bench: impl FnOnce()) {
    let _ = simd::with_level(level(name), bench);
}

fn chain(n: usize) -> RuntimeChain {
    RuntimeChain::builder(n, 0.8, 1.0e4, 0.58).build().unwrap()
}

fn main() {
    check_agreement();
    divan::Divan::default().sample_count(200).sample_size(200).config_with_args().main();
}

/// The fused outputs at every level equal the scalar separate ones (to 1e-12 of the largest entry).
fn check_agreement() {
    for n in [60, 1000] {
        let (c, theta) = (chain(n), angles(n));
        let (mut g, mut k) = (vec![0.0; n], vec![0.0; 2 * n - 1]);
        let energy = simd::with_level(Level::Scalar, || {
            c.gradient_into(&theta, &mut g);
            c.tangent_stiffness_into(&theta, &mut k);
            c.energy(&theta)
        })
        .unwrap();
        for l in Level::ALL.into_iter().filter(|l| l.is_supported()) {
            let (mut g2, mut k2) = (vec![0.0; n], vec![0.0; 2 * n - 1]);
            let e2 =
                simd::with_level(l, || c.energy_gradient_stiffness_into(&theta, &mut g2, &mut k2)).unwrap();
            for (what, a, b) in
                [("energy", &vec![energy], &vec![e2]), ("gradient", &g, &g2), ("(diag, off)", &k, &k2)]
            {
                let scale = a.iter().fold(0.0f64, |s, x| s.max(x.abs()));
                for (x, y) in a.iter().zip(b.iter()) {
                    assert!((x - y).abs() <= 1e-12 * scale, "n = {n}, {}: {what} {x} vs {y}", l.name());
                }
            }
        }
    }
}

#[divan::bench]
fn floor(bencher: Bencher) {
    let theta = configuration();
    bencher.bench_local(|| transcendental_floor(black_box(&theta)));
}

#[divan::bench(args = LEVELS)]
fn vector_floor(bencher: Bencher, level: &str) {
    let (c, theta) = (chain(N), configuration());
    let mut lengths = [0.0; N - 1];
    at(level, || {
        bencher.bench_local(|| {
            black_box(&c).spring_lengths_into(black_box(&theta), &mut lengths);
            black_box(&lengths);
        })
    });
}

#[divan::bench(args = LEVELS)]
fn sin_cos_60(bencher: Bencher, level: &str) {
    let theta = configuration();
    let (mut s, mut c) = ([0.0; N], [0.0; N]);
    at(level, || {
        bencher.bench_local(|| {
            math::sin_cos_into(black_box(&theta), &mut s, &mut c);
            black_box((&s, &c));
        })
    });
}

/// `level/n` pairs for the fused benchmarks (n = 1e5 has its own functions, `*_100000`).
const FUSED: [(&str, usize); 6] =
    [("scalar", 60), ("avx2", 60), ("avx512", 60), ("scalar", 1000), ("avx2", 1000), ("avx512", 1000)];

/// `runtime_energy_gradient` at n = 1e5 (a call takes 0.2-2 ms: with `main`'s 200 x 200 samples
/// the n = 1e5 benchmarks take minutes; leave them out with a filter when iterating).
#[divan::bench(args = LEVELS)]
fn runtime_energy_gradient_100000(bencher: Bencher, level: &str) {
    runtime_energy_gradient(bencher, (level, 100_000));
}

/// `runtime_energy_gradient_stiffness` at n = 1e5.
#[divan::bench(args = LEVELS)]
fn runtime_energy_gradient_stiffness_100000(bencher: Bencher, level: &str) {
    runtime_energy_gradient_stiffness(bencher, (level, 100_000));
}

#[divan::bench(args = FUSED)]
fn runtime_energy_gradient(bencher: Bencher, (level, n): (&str, usize)) {
    let (c, theta) = (chain(n), angles(n));
    let mut g = vec![0.0; n];
    at(level, || bencher.bench_local(|| black_box(&c).energy_and_gradient_into(black_box(&theta), &mut g)));
}

#[divan::bench(args = FUSED)]
fn runtime_energy_gradient_stiffness(bencher: Bencher, (level, n): (&str, usize)) {
    let (c, theta) = (chain(n), angles(n));
    let (mut g, mut k) = (vec![0.0; n], vec![0.0; 2 * n - 1]);
    at(level, || {
        bencher
            .bench_local(|| black_box(&c).energy_gradient_stiffness_into(black_box(&theta), &mut g, &mut k))
    });
}

// ---------------------------------------------------------------------------------------------
// Crossover: unrolled scalar code against the vectorised loop, n = 16 ... 1000.
// ---------------------------------------------------------------------------------------------

const CROSSOVER_N: [usize; 7] = [16, 32, 64, 128, 256, 512, 1000];

/// `(level, n)` for every level and crossover length.
fn crossover_args() -> Vec<(&'static str, usize)> {
    LEVELS.iter().flat_map(|&l| CROSSOVER_N.map(|n| (l, n))).collect()
}

// The same chain unrolled (up to n = 512: the macro's own `#[rotor_chain]` key values must be
// literals, so the lengths are spelled out) and looped.
#[rotor_chain(n = 16, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 512)]
struct U16;
#[rotor_chain(n = 32, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 512)]
struct U32;
#[rotor_chain(n = 64, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 512)]
struct U64;
#[rotor_chain(n = 128, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 512)]
struct U128;
#[rotor_chain(n = 256, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 512)]
struct U256;
#[rotor_chain(n = 512, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 512)]
struct U512;
#[rotor_chain(n = 16, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0)]
struct L16;
#[rotor_chain(n = 32, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0)]
struct L32;
#[rotor_chain(n = 64, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0)]
struct L64;
#[rotor_chain(n = 128, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0)]
struct L128;
#[rotor_chain(n = 256, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0)]
struct L256;
#[rotor_chain(n = 512, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0)]
struct L512;
#[rotor_chain(n = 1000, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0)]
struct L1000;

fn bench_unrolled<const K: usize>(bencher: Bencher, chain: &impl Unrolled<K>, theta: &[f64]) {
    let t: &[f64; K] = theta.try_into().unwrap();
    bencher.bench_local(|| chain.gradient_array(black_box(t)));
}

/// The unrolled chains' inherent array gradient, behind one name.
trait Unrolled<const K: usize> {
    fn gradient_array(&self, theta: &[f64; K]) -> [f64; K];
}
macro_rules! unrolled {
    ($($t:ident = $n:literal),*) => { $(impl Unrolled<$n> for $t {
        fn gradient_array(&self, theta: &[f64; $n]) -> [f64; $n] {
            black_box(self).gradient(theta)
        }
    })* };
}
unrolled!(U16 = 16, U32 = 32, U64 = 64, U128 = 128, U256 = 256, U512 = 512);

/// The unrolled macro chain's scalar gradient (its energy + gradient costs about the same: both
/// are dominated by the `n` `sin_cos` calls they share).
#[divan::bench(args = [16, 32, 64, 128, 256, 512])]
fn crossover_unrolled_gradient(bencher: Bencher, n: usize) {
    let theta = angles(n);
    match n {
        16 => bench_unrolled(bencher, &U16, &theta),
        32 => bench_unrolled(bencher, &U32, &theta),
        64 => bench_unrolled(bencher, &U64, &theta),
        128 => bench_unrolled(bencher, &U128, &theta),
        256 => bench_unrolled(bencher, &U256, &theta),
        512 => bench_unrolled(bencher, &U512, &theta),
        _ => unreachable!("one chain per length"),
    }
}

/// The macro's looped gradient (vectorised drivers; parameters through a closure).
#[divan::bench(args = crossover_args())]
fn crossover_looped_gradient(bencher: Bencher, (level, n): (&str, usize)) {
    let theta = angles(n);
    let mut g = vec![0.0; n];
    at(level, || match n {
        16 => bencher.bench_local(|| black_box(&L16).gradient_into(black_box(&theta), &mut g)),
        32 => bencher.bench_local(|| black_box(&L32).gradient_into(black_box(&theta), &mut g)),
        64 => bencher.bench_local(|| black_box(&L64).gradient_into(black_box(&theta), &mut g)),
        128 => bencher.bench_local(|| black_box(&L128).gradient_into(black_box(&theta), &mut g)),
        256 => bencher.bench_local(|| black_box(&L256).gradient_into(black_box(&theta), &mut g)),
        512 => bencher.bench_local(|| black_box(&L512).gradient_into(black_box(&theta), &mut g)),
        1000 => bencher.bench_local(|| black_box(&L1000).gradient_into(black_box(&theta), &mut g)),
        _ => unreachable!("one chain per length"),
    });
}

/// The runtime chain's fused energy + gradient (vectorised drivers, parameters in slices).
#[divan::bench(args = crossover_args())]
fn crossover_runtime_energy_gradient(bencher: Bencher, (level, n): (&str, usize)) {
    let (c, theta) = (chain(n), angles(n));
    let mut g = vec![0.0; n];
    at(level, || bencher.bench_local(|| black_box(&c).energy_and_gradient_into(black_box(&theta), &mut g)));
}

// ---------------------------------------------------------------------------------------------
// Macro chains' fused methods, Verlet steps and batches (n = 60 unless stated).
// ---------------------------------------------------------------------------------------------

#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 128)]
struct Unrolled60;
#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0)]
struct Looped60;

/// The unrolled macro chain's fused `energy_and_gradient` (straight-line scalar code: one level).
#[divan::bench]
fn macro_unrolled_energy_gradient(bencher: Bencher) {
    let theta = configuration();
    bencher.bench_local(|| black_box(&Unrolled60).energy_and_gradient(black_box(&theta)));
}

/// The unrolled macro chain's fused `energy_gradient_stiffness`.
#[divan::bench]
fn macro_unrolled_energy_gradient_stiffness(bencher: Bencher) {
    let theta = configuration();
    bencher.bench_local(|| black_box(&Unrolled60).energy_gradient_stiffness(black_box(&theta)));
}

/// The looped macro chain's fused `energy_and_gradient` (vectorised drivers) at each level.
#[divan::bench(args = LEVELS)]
fn macro_looped_energy_gradient(bencher: Bencher, level: &str) {
    let theta = configuration();
    at(level, || bencher.bench_local(|| black_box(&Looped60).energy_and_gradient(black_box(&theta))));
}

/// The looped macro chain's fused `energy_gradient_stiffness` at each level.
#[divan::bench(args = LEVELS)]
fn macro_looped_energy_gradient_stiffness(bencher: Bencher, level: &str) {
    let theta = configuration();
    at(level, || bencher.bench_local(|| black_box(&Looped60).energy_gradient_stiffness(black_box(&theta))));
}

/// One velocity-Verlet step (`Verlet::step_to`: one fused energy + gradient and two sweeps) of a
/// runtime chain of 60 rotors, at each level.
#[divan::bench(args = LEVELS)]
fn verlet_step(bencher: Bencher, level: &str) {
    verlet_step_n(bencher, level, N);
}

/// The same at n = 1e5 (per-rotor cost = time / 1e5).
#[divan::bench(args = LEVELS)]
fn verlet_step_100000(bencher: Bencher, level: &str) {
    verlet_step_n(bencher, level, 100_000);
}

fn verlet_step_n(bencher: Bencher, level: &str, n: usize) {
    use rotor_chain::integrate::{State, Verlet, VerletOptions};
    let c = chain(n);
    let theta = angles(n);
    let dt = VerletOptions::stable_for(&c, &theta, VerletOptions::DEFAULT_SAFETY).unwrap().dt;
    // The runs' stepper: damping rates (zero) and the energy with every gradient.
    at(level, || {
        let mut stepper = Verlet::damped(&c, State::at_rest(theta.clone()), dt, &vec![0.0; n]).unwrap();
        let mut time = 0.0;
        bencher.bench_local(|| {
            time += dt;
            stepper.step_to(&c, time).unwrap();
        })
    });
}

/// The unrolled macro chain's Verlet step (scalar straight-line fused energy + gradient).
#[divan::bench]
fn verlet_step_macro_unrolled(bencher: Bencher) {
    use rotor_chain::integrate::{State, Verlet, VerletOptions};
    let theta = angles(N);
    let dt = VerletOptions::stable_for(&Unrolled60, &theta, VerletOptions::DEFAULT_SAFETY).unwrap().dt;
    let mut stepper = Verlet::damped(&Unrolled60, State::at_rest(theta), dt, &[0.0; N]).unwrap();
    let mut time = 0.0;
    bencher.bench_local(|| {
        time += dt;
        stepper.step_to(&Unrolled60, time).unwrap();
    });
}

/// `batch::gradients` of 1024 configurations on rayon's pool (all cores, detected level): time /
/// 1024 is the cost per configuration.
#[divan::bench]
fn batch_gradients_1024(bencher: Bencher) {
    let (c, thetas) = (chain(N), batch_angles());
    let mut g = vec![0.0; BATCH * N];
    bencher.bench_local(|| rotor_chain::batch::gradients(black_box(&c), black_box(&thetas), &mut g).unwrap());
}

/// The same 1024 gradients one by one on one core (detected level).
#[divan::bench]
fn batch_one_by_one_1024(bencher: Bencher) {
    let (c, thetas) = (chain(N), batch_angles());
    let mut g = vec![0.0; BATCH * N];
    bencher.bench_local(|| {
        for (t, g) in thetas.chunks(N).zip(g.chunks_mut(N)) {
            black_box(&c).gradient_into(black_box(t), g);
        }
    });
}

/// The same 1024 gradients on one core as one long chain (`ChainModel::batch_gradient_into`:
/// the configurations back to back, the springs joining them dropped), detected level.
#[divan::bench]
fn batch_back_to_back_1024(bencher: Bencher) {
    let (c, thetas) = (chain(N), batch_angles());
    let mut g = vec![0.0; BATCH * N];
    bencher.bench_local(|| black_box(&c).batch_gradient_into(black_box(&thetas), &mut g));
}
