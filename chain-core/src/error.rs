//! Errors of the model layer. Each carries the numbers that explain it, as `f64`: an `f32`
//! chain's branch solve widens its numbers (exactly) into the same errors.

pub use chain_geometry::ParameterError;

/// The branch solve of paper Appendix A has no real root: the two circles (the tip of rotor
/// `p + 1` must lie on its circle of radius `r_{p+1}` about its pivot, and at distance `l0` from
/// the tip of rotor `p`) do not meet.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BranchError {
    #[error(
        "spring {spring}: no real root for theta = {theta}: the known tip is {distance} from the \
         other rotor's pivot, but a spring of rest length {rest_length} reaches a rotor of length \
         {rotor_length} only from distances in [{min}, {max}]"
    )]
    NoRealRoot {
        spring: usize,
        theta: f64,
        distance: f64,
        rotor_length: f64,
        rest_length: f64,
        min: f64,
        max: f64,
    },
    #[error("spring {spring}: the angle {theta} is not finite")]
    NotFinite { spring: usize, theta: f64 },
    #[error("spring index {spring} is out of range: the chain has {springs} springs")]
    NoSuchSpring { spring: usize, springs: usize },
    /// The tip of rotor `p` sits exactly on the pivot of rotor `p + 1` (and the spring's rest
    /// length equals that rotor's length): every angle puts the spring at rest, none is singled out.
    #[error(
        "spring {spring}: for theta = {theta} the known tip sits on the other rotor's pivot, so \
         every angle of that rotor puts the spring at rest length"
    )]
    Degenerate { spring: usize, theta: f64 },
}
