//! Errors of the model layer. Each carries the numbers that explain it, as `f64`: an `f32`
//! chain's branch solve widens its numbers (exactly) into the same errors.

pub use chain_geometry::ParameterError;
use chain_geometry::Short;

/// The branch solve of paper Appendix A has no real root: the two circles (the tip of rotor
/// `p + 1` must lie on its circle of radius `r_{p+1}` about its pivot, and at distance `l0` from
/// the tip of rotor `p`) do not meet.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BranchError {
    #[error(
        "spring {spring}: no real root for theta = {theta}: the known tip is {distance} from the \
         other rotor's pivot, but a spring of rest length {rest_length} reaches a rotor of length \
         {rotor_length} only from distances in [{min}, {max}]", distance = Short(*distance), max = Short(*max), min = Short(*min), rest_length = Short(*rest_length), rotor_length = Short(*rotor_length), theta = Short(*theta)
    )]
    /// The spring cannot reach the other rotor at its rest length (paper Appendix A: the quadratic has no real root).
    NoRealRoot {
        /// The spring being solved.
        spring: usize,
        /// The known rotor's angle, in radians.
        theta: f64,
        /// Distance from the known tip to the other rotor's pivot.
        distance: f64,
        /// The other rotor's length.
        rotor_length: f64,
        /// The spring's rest length.
        rest_length: f64,
        /// The smallest distance from which the spring reaches the rotor (`|l0 - r|`).
        min: f64,
        /// The largest such distance (`l0 + r`).
        max: f64,
    },
    #[error("spring {spring}: the angle {theta} is not finite", theta = Short(*theta))]
    /// The known angle is NaN or infinite.
    NotFinite {
        /// The spring being solved.
        spring: usize,
        /// The angle given.
        theta: f64,
    },
    #[error("spring index {spring} is out of range: the chain has {}", chain_geometry::Counted(*springs, "spring"))]
    /// A spring index past the end of the chain.
    NoSuchSpring {
        /// The spring index given.
        spring: usize,
        /// How many springs the chain has (`n - 1`).
        springs: usize,
    },
    /// The tip of rotor `p` sits exactly on the pivot of rotor `p + 1` (and the spring's rest
    /// length equals that rotor's length): every angle puts the spring at rest, none is singled out.
    #[error(
        "spring {spring}: for theta = {theta} the known tip sits on the other rotor's pivot, so \
         every angle of that rotor puts the spring at rest length", theta = Short(*theta)
    )]
    Degenerate {
        /// The spring being solved.
        spring: usize,
        /// The known angle (radians).
        theta: f64,
    },
}
