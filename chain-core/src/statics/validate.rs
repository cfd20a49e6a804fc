//! The input checks every public analysis makes at its boundary, so that nothing downstream
//! iterates on a NaN, indexes past the chain, or runs with a setting that makes its loop
//! meaningless. Each failure is a [`StaticsError`] carrying the offending value.

use super::error::StaticsError;
use crate::error::BranchError;
use crate::model::{ChainGeometry, Potential, SpringNetwork};

/// `theta` has one finite value per degree of freedom (an angle per rotor for a chain).
pub(crate) fn angles<M: Potential + ?Sized>(model: &M, theta: &[f64]) -> Result<(), StaticsError> {
    let n = model.dof_count();
    if theta.len() != n {
        return Err(StaticsError::WrongLength { what: "theta", len: theta.len(), expected: n });
    }
    finite("theta", theta)
}

/// Every entry of `values` is finite.
pub(crate) fn finite(what: &'static str, values: &[f64]) -> Result<(), StaticsError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(StaticsError::NotFinite { what, index, value: values[index] }),
        None => Ok(()),
    }
}

/// `p` is a spring of the chain.
pub(crate) fn spring<M: SpringNetwork + ?Sized>(model: &M, p: usize) -> Result<(), StaticsError> {
    let springs = model.spring_count();
    if p < springs { Ok(()) } else { Err(BranchError::NoSuchSpring { spring: p, springs }.into()) }
}

/// A setting that must be finite and `>= 0`.
pub(crate) fn non_negative(what: &'static str, value: f64) -> Result<f64, StaticsError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(StaticsError::InvalidValue { what, value, expected: "a finite number >= 0" })
    }
}

/// A setting that must be finite and `> 0`.
pub(crate) fn positive(what: &'static str, value: f64) -> Result<f64, StaticsError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(StaticsError::InvalidValue { what, value, expected: "a finite number > 0" })
    }
}

/// The model's `theta_bar`, which must be finite and `> 0` (a chain declared with a field for its
/// rest length that admits no uniform state reports NaN; its `check()` says why).
pub(crate) fn theta_bar<M: ChainGeometry + ?Sized>(model: &M) -> Result<f64, StaticsError> {
    let value = model.theta_bar();
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(StaticsError::InvalidValue {
            what: "the model's theta_bar",
            value,
            expected: "a finite angle > 0 (check the model's parameters with check())",
        })
    }
}

/// A count of at most `max`.
pub(crate) fn at_most(what: &'static str, value: usize, max: usize) -> Result<usize, StaticsError> {
    if value <= max { Ok(value) } else { Err(StaticsError::TooLarge { what, value, max }) }
}
