//! The model traits every analysis is generic over: a capability ladder, each rung a small trait
//! that states what its consumers need (in the style of argmin's `CostFunction` / `Gradient` /
//! `Hessian` and diffsol's operator traits).
//!
//! | rung | trait | what it adds | who binds on it |
//! |---|---|---|---|
//! | 1 | [`Potential<T>`] | degrees of freedom, inertia, energy, gradient | Verlet, DOP853, relaxation, the firmware loop |
//! | 2 | [`Stiffness<T>`] | the tangent stiffness in a [`StiffnessLayout`] (tridiagonal or sparse) | Newton, modes, the step bound, classification |
//! | 3 | [`SpringNetwork<T>`] | springs: lengths, tensions, compatibility matrix, material part and stress matrix | Maxwell-Calladine counting, impurities |
//! | 4 | [`ChainGeometry<T>`] | the rotor chain: lattice spacing, rotor lengths, `theta_bar`, the branch solve | kinks, walls, cobweb, launches |
//!
//! Each rung requires the one before. [`ChainModel`] is the whole ladder in `f64`, what the
//! chain's analyses take. Both kinds of chain climb it: the structs of `#[rotor_chain]` (sizes
//! and constants fixed at compile time; `f32` chains too) and [`crate::RuntimeChain`]. A model of
//! your own implements the rungs it honestly has (the guide `rotor_chain::guide::models`).
//!
//! Required methods work in place on slices and need no allocation; allocating conveniences are
//! provided methods. Matrices are filled into flat slices laid out as [`layout`] describes.
//!
//! # Panics
//! The slice methods panic if a slice has the wrong length: that is a programming error, not a
//! property of the model. Both kinds of chain check with [`check_lengths`], whose message names
//! the slice and both counts; an implementation of your own can call it too.

mod chain;
pub mod layout;
mod potential;
mod springs;
mod stiffness;

pub use chain::{ChainGeometry, ChainModel, chain_energy_floor};
pub use layout::{CompatibilityLayout, Pattern, PatternError, StiffnessLayout};
pub use potential::Potential;
pub use springs::SpringNetwork;
pub use stiffness::Stiffness;

/// The number of configurations of `n` degrees of freedom in a batch of `xs` numbers, checking
/// the lengths of `out` and `energies` as the batch methods of [`Potential`] document (panics: a
/// programming error; `crate::batch` returns typed errors first).
#[track_caller]
pub(crate) fn batch_count(n: usize, xs: usize, out: usize, energies: Option<usize>) -> usize {
    use chain_geometry::Counted;
    assert!(
        n > 0 && xs.is_multiple_of(n),
        "the batch has {}, not a whole number of configurations of {n} degrees of freedom",
        Counted(xs, "value")
    );
    assert!(
        out == xs,
        "out has {}, the configurations {}: one gradient entry per degree of freedom",
        Counted(out, "value"),
        Counted(xs, "value")
    );
    let count = xs / n;
    if let Some(e) = energies {
        assert!(
            e == count,
            "energies has {}, the batch {}: one energy per configuration",
            Counted(e, "value"),
            Counted(count, "configuration")
        );
    }
    count
}

/// Panics unless a chain of `n` rotors gets `theta` (of length `theta`) and slices of one value
/// per rotor (`rotors`: name and length) and one per spring (`springs`): the check of every
/// slice method of [`crate::RuntimeChain`] and of the `#[rotor_chain]` chains. A wrong length is
/// a programming error of the caller, so the message names the slice and both counts ("off has
/// 60 values, the chain has 59 springs (one value per spring)"), and `#[track_caller]` (here and
/// on the methods that call it) points it at the call. Inlined, it is a few compares on the hot
/// path; the message is built out of line.
///
/// ```should_panic
/// // A chain of 6 rotors: `diag` holds one value per rotor, `off` one per spring.
/// rotor_chain::model::check_lengths(6, 6, &[("diag", 6)], &[("off", 6)]);
/// // panics: "off has 6 values, the chain has 5 springs (one value per spring)"
/// ```
#[inline(always)]
#[track_caller]
pub fn check_lengths(n: usize, theta: usize, rotors: &[(&str, usize)], springs: &[(&str, usize)]) {
    if theta != n || rotors.iter().any(|r| r.1 != n) || springs.iter().any(|s| s.1 + 1 != n) {
        wrong_length(n, theta, rotors, springs);
    }
}

/// The panic of [`check_lengths`]: the first slice of the wrong length, by name.
#[cold]
#[inline(never)]
#[track_caller]
fn wrong_length(n: usize, theta: usize, rotors: &[(&str, usize)], springs: &[(&str, usize)]) -> ! {
    use chain_geometry::Counted;
    let theta = [("theta", theta)];
    let per_rotor = theta.iter().chain(rotors).map(|&(s, l)| (s, l, n, "rotor"));
    let per_spring = springs.iter().map(|&(s, l)| (s, l, n - 1, "spring"));
    let (name, len, count, what) =
        per_rotor.chain(per_spring).find(|&(_, l, c, _)| l != c).unwrap_or(("a slice", 0, n, "rotor"));
    panic!(
        "{name} has {}, the chain has {} (one value per {what})",
        Counted(len, "value"),
        Counted(count, what)
    )
}
