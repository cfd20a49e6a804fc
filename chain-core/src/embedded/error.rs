//! Why a no-alloc analysis could not be carried out. Every variant carries the numbers that
//! explain it, widened to `f64` for an `f32` chain (exactly).

use crate::BranchError;

/// Building a kink, launching it or stepping it went wrong.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum EmbeddedError {
    /// The chain and the arrays disagree on the number of rotors.
    #[error("the chain has {rotors} rotors, but the arrays hold {expected} angles")]
    WrongRotorCount {
        /// Rotors of the chain.
        rotors: usize,
        /// Angles the arrays hold.
        expected: usize,
    },
    /// A parameter outside its range (a time step, a launch speed).
    #[error("{name} = {value} must be {rule}")]
    InvalidParameter {
        /// The parameter.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The rule it breaks.
        rule: &'static str,
    },
    /// The kink centre is not inside the chain.
    #[error("kink centre {centre} is outside the chain: need 0 <= centre <= {max}")]
    CentreOutOfRange {
        /// The centre given, in rotor indices.
        centre: f64,
        /// The largest allowed centre.
        max: f64,
    },
    /// A wall built with its centre inside the chain shows no wall there (or more than one): at
    /// so small a `theta_bar` the wall is far wider than the chain, and its angles round to zero.
    #[error(
        "the {expected} centred at {centre} has no wall inside the chain: it is far wider than the \
         chain and its angles round to zero (found {kinks} kink(s), {antikinks} antikink(s))"
    )]
    NoWall {
        /// The wall asked for: `kink` or `antikink` (the reflected kink).
        expected: &'static str,
        /// Its centre, in rotor indices.
        centre: f64,
        /// Kinks found.
        kinks: usize,
        /// Antikinks found.
        antikinks: usize,
    },
    /// The branch solve found no angle that puts a spring at rest length.
    #[error("branch solve: {0}")]
    Branch(#[from] BranchError),
    /// The compatibility matrix has no zero mode through the kink: a spring whose length does not
    /// depend on the next rotor's angle (`C[p][p+1] = 0`) stops the construction of the mode.
    #[error(
        "no translation mode: spring {spring} has compatibility entries C[p][p] = {left}, \
         C[p][p+1] = {right}, so its zero mode cannot be continued past it"
    )]
    NoTranslationMode {
        /// The spring where the recurrence broke down.
        spring: usize,
        /// Its entry `C_{p,p}` of the compatibility matrix.
        left: f64,
        /// Its entry `C_{p,p+1}`.
        right: f64,
    },
    /// A rotor with zero, negative or non-finite moment of inertia has no dynamics.
    #[error("rotor {index} has moment of inertia {inertia}: it must be positive and finite")]
    BadInertia {
        /// The rotor.
        index: usize,
        /// Its moment of inertia `M r_i^2`.
        inertia: f64,
    },
    /// The energy left its band around a reference ([`super::Verlet::check_energy`]): most often
    /// a time step too long for the chain's fastest phonon, whose energy then grows step by step
    /// while every number stays finite.
    #[error(
        "energy {energy} after step {step} is {} from the reference {reference}, more than the \
         tolerance {tolerance}: is dt = {dt} within the stability limit omega_max dt < 2?",
        (energy - reference).abs()
    )]
    EnergyDrift {
        /// The Verlet step.
        step: u32,
        /// `T + V` after it.
        energy: f64,
        /// The energy it was checked against.
        reference: f64,
        /// The largest `|energy - reference|` allowed.
        tolerance: f64,
        /// The stepper's time step.
        dt: f64,
    },
    /// A number of the state became NaN or infinite (an unstable time step, or a NaN force).
    #[error("{what}[{index}] = {value} is not finite after step {step}")]
    NotFinite {
        /// Which input.
        what: &'static str,
        /// The Verlet step.
        step: u32,
        /// Which entry.
        index: usize,
        /// The value found.
        value: f64,
    },
}
