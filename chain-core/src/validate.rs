//! One validation for every public options struct (issue 37): [`Validate::validate`] checks every
//! field of the struct on its own (finite, of its sign, within its documented bounds) and returns
//! the subsystem's typed error carrying an [`InvalidOption`]: the struct's name, the field's, the
//! value given and the rule it breaks, the number printed short and exact ([`Short`]).
//!
//! Every entry point that takes an options struct calls it before any work, and each crate's
//! tests enumerate every field of every struct by an exhaustive destructuring (no `..`), so a
//! field added without its check fails a test. Checks that need more than the struct (a
//! scattering setup's start on a chain of `n` rotors, a strip's direction in its cell) are made by
//! the entry point after `validate`.
//!
//! The rules are written once, in [`Fields`]; chain-network and chain-sweep use the same.
//!
//! **Counts.** Every count field (iterations, steps, outputs, modes, sites, threads) has a
//! documented range, checked by [`Fields::count_in`]: a lower bound where 0 means nothing (a run
//! of no steps), 0 kept where it has a meaning (Newton's `max_iterations = 0` measures the
//! start's residual), and an upper bound with a reason, so that no count set by a user makes a
//! loop that never ends in practice or a thread count without a bound: an iteration's
//! convergence
//! ([`NewtonOptions::MAX_ITERATIONS`](crate::statics::equilibrium::NewtonOptions::MAX_ITERATIONS)),
//! the step budget of any integrator ([`MAX_STEP_BUDGET`](crate::integrate::MAX_STEP_BUDGET)),
//! or a size limit the library already has (`MAX_ROTORS`, `MAX_SPACE_TIME_VALUES`,
//! `MAX_DENSE_VALUES`, a network patch's bonds). Each bound is stated in the field's doc and in
//! the rule's text, with its number.

use chain_geometry::Short;

/// The check of one options struct: every field in its range, independently of what the struct is
/// used on. `Ok(())` promises that no field is NaN, infinite where it must be finite, of the wrong
/// sign or outside its documented bounds.
pub trait Validate {
    /// The subsystem's error (it converts from [`InvalidOption`]).
    type Error;

    /// Checks every field; the first one out of range is the error.
    fn validate(&self) -> Result<(), Self::Error>;
}

/// A field of an options struct outside its range: which struct, which field, the value given and
/// the rule it breaks, in words. Counts are carried as `f64` (exact below `2^53`).
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("{options}.{field} = {} is invalid: it must be {rule}", Short(*value))]
pub struct InvalidOption {
    /// The options struct (`ScatterSetup`, `RunOptions`, ...), or the function whose argument it is.
    pub options: &'static str,
    /// The field (for a nested struct's field, the inner struct names itself in `options`).
    pub field: &'static str,
    /// The value given.
    pub value: f64,
    /// The rule it breaks.
    pub rule: &'static str,
}

/// The rules of the fields of one struct: `Fields("RunOptions").positive("output_interval", x)?`.
#[derive(Clone, Copy, Debug)]
pub struct Fields(pub &'static str);

impl Fields {
    /// `Ok` if `ok`, else the field's [`InvalidOption`] with `rule`.
    pub fn rule(
        self,
        field: &'static str,
        value: f64,
        ok: bool,
        rule: &'static str,
    ) -> Result<(), InvalidOption> {
        if ok { Ok(()) } else { Err(InvalidOption { options: self.0, field, value, rule }) }
    }

    /// A finite number.
    pub fn finite(self, field: &'static str, value: f64) -> Result<(), InvalidOption> {
        self.rule(field, value, value.is_finite(), "finite")
    }

    /// A finite number `> 0`.
    pub fn positive(self, field: &'static str, value: f64) -> Result<(), InvalidOption> {
        self.rule(field, value, value > 0.0 && value.is_finite(), "positive and finite")
    }

    /// A finite number `>= 0`.
    pub fn non_negative(self, field: &'static str, value: f64) -> Result<(), InvalidOption> {
        self.rule(field, value, value >= 0.0 && value.is_finite(), "non-negative and finite")
    }

    /// A count of at least 1.
    pub fn at_least_one(self, field: &'static str, value: u64) -> Result<(), InvalidOption> {
        self.rule(field, value as f64, value >= 1, "at least 1")
    }

    /// A count in `lo..=hi`; `rule` says it in words with both bounds and why the upper one
    /// (`"between 1 and MAX_STEP_BUDGET = 10000000000 (...)"`). The count is reported as `f64`
    /// (exact below `2^53`, far above every bound).
    pub fn count_in(
        self,
        field: &'static str,
        value: u64,
        lo: u64,
        hi: u64,
        rule: &'static str,
    ) -> Result<(), InvalidOption> {
        self.rule(field, value as f64, (lo..=hi).contains(&value), rule)
    }
}

/// An error that may be an invalid option, wherever its [`InvalidOption`] sits (a variant of its
/// own or a nested error's): how a caller (a binding, a test) asks any subsystem's error which
/// struct, field and value it refused, and by which rule.
pub trait OptionError {
    /// The invalid option this error reports, if it is one.
    fn invalid_option(&self) -> Option<InvalidOption>;
}

impl OptionError for InvalidOption {
    fn invalid_option(&self) -> Option<InvalidOption> {
        Some(*self)
    }
}

impl OptionError for crate::integrate::IntegrateError {
    fn invalid_option(&self) -> Option<InvalidOption> {
        match *self {
            Self::InvalidOption { options, name, value, rule } => {
                Some(InvalidOption { options, field: name, value, rule })
            }
            _ => None,
        }
    }
}

impl OptionError for crate::statics::StaticsError {
    fn invalid_option(&self) -> Option<InvalidOption> {
        match *self {
            Self::InvalidOption { options, name, value, rule } => {
                Some(InvalidOption { options, field: name, value, rule })
            }
            _ => None,
        }
    }
}

impl OptionError for crate::dynamics::DynamicsError {
    fn invalid_option(&self) -> Option<InvalidOption> {
        match self {
            &Self::InvalidSetup { options, name, value, rule } => {
                Some(InvalidOption { options, field: name, value, rule })
            }
            Self::Integrate(e) => e.invalid_option(),
            Self::Statics(e) => e.invalid_option(),
            _ => None,
        }
    }
}

#[cfg(feature = "alloc")]
impl OptionError for crate::dynamics::scatter::BudgetError {
    fn invalid_option(&self) -> Option<InvalidOption> {
        match self {
            Self::InvalidOption(o) => Some(*o),
            Self::Setup(source) => source.invalid_option(),
            _ => None,
        }
    }
}
