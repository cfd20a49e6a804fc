//! The checks of the options tests (issue 37), written once for chain-core's, chain-network's and
//! chain-sweep's `tests/options_validated.rs`: an invalid value of a field must fail
//! [`Validate::validate`] with the error naming that struct, that field and exactly that value,
//! while the valid value it replaced passes; a count's range is enumerated at both bounds.
//!
//! Any subsystem's error works through [`OptionError`], which finds its [`InvalidOption`] wherever
//! it sits.

use core::fmt::{Debug, Display};

use chain_core::validate::{InvalidOption, OptionError, Validate};

/// `error` is an invalid option naming `options`, `field` and exactly `value` (bit for bit; any
/// NaN for a NaN), and its text says `options.field = `; returns the option.
pub fn assert_names<E: OptionError + Display>(
    error: &E,
    options: &str,
    field: &str,
    value: f64,
) -> InvalidOption {
    let o = error.invalid_option().unwrap_or_else(|| panic!("not an invalid option: {error}"));
    assert_eq!((o.options, o.field), (options, field), "{error}");
    assert!(
        o.value.to_bits() == value.to_bits() || (o.value.is_nan() && value.is_nan()),
        "{value} -> {error}"
    );
    assert!(error.to_string().contains(&format!("{options}.{field} = ")), "{error}");
    o
}

/// `make(valid)` validates, and `make(v)` for each `v` of `bad` fails naming `options.field = v`.
pub fn values<S: Validate>(options: &str, field: &str, valid: f64, bad: &[f64], make: impl Fn(f64) -> S)
where
    S::Error: OptionError + Display + Debug,
{
    if let Err(e) = make(valid).validate() {
        panic!("{options}.{field} = {valid} is valid, got {e}");
    }
    for &v in bad {
        match make(v).validate() {
            Ok(()) => panic!("{options}.{field} = {v} passed"),
            Err(e) => {
                assert_names(&e, options, field, v);
            }
        }
    }
}

/// A count's range `lo..=hi`: `make(lo)` and `make(hi)` validate, `make(hi + 1)` and (when
/// `lo > 0`) `make(0)` and `make(lo - 1)` fail naming `options.field` and the count. Returns the
/// option of `hi + 1`, whose rule the caller checks for the bound's number.
pub fn count_range<S: Validate>(
    options: &str,
    field: &str,
    lo: u64,
    hi: u64,
    make: impl Fn(u64) -> S,
) -> InvalidOption
where
    S::Error: OptionError + Display + Debug,
{
    assert!(lo <= hi && hi < u64::MAX, "{options}.{field}: the range {lo}..={hi}");
    for v in [lo, hi] {
        if let Err(e) = make(v).validate() {
            panic!("{options}.{field} = {v} is within {lo}..={hi}, got {e}");
        }
    }
    let below: &[u64] = if lo > 0 { &[0, lo - 1] } else { &[] };
    for &v in below {
        match make(v).validate() {
            Ok(()) => panic!("{options}.{field} = {v} passed, below {lo}"),
            Err(e) => {
                assert_names(&e, options, field, v as f64);
            }
        }
    }
    match make(hi + 1).validate() {
        Ok(()) => panic!("{options}.{field} = {} passed, above {hi}", hi + 1),
        Err(e) => assert_names(&e, options, field, (hi + 1) as f64),
    }
}

/// The rule of `option` states `bound` (the number, as the constant's doc gives it).
pub fn rule_states(option: InvalidOption, bound: u64) {
    assert!(
        option.rule.contains(&bound.to_string()),
        "{}.{}: the rule `{}` does not state {bound}",
        option.options,
        option.field,
        option.rule
    );
}

/// A field that takes every value: both values given pass.
pub fn any_value<S: Validate>(what: &str, values: [S; 2])
where
    S::Error: Debug,
{
    for s in values {
        if let Err(e) = s.validate() {
            panic!("{what}: every value is valid, got {e:?}");
        }
    }
}
