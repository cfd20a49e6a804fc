//! The fourth rung: what only a one-dimensional rotor chain has. Its lattice spacing, rotor
//! lengths and tip mass, the angle `theta_bar` of its uniform states, and the branch solve of
//! paper Appendix A. Kink construction, domain walls, the cobweb map and the launch's translation
//! mode bind on it.

use super::springs::SpringNetwork;
use crate::branch;
use crate::error::BranchError;
use crate::real::Real;

/// A topological rotor chain: `n` rotors on a line, pivot `i` at `(i a, 0)`, their tips joined
/// by the `n - 1` springs of [`SpringNetwork`] (spring `p` joins rotors `p` and `p + 1`). Its
/// degrees of freedom are the angles `theta_i` measured from the vertical (docs/theory.md §1),
/// its tangent stiffness is tridiagonal and its compatibility matrix bidiagonal.
///
/// Units: angles in radians, lengths in the unit of `a`, spring constants in energy per length
/// squared, so energies are absolute, in the unit of `k` times the length unit squared
/// (`M a^2 / t^2` with the paper's `k` in `M / t^2`).
pub trait ChainGeometry<T: Real = f64>: SpringNetwork<T> {
    /// The number of rotors `n` (the degrees of freedom).
    fn rotor_count(&self) -> usize {
        self.dof_count()
    }

    /// Lattice spacing `a` (distance between neighbouring pivots).
    fn lattice_spacing(&self) -> T;

    /// Length `r_i` of rotor `i`.
    fn rotor_length(&self, i: usize) -> T;

    /// Mass `M` at each rotor tip (rotor `i`'s inertia is `M r_i^2`).
    fn mass(&self) -> T;

    /// Equilibrium angle `theta_bar` of the uniform states `theta_i = +-theta_bar`.
    fn theta_bar(&self) -> T;

    /// Both `theta_{p+1}` that put spring `p` at its rest length given `theta_p` (paper Appendix
    /// A), flipper branch first.
    fn next_angles(&self, p: usize, theta_p: T) -> Result<[T; 2], BranchError> {
        self.check_spring(p)?;
        branch::next_angles(
            p,
            self.lattice_spacing(),
            self.rotor_length(p),
            self.rotor_length(p + 1),
            self.rest_length(p),
            theta_p,
        )
    }

    /// Both `theta_p` that put spring `p` at its rest length given `theta_{p+1}`: the inverse map.
    fn previous_angles(&self, p: usize, theta_next: T) -> Result<[T; 2], BranchError> {
        self.check_spring(p)?;
        branch::previous_angles(
            p,
            self.lattice_spacing(),
            self.rotor_length(p),
            self.rotor_length(p + 1),
            self.rest_length(p),
            theta_next,
        )
    }

    /// `Ok` if `p` is a spring of this chain.
    fn check_spring(&self, p: usize) -> Result<(), BranchError> {
        if p < self.spring_count() {
            Ok(())
        } else {
            Err(BranchError::NoSuchSpring { spring: p, springs: self.spring_count() })
        }
    }
}

/// A chain's [`Potential::energy_floor`](super::Potential::energy_floor): `1e-12 k_max a^2`, the
/// energy of a spring stretched by a millionth of the lattice spacing (both kinds of chain return
/// it).
pub fn chain_energy_floor<T: Real, C: ChainGeometry<T> + ?Sized>(chain: &C) -> T {
    let k = (0..chain.spring_count()).map(|p| chain.spring_constant(p).abs()).fold(T::ZERO, |m, k| m.max(k));
    let a = chain.lattice_spacing();
    T::of(1e-12) * k * a * a
}

/// A rotor chain in `f64` with every capability: what the chain's analyses take. Every
/// [`ChainGeometry<f64>`] is one (a blanket implementation), so a chain implements the four
/// rungs and gets this name for free; generic code written against `ChainModel` keeps compiling.
pub trait ChainModel: ChainGeometry<f64> {}

impl<C: ChainGeometry<f64> + ?Sized> ChainModel for C {}
