//! The third rung: what every spring network has. Springs with lengths and tensions, the
//! compatibility matrix, and the split of the tangent stiffness into its material part and stress
//! matrix (Guest 2006; paper Appendix D). Maxwell-Calladine counting and the impurity analyses
//! bind on it.

use super::layout::CompatibilityLayout;
use super::stiffness::Stiffness;
use crate::real::Real;

/// A model made of springs: `spring_count()` springs, spring `p` with constant `k_p`, rest length
/// `l0_p` and energy `law(l_p)`, its length `l_p(x)` a function of the degrees of freedom.
///
/// Conventions (docs/theory.md §7):
/// - the **compatibility matrix** `C[p][i] = dl_p / du_i` has one row per spring and one column
///   per degree of freedom, each column a displacement in length units: for a rotor `u_i = r_i
///   theta_i` (its tip's arc length), for a joint its `x` or `y`. `C` maps displacements to
///   elongations; its transpose maps tensions to forces (the equilibrium matrix).
/// - the **tension** `t_p = d law / dl` at the current length (positive when stretched).
/// - the tangent stiffness is **material part plus stress matrix**: `K = sum_p g^_p a_p a_p^T +
///   sum_p S_p` with `a_p = dl_p/dx`, `g^_p = d2 law / dl^2` and `S_p = t_p d2 l_p / dx^2`; both
///   are laid out as the tangent stiffness ([`Stiffness::stiffness_layout`]) and sum to it.
pub trait SpringNetwork<T: Real = f64>: Stiffness<T> {
    /// The number of springs.
    fn spring_count(&self) -> usize;

    /// The spring constant `k_p` of spring `p` (energy per length squared).
    fn spring_constant(&self, p: usize) -> T;

    /// The rest length `l0_p` of spring `p`.
    fn rest_length(&self, p: usize) -> T;

    /// The spring lengths `l_p` at `x` (one per spring).
    fn spring_lengths_into(&self, x: &[T], out: &mut [T]);

    /// The tensions `t_p = d law / dl` at the lengths of `x` (one per spring).
    fn tensions_into(&self, x: &[T], out: &mut [T]);

    /// How [`SpringNetwork::compatibility_into`] lays out its values. Fixed for the model.
    fn compatibility_layout(&self) -> CompatibilityLayout<'_>;

    /// The compatibility matrix at `x` into `values`, laid out as
    /// [`SpringNetwork::compatibility_layout`] says.
    fn compatibility_into(&self, x: &[T], values: &mut [T]);

    /// The material part `sum_p g^_p a_p a_p^T` of the tangent stiffness, in its layout.
    fn material_stiffness_into(&self, x: &[T], values: &mut [T]);

    /// The stress matrix `sum_p S_p`, in the tangent stiffness's layout; material part plus
    /// stress matrix is the tangent stiffness.
    fn stress_matrix_into(&self, x: &[T], values: &mut [T]);

    /// The number of values the compatibility matrix has in its layout.
    fn compatibility_values(&self) -> usize {
        self.compatibility_layout().values(self.spring_count())
    }
}
