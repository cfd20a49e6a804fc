//! Dynamics of the chain (paper Secs. V, VI, VII-B and Appendix B): `M r_i^2 thetadd_i = -dV/dtheta_i`,
//! generic over [`crate::ChainModel`].
//!
//! - [`integrate`]: velocity Verlet (symplectic, fixed step) and an adaptive high-order Runge-Kutta
//!   with dense output; optional viscous damping; energy monitoring;
//! - [`launch`]: a kink or antikink set in motion along its translation mode (Appendix B);
//! - [`track`]: kink and antikink positions and charges at every output (Appendix C);
//! - [`run`]: propagation with tracking, kinetic energy and space-time image, stopped on demand;
//! - [`observe`]: trajectories, kinetic-energy fluctuations, Peierls-Nabarro trapping;
//! - [`scatter`]: scattering on a stiffness impurity and its outcome (Sec. VI).

/// The integrators, which live above the statics and the dynamics ([`crate::integrate`]);
/// re-exported here, where earlier versions had them.
#[doc(no_inline)]
pub use crate::integrate;
pub mod launch;
#[cfg(feature = "alloc")]
pub mod observe;
#[cfg(feature = "alloc")]
pub mod run;
#[cfg(feature = "alloc")]
pub mod scatter;
#[cfg(feature = "alloc")]
pub mod track;

use chain_geometry::Short;

use crate::integrate::IntegrateError;
use crate::statics::StaticsError;

/// A dynamics run that could not be carried out.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DynamicsError {
    #[error("integration: {0}")]
    /// The integrator failed.
    Integrate(#[from] IntegrateError),
    /// A result sized by the input (a space-time image) could not be allocated.
    #[cfg(feature = "alloc")]
    #[error("{0}")]
    OutOfMemory(#[from] crate::allocation::AllocationError),
    /// Building the static defect or its modes failed.
    #[error("statics: {0}")]
    Statics(#[from] StaticsError),
    /// No mode localised at the defect was classified as its translation mode.
    #[error("no translation mode found for the defect at {position}", position = Short(*position))]
    NoTranslationMode {
        /// Where the defect was, in rotor indices.
        position: f64,
    },
    /// A launch speed that is negative or not finite.
    #[error("launch speed v0 = {v0} must be finite and >= 0", v0 = Short(*v0))]
    BadSpeed {
        /// The launch speed given, in `a / t`.
        v0: f64,
    },
    /// A scattering setup naming a spring the chain does not have.
    #[error("spring {spring} does not exist: the chain has {}", chain_geometry::Counted(*springs, "spring"))]
    NoSuchSpring {
        /// The spring index given.
        spring: usize,
        /// How many springs the chain has (`n - 1`).
        springs: usize,
    },
    /// A number of a scattering setup outside its range (a field of an options struct,
    /// [`crate::validate::Validate`], or where the setup lies on the chain), or an argument of a
    /// dynamics function.
    #[error("{options}.{name} = {} is invalid: it must be {rule}", Short(*value))]
    InvalidSetup {
        /// The options struct (`ScatterSetup`), or the function whose argument it is.
        options: &'static str,
        /// The setting.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The rule it breaks, in words.
        rule: &'static str,
    },
    /// A chain's analysis given a model whose matrices are not in a chain's layout.
    #[error("{what} of the model is not {expected}, as a rotor chain's is")]
    NotAChain {
        /// Which matrix.
        what: &'static str,
        /// The chain's layout.
        expected: &'static str,
    },
    /// The kink's zero mode cannot be continued along the chain: a spring's compatibility entry
    /// divides by zero or the recurrence overflows.
    #[error(
        "no translation mode: spring {spring} has compatibility entries C[p][p] = {left}, \
         C[p][p+1] = {right}, so its zero mode cannot be continued past it", left = Short(*left), right = Short(*right)
    )]
    NoZeroMode {
        /// The spring.
        spring: usize,
        /// `C[p][p]`.
        left: f64,
        /// `C[p][p + 1]`.
        right: f64,
    },
}

impl From<crate::validate::InvalidOption> for DynamicsError {
    fn from(e: crate::validate::InvalidOption) -> Self {
        DynamicsError::InvalidSetup { options: e.options, name: e.field, value: e.value, rule: e.rule }
    }
}
