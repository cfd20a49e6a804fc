//! Many configurations of one chain at once: energies and gradients of a batch of angle vectors
//! (a sweep's grid, an ensemble, a line search's trial points), in parallel over the machine's
//! cores with rayon's pool.
//!
//! A batch is one flat slice, configuration after configuration (`count * n` angles for a chain
//! of `n` rotors), and so are the gradients. The batch is split into a few tasks per core, and
//! each task hands its configurations to the model's [`ChainModel::batch_gradient_into`] /
//! [`ChainModel::batch_energy_and_gradient_into`]: one by one for a macro chain, and for a
//! [`crate::RuntimeChain`] as one long chain through its vector loop (the configurations back
//! to back, the springs that would join them dropped: `kernel::BackToBack`), which saves the
//! loop's start and end per configuration. The gradients are the same either way; the energies
//! of a runtime chain's batch agree with its one-by-one energies to rounding (their terms are
//! summed in another order). The forced level of `simd::with_level` is per thread, so it does
//! not reach the pool's threads: a batch runs at the detected level.

use rayon::prelude::*;

use crate::model::ChainModel;

/// Configurations per rayon task, at least: enough work to hide a task's overhead (a few
/// microseconds) behind evaluations of 0.1-1 us each.
const MIN_PER_TASK: usize = 16;

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

/// The number of configurations of a batch, and how many a task takes.
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
    let tasks = 4 * rayon::current_num_threads();
    Ok((count, count.div_ceil(tasks).max(MIN_PER_TASK)))
}

/// The energies and gradients of every configuration in `thetas` (`count * n` angles,
/// configuration after configuration): `gradients` gets `count * n` entries laid out the same
/// way, `energies` one per configuration.
///
/// # Errors
/// [`BatchError`] if `thetas` is not a whole number of configurations, or `gradients` /
/// `energies` do not match it; nothing is evaluated then.
pub fn energies_and_gradients<M: ChainModel + Sync + ?Sized>(
    model: &M,
    thetas: &[f64],
    energies: &mut [f64],
    gradients: &mut [f64],
) -> Result<(), BatchError> {
    let n = model.rotor_count();
    let (count, per_task) = split(n, thetas, gradients)?;
    if energies.len() != count {
        return Err(BatchError::OutputLength { what: "energies", len: energies.len(), expected: count });
    }
    thetas
        .par_chunks(n * per_task)
        .zip(gradients.par_chunks_mut(n * per_task))
        .zip(energies.par_chunks_mut(per_task))
        .for_each(|((theta, gradient), energy)| {
            model.batch_energy_and_gradient_into(theta, energy, gradient)
        });
    Ok(())
}

/// The gradients of every configuration in `thetas` (layout as [`energies_and_gradients`]).
///
/// # Errors
/// As [`energies_and_gradients`].
pub fn gradients<M: ChainModel + Sync + ?Sized>(
    model: &M,
    thetas: &[f64],
    gradients: &mut [f64],
) -> Result<(), BatchError> {
    let n = model.rotor_count();
    let (_, per_task) = split(n, thetas, gradients)?;
    thetas
        .par_chunks(n * per_task)
        .zip(gradients.par_chunks_mut(n * per_task))
        .for_each(|(theta, gradient)| model.batch_gradient_into(theta, gradient));
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
        let chain = RuntimeChain::builder(23, 0.8, 1.0e4, 0.58).spring(7, Some(50.0), None).build().unwrap();
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
