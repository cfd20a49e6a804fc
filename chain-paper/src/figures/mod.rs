//! One function per figure of the paper, each taking the chain's parameters and a [`Quality`],
//! returning a [`crate::Figure`] (data and summary rows). Grouped by the paper's sections.

use crate::model::{Figure, Quality};

pub mod dynamics;
pub mod statics_a;
pub mod statics_b;

/// The chain of the paper's figures (Appendix B: `a = 1`, `M = 1`, `k = 1e4`, `r/a = 0.8`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    pub n: usize,
    pub r: f64,
    pub k: f64,
    pub mass: f64,
}

impl Default for Params {
    fn default() -> Self {
        Self { n: 60, r: 0.8, k: 1.0e4, mass: 1.0 }
    }
}

/// An error while computing a figure, with the label and what failed.
#[derive(Debug, thiserror::Error)]
#[error("{label}: {message}")]
pub struct FigureError {
    pub label: &'static str,
    pub message: String,
}

impl FigureError {
    pub fn new(label: &'static str, err: impl std::fmt::Display) -> Self {
        Self { label, message: err.to_string() }
    }

    /// Maps any displayable error to a `FigureError` of `label`: `.map_err(FigureError::on(LABEL))`.
    pub fn on<E: std::fmt::Display>(label: &'static str) -> impl Fn(E) -> FigureError {
        move |e| FigureError::new(label, e)
    }
}

/// A figure function.
pub type FigureFn = fn(&Params, Quality) -> Result<Figure, FigureError>;

/// Every figure: `(label, function)`, statics first, then dynamics.
pub fn all() -> Vec<(&'static str, FigureFn)> {
    let mut all = statics_a::figures();
    all.extend(statics_b::figures());
    all.extend(dynamics::figures());
    all
}
