//! What the run needs from a chain, in the chain's own float type.
//!
//! Every `#[rotor_chain]` struct and `RuntimeChain` implements [`ChainModel`], which is `f64`; the blanket impl below makes each of them a `Model<f64>`. A chain
//! that computes in `f32` implements `Model<f32>` with its own `f32` methods.

use rotor_chain::{BranchError, ChainModel};

use crate::Real;

/// The generated quantities a kink run uses, all from the symbolic engine: energy, gradient,
/// compatibility matrix and the flipper branch of the branch solve (paper Appendix A).
///
/// # Panics
/// The `*_into` methods may panic if a slice has the wrong length (a programming error; the run
/// checks the rotor count before it starts).
pub trait Model<T: Real> {
    /// Number of rotors `n`.
    fn rotor_count(&self) -> usize;

    /// Length `r_i` of rotor `i`.
    fn rotor_length(&self, i: usize) -> T;

    /// Moment of inertia `M r_i^2` of rotor `i`.
    fn inertia(&self, i: usize) -> T;

    /// Potential energy `V`.
    fn energy(&self, theta: &[T]) -> T;

    /// `out[i] = dV/dtheta_i`.
    fn gradient_into(&self, theta: &[T], out: &mut [T]);

    /// The compatibility matrix `C[p][i] = dl_p / d(r_i theta_i)`: `left[p] = C[p][p]`,
    /// `right[p] = C[p][p+1]` (length `n - 1` each).
    fn compatibility_into(&self, theta: &[T], left: &mut [T], right: &mut [T]);

    /// The `theta_{p+1}` on the flipper branch that puts spring `p` at rest length.
    fn next_angle(&self, p: usize, theta_p: T) -> Result<T, BranchError>;

    /// The `theta_p` on the flipper branch that puts spring `p` at rest length: the inverse map.
    fn previous_angle(&self, p: usize, theta_next: T) -> Result<T, BranchError>;
}

impl<C: ChainModel + ?Sized> Model<f64> for C {
    fn rotor_count(&self) -> usize {
        ChainModel::rotor_count(self)
    }
    fn rotor_length(&self, i: usize) -> f64 {
        ChainModel::rotor_length(self, i)
    }
    fn inertia(&self, i: usize) -> f64 {
        ChainModel::inertia(self, i)
    }
    fn energy(&self, theta: &[f64]) -> f64 {
        ChainModel::energy(self, theta)
    }
    fn gradient_into(&self, theta: &[f64], out: &mut [f64]) {
        ChainModel::gradient_into(self, theta, out)
    }
    fn compatibility_into(&self, theta: &[f64], left: &mut [f64], right: &mut [f64]) {
        ChainModel::compatibility_into(self, theta, left, right)
    }
    fn next_angle(&self, p: usize, theta_p: f64) -> Result<f64, BranchError> {
        Ok(self.next_angles(p, theta_p)?[0])
    }
    fn previous_angle(&self, p: usize, theta_next: f64) -> Result<f64, BranchError> {
        Ok(self.previous_angles(p, theta_next)?[0])
    }
}
