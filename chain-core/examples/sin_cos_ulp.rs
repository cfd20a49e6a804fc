//! The error of `math::sin_cos_into` at every dispatch level this machine supports, against
//! correctly rounded sines and cosines, on 3.4e6 points per range, 1.02e7 in all (or the count
//! per range given):
//!
//! ```sh
//! cargo run --release -p rotor-chain-core --example sin_cos_ulp -- [points-per-range]
//! ```
//!
//! The reference (dashu-float, arbitrary precision) dominates the run time: computed once per
//! point on both cores, then every level is compared with it.

use chain_core::math;
use chain_core::simd::{self, Level};
use test_support::ulp;

fn main() {
    let count: usize = std::env::args().nth(1).map_or(3_400_000, |s| s.parse().expect("a point count"));
    println!("points per range: {count}; detected level: {}", simd::detected().name());
    println!("| range | level | points | max ulp (sin, cos) | at | points at 1 ulp | at >= 2 ulp |");
    println!("|---|---|---:|---:|---:|---:|---:|");
    for (seed, (name, range)) in ulp::RANGES.iter().enumerate() {
        let theta = ulp::angles(*range, count, 0x5EED_0000 + seed as u64);
        let reference = reference_in_parallel(&theta);
        for level in Level::ALL.into_iter().filter(|l| l.is_supported()) {
            let (mut sin, mut cos) = (vec![0.0; count], vec![0.0; count]);
            simd::with_level(level, || math::sin_cos_into(&theta, &mut sin, &mut cos));
            let w = ulp::worst(&theta, &sin, &cos, &reference);
            println!(
                "| {name} | {} | {count} | {} | {:.17e} | {} | {} |",
                level.name(),
                w.ulps,
                w.angle,
                w.at_one,
                w.at_two_or_more
            );
        }
    }
}

fn reference_in_parallel(theta: &[f64]) -> Vec<(f64, f64)> {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let chunk = theta.len().div_ceil(threads).max(1);
    std::thread::scope(|s| {
        let handles: Vec<_> = theta
            .chunks(chunk)
            .map(|c| s.spawn(move || c.iter().map(|&x| ulp::reference(x)).collect::<Vec<_>>()))
            .collect();
        handles.into_iter().flat_map(|h| h.join().expect("reference thread")).collect()
    })
}
