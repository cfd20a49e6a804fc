//! The launch of a kink or an antikink from its near-null modes (the module doc of
//! [`launch`](super) says why the most localised vector).

use alloc::vec;
use alloc::vec::Vec;

use nalgebra::DMatrix;

use crate::dynamics::DynamicsError;
use crate::integrate::State;
use crate::model::ChainModel;
use crate::statics::antikink::{AntikinkOptions, relaxed_nearest};
use crate::statics::kink::kink;
use crate::statics::modes::{ModeOptions, modes};
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
    /// The normalised launch vector in tip displacements (`sum e_i^2 = 1`).
    pub mode: Vec<f64>,
    /// Where the defect starts (Appendix C wall position).
    pub position: f64,
    /// Kink or antikink.
    pub charge: Charge,
}

impl Launch {
    /// The fraction of the launch's kinetic energy on rotors farther than `distance` sites from
    /// the wall: `sum_{|i - x| > distance} e_i^2` (the kinetic energy of rotor `i` is
    /// `M (v0 e_i)^2 / 2`).
    pub fn kinetic_energy_beyond(&self, distance: f64) -> f64 {
        energy_beyond(&self.mode, self.position, distance)
    }
}

fn energy_beyond(e: &[f64], position: f64, distance: f64) -> f64 {
    e.iter().enumerate().filter(|(i, _)| (*i as f64 - position).abs() > distance).map(|(_, x)| x * x).sum()
}

/// The wall width in sites (it lives with the walls; here for the launches that use it).
pub use crate::statics::walls::wall_width;

/// How many of the lowest modes of a single wall of `charge` lie far below the phonon band: the
/// translation, plus for an antikink the edge mechanisms of its two domains (module doc).
pub fn near_null_count(charge: Charge) -> usize {
    match charge {
        Charge::Kink => 1,
        Charge::Antikink => 3,
    }
}

/// The static defect of `charge` at `position`: the kink centred there, or the antikink relaxed
/// from there (as [`antikink_relaxed`](crate::statics::antikink::antikink_relaxed) before its descent
/// downhill): in the middle of a chain the Peierls-Nabarro minimum nearest
/// to it; near an end the ends push a wide antikink inward, possibly far (docs/dynamics.md §2), so
/// the launch's `position` is the centre actually used.
pub fn static_defect<M: ChainModel + ?Sized>(
    model: &M,
    charge: Charge,
    position: f64,
) -> Result<Vec<f64>, DynamicsError> {
    Ok(match charge {
        Charge::Kink => kink(model, position)?,
        Charge::Antikink => relaxed_nearest(model, position, &AntikinkOptions::default())?.theta,
    })
}

/// The smallest cosine between the launch vector and the wall's own displacement `dtheta/dx`
/// (both in tip displacements) that is accepted as a translation. Measured: 0.987-1.000 over
/// `theta_bar = 0.1 ... 0.65`, both defects, every start from rotor 8 to `n - 9` (`n` = 60 and
/// 120); a vector that is mostly an edge mode has a cosine near 0.
const MIN_OVERLAP: f64 = 0.5;

/// The translation mode of the defect of `charge` in `theta` located at `position`, separated
/// from the edge modes (module doc), normalised in tip displacements and signed so that it moves
/// the defect towards `direction`.
pub fn translation_mode<M: ChainModel + ?Sized>(
    model: &M,
    theta: &[f64],
    charge: Charge,
    position: f64,
    direction: Direction,
) -> Result<Vec<f64>, DynamicsError> {
    let n = model.rotor_count();
    let count = near_null_count(charge).min(n);
    let found = modes(model, theta, &ModeOptions { count: Some(count), ..ModeOptions::default() })?;
    // u_i = sqrt(I_i) v_i: orthonormal, and proportional to the tip displacement r_i v_i.
    let basis: Vec<Vec<f64>> = found
        .iter()
        .map(|m| m.shape.iter().enumerate().map(|(i, v)| v * crate::math::sqrt(model.inertia(i))).collect())
        .collect();
    let spread = |i: usize| {
        let d = i as f64 - position;
        d * d
    };
    let m = basis.len();
    let form = DMatrix::<f64>::from_fn(m, m, |a, b| {
        basis[a].iter().zip(&basis[b]).enumerate().map(|(i, (x, y))| spread(i) * x * y).sum::<f64>()
    });
    let eigen = form.symmetric_eigen();
    let lowest = eigen.eigenvalues.iamin();
    let mut u = vec![0.0; n];
    for (a, b) in basis.iter().enumerate() {
        let weight = eigen.eigenvectors[(a, lowest)];
        u.iter_mut().zip(b).for_each(|(x, y)| *x += weight * y);
    }
    // Tip displacements e_i = r_i v_i = u_i sqrt(M) for equal masses; normalised below.
    let mut e: Vec<f64> = u
        .iter()
        .enumerate()
        .map(|(i, x)| x * model.rotor_length(i) / crate::math::sqrt(model.inertia(i)))
        .collect();
    let norm = crate::math::sqrt(e.iter().map(|x| x * x).sum::<f64>());
    if !(norm > 0.0 && norm.is_finite()) {
        return Err(DynamicsError::NoTranslationMode { position });
    }
    e.iter_mut().for_each(|x| *x /= norm);
    // Moving right, the profile shifts as theta(x - v t), so thetadot = -v dtheta/dx: the
    // displacement of a wall moving right is -r_i dtheta_i/dx.
    let shift: Vec<f64> = (0..n)
        .map(|i| {
            let (l, r) = (theta[i.saturating_sub(1)], theta[(i + 1).min(n - 1)]);
            -model.rotor_length(i) * (r - l) / ((i + 1).min(n - 1) - i.saturating_sub(1)).max(1) as f64
        })
        .collect();
    let shift_norm = crate::math::sqrt(shift.iter().map(|x| x * x).sum::<f64>());
    let push: f64 = e.iter().zip(&shift).map(|(a, b)| a * b).sum();
    let overlap = push.abs() / shift_norm.max(f64::MIN_POSITIVE);
    if overlap.is_nan() || overlap < MIN_OVERLAP {
        return Err(DynamicsError::NoTranslationMode { position });
    }
    let want = if direction == Direction::Right { 1.0 } else { -1.0 };
    if push * want < 0.0 {
        e.iter_mut().for_each(|x| *x = -*x);
    }
    Ok(e)
}

/// A `charge` defect at `position` launched towards `direction` with speed amplitude `v0`
/// (Appendix B: `r_i thetadot_i = v0 e_i`, kinetic energy `M v0^2 / 2`).
/// # Example
///
/// ```
/// use rotor_chain::RuntimeChain;
/// use rotor_chain::dynamics::launch::{Direction, launch};
/// use rotor_chain::statics::walls::Charge;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let chain = RuntimeChain::builder(60, 0.8, 1.0e4, 0.58).build()?; // M = 1
/// let v0 = 3.0;                                                     // a / t
/// let kink = launch(&chain, Charge::Kink, 40.0, v0, Direction::Left)?;
/// let r = 0.8;
/// let kinetic: f64 = kink.state.omega.iter().map(|w| 0.5 * r * r * w * w).sum();
/// assert!((kinetic - 0.5 * v0 * v0).abs() < 1e-9);                 // M v0^2 / 2
/// # Ok(())
/// # }
/// ```
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
        .filter(|w| w.charge == charge)
        .min_by(|a, b| (a.position - position).abs().total_cmp(&(b.position - position).abs()))
        .map(|w| w.position)
        .ok_or(DynamicsError::NoTranslationMode { position })?;
    let mode = translation_mode(model, &theta, charge, actual, direction)?;
    let omega = mode.iter().enumerate().map(|(i, e)| v0 * e / model.rotor_length(i)).collect();
    Ok(Launch { state: State { time: 0.0, theta, omega }, mode, position: actual, charge })
}
