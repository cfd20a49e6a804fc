//! Figures of the paper (see [`super::all`]).

use super::FigureFn;

/// This module's figures, in the paper's order.
pub fn figures() -> Vec<(&'static str, FigureFn)> {
    Vec::new()
}
