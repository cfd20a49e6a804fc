//! [`MotionError`]: a run of [`crate::motion`] that cannot be set up or went wrong.

use crate::error::NetworkError;
use chain_core::integrate::IntegrateError;

/// A demonstration run that cannot be set up or did not give its measurement.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MotionError {
    /// A parameter out of its range (the name, the value, the rule).
    #[error("{name} = {value}: {rule}")]
    Parameter {
        /// The parameter.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        rule: &'static str,
    },
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
    #[error("chain {chain} has {kinks} kinks at t = {time}, not one: its wall was lost")]
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
        "the wall moved from rotor {start} to {end}, not beyond the margins of {margin} rotors around both"
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
        "at t = {time} the wall at rotor {wall} is within {margin} rotors of an end of the {rotors}-rotor chains"
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
