//! Classifying an equilibrium by the spectrum of its tangent stiffness (paper Sec. IV, V).
//!
//! The Morse index (number of negative eigenvalues) and the number of eigenvalues within a
//! tolerance of zero come from Sturm counts of the tridiagonal matrix, O(n) each: a minimum has
//! index 0; a saddle of index 1 is the top of a Peierls-Nabarro barrier; near-zero eigenvalues are
//! mechanisms (the kink's translation) or exponentially soft edge modes.

use super::error::StaticsError;
use super::validate;
use crate::linalg::SymmetricMatrix;

/// What kind of equilibrium the spectrum shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EquilibriumKind {
    /// Every eigenvalue above the tolerance.
    Minimum,
    /// No negative eigenvalue, but `nullity` within the tolerance of zero (flat directions).
    DegenerateMinimum {
        /// How many zero eigenvalues.
        nullity: usize,
    },
    /// `index` eigenvalues below `-tolerance`.
    Saddle {
        /// How many negative eigenvalues (the Morse index).
        index: usize,
    },
}

/// The inertia of the tangent stiffness at an equilibrium.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Classification {
    /// Eigenvalues below `-tolerance`.
    pub index: usize,
    /// Eigenvalues in `[-tolerance, tolerance]`.
    pub nullity: usize,
    /// The absolute tolerance used, `relative * ||K||`.
    pub tolerance: f64,
    /// Minimum, saddle or degenerate.
    pub kind: EquilibriumKind,
}

/// Classifies the tangent stiffness `k` (of any model, [`SymmetricMatrix::tangent_stiffness`]):
/// eigenvalues within `relative * ||K||` of zero count as zero. A relative tolerance of `1e-10`
/// separates rounding (`~1e-16`) and exponentially soft edge modes from physical soft modes.
/// The counts are Sturm counts for a chain's tridiagonal `K` (O(n)).
///
/// # Errors
/// A non-finite entry ([`StaticsError::Linalg`]), or a `relative` tolerance that is not finite
/// and `>= 0`.
pub fn classify(k: &SymmetricMatrix, relative: f64) -> Result<Classification, StaticsError> {
    let relative = validate::non_negative("relative tolerance", relative)?;
    k.check_finite()?;
    let tolerance = relative * k.inf_norm();
    let index = k.count_below(-tolerance)?;
    let nullity = k.count_below(tolerance)? - index;
    let kind = match (index, nullity) {
        (0, 0) => EquilibriumKind::Minimum,
        (0, nullity) => EquilibriumKind::DegenerateMinimum { nullity },
        (index, _) => EquilibriumKind::Saddle { index },
    };
    Ok(Classification { index, nullity, tolerance, kind })
}
