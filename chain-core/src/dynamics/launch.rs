//! Setting a kink or an antikink in motion (paper Sec. V and Appendix B).
//!
//! The static defect (the zero-energy kink, or the antikink at its Peierls-Nabarro minimum) is
//! given velocities along its **translation mode** `e`, normalised in tip displacements
//! (`sum_i e_i^2 = 1`, `e_i = r_i v_i / |r v|` for the angular mode `v`): `r_i thetadot_i = v0 e_i`,
//! so the initial kinetic energy is `sum_i M (v0 e_i)^2 / 2 = M v0^2 / 2` (Appendix B). The
//! antikink's translation mode lies in a near-zero subspace with the edge modes of its domains;
//! [`crate::statics::modes`] separates them, and the mode used is the one localised at the
//! antikink, so the launch does not also excite the ends.

use alloc::vec::Vec;

use super::DynamicsError;
use super::integrate::State;
use crate::model::ChainModel;
use crate::statics::antikink::{AntikinkOptions, antikink_relaxed};
use crate::statics::kink::kink;
use crate::statics::modes::{ModeKind, ModeOptions, modes};
use crate::statics::walls::{Charge, domain_walls};

/// Which way the defect moves along the chain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// Towards rotor 0.
    Left,
    /// Towards rotor n - 1.
    Right,
}

/// A defect set in motion.
#[derive(Clone, Debug, PartialEq)]
pub struct Launch {
    /// Angles and angular velocities at time 0.
    pub state: State,
    /// The normalised translation mode in tip displacements (`sum e_i^2 = 1`).
    pub mode: Vec<f64>,
    /// Where the defect starts (Appendix C wall position).
    pub position: f64,
    pub charge: Charge,
}

/// The static defect of `charge` at `position`: the kink centred there, or the antikink at the
/// Peierls-Nabarro minimum nearest to it.
pub fn static_defect<M: ChainModel + ?Sized>(
    model: &M,
    charge: Charge,
    position: f64,
) -> Result<Vec<f64>, DynamicsError> {
    Ok(match charge {
        Charge::Kink => kink(model, position)?,
        Charge::Antikink => antikink_relaxed(model, position, &AntikinkOptions::default())?.theta,
    })
}

/// The translation mode of the defect in `theta` located at `position`, normalised in tip
/// displacements and signed so that it moves the defect towards `direction`.
pub fn translation_mode<M: ChainModel + ?Sized>(
    model: &M,
    theta: &[f64],
    position: f64,
    direction: Direction,
) -> Result<Vec<f64>, DynamicsError> {
    let n = model.rotor_count();
    let found = modes(model, theta, &ModeOptions { count: Some(8.min(n)), ..ModeOptions::default() })?;
    let mode = found
        .iter()
        .filter(|m| m.kind == ModeKind::Translation)
        .min_by(|a, b| (a.position - position).abs().total_cmp(&(b.position - position).abs()))
        .ok_or(DynamicsError::NoTranslationMode { position })?;
    let mut e: Vec<f64> = mode.shape.iter().enumerate().map(|(i, v)| model.rotor_length(i) * v).collect();
    let norm = crate::math::sqrt(e.iter().map(|x| x * x).sum::<f64>());
    e.iter_mut().for_each(|x| *x /= norm);
    // Moving right, the profile shifts as theta(x - v t), so thetadot = -v dtheta/dx.
    let push: f64 = (0..n)
        .map(|i| {
            let (l, r) = (theta[i.saturating_sub(1)], theta[(i + 1).min(n - 1)]);
            -(r - l) * e[i] / model.rotor_length(i)
        })
        .sum();
    let want = if direction == Direction::Right { 1.0 } else { -1.0 };
    if push * want < 0.0 {
        e.iter_mut().for_each(|x| *x = -*x);
    }
    Ok(e)
}

/// A `charge` defect at `position` launched towards `direction` with speed amplitude `v0`
/// (Appendix B: `r_i thetadot_i = v0 e_i`, kinetic energy `M v0^2 / 2`).
pub fn launch<M: ChainModel + ?Sized>(
    model: &M,
    charge: Charge,
    position: f64,
    v0: f64,
    direction: Direction,
) -> Result<Launch, DynamicsError> {
    if !(v0.is_finite() && v0 >= 0.0) {
        return Err(DynamicsError::BadSpeed { v0 });
    }
    let theta = static_defect(model, charge, position)?;
    let actual = domain_walls(&theta)
        .iter()
        .find(|w| w.charge == charge)
        .map(|w| w.position)
        .ok_or(DynamicsError::NoTranslationMode { position })?;
    let mode = translation_mode(model, &theta, actual, direction)?;
    let omega = mode.iter().enumerate().map(|(i, e)| v0 * e / model.rotor_length(i)).collect();
    Ok(Launch { state: State { time: 0.0, theta, omega }, mode, position: actual, charge })
}
