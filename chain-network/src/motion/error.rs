//! [`MotionError`]: a run of [`crate::motion`] that cannot be set up or went wrong.

use crate::error::NetworkError;
use chain_core::geometry::Short;
use chain_core::integrate::IntegrateError;
use chain_core::validate::{InvalidOption, OptionError};

/// A demonstration run that cannot be set up or did not give its measurement.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MotionError {
    /// A field of an options struct ([`super::transition::BistableChain`],
    /// [`super::wall::CoupledChains`]) outside its range
    /// ([`chain_core::Validate`]).
    #[error(transparent)]
    InvalidOption(#[from] InvalidOption),
    /// The demonstration's cell is not valid.
    #[error(transparent)]
    Cell(#[from] crate::error::CellError),
    /// Building the patch or the model failed.
    #[error(transparent)]
    Network(#[from] NetworkError),
    /// The integration failed (a non-finite state, a bad step).
    #[error(transparent)]
    Integrate(#[from] IntegrateError),
    /// The launch of a chain's kink failed (the chain code's static kink or translation mode).
    #[error(transparent)]
    Launch(#[from] chain_core::dynamics::DynamicsError),
    /// A chain's wall was lost: at `time` the chain had `kinks` kinks, not one (the wall left
    /// the chain, or the launch's phonons broke it up).
    #[error("chain {chain} has {kinks} kinks at t = {time}, not one: its wall was lost", time = Short(*time))]
    WallLost {
        /// The chain (row).
        chain: usize,
        /// When.
        time: f64,
        /// Kinks found.
        kinks: usize,
    },
    /// The wall moved from `start` to `end` (rotors), less than the `2 margin` needed for a
    /// region it crossed that is `margin` away from both.
    #[error(
        "the wall moved from rotor {start} to {end}, not beyond the margins of {margin} rotors around both",
        start = Short(*start), end = Short(*end), margin = Short(*margin)
    )]
    WallDidNotCross {
        /// Where it started (chains' mean).
        start: f64,
        /// Where it ended.
        end: f64,
        /// The distance from the wall at which a region counts as uniform.
        margin: f64,
    },
    /// At `time` the wall stood within `margin` rotors of an end of the `rotors`-rotor chains:
    /// no region beside it is uniform.
    #[error(
        "at t = {time} the wall at rotor {wall} is within {margin} rotors of an end of the {rotors}-rotor chains",
        time = Short(*time), wall = Short(*wall), margin = Short(*margin)
    )]
    WallNearEnd {
        /// When.
        time: f64,
        /// Where (chains' mean).
        wall: f64,
        /// The distance from the wall at which a region counts as uniform.
        margin: f64,
        /// Rotors per chain.
        rotors: usize,
    },
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

impl OptionError for MotionError {
    fn invalid_option(&self) -> Option<InvalidOption> {
        match self {
            Self::InvalidOption(o) => Some(*o),
            Self::Network(e) => e.invalid_option(),
            Self::Integrate(e) => e.invalid_option(),
            Self::Launch(e) => e.invalid_option(),
            _ => None,
        }
    }
}
