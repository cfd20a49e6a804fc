//! The one bound on a model's fastest mode, from which the Verlet runs and the statics'
//! relaxation choose their steps.
//!
//! Every eigenvalue of the generalised problem `K v = omega^2 I v` is at most `||K||_inf / I_min`
//! (Gershgorin's theorem on `I^-1 K`, whose rows sum to at most `||K||_inf / I_min` in absolute
//! value), so `omega_max <= sqrt(||K||_inf / I_min)`, the tangent stiffness `K` taken at the
//! configuration. Velocity Verlet is stable for `omega_max dt < 2`.

use crate::integrate::IntegrateError;
use crate::linalg::SymmetricMatrix;
use crate::model::Stiffness;

/// The bound of the module doc at a configuration, with what it was made of.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OmegaBound {
    /// `||K||_inf` at the configuration, in energy per unit of the degrees of freedom squared.
    pub norm: f64,
    /// The smallest inertia `I_min`.
    pub inertia: f64,
    /// `sqrt(norm / inertia)`: every mode's angular frequency is at most this, in `1 / t`.
    pub omega: f64,
}

/// The bound of the module doc for `model` at `x`, after checking the inputs.
///
/// # Errors
/// `x` of the wrong length or not finite, an inertia that is not positive and finite with a
/// finite inverse, a stiffness that is zero or not finite ([`IntegrateError::NoTimeScale`]), or a
/// bound that overflows ([`IntegrateError::NoStableStep`]).
pub fn omega_bound<M: Stiffness + ?Sized>(model: &M, x: &[f64]) -> Result<OmegaBound, IntegrateError> {
    let n = model.dof_count();
    if x.len() != n {
        return Err(IntegrateError::WrongLength { what: "theta", len: x.len(), expected: n });
    }
    super::not_finite("theta", 0.0, x)?;
    if n == 0 {
        return Err(IntegrateError::NoTimeScale { norm: 0.0 });
    }
    let mut inertia = f64::INFINITY;
    for i in 0..n {
        let value = model.inertia(i);
        if !(value > 0.0 && value.is_finite() && (1.0 / value).is_finite()) {
            return Err(IntegrateError::BadInertia { index: i, inertia: value });
        }
        inertia = inertia.min(value);
    }
    let norm = SymmetricMatrix::tangent_stiffness(model, x)
        .map_err(|_| IntegrateError::NoTimeScale { norm: f64::NAN })?
        .inf_norm();
    if !(norm > 0.0 && norm.is_finite()) {
        return Err(IntegrateError::NoTimeScale { norm });
    }
    // `norm * (1 / I_min)`: the largest of the inverse inertias, as the runs have always taken it
    // (the same bits as the steps of earlier versions).
    let omega = crate::math::sqrt(norm * (1.0 / inertia));
    if !omega.is_finite() {
        return Err(IntegrateError::NoStableStep { norm, inverse_inertia: 1.0 / inertia });
    }
    Ok(OmegaBound { norm, inertia, omega })
}
