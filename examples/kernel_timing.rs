//! A standalone timing of the vectorised kernels of a 60-rotor `RuntimeChain`, outside the
//! benchmark binary (whose many chains change how the drivers are compiled and placed; see
//! `docs/benchmarks.md`). Each figure is the smallest of 15 medians of 201 samples of 200 calls,
//! at AVX2 and AVX-512 when the machine has them, beside the scalar floor of `benches/`.
//!
//! ```sh
//! cargo run --release --example kernel_timing
//! ```
//!
//! A second table gives the throughput the batch rests on: energy + gradient per rotor of a
//! 6 400-rotor chain, and 1 024 gradients of 60 rotors laid back to back
//! (`ChainModel::batch_gradient_into`, one core, per configuration), and through
//! `batch::gradients` (every core, at the detected level).
//!
//! Not a benchmark of record (those are `cargo bench --bench simd`): a quick check that a number
//! seen in the benchmark binary is the code's and not its placement.

#[path = "../benches/support/mod.rs"]
mod support;

use rotor_chain::integrate::{State, Verlet, VerletOptions};
use rotor_chain::math;
use rotor_chain::prelude::*;
use rotor_chain::simd::{self, Level};
use std::hint::black_box;
use std::time::Instant;
use support::{BATCH, N, angles, batch_angles, configuration, transcendental_floor};

/// The smallest of 15 medians of 201 samples of 200 calls, in ns per call.
fn time(f: impl FnMut()) -> f64 {
    smallest_median(201, 200, f)
}

/// The smallest of 15 medians of 21 single calls, in ns per call (for calls of tens of
/// microseconds).
fn time_once(f: impl FnMut()) -> f64 {
    smallest_median(21, 1, f)
}

/// The smallest of 15 medians of `samples` samples of `calls` calls each, in ns per call.
fn smallest_median(samples: usize, calls: u32, mut f: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..15 {
        let mut times: Vec<f64> = (0..samples)
            .map(|_| {
                let t = Instant::now();
                for _ in 0..calls {
                    f();
                }
                t.elapsed().as_nanos() as f64 / f64::from(calls)
            })
            .collect();
        times.sort_by(f64::total_cmp);
        best = best.min(times[samples / 2]);
    }
    best
}

fn main() {
    let n = N;
    let angles = configuration();
    let theta = angles.to_vec();
    let chain = RuntimeChain::builder(n, 0.8, 1.0e4, 0.58).build().expect("valid parameters");
    let fl = time(|| {
        black_box(transcendental_floor(black_box(&angles)));
    });
    println!("scalar floor: {fl:.1} ns");
    println!("| level | sin_cos of 60 | spring lengths | E + g | E + g + K | Verlet step |");
    println!("|---|---:|---:|---:|---:|---:|");
    for level in [Level::Avx2, Level::Avx512] {
        let row = simd::with_level(level, || {
            let c = &chain;
            let (mut s, mut co) = (vec![0.0; n], vec![0.0; n]);
            let sc = time(|| {
                math::sin_cos_into(black_box(&theta), &mut s, &mut co);
                black_box((&s, &co));
            });
            let mut l = vec![0.0; n - 1];
            let lengths = time(|| {
                black_box(c).spring_lengths_into(black_box(&theta), &mut l);
                black_box(&l);
            });
            let mut g = vec![0.0; n];
            let eg = time(|| {
                black_box(black_box(c).energy_and_gradient_into(black_box(&theta), &mut g));
            });
            let mut k = vec![0.0; 2 * n - 1];
            let egk = time(|| {
                black_box(black_box(c).energy_gradient_stiffness_into(black_box(&theta), &mut g, &mut k));
            });
            let dt =
                VerletOptions::stable_for(c, &theta, VerletOptions::DEFAULT_SAFETY).expect("a time step").dt;
            let mut stepper =
                Verlet::damped(c, State::at_rest(theta.clone()), dt, &vec![0.0; n]).expect("a stepper");
            let mut t = 0.0;
            let verlet = time(|| {
                t += dt;
                stepper.step_to(c, t).expect("a step");
            });
            [sc, lengths, eg, egk, verlet]
        });
        if let Some(row) = row {
            let cells: Vec<String> = row.iter().map(|ns| format!("{ns:.1} ns ({:.3}x)", ns / fl)).collect();
            println!("| {} | {} |", level.name(), cells.join(" | "));
        }
    }

    long_chains_and_batches();
}

/// Energy + gradient of a long chain per rotor, and the 1 024 x 60 batch per configuration.
fn long_chains_and_batches() {
    const LONG: usize = 6_400;
    let long = RuntimeChain::builder(LONG, 0.8, 1.0e4, 0.58).build().expect("valid parameters");
    let theta_long = angles(LONG);
    let chain = RuntimeChain::builder(N, 0.8, 1.0e4, 0.58).build().expect("valid parameters");
    let thetas = batch_angles();
    println!();
    println!("| level | E + g per rotor, n = 6 400 | 1 024 x 60 gradients back to back, one core |");
    println!("|---|---:|---:|");
    for level in [Level::Avx2, Level::Avx512] {
        let row = simd::with_level(level, || {
            let mut g = vec![0.0; LONG];
            let eg = time_once(|| {
                black_box(black_box(&long).energy_and_gradient_into(black_box(&theta_long), &mut g));
            }) / LONG as f64;
            let mut gb = vec![0.0; BATCH * N];
            let one = time_once(|| {
                black_box(&chain).batch_gradient_into(black_box(&thetas), &mut gb);
                black_box(&gb);
            }) / BATCH as f64;
            [eg, one]
        });
        if let Some([eg, one]) = row {
            println!("| {} | {eg:.2} ns | {one:.1} ns |", level.name());
        }
    }
    // Outside `with_level`: this thread, and so the pool's helpers, run at the detected level.
    let mut gb = vec![0.0; BATCH * N];
    let all = time_once(|| {
        rotor_chain::batch::gradients(black_box(&chain), black_box(&thetas), &mut gb).expect("a batch");
        black_box(&gb);
    }) / BATCH as f64;
    println!(
        "\n`batch::gradients`, 1 024 x 60, every core, detected level ({}): {all:.1} ns per configuration",
        simd::detected().name()
    );
}
