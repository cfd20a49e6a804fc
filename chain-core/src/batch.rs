//! Many configurations of one chain at once: energies and gradients of a batch of angle vectors
//! (a sweep's grid, an ensemble, a line search's trial points), in parallel over the machine's
//! cores with rayon's pool.
//!
//! A batch is one flat slice, configuration after configuration (`count * n` angles for a chain
//! of `n` rotors), and so are the gradients. The batch is cut into pieces of several
//! configurations, which the calling thread and one helper per other thread of rayon's pool take
//! one after another from a shared queue until none is left. The calling thread works rather than
//! waiting for the pool, and a core that runs slower (another process on it) takes fewer pieces.
//! Each piece goes to the model's [`Potential::batch_gradient_into`] /
//! [`Potential::batch_energy_and_gradient_into`]: one by one for a macro chain, and for a
//! [`crate::RuntimeChain`] as one long chain through its vector loop (the configurations back
//! to back, the springs that would join them dropped: `kernel::BackToBack`), which saves the
//! loop's start and end per configuration. The gradients are the same either way; the energies
//! of a runtime chain's batch agree with its one-by-one energies to rounding (their terms are
//! summed in another order). The helpers run at the calling thread's dispatch level (a level
//! forced with `simd::with_level` included), so which thread takes a piece never changes a bit.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

use crate::model::Potential;

/// Configurations per piece, at least: enough work (a few microseconds at 0.1-1 us per
/// evaluation) to hide taking a piece from the queue, a lock whose cache line moves between cores.
const MIN_PER_PIECE: usize = 16;

/// Pieces per thread, at most: enough that the threads finish within a piece of each other.
const PIECES_PER_THREAD: usize = 8;

/// How long the calling thread spins, at most, for a helper still on a piece once the queue is
/// empty: long past a piece of a sweep-sized batch (~7 us for 64 configurations of 60 rotors),
/// short enough that a piece that runs longer (a long chain, a helper preempted) costs a
/// millisecond of one core before the caller sleeps after all.
const SPIN_LIMIT: Duration = Duration::from_millis(1);

/// A batch whose slices do not fit the chain or each other.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum BatchError {
    /// The angles are not a whole number of configurations of the chain.
    #[error("a batch of {len} angles is not a whole number of configurations of {rotors} rotors")]
    PartialConfiguration {
        /// The length of the angles' slice.
        len: usize,
        /// The chain's rotor count.
        rotors: usize,
    },
    /// An output slice has the wrong length.
    #[error("the batch's {what} hold {len} values, {expected} expected")]
    OutputLength {
        /// Which output (`"gradients"`, `"energies"`).
        what: &'static str,
        /// Its length.
        len: usize,
        /// The length the batch needs.
        expected: usize,
    },
}

/// The number of configurations of a batch, and how many a piece holds.
fn split(n: usize, thetas: &[f64], gradients: &[f64]) -> Result<(usize, usize), BatchError> {
    if n == 0 || !thetas.len().is_multiple_of(n) {
        return Err(BatchError::PartialConfiguration { len: thetas.len(), rotors: n });
    }
    if gradients.len() != thetas.len() {
        return Err(BatchError::OutputLength {
            what: "gradients",
            len: gradients.len(),
            expected: thetas.len(),
        });
    }
    let count = thetas.len() / n;
    let pieces = PIECES_PER_THREAD * rayon::current_num_threads();
    Ok((count, count.div_ceil(pieces).max(MIN_PER_PIECE)))
}

/// Runs `work` on every item of `pieces`: the calling thread takes them from a shared queue, and
/// so does one helper per other thread of the current rayon pool, spawned with
/// `rayon::in_place_scope` (which runs its body on the calling thread, unlike `rayon::scope`,
/// whose caller outside the pool sleeps until the pool is done). Returns when every piece is done.
///
/// When the queue is empty the calling thread spins while a helper is still on its last piece
/// (for [`SPIN_LIMIT`] at most), so that the scope finds every helper done rather than putting
/// the caller to sleep: waking a sleeping thread cost ~10-50 us on this project's machines (a
/// virtual machine), as long as the whole of a 1 024 x 60 batch on two cores. Measured against
/// rayon's `par_chunks` and against the queue without the spin: docs/benchmarks.md, eleventh
/// round.
fn share<P: Send>(pieces: impl ExactSizeIterator<Item = P> + Send, work: impl Fn(P) + Sync) {
    let helpers = rayon::current_num_threads().min(pieces.len()).saturating_sub(1);
    let queue = Mutex::new(pieces);
    // A panic in `work` on another thread poisons nothing that matters: the queue's iterator is
    // only ever advanced, and the scope re-raises that panic once every thread has stopped (the
    // panicking helper never counts as finished, so the caller's spin ends at `SPIN_LIMIT`).
    let drain = || {
        loop {
            // Its own statement: the guard is dropped here, not held through `work` (a `while
            // let` keeps its scrutinee's temporaries to the end of the body).
            let next = queue.lock().unwrap_or_else(PoisonError::into_inner).next();
            let Some(piece) = next else { break };
            work(piece);
        }
    };
    // Helpers that have started, and those that have finished (a helper that starts after the
    // queue ran dry finishes at once).
    let (started, finished) = (AtomicUsize::new(0), AtomicUsize::new(0));
    let level = crate::simd::level();
    rayon::in_place_scope(|scope| {
        for _ in 0..helpers {
            scope.spawn(|_| {
                started.fetch_add(1, Ordering::AcqRel);
                // The calling thread's level is one this machine runs, so `with_level` runs it.
                _ = crate::simd::with_level(level, drain);
                finished.fetch_add(1, Ordering::AcqRel);
            });
        }
        drain();
        let since = Instant::now();
        while finished.load(Ordering::Acquire) < started.load(Ordering::Acquire)
            && since.elapsed() < SPIN_LIMIT
        {
            core::hint::spin_loop();
        }
    });
}

/// The energies and gradients of every configuration in `thetas` (`count * n` angles,
/// configuration after configuration): `gradients` gets `count * n` entries laid out the same
/// way, `energies` one per configuration.
///
/// # Errors
/// [`BatchError`] if `thetas` is not a whole number of configurations, or `gradients` /
/// `energies` do not match it; nothing is evaluated then.
pub fn energies_and_gradients<M: Potential + Sync + ?Sized>(
    model: &M,
    thetas: &[f64],
    energies: &mut [f64],
    gradients: &mut [f64],
) -> Result<(), BatchError> {
    let n = model.dof_count();
    let (count, per_piece) = split(n, thetas, gradients)?;
    if energies.len() != count {
        return Err(BatchError::OutputLength { what: "energies", len: energies.len(), expected: count });
    }
    let pieces = thetas
        .chunks(n * per_piece)
        .zip(gradients.chunks_mut(n * per_piece))
        .zip(energies.chunks_mut(per_piece));
    share(pieces, |((theta, gradient), energy)| {
        model.batch_energy_and_gradient_into(theta, energy, gradient)
    });
    Ok(())
}

/// The gradients of every configuration in `thetas` (layout as [`energies_and_gradients`]).
///
/// # Errors
/// As [`energies_and_gradients`].
pub fn gradients<M: Potential + Sync + ?Sized>(
    model: &M,
    thetas: &[f64],
    gradients: &mut [f64],
) -> Result<(), BatchError> {
    let n = model.dof_count();
    let (_, per_piece) = split(n, thetas, gradients)?;
    let pieces = thetas.chunks(n * per_piece).zip(gradients.chunks_mut(n * per_piece));
    share(pieces, |(theta, gradient)| model.batch_gradient_into(theta, gradient));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::RuntimeChain;

    /// Every configuration of a batch equals its own evaluation, whatever the batch size (one
    /// configuration, fewer than a task, many tasks).
    #[test]
    fn a_batch_equals_its_configurations_one_by_one() {
        let chain = RuntimeChain::builder(23, 0.8, 1.0e4, 0.58).spring_constant(7, 50.0).build().unwrap();
        let n = 23;
        for count in [1, 5, 17, 300] {
            let thetas: Vec<f64> = (0..count * n)
                .map(|i| 0.58 * (0.37 * i as f64).cos() + 0.1 * (0.011 * i as f64).sin())
                .collect();
            let (mut e, mut g) = (vec![0.0; count], vec![0.0; count * n]);
            energies_and_gradients(&chain, &thetas, &mut e, &mut g).unwrap();
            let mut g2 = vec![0.0; count * n];
            gradients(&chain, &thetas, &mut g2).unwrap();
            for c in 0..count {
                let t = &thetas[c * n..(c + 1) * n];
                let mut expected = vec![0.0; n];
                chain.gradient_into(t, &mut expected);
                // Summed in another order than alone (module doc): within the rounding of a
                // sum of n positive terms.
                let alone = chain.energy(t);
                assert!((e[c] - alone).abs() <= n as f64 * f64::EPSILON * alone, "energy {c} of {count}");
                assert_eq!(&g[c * n..(c + 1) * n], expected.as_slice(), "gradient {c} of {count}");
                assert_eq!(&g2[c * n..(c + 1) * n], expected.as_slice(), "gradient {c} of {count}");
            }
        }
    }

    #[test]
    fn mismatched_slices_are_typed_errors() {
        let chain = RuntimeChain::builder(4, 0.8, 1.0e4, 0.58).build().unwrap();
        assert_eq!(
            gradients(&chain, &[0.0; 7], &mut [0.0; 7]),
            Err(BatchError::PartialConfiguration { len: 7, rotors: 4 })
        );
        assert_eq!(
            gradients(&chain, &[0.0; 8], &mut [0.0; 7]),
            Err(BatchError::OutputLength { what: "gradients", len: 7, expected: 8 })
        );
        assert_eq!(
            energies_and_gradients(&chain, &[0.0; 8], &mut [0.0; 3], &mut [0.0; 8]),
            Err(BatchError::OutputLength { what: "energies", len: 3, expected: 2 })
        );
    }
}
