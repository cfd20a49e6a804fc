//! Batches of configurations laid back to back: a runtime chain drives them through its vector
//! loop as one long chain, dropping the springs that would join two configurations
//! (`kernel::BackToBack`). Every configuration must get what it gets alone, at every dispatch
//! level, for chains shorter than a vector (several joins in one group of lanes) and longer, and
//! a NaN in one configuration must not leak into its neighbours.

use chain_core::ChainGeometry;
use chain_core::Potential;
use chain_core::simd::{self, Level};
use chain_core::{Law, RuntimeChain, batch};

/// A chain of `n` rotors with one softer, longer spring and one shorter rotor where it has room.
fn chain(n: usize, law: Law) -> RuntimeChain {
    let mut b = RuntimeChain::builder(n, 0.8, 1.0e4, 0.58).law(law);
    if n > 2 {
        b = b.spring(n / 2, Some(50.0), Some(0.9)).rotor(n - 2, 0.7);
    }
    b.build().expect("valid parameters")
}

/// `count` configurations of `n` angles near the uniform state, each one different.
fn configurations(n: usize, count: usize) -> Vec<f64> {
    (0..count * n)
        .map(|i| {
            let (c, j) = ((i / n) as f64, (i % n) as f64);
            0.58 * (0.37 * j + 0.9 * c).cos() + 0.2 * (0.011 * i as f64 + c).sin()
        })
        .collect()
}

/// Same value, or both NaN (the sign of a zero aside).
fn same(a: f64, b: f64) -> bool {
    a == b || (a.is_nan() && b.is_nan())
}

/// Checks a batch against one-by-one evaluation, at the current level.
fn check(chain: &RuntimeChain, thetas: &[f64], what: &str) {
    let n = chain.rotor_count();
    let count = thetas.len() / n;
    let mut g = vec![f64::NAN; thetas.len()];
    chain.batch_gradient_into(thetas, &mut g);
    let (mut e2, mut g2) = (vec![f64::NAN; count], vec![f64::NAN; thetas.len()]);
    chain.batch_energy_and_gradient_into(thetas, &mut e2, &mut g2);
    for c in 0..count {
        let t = &thetas[c * n..(c + 1) * n];
        let mut alone = vec![0.0; n];
        let energy = chain.energy_and_gradient_into(t, &mut alone);
        for (i, &x) in alone.iter().enumerate() {
            let k = c * n + i;
            assert!(
                same(g[k], x),
                "{what}: gradient {i} of configuration {c}: {x} alone, {} in the batch",
                g[k]
            );
            assert!(same(g2[k], x), "{what}: fused gradient {i} of configuration {c}: {x} alone, {}", g2[k]);
        }
        // The terms of each energy are summed in another order than alone: within the rounding
        // of a sum of n - 1 non-negative terms.
        let tolerance = n as f64 * f64::EPSILON * energy.abs();
        assert!(
            (e2[c] - energy).abs() <= tolerance || same(e2[c], energy),
            "{what}: energy of configuration {c}: {energy} alone, {} in the batch",
            e2[c]
        );
    }
}

#[test]
fn a_batch_gives_every_configuration_what_it_gets_alone_at_every_level() {
    for level in Level::ALL.into_iter().filter(|l| l.is_supported()) {
        simd::with_level(level, || {
            for law in [Law::Harmonic, Law::Quartic] {
                for n in [2, 3, 5, 7, 8, 9, 16, 23, 60] {
                    let chain = chain(n, law);
                    for count in [1, 2, 3, 17, 40] {
                        check(
                            &chain,
                            &configurations(n, count),
                            &format!("{level:?}, {law:?}, n = {n}, {count} configurations"),
                        );
                    }
                }
            }
        });
    }
}

/// More configurations than one block of the tiled parameters holds (1024 rotors), with a last
/// block shorter than the others.
#[test]
fn batches_longer_than_a_block_split_into_whole_configurations() {
    for n in [7, 60, 1500] {
        let chain = chain(n, Law::Harmonic);
        let count = 2048 / n + 3;
        check(&chain, &configurations(n, count), &format!("n = {n}, {count} configurations"));
    }
}

#[test]
fn a_nan_stays_in_its_own_configuration() {
    for level in Level::ALL.into_iter().filter(|l| l.is_supported()) {
        simd::with_level(level, || {
            for n in [3, 9, 23] {
                let chain = chain(n, Law::Harmonic);
                // The last angle of the first configuration, the first of the third, and an
                // infinite angle in the middle of the fifth: each touches a joining spring or
                // its neighbours.
                let mut thetas = configurations(n, 6);
                thetas[n - 1] = f64::NAN;
                thetas[2 * n] = f64::NAN;
                thetas[4 * n + n / 2] = f64::INFINITY;
                check(&chain, &thetas, &format!("{level:?}, n = {n}, NaN and infinity"));
                let mut g = vec![0.0; thetas.len()];
                chain.batch_gradient_into(&thetas, &mut g);
                for c in [1, 3, 5] {
                    assert!(
                        g[c * n..(c + 1) * n].iter().all(|x| x.is_finite()),
                        "{level:?}, n = {n}: configuration {c} caught a NaN"
                    );
                }
            }
        });
    }
}

/// No configurations: a valid batch (not an error, not a panic), with nothing written.
#[test]
fn an_empty_batch_is_a_valid_batch() {
    let chain = chain(5, Law::Harmonic);
    assert_eq!(batch::gradients(&chain, &[], &mut []), Ok(()));
    assert_eq!(batch::energies_and_gradients(&chain, &[], &mut [], &mut []), Ok(()));
}

/// The tiled parameters a chain keeps for its batches do not fill its `Debug` output.
#[test]
fn a_chains_batch_tiles_are_not_printed() {
    let a = chain(60, Law::Harmonic);
    let printed = format!("{a:?}");
    // 60 rotor lengths of 0.8 printed once, not 17 times over.
    assert!(printed.matches("0.8").count() <= 61, "{} copies of 0.8", printed.matches("0.8").count());
}

/// `batch::gradients` hands pieces of a batch to the pool's threads as well as the calling one:
/// each must run at the calling thread's level, forced or not, or a configuration's bits would
/// depend on which thread took it. The levels' gradients differ in their last bits (vector and
/// scalar `sin_cos`), which the second half checks so that the first can fail. It can fail only
/// where rayon's pool has a second thread to take pieces and the machine runs a second level;
/// on a one-core or scalar-only machine it checks less.
#[test]
fn the_pools_threads_run_a_batch_at_the_callers_level() {
    let (n, count) = (60, 600);
    let chain = chain(n, Law::Harmonic);
    let thetas = configurations(n, count);
    let mut by_level = Vec::new();
    for level in Level::ALL.into_iter().filter(|l| l.is_supported()) {
        simd::with_level(level, || {
            let mut alone = vec![0.0; thetas.len()];
            chain.batch_gradient_into(&thetas, &mut alone);
            let (mut g, mut g2, mut e) = (vec![0.0; thetas.len()], vec![0.0; thetas.len()], vec![0.0; count]);
            batch::gradients(&chain, &thetas, &mut g).expect("a whole batch");
            batch::energies_and_gradients(&chain, &thetas, &mut e, &mut g2).expect("a whole batch");
            let mut e_alone = vec![0.0; count];
            chain.batch_energy_and_gradient_into(&thetas, &mut e_alone, &mut alone.clone());
            assert!(g == alone, "{level:?}: a gradient on the pool differs from the calling thread's");
            assert!(g2 == alone, "{level:?}: a fused gradient on the pool differs from the calling thread's");
            // The energies' terms are summed per piece, in another order (module doc of `batch`).
            for (c, (a, b)) in e.iter().zip(&e_alone).enumerate() {
                assert!(
                    (a - b).abs() <= n as f64 * f64::EPSILON * b.abs(),
                    "{level:?}: energy {c}: {a} against {b}"
                );
            }
            by_level.push((level, alone));
        });
    }
    if let [(first, a), rest @ ..] = by_level.as_slice() {
        for (level, b) in rest {
            assert!(a != b, "{first:?} and {level:?} agree to the bit: the check above could not fail");
        }
    }
}
