//! The second rung: the tangent stiffness, the Hessian of the potential. What Newton's method,
//! the modes, the integrators' step bound and the classification of equilibria bind on.

use super::layout::StiffnessLayout;
use super::potential::Potential;
use crate::real::Real;

/// A potential whose Hessian `K_ij = d2V/dx_i dx_j` (the tangent stiffness, paper Appendix D) is
/// known, as a symmetric matrix in a fixed [`StiffnessLayout`]: tridiagonal for a rotor chain
/// (the fast path of every analysis), or a sparse upper triangle for a spring network.
///
/// `linalg::SymmetricMatrix` (with `alloc`) holds such a matrix and carries the algorithms:
/// norms, Sturm counts or inertia, eigenpairs, shifted solves.
pub trait Stiffness<T: Real = f64>: Potential<T> {
    /// How [`Stiffness::tangent_stiffness_into`] lays out its values. Fixed for the model.
    fn stiffness_layout(&self) -> StiffnessLayout<'_>;

    /// The tangent stiffness at `x` into `values`, laid out as
    /// [`Stiffness::stiffness_layout`] says.
    fn tangent_stiffness_into(&self, x: &[T], values: &mut [T]);

    /// The energy, with the gradient into `grad` and the tangent stiffness into `values`, in one
    /// pass. The default calls the separate methods; the chains of this crate override it.
    fn energy_gradient_stiffness_into(&self, x: &[T], grad: &mut [T], values: &mut [T]) -> T {
        self.tangent_stiffness_into(x, values);
        self.energy_and_gradient_into(x, grad)
    }

    /// The number of values the tangent stiffness has in its layout.
    fn stiffness_values(&self) -> usize {
        self.stiffness_layout().values(self.dof_count())
    }
}
