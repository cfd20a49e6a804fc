//! Errors of the static analyses. Each carries the numbers that explain it.

use chain_geometry::Short;

use crate::error::BranchError;
use crate::linalg::LinalgError;

/// A static analysis that could not be carried out.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum StaticsError {
    /// The branch solve failed while building a profile (no real root, bad index).
    #[error("branch solve: {0}")]
    Branch(#[from] BranchError),
    /// A chain parameter outside the rules (for analyses that build chains).
    #[error("{0}")]
    Parameter(#[from] crate::error::ParameterError),
    /// A spectral computation failed.
    #[error("linear algebra: {0}")]
    Linalg(#[from] LinalgError),
    /// A requested defect centre outside the chain.
    #[error("centre {centre} is outside the chain: it must lie in [0, {max}] for {n} rotors", centre = Short(*centre), max = Short(*max))]
    CentreOutOfRange {
        /// The centre given, in rotor indices.
        centre: f64,
        /// Number of rotors `n`.
        n: usize,
        /// The largest allowed centre.
        max: f64,
    },
    /// An iterative method stopped before reaching its tolerance.
    #[error(
        "{method} did not converge: after {iterations} iterations the residual is {residual:e} \
         (tolerance {tolerance:e})"
    )]
    NoConvergence {
        /// Which method.
        method: &'static str,
        /// Iterations used.
        iterations: usize,
        /// The residual reached (relative, as the message says).
        residual: f64,
        /// The tolerance it had to meet.
        tolerance: f64,
    },
    /// A wall built by the branch solve with its centre inside the chain shows no wall there: at
    /// so small a `theta_bar` the wall is far wider than the chain, and its angles round to zero.
    #[error(
        "the {expected} centred at {centre} has no wall inside the chain: at theta_bar = {theta_bar} it \
         is far wider than the chain and its angles round to zero (found {kinks} kink(s), {antikinks} \
         antikink(s))", centre = Short(*centre), theta_bar = Short(*theta_bar)
    )]
    NoWall {
        /// The wall asked for: `kink` or `antikink` (the reflected kink).
        expected: &'static str,
        /// Its centre, in rotor indices.
        centre: f64,
        /// The chain's `theta_bar`.
        theta_bar: f64,
        /// Kinks found.
        kinks: usize,
        /// Antikinks found.
        antikinks: usize,
    },
    /// The relaxed configuration no longer holds the defect it started with (for example an
    /// antikink annihilated by a kink entering from a free end).
    #[error(
        "the relaxed configuration lost its {expected}: it has {kinks} kink(s) and {antikinks} antikink(s)"
    )]
    DefectLost {
        /// The defect the analysis was about.
        expected: &'static str,
        /// Kinks found.
        kinks: usize,
        /// Antikinks found.
        antikinks: usize,
    },
    /// A spring-length impurity with no symmetric zero-energy state: beyond `l_critical` (paper
    /// Sec. VII-A), or shorter than the spring between rotors leaning at `+theta_bar`, `-theta_bar`.
    #[error(
        "spring {spring} with rest length {rest_length} has no symmetric zero-energy state: with its \
         rotors at -phi, +phi (|phi| <= theta_bar) it spans lengths from {min} to {max} (= l_critical)", max = Short(*max), min = Short(*min), rest_length = Short(*rest_length)
    )]
    NoZeroEnergyState {
        /// The impurity spring.
        spring: usize,
        /// Its rest length.
        rest_length: f64,
        /// The shortest rest length with a zero-energy state.
        min: f64,
        /// The longest.
        max: f64,
    },
    /// No antikink equilibrium at the centring asked for: Newton's method from the symmetric guess
    /// there went to an antikink centred at `found` (for example next to an impurity that repels
    /// it, whose force beats the Peierls-Nabarro pinning), or had to hold the translation.
    #[error(
        "no antikink equilibrium centred at {requested}: Newton's method went to {found} (index \
         {index}, {held} direction(s) held); see peierls_nabarro's landscape for the equilibria near it", found = Short(*found), requested = Short(*requested)
    )]
    NotAnEquilibrium {
        /// The centring asked for.
        requested: f64,
        /// Where the antikink found is centred (Appendix C wall coordinate).
        found: f64,
        /// The Morse index of what was found.
        index: usize,
        /// The directions Newton's method held ([`super::equilibrium::Solution::held`]).
        held: usize,
    },
    /// No Peierls-Nabarro minimum (a free equilibrium of Morse index 0) where one was asked for:
    /// `found` is what the search ended at, with its index and held directions.
    #[error(
        "no antikink minimum near {near}: the search ended at an antikink centred at {found} of index \
         {index} with {held} direction(s) held", found = Short(*found), near = Short(*near)
    )]
    NoMinimum {
        /// Where the minimum was looked for.
        near: f64,
        /// The centre of the lowest equilibrium found.
        found: f64,
        /// Its Morse index.
        index: usize,
        /// Its held directions (above 0: a fixed-centring point, not a free equilibrium).
        held: usize,
    },
    /// The descent along the antikink's adiabatic path ([`super::path::descend`]) reached the edge
    /// of its region with the energy still falling: no well within it. `reached` is where the
    /// antikink went, with its energy and `dE/dc` there (the sign says which way it kept going).
    #[error(
        "the antikink started at {start} slid out of [{lo}, {hi}] without reaching a minimum: at \
         centre {reached} its energy {energy} still falls ({slope} per site)",
        start = Short(*start), lo = Short(*lo), hi = Short(*hi), reached = Short(*reached),
        energy = Short(*energy), slope = Short(*slope)
    )]
    DescentLeftRegion {
        /// The centre the descent started from.
        start: f64,
        /// The region's lower end (sites).
        lo: f64,
        /// The region's upper end.
        hi: f64,
        /// The centre the descent reached.
        reached: f64,
        /// The antikink's energy there.
        energy: f64,
        /// `dE/dc` there.
        slope: f64,
    },
    /// A slice with the wrong length for the chain.
    #[error("{what} has {}, the chain needs {expected}", chain_geometry::Counted(*len, "value"))]
    WrongLength {
        /// Which input.
        what: &'static str,
        /// Its length.
        len: usize,
        /// The length it must have.
        expected: usize,
    },
    /// A non-finite number where a finite one is needed.
    #[error("{what} is not finite ({value}) at index {index}", value = Short(*value))]
    NotFinite {
        /// Which input.
        what: &'static str,
        /// Which entry.
        index: usize,
        /// The value found.
        value: f64,
    },
    /// A setting or a model parameter outside its range (`expected` says the range).
    #[error("{what} = {value} is invalid: expected {expected}", value = Short(*value))]
    InvalidValue {
        /// What the value is (the name of the input or quantity).
        what: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
    /// A field of an options struct outside its range ([`crate::validate::Validate`]).
    #[error("{options}.{name} = {} is invalid: it must be {rule}", Short(*value))]
    InvalidOption {
        /// The options struct (`NewtonOptions`, `RelaxOptions`, `ModeOptions`, `AntikinkOptions`).
        options: &'static str,
        /// The field.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The rule it breaks, in words.
        rule: &'static str,
    },
    /// A count larger than the analysis accepts (its result would not fit in memory).
    #[error("{what} = {value} is too large: at most {max}")]
    TooLarge {
        /// What the value is (the name of the input or quantity).
        what: &'static str,
        /// The size asked for.
        value: usize,
        /// The most allowed.
        max: usize,
    },
}

impl From<crate::validate::InvalidOption> for StaticsError {
    fn from(e: crate::validate::InvalidOption) -> Self {
        StaticsError::InvalidOption { options: e.options, name: e.field, value: e.value, rule: e.rule }
    }
}
