//! Which generated kernel evaluates a model's bonds ([`crate::kernel`]'s harmonic, quartic or
//! polynomial module), chosen once from every spring's law (`chain_cell::BondLaw`): one law for
//! every bond uses its own kernel; harmonic and polynomial bonds together all take the
//! polynomial kernel, a harmonic bond as the polynomial `c2 = 1` (the same function; the
//! energy's roundings differ, both within a few ulps of it).

use crate::cell::{BondLaw, Polynomial};
use crate::error::NetworkError;

/// The kernel module of a model (the dispatch of `bonds.rs` and `lanes.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kernel {
    Harmonic,
    Quartic,
    Polynomial,
}

/// A spring law for [`NetworkModelBuilder::law`](super::NetworkModelBuilder::law): a cell's
/// [`BondLaw`], or chain-core's [`Law`](chain_core::Law) of the rotor chain (harmonic or
/// quartic), so the two crates' laws name the same kernels.
pub trait IntoBondLaw {
    /// The law as a cell's bond law.
    fn into_bond_law(self) -> BondLaw;
}

impl IntoBondLaw for BondLaw {
    fn into_bond_law(self) -> BondLaw {
        self
    }
}

impl IntoBondLaw for Polynomial {
    fn into_bond_law(self) -> BondLaw {
        BondLaw::Polynomial(self)
    }
}

impl IntoBondLaw for chain_core::Law {
    fn into_bond_law(self) -> BondLaw {
        match self {
            chain_core::Law::Quartic => BondLaw::Quartic,
            chain_core::Law::Harmonic => BondLaw::Harmonic,
            // chain-core's `Law` is non-exhaustive; a law added there has no bond kernel until
            // one is rendered here, which is this crate's change to make, not a caller's input.
            other => unreachable!("chain-core's law {other:?} has no network kernel"),
        }
    }
}

/// The kernel for `springs` springs whose laws are `law(p)` and, for the polynomial kernel, each
/// spring's coefficients `c2 .. c6` (empty otherwise). Quartic bonds with other laws are refused:
/// no one kernel evaluates both.
pub(super) fn kernel_of(
    springs: usize,
    law: impl Fn(usize) -> BondLaw,
) -> Result<(Kernel, Vec<[f64; 5]>), NetworkError> {
    let quartic = (0..springs).find(|&p| law(p) == BondLaw::Quartic);
    let other = (0..springs).find(|&p| law(p) != BondLaw::Quartic);
    match (quartic, other) {
        (Some(q), Some(o)) => Err(NetworkError::Argument {
            what: "law",
            problem: format!(
                "spring {q} is quartic and spring {o} {}: a model evaluates quartic bonds alone",
                law(o).name()
            ),
        }),
        (Some(_), None) => Ok((Kernel::Quartic, Vec::new())),
        _ if (0..springs).all(|p| law(p) == BondLaw::Harmonic) => Ok((Kernel::Harmonic, Vec::new())),
        _ => {
            let mut coefficients =
                chain_core::allocation::try_vec(springs, "the springs' polynomial coefficients")?;
            coefficients.extend((0..springs).map(|p| match law(p) {
                BondLaw::Polynomial(c) => c.coefficients,
                _ => Polynomial::harmonic().coefficients,
            }));
            Ok((Kernel::Polynomial, coefficients))
        }
    }
}
