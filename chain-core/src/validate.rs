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
}
