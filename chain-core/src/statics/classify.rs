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

/// The factor `C` of [`rounding_tolerance`]: the tolerance is `C n eps` relative to `||K||`.
///
/// Why 64: each entry of a chain's tangent stiffness is a sum of a few spring terms, each computed
/// to a few ulps of `||K||`; a Sturm count perturbs the eigenvalues by at most `n eps ||K||` more
/// (backward stability of the LDL^T recurrence). 64 covers both with a margin of about ten, and
/// stays far below the smallest physical curvature the analyses resolve (the antikink's
/// translation at `theta_bar = 0.2`, n = 60, held ends: `4e-7 = 6e-11 ||K||` against
/// `64 n eps = 8e-13`).
pub const ROUNDING_FACTOR: f64 = 64.0;

/// The relative zero tolerance of an `n x n` tangent stiffness computed in double precision:
/// [`ROUNDING_FACTOR`]` n eps`, an estimate of the rounding error of the stiffness evaluation and
/// of the Sturm count (absolute: times `||K||`). Eigenvalues within it of zero cannot be told from
/// zero; anything above it is resolved.
pub fn rounding_tolerance(n: usize) -> f64 {
    ROUNDING_FACTOR * n.max(1) as f64 * f64::EPSILON
}

/// Classifies the tangent stiffness `k` (of any model, [`SymmetricMatrix::tangent_stiffness`]):
/// eigenvalues within `relative * ||K||` of zero count as zero. [`rounding_tolerance`]`(n)` (the
/// antikink analyses' default) separates rounding from every resolved curvature; a larger
/// `relative` also calls exponentially soft edge modes zero. The counts are Sturm counts for a
/// chain's tridiagonal `K` (O(n)).
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
