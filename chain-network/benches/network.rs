//! Speed of the network analyses (issue 33), side by side in one run: periodic counts through
//! Bloch blocks (the 100 x 100 kagome patch, 60 000 degrees of freedom), free counts by one
//! dense SVD (kagome 10 x 10 and 20 x 20; the 40 x 40 patch is timed once by the `network`
//! command, docs/benchmarks.md), a winding number, a strip. `cargo bench -p rotor-chain-network`;
//! results and the CPU in docs/benchmarks.md. Threads: the free-patch SVD uses 2.

use chain_network::cell::ready;
use chain_network::counts::counts;
use chain_network::patch::{Boundary, Patch};
use chain_network::strip::{Strip, strip_modes};
use chain_network::winding::{WindingOptions, winding};

fn main() {
    divan::main();
}

#[divan::bench(args = [20, 50, 100], sample_count = 10, sample_size = 1)]
fn periodic_kagome_counts(n: usize) -> usize {
    let cell = ready::kagome();
    counts(&Patch::new(&cell, [n, n], Boundary::Periodic).unwrap()).unwrap().zero_modes
}

#[divan::bench(args = [10, 20], sample_count = 3, sample_size = 1)]
fn free_kagome_counts(n: usize) -> usize {
    let cell = ready::kagome();
    counts(&Patch::new(&cell, [n, n], Boundary::Free).unwrap()).unwrap().zero_modes
}

#[divan::bench(sample_count = 50, sample_size = 1)]
fn winding_deformed_kagome() -> i64 {
    let cell = ready::deformed_kagome(-0.05, 0.05, 0.05, 0.0).unwrap();
    winding(&cell, &WindingOptions::default()).unwrap().winding[0]
}

#[divan::bench(sample_count = 10, sample_size = 1)]
fn strip_deformed_kagome_24() -> usize {
    let cell = ready::deformed_kagome(0.1, 0.1, -0.1, 0.0).unwrap();
    strip_modes(&cell, &Strip { along: 0, cells: 24, q: 2.0 }).unwrap().low
}
