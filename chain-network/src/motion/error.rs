//! [`MotionError`]: a run of [`crate::motion`] that cannot be set up or went wrong.

use crate::error::NetworkError;
use chain_core::geometry::Short;
use chain_core::integrate::IntegrateError;

/// A demonstration run that cannot be set up or did not give its measurement.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MotionError {
    /// A parameter out of its range (the name, the value, the rule).
    #[error("{name} = {}: {rule}", Short(*value))]
    Parameter {
        /// The parameter.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        rule: &'static str,
    },
    /// A field of an options struct ([`super::transition::BistableChain`]) outside its range
    /// ([`chain_core::Validate`]).
    #[error(transparent)]
    InvalidOption(#[from] chain_core::validate::InvalidOption),
    /// The demonstration's cell is not valid.
    #[error(transparent)]
    Cell(#[from] crate::error::CellError),
    /// Building the patch or the model failed.
    #[error(transparent)]
    Network(#[from] NetworkError),
    /// The integration failed (a non-finite state, a bad step).
    #[error(transparent)]
    Integrate(#[from] IntegrateError),
    /// The front was not found in enough samples to fit a speed: it never formed, stalled
    /// (pinned by the lattice) or left the patch.
    #[error("the front was found in {found} of the {needed} samples needed to fit its speed")]
    NoFront {
        /// Samples with a front inside the fitting window.
        found: usize,
        /// Samples needed.
        needed: usize,
    },
}
