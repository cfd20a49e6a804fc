//! A 1000 x 1000 periodic kagome patch (6 000 000 degrees of freedom, 6 000 000 bonds) built and
//! stepped with velocity Verlet: the model's heap, the process's peak resident memory and the
//! time per step (docs/benchmarks.md, "Networks in motion"). `cargo run --release -p
//! rotor-chain-network --example large_patch [cells]` (at most `patch::MAX_PATCH_BONDS` bonds).

use chain_core::integrate::{Phase, Verlet};
use chain_core::{Potential, SpringNetwork};
use chain_network::NetworkModel;
use chain_network::cell::ready;
use chain_network::patch::{Boundary, Patch};
use std::time::Instant;

/// The process's peak resident set (`VmHWM`, Linux), in bytes.
fn peak_resident() -> Option<usize> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: usize = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = std::env::args().nth(1).map(|s| s.parse()).transpose()?.unwrap_or(1000);
    let steps = 10;
    let cell = ready::kagome();
    let start = Instant::now();
    let model = {
        let patch = Patch::new(&cell, [n, n], Boundary::Periodic)?;
        NetworkModel::builder(&patch).build()?
    };
    let built = start.elapsed();
    // The build's own peak (its transients: the per-spring laws, the runs' bucketing), before any
    // Verlet state or gradient buffer exists.
    let peak_built = peak_resident();
    let dof = model.dof_count();
    let mut x = model.reference();
    for (i, x) in x.iter_mut().enumerate() {
        *x += 0.01 * (i as f64 * 0.37).sin();
    }
    let e0 = model.energy(&x);
    let mut stepper = Verlet::new(&model, Phase { time: 0.0, theta: x, omega: vec![0.0; dof] }, 0.01)?;
    let start = Instant::now();
    for _ in 0..steps {
        stepper.step(&model)?;
    }
    let per_step = start.elapsed() / steps;
    let e1 = stepper.kinetic_energy(&model) + stepper.potential_energy(&model);
    let heap = model.heap_bytes();
    println!("kagome {n} x {n}: {dof} dof, {} bonds, built in {built:.2?}", model.spring_count());
    println!("model heap {heap} B = {:.1} B per dof", heap as f64 / dof as f64);
    if let (Some(built), Some(peak)) = (peak_built, peak_resident()) {
        let per_dof = |b: usize| b as f64 / dof as f64;
        println!(
            "peak resident {peak} B = {:.1} B per dof (after the build: {built} B = {:.1} B per dof)",
            per_dof(peak),
            per_dof(built)
        );
    }
    println!(
        "Verlet step {per_step:.2?} = {:.2} ns per dof at dispatch level {:?}; energy {e0:.6e} -> {e1:.6e}",
        per_step.as_nanos() as f64 / dof as f64,
        chain_core::simd::level()
    );
    Ok(())
}
