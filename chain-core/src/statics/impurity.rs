//! A spring-length impurity (paper Sec. VII-A, Fig. `fig:longbar`).
//!
//! Give spring `p` a rest length `l0` longer than `lbar`. The chain still has zero-energy states,
//! now with two kinks, one on each side of the impurity: the impurity's rotors lean apart,
//! `theta_p = -phi`, `theta_{p+1} = +phi`, with `phi` set by `l_p(-phi, phi) = l0`, and each
//! sub-chain is built outward by the branch maps. As `l0` grows to
//! `l_critical = l_p(-theta_bar, +theta_bar) = sqrt((2 r sin theta_bar + a)^2 + (2 r cos theta_bar)^2)`,
//! `phi -> theta_bar`, both kinks leave through the free ends, a soft vibrational mode (the two
//! kinks moving in opposite directions) and its dual soft tensional mode (localised on the
//! impurity) go to zero, and at `l0 = l_critical` the tensional mode becomes a state of self-stress.
//! Beyond `l_critical` no zero-energy state exists.

use alloc::vec;
use alloc::vec::Vec;

use super::counting::{Counting, TensionalMode, maxwell_calladine, tensional_modes};
use super::error::StaticsError;
use super::modes::{Mode, ModeOptions, modes};
use super::validate;
use crate::model::ChainModel;

/// The length of spring `p` with its rotors at `theta_p`, `theta_{p+1}`: O(1), from the model's
/// own lattice spacing and rotor lengths.
fn spring_length<M: ChainModel + ?Sized>(model: &M, p: usize, theta_p: f64, theta_next: f64) -> f64 {
    let (a, r1, r2) = (model.lattice_spacing(), model.rotor_length(p), model.rotor_length(p + 1));
    chain_geometry::spring_length(a, r1, r2, theta_p, theta_next)
}

/// `l_critical` of spring `p`, computed: the spring's length with its left rotor at `-theta_bar`
/// and its right rotor at `+theta_bar` (both sub-chains uniform, the kinks gone through the ends).
///
/// # Errors
/// A spring `p` the chain does not have (`NoSuchSpring`), or a model whose `theta_bar` is not a
/// finite positive angle.
pub fn critical_length<M: ChainModel + ?Sized>(model: &M, p: usize) -> Result<f64, StaticsError> {
    validate::spring(model, p)?;
    let tb = validate::theta_bar(model)?;
    Ok(spring_length(model, p, -tb, tb))
}

/// The zero-energy configuration around the impurity spring `p`, symmetric about it. For
/// `l0 >= sqrt(a^2 + 4 r^2)` (`phi >= 0`) it holds two kinks, one on each side of the impurity; for
/// shorter rest lengths (`phi < 0`) a single kink straddles the impurity.
///
/// # Errors
/// A spring `p` the chain does not have (`NoSuchSpring`), a model whose `theta_bar` or rest
/// length of spring `p` is not finite and positive, a rest length with no symmetric zero-energy
/// state ([`StaticsError::NoZeroEnergyState`]), or a failed branch solve.
pub fn two_kink_configuration<M: ChainModel + ?Sized>(model: &M, p: usize) -> Result<Vec<f64>, StaticsError> {
    validate::spring(model, p)?;
    let n = model.rotor_count();
    let l0 = validate::positive("the rest length of the impurity spring", model.rest_length(p))?;
    let tb = validate::theta_bar(model)?;
    let reach = |phi: f64| spring_length(model, p, -phi, phi);
    let (shortest, critical) = (reach(-tb), reach(tb));
    if l0 > critical * (1.0 + 1e-14) || l0 < shortest * (1.0 - 1e-14) {
        return Err(StaticsError::NoZeroEnergyState {
            spring: p,
            rest_length: l0,
            min: shortest,
            max: critical,
        });
    }
    // l_p(-phi, phi) grows with phi on [-theta_bar, theta_bar]: bisection.
    let (mut lo, mut hi) = (-tb, tb);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid == lo || mid == hi {
            break;
        }
        if reach(mid) < l0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let phi = 0.5 * (lo + hi);
    let mut theta = vec![0.0; n];
    theta[p] = -phi;
    theta[p + 1] = phi;
    for q in p + 1..n - 1 {
        theta[q + 1] = model.next_angles(q, theta[q])?[0];
    }
    for q in (0..p).rev() {
        theta[q] = model.previous_angles(q, theta[q + 1])?[0];
    }
    Ok(theta)
}

/// The linear analysis of the two-kink state around impurity spring `p`.
#[derive(Clone, Debug, PartialEq)]
pub struct ImpurityAnalysis {
    /// The impurity's rest length and the critical length.
    pub rest_length: f64,
    /// `l_critical`: the rest length at which the soft mode vanishes (Sec. VII-A), in units of length.
    pub critical_length: f64,
    /// The zero-energy two-kink configuration.
    pub theta: Vec<f64>,
    /// The lowest modes: the zero mode (kinks moving together), then the soft mode (apart).
    pub modes: Vec<Mode>,
    /// The softest tensional mode (eigenvector of `C C^T`), localised on the impurity.
    pub tensional: TensionalMode,
    /// Maxwell-Calladine counting at the configuration.
    pub counting: Counting,
}

/// Zero-energy state, lowest modes and softest tensional mode around impurity spring `p`
/// (errors as [`two_kink_configuration`]).
pub fn impurity_analysis<M: ChainModel + ?Sized>(
    model: &M,
    p: usize,
) -> Result<ImpurityAnalysis, StaticsError> {
    let theta = two_kink_configuration(model, p)?;
    let lowest = modes(model, &theta, &ModeOptions { count: Some(3), ..ModeOptions::default() })?;
    let tensional = tensional_modes(model, &theta, 1)?.remove(0);
    let counting = maxwell_calladine(model, &theta, None)?;
    Ok(ImpurityAnalysis {
        rest_length: model.rest_length(p),
        critical_length: critical_length(model, p)?,
        theta,
        modes: lowest,
        tensional,
        counting,
    })
}
