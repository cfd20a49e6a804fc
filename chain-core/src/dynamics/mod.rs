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

pub mod integrate;
pub mod launch;
pub mod observe;
pub mod run;
pub mod scatter;
pub mod track;

use crate::statics::StaticsError;
use integrate::IntegrateError;

/// A dynamics run that could not be carried out.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DynamicsError {
    #[error("integration: {0}")]
    Integrate(#[from] IntegrateError),
    /// Building the static defect or its modes failed.
    #[error("statics: {0}")]
    Statics(#[from] StaticsError),
    /// No mode localised at the defect was classified as its translation mode.
    #[error("no translation mode found for the defect at {position}")]
    NoTranslationMode { position: f64 },
    /// A launch speed that is negative or not finite.
    #[error("launch speed v0 = {v0} must be finite and >= 0")]
    BadSpeed { v0: f64 },
    /// A scattering setup naming a spring the chain does not have.
    #[error("spring {spring} does not exist: the chain has {springs} springs")]
    NoSuchSpring { spring: usize, springs: usize },
    /// A number of a scattering setup outside its range.
    #[error("{name} = {value} is invalid: it must be {rule}")]
    InvalidSetup { name: &'static str, value: f64, rule: &'static str },
}
