//! A standalone timing of the vectorised kernels of a 60-rotor `RuntimeChain`, outside the
//! benchmark binary (whose many chains change how the drivers are compiled and placed; see
//! `docs/benchmarks.md`). Each figure is the smallest of 15 medians of 201 samples of 200 calls,
//! at AVX2 and AVX-512 when the machine has them, beside the scalar floor of `benches/`.
//!
//! ```sh
//! cargo run --release --example kernel_timing
//! ```
//!
//! Not a benchmark of record (those are `cargo bench --bench simd`): a quick check that a number
//! seen in the benchmark binary is the code's and not its placement.

#[path = "../benches/support/mod.rs"]
mod support;

use rotor_chain::dynamics::integrate::{State, VerletOptions, verlet::Stepper};
use rotor_chain::math;
use rotor_chain::prelude::*;
use rotor_chain::simd::{self, Level};
use std::hint::black_box;
use std::time::Instant;
use support::{N, configuration, transcendental_floor};

/// The smallest of 15 medians, in ns per call.
fn time(mut f: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..15 {
        let mut samples: Vec<f64> = (0..201)
            .map(|_| {
                let t = Instant::now();
                for _ in 0..200 {
                    f();
                }
                t.elapsed().as_nanos() as f64 / 200.0
            })
            .collect();
        samples.sort_by(f64::total_cmp);
        best = best.min(samples[100]);
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
            let (mut d, mut o) = (vec![0.0; n], vec![0.0; n - 1]);
            let egk = time(|| {
                black_box(black_box(c).energy_gradient_stiffness_into(
                    black_box(&theta),
                    &mut g,
                    &mut d,
                    &mut o,
                ));
            });
            let dt =
                VerletOptions::stable_for(c, &theta, VerletOptions::DEFAULT_SAFETY).expect("a time step").dt;
            let mut state = State::at_rest(theta.clone());
            let mut stepper = Stepper::new(c, &mut state, dt, &vec![0.0; n]).expect("a stepper");
            let mut t = 0.0;
            let verlet = time(|| {
                t += dt;
                stepper.step(t).expect("a step");
            });
            [sc, lengths, eg, egk, verlet]
        });
        if let Some(row) = row {
            let cells: Vec<String> = row.iter().map(|ns| format!("{ns:.1} ns ({:.3}x)", ns / fl)).collect();
            println!("| {} | {} |", level.name(), cells.join(" | "));
        }
    }
}
