//! Closed-form geometry and parameter rules of the topological rotor chain.
//!
//! One source of truth for what a valid chain is: the `#[rotor_chain]` macro calls these rules at
//! compile time (and turns a violation into a compile error at the offending key), and
//! `chain-core`'s runtime-sized chain calls them when it is built. `no_std`, no allocation.
//!
//! Conventions are those of `docs/theory.md` (paper Sec. II): lattice spacing `a`, rotor length
//! `r`, equilibrium angle `theta_bar` measured from the vertical, spring rest length
//! `lbar = sqrt(a^2 + 4 r^2 cos^2 theta_bar)`.
#![deny(missing_docs)]
#![no_std]

use core::fmt;

/// A parameter of the chain that violates a rule. The `Display` text is the message the macro
/// shows at compile time and the runtime model returns, so both say the same thing.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ParameterError {
    /// Fewer than two rotors: there is no spring.
    #[error("{}", CountText::TooFew(n))]
    TooFewRotors {
        /// The number of rotors given.
        n: usize,
    },
    /// A length, stiffness or mass that must be positive is not (or is not finite).
    #[error("`{key}` must be a finite number > 0, got {}", Short(*value))]
    NotPositive {
        /// Which parameter.
        key: Key,
        /// The value given.
        value: f64,
    },
    /// `theta_bar` outside the flipper phase `0 < theta_bar < pi/2`, `2 r sin(theta_bar) < a`.
    #[error("{}", PhaseMessage { theta_bar: *theta_bar, a: *a, r: *r, two_r_sin: *two_r_sin, limit: *limit })]
    OutsideFlipperPhase {
        /// The angle given, in radians.
        theta_bar: f64,
        /// Lattice spacing `a` (pivot distance), in units of length.
        a: f64,
        /// Rotor length `r`, in units of length.
        r: f64,
        /// `2 r sin(theta_bar)`, which must be below `a`.
        two_r_sin: f64,
        /// Where the flipper phase ends: `asin(a / 2r)`, in radians.
        limit: f64,
    },
    /// A rest length that no uniform state `theta_i = theta_bar` can have.
    #[error(
        "rest_length = {} admits no uniform state: need a < rest_length < \
         sqrt(a^2 + 4 r^2) = {:.6} (a = {}, r = {})",
        Short(*rest_length), Short(*max), Short(*a), Short(*r)
    )]
    RestLengthOutOfRange {
        /// Rest length `l0`, in units of length (lattice spacing `a` = 1 in the paper).
        rest_length: f64,
        /// Lattice spacing `a` (pivot distance), in units of length.
        a: f64,
        /// Rotor length `r`, in units of length.
        r: f64,
        /// The longest rest length a uniform state admits, `sqrt(a^2 + 4 r^2)`.
        max: f64,
    },
    /// The chain is scaled so far down that one of its scales (a squared length, the energy
    /// unit `k a^2`, the inertia `M r^2`) is below the smallest normal `f64`: its energies,
    /// forces or inertias would be subnormal or zero, and its analyses would fail far from the
    /// cause (an angle that is NaN).
    #[error(
        "the chain's scale underflowed: {quantity} = {} is below the smallest normal number ({}), so its \
         energies, forces or inertias would be subnormal or zero; give a, r, k and M in units nearer 1",
        Short(*value), Short(f64::MIN_POSITIVE)
    )]
    ScaleUnderflow {
        /// Which scale (`a^2`, `r^2`, `k a^2`, `M r^2`).
        quantity: &'static str,
        /// Its value.
        value: f64,
    },
    /// A spring or rotor index past the end of the chain.
    #[error("{}", CountText::OutOfRange { kind: *kind, index, count: *count })]
    IndexOutOfRange {
        /// Spring or rotor.
        kind: IndexKind,
        /// The index given.
        index: usize,
        /// How many springs or rotors the chain has.
        count: usize,
    },
    /// More rotors than [`MAX_ROTORS`].
    #[error("{}", CountText::TooMany { n, max: *max })]
    TooManyRotors {
        /// The number of rotors asked for.
        n: usize,
        /// The most allowed, [`MAX_ROTORS`].
        max: usize,
    },
    /// An override that gives no value.
    #[error("the override of {kind} {index} changes nothing: give {}", match kind {
        IndexKind::Spring => "a stiffness `k` and/or a rest length `l0`",
        IndexKind::Rotor => "a length `r`",
    })]
    EmptyOverride {
        /// Spring or rotor.
        kind: IndexKind,
        /// The index of the override.
        index: usize,
    },
    /// Two overrides of the same spring or rotor.
    #[error("{kind} {index} is overridden twice: give all of its values in one override")]
    OverriddenTwice {
        /// Spring or rotor.
        kind: IndexKind,
        /// The index overridden twice.
        index: usize,
    },
    /// The memory for a chain of `n` rotors could not be allocated.
    #[error("a chain of {n} rotors needs {bytes} bytes for its parameters, which could not be allocated")]
    AllocationFailed {
        /// Number of rotors `n`.
        n: usize,
        /// The bytes that could not be allocated.
        bytes: usize,
    },
}

/// The most rotors a chain may have, generated or built at run time. A chain that long already
/// needs 800 MB per vector of angles; the limit keeps every size computation (`n` rotors, `n - 1`
/// springs, their bytes) far from overflow and turns an absurd `n` into an error instead of an
/// allocation failure.
pub const MAX_ROTORS: usize = 100_000_000;

/// A count and its noun for a message, plural unless the count is 1: `Counted(1, "spring")` shows
/// `1 spring`, `Counted(59, "spring")` shows `59 springs` (through `Display`, so the crate needs no
/// allocation).
#[derive(Clone, Copy, Debug)]
pub struct Counted<T>(pub usize, pub T);

impl<T: fmt::Display> fmt::Display for Counted<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {}{}", self.0, self.1, if self.0 == 1 { "" } else { "s" })
    }
}

/// The texts of [`ParameterError::TooFewRotors`], [`ParameterError::TooManyRotors`] and
/// [`ParameterError::IndexOutOfRange`] for a number `N` of any integer type: the variants show
/// them with their `usize`, and a binding whose integers are unbounded (Python's `-1` or `10**20`,
/// which no `usize` holds) shows the same words with its own number.
#[derive(Clone, Copy, Debug)]
pub enum CountText<N> {
    /// `n` below 2.
    TooFew(N),
    /// `n` above `max`.
    TooMany {
        /// The rotors asked for.
        n: N,
        /// The most allowed.
        max: usize,
    },
    /// An index outside `0..count`.
    OutOfRange {
        /// Spring or rotor.
        kind: IndexKind,
        /// The index given.
        index: N,
        /// How many springs or rotors the chain has.
        count: usize,
    },
}

impl<N: fmt::Display> fmt::Display for CountText<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TooFew(n) => {
                write!(f, "`n` must be at least 2 (a chain needs two rotors and one spring), got {n}")
            }
            Self::TooMany { n, max } => {
                write!(f, "`n` = {n} is more rotors than a chain may have: at most {max}")
            }
            Self::OutOfRange { kind, index, count } => write!(
                f,
                "{kind} index {index} is out of range: the chain has {}, numbered 0 to {}",
                Counted(*count, kind),
                count.saturating_sub(1)
            ),
        }
    }
}

/// The message of [`ParameterError::OutsideFlipperPhase`], naming the bound that is broken
/// (written through `Display`, so the crate needs no allocation).
struct PhaseMessage {
    theta_bar: f64,
    a: f64,
    r: f64,
    two_r_sin: f64,
    limit: f64,
}

impl fmt::Display for PhaseMessage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Self { theta_bar, a, r, two_r_sin, limit } = *self;
        let (theta_bar, a, r, two_r_sin, limit) =
            (Short(theta_bar), Short(a), Short(r), Short(two_r_sin), Short(limit));
        write!(f, "theta_bar = {theta_bar} is outside the flipper phase: ")?;
        if theta_bar.0.is_nan() {
            write!(f, "it must be a number (the uniform states are theta_i = +theta_bar and -theta_bar)")
        } else if theta_bar.0 <= 0.0 {
            write!(f, "it must be > 0 (the uniform states are theta_i = +theta_bar and -theta_bar)")
        } else if two_r_sin.0 >= a.0 {
            write!(
                f,
                "need 2 r sin(theta_bar) < a, here 2 r sin(theta_bar) = {two_r_sin:.6} with a = {a}, r = {r}; \
                 the flipper phase ends at theta_bar = asin(a / 2r) = {limit:.6}, where the chain turns into a wobbler"
            )
        } else {
            write!(f, "need theta_bar < pi/2 (the angle is measured from the vertical)")
        }
    }
}

/// A number in an error message, in a short exact form: the shortest decimal that reads back to
/// the same `f64` (Rust's `{}`), in exponent form (`5e-324`, `1e300`) where the plain form would
/// spell out hundreds of zeros. A precision (`{:.6}`) is honoured in either form. Every message
/// of the chain's rules prints its numbers through it, so no message holds a 300-digit decimal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Short(pub f64);

impl Short {
    /// Magnitudes printed plainly: from 1e-5 up to (not including) 1e16, as Rust's `{:?}` does.
    fn plain(x: f64) -> bool {
        !x.is_finite() || x == 0.0 || (1e-5..1e16).contains(&x.abs())
    }
}

impl fmt::Display for Short {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        match (Self::plain(x), f.precision()) {
            (true, None) => write!(f, "{x}"),
            (true, Some(p)) => write!(f, "{x:.p$}"),
            (false, None) => write!(f, "{x:e}"),
            (false, Some(p)) => write!(f, "{x:.p$e}"),
        }
    }
}

/// Which parameter a [`ParameterError::NotPositive`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Key {
    /// The lattice spacing `a`.
    LatticeSpacing,
    /// A rotor length `r`.
    RotorLength,
    /// A spring stiffness `k`.
    Stiffness,
    /// The tip mass `M`.
    Mass,
    /// A spring rest length `l0`.
    RestLength,
}

impl fmt::Display for Key {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Key::LatticeSpacing => "a",
            Key::RotorLength => "r",
            Key::Stiffness => "k",
            Key::Mass => "mass",
            Key::RestLength => "l0",
        })
    }
}

/// Spring or rotor, for [`ParameterError::IndexOutOfRange`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IndexKind {
    /// A spring `p` (joins rotors `p` and `p + 1`).
    Spring,
    /// A rotor `i`.
    Rotor,
}

impl fmt::Display for IndexKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            IndexKind::Spring => "spring",
            IndexKind::Rotor => "rotor",
        })
    }
}

/// `value` must be finite and strictly positive.
pub fn check_positive(key: Key, value: f64) -> Result<f64, ParameterError> {
    if value.is_finite() && value > 0.0 { Ok(value) } else { Err(ParameterError::NotPositive { key, value }) }
}

/// The scales of a chain with lattice spacing `a`, shortest rotor `r_min`, softest spring
/// `k_min` and tip mass `mass` (each already finite and positive) must be normal numbers: `a^2`,
/// `r^2`, the energy unit `k a^2` and the inertia `M r^2` (the smallest of each), else
/// [`ParameterError::ScaleUnderflow`] names the first that is not.
pub fn check_scales(a: f64, r_min: f64, k_min: f64, mass: f64) -> Result<(), ParameterError> {
    let scales =
        [("a^2", a * a), ("r^2", r_min * r_min), ("k a^2", k_min * a * a), ("M r^2", mass * r_min * r_min)];
    match scales.into_iter().find(|&(_, value)| value < f64::MIN_POSITIVE) {
        Some((quantity, value)) => Err(ParameterError::ScaleUnderflow { quantity, value }),
        None => Ok(()),
    }
}

/// A chain needs at least two rotors, and at most [`MAX_ROTORS`].
pub fn check_rotor_count(n: usize) -> Result<usize, ParameterError> {
    if n < 2 {
        Err(ParameterError::TooFewRotors { n })
    } else if n > MAX_ROTORS {
        Err(ParameterError::TooManyRotors { n, max: MAX_ROTORS })
    } else {
        Ok(n)
    }
}

/// `index` must address one of `count` springs or rotors.
pub fn check_index(kind: IndexKind, index: usize, count: usize) -> Result<usize, ParameterError> {
    if index < count { Ok(index) } else { Err(ParameterError::IndexOutOfRange { kind, index, count }) }
}

/// The rules of an override of spring or rotor `index` in a chain with `count` of them: the index
/// exists, the override gives at least one value (`gives_a_value`), and it is the first override
/// of that index (`overridden_before` says whether an earlier one exists). The macro applies them
/// to `spring(..)` / `rotor(..)` entries and `RuntimeChain`'s builder to its `spring` / `rotor`
/// calls, so both accept and reject the same overrides.
pub fn check_override(
    kind: IndexKind,
    index: usize,
    count: usize,
    gives_a_value: bool,
    overridden_before: bool,
) -> Result<usize, ParameterError> {
    check_index(kind, index, count)?;
    if !gives_a_value {
        return Err(ParameterError::EmptyOverride { kind, index });
    }
    if overridden_before {
        return Err(ParameterError::OverriddenTwice { kind, index });
    }
    Ok(index)
}

/// The end of the flipper phase: `theta_bar = asin(a / 2r)` if `2r > a`, else `pi/2`.
pub fn flipper_limit(a: f64, r: f64) -> f64 {
    if 2.0 * r > a { libm::asin(a / (2.0 * r)) } else { core::f64::consts::FRAC_PI_2 }
}

/// The flipper phase (paper Sec. II, footnote; Chen et al. 2014): `0 < theta_bar < pi/2` and
/// `2 r sin(theta_bar) < a`. Outside it the continuum theory is not phi^4 and the kink construction
/// of Sec. II does not apply.
pub fn check_flipper_phase(a: f64, r: f64, theta_bar: f64) -> Result<f64, ParameterError> {
    let two_r_sin = 2.0 * r * libm::sin(theta_bar);
    let inside =
        theta_bar.is_finite() && theta_bar > 0.0 && theta_bar < core::f64::consts::FRAC_PI_2 && two_r_sin < a;
    if inside {
        Ok(theta_bar)
    } else {
        Err(ParameterError::OutsideFlipperPhase { theta_bar, a, r, two_r_sin, limit: flipper_limit(a, r) })
    }
}

/// The rest length of the uniform state, `lbar = sqrt(a^2 + 4 r^2 cos^2 theta_bar)` (paper Sec. III,
/// below Eq. `eq:instantlength`).
pub fn rest_length(a: f64, r: f64, theta_bar: f64) -> f64 {
    let c = libm::cos(theta_bar);
    libm::sqrt(a * a + 4.0 * r * r * c * c)
}

/// The equilibrium angle `theta_bar` in `[0, pi/2)` whose uniform state has springs of length
/// `rest_length`: the inverse of [`rest_length`].
pub fn theta_bar_from_rest_length(a: f64, r: f64, rest_length: f64) -> Result<f64, ParameterError> {
    let max = libm::sqrt(a * a + 4.0 * r * r);
    if !(rest_length.is_finite() && rest_length > a && rest_length < max) {
        return Err(ParameterError::RestLengthOutOfRange { rest_length, a, r, max });
    }
    let cos = libm::sqrt(rest_length * rest_length - a * a) / (2.0 * r);
    Ok(libm::acos(cos.min(1.0)))
}

/// Spring length for two rotor angles (paper Eq. `eq:instantlength`, with rotor lengths `r1`, `r2`;
/// angles measured alternately, so the formula is the same for every spring).
pub fn spring_length(a: f64, r1: f64, r2: f64, theta1: f64, theta2: f64) -> f64 {
    let dx = a + r2 * libm::sin(theta2) - r1 * libm::sin(theta1);
    let dy = r1 * libm::cos(theta1) + r2 * libm::cos(theta2);
    libm::sqrt(dx * dx + dy * dy)
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;
    use std::format;
    use std::string::ToString;

    #[test]
    fn numbers_in_messages_are_short_and_exact() {
        for (x, text) in [
            (5e-324, "5e-324"),
            (1e300, "1e300"),
            (-1e-300, "-1e-300"),
            (f64::MAX, "1.7976931348623157e308"),
            (0.1, "0.1"),
            (20.0, "20"),
            (1e15, "1000000000000000"),
            (1e16, "1e16"),
            (1e-5, "0.00001"),
            (f64::NAN, "NaN"),
            (f64::NEG_INFINITY, "-inf"),
            (-0.0, "-0"),
        ] {
            assert_eq!(Short(x).to_string(), text);
            if x.is_finite() {
                assert_eq!(Short(x).to_string().parse::<f64>().unwrap().to_bits(), x.to_bits(), "{text}");
            }
        }
        assert_eq!(format!("{:.3}", Short(1e300)), "1.000e300");
        assert_eq!(format!("{:.3}", Short(2.5)), "2.500");
        // The builder's messages: no 300-digit decimals.
        let e = ParameterError::NotPositive { key: Key::RotorLength, value: 5e-324 };
        assert!(e.to_string().ends_with("got 5e-324"), "{e}");
        let e = ParameterError::RestLengthOutOfRange { rest_length: 1e300, a: 1.0, r: 0.8, max: 1.886796 };
        assert!(e.to_string().starts_with("rest_length = 1e300 admits"), "{e}");
    }

    #[test]
    fn rest_length_and_its_inverse_agree() {
        let l = rest_length(1.0, 0.8, 0.58);
        // sqrt(1 + 4 * 0.64 * cos^2 0.58) = 1.6707; paper Fig. `fig:longbar` quotes lbar / a = 1.68,
        // within its two-digit rounding of a slightly different theta_bar (docs/theory.md).
        assert!((l - 1.6707).abs() < 1e-4, "{l}");
        assert!((l - 1.68).abs() < 0.01, "{l}");
        let back = theta_bar_from_rest_length(1.0, 0.8, l).unwrap();
        assert!((back - 0.58).abs() < 1e-12);
    }

    #[test]
    fn uniform_state_has_rest_length_springs() {
        for t in [0.1, 0.58, -0.58] {
            let l = spring_length(1.0, 0.8, 0.8, t, t);
            assert!((l - rest_length(1.0, 0.8, t)).abs() < 1e-14);
        }
    }

    #[test]
    fn flipper_phase_ends_at_the_wobbler_transition() {
        // paper Fig. `fig:akenergy` caption: asin(a / 2r) = 0.67 for r / a = 0.8
        assert!((flipper_limit(1.0, 0.8) - 0.6751).abs() < 1e-4);
        assert!(check_flipper_phase(1.0, 0.8, 0.58).is_ok());
        assert!(matches!(
            check_flipper_phase(1.0, 0.8, 0.7),
            Err(ParameterError::OutsideFlipperPhase { .. })
        ));
        assert!(check_flipper_phase(1.0, 0.8, 0.0).is_err());
        assert!(check_flipper_phase(1.0, 0.3, 1.6).is_err());
    }

    #[test]
    fn rules_reject_bad_values() {
        assert!(check_positive(Key::Stiffness, 0.0).is_err());
        assert!(check_positive(Key::Stiffness, f64::NAN).is_err());
        assert!(check_rotor_count(1).is_err());
        assert_eq!(check_rotor_count(MAX_ROTORS), Ok(MAX_ROTORS));
        assert_eq!(
            check_rotor_count(usize::MAX),
            Err(ParameterError::TooManyRotors { n: usize::MAX, max: MAX_ROTORS })
        );
        assert!(check_index(IndexKind::Spring, 59, 59).is_err());
        assert!(theta_bar_from_rest_length(1.0, 0.8, 0.9).is_err());
    }

    #[test]
    fn an_override_names_a_spring_gives_a_value_and_comes_once() {
        use IndexKind::{Rotor, Spring};
        assert_eq!(check_override(Spring, 3, 9, true, false), Ok(3));
        assert!(matches!(
            check_override(Spring, 9, 9, true, false),
            Err(ParameterError::IndexOutOfRange { .. })
        ));
        assert_eq!(
            check_override(Spring, 3, 9, false, false),
            Err(ParameterError::EmptyOverride { kind: Spring, index: 3 })
        );
        assert_eq!(
            check_override(Rotor, 2, 9, true, true),
            Err(ParameterError::OverriddenTwice { kind: Rotor, index: 2 })
        );
    }
}
