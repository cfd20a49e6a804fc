//! Stepping off a saddle that a descent of the antikink stopped at (paper Sec. V; issue 34).
//!
//! The descent along the adiabatic path ([`super::path::descend`]) stops where `dE/dc` changes
//! sign. That point is a free equilibrium, but it is a minimum only if the path is a valley floor
//! there: where a direction *across* the path is unstable, the path's stationary point is a saddle
//! of the free energy. (The saddle of n = 40, `theta_bar = 0.4`, spring 19 at `0.3k`, index 1
//! at 16.911 and `V = 4166`, that first called for this was on another branch, reached by a step
//! of the path that climbed; the descent now refuses such steps, `path::descend`.) The search
//! leaves such a saddle along the unstable eigenvector `v` of its tangent stiffness (end rotors held), both signs:
//!
//! - **The step** `s` along `v` is scaled by the curvature `lambda < 0`: the force there,
//!   `|lambda| s`, is [`STEP_FORCE`] times the relaxation's tolerance (relative to `||K||`), so
//!   the relaxation starts moving; at most [`MAX_STEP`] radians, so the step stays in the
//!   saddle's neighbourhood where the quadratic picture holds.
//! - **The descent** from there is the paper's damped relaxation ([`super::equilibrium::relax`],
//!   ends held), run until the force is a quarter of the step's. Why relaxation: it lowers the
//!   energy at every step, so it cannot climb back to the saddle (the step already put it below);
//!   Newton's method converges to the nearest stationary point whatever its index, which from a
//!   small step is the saddle again; the constrained path from the new centre is solved by a
//!   Newton iteration too, and would follow the same unstable branch across the path.
//! - **Then** the result is polished by free Newton and, where that is not a free minimum (the
//!   relaxation stopped on a slope too flat for its tolerance), descends the adiabatic path again;
//!   [`super::antikink::antikink_relaxed`] classifies where it ends and keeps the lower of the two
//!   signs' ends, a free minimum before anything else.
//!
//! At most [`MAX_STEP_OFFS`] saddles are left in one search; a saddle is never labelled a minimum.

use alloc::vec::Vec;

use super::antikink::{Antikink, AntikinkOptions};
use super::equilibrium::{RelaxOptions, relax};
use super::error::StaticsError;
use crate::linalg::SymmetricMatrix;
use crate::model::ChainModel;

/// How many saddles one search steps off at most. Why 4: each step-off leaves a saddle for an
/// equilibrium of lower energy, so the search cannot cycle; on a chain with a few impurities a
/// descent crosses at most one impurity's saddle on either side of its start, and 4 leaves room
/// for an index-2 saddle left one direction at a time.
pub const MAX_STEP_OFFS: usize = 4;

/// The force at the step, as a multiple of the relaxation's force tolerance. Why 16: well above
/// the tolerance, so the relaxation moves and is stopped only after it has left the saddle's
/// neighbourhood (at a quarter of that force), yet a step small enough to start inside it.
pub const STEP_FORCE: f64 = 16.0;

/// The longest step off a saddle, radians (Euclidean norm over the rotors). Why 0.05: an eighth
/// of the paper's `theta_bar = 0.4`; the antikink's core angles change by about `theta_bar` per
/// site, so the step moves the centre by a small fraction of a site.
pub const MAX_STEP: f64 = 0.05;

/// One step off a saddle: where the search stood and where it went.
#[derive(Clone, Debug, PartialEq)]
pub struct StepOff {
    /// The saddle's centre (Appendix C wall coordinate, rotor indices).
    pub saddle: f64,
    /// The saddle's angles, radians.
    pub theta: Vec<f64>,
    /// Its energy.
    pub saddle_energy: f64,
    /// Its Morse index (ends held).
    pub index: usize,
    /// The curvature along the unstable direction (the lowest eigenvalue of the tangent
    /// stiffness, energy per rad^2; negative).
    pub curvature: f64,
    /// The signed step taken along the unit eigenvector, radians (the sign chosen: the one whose
    /// descent ended lower, a free minimum first).
    pub step: f64,
    /// The centre where the descent from the step ended.
    pub reached: f64,
    /// Its energy.
    pub energy: f64,
}

/// The configuration `theta` moved off the saddle `saddle` along its lowest eigenvector by `sign`
/// times the step (module doc), relaxed by damped dynamics with the ends held. Returns the relaxed
/// angles, the time steps taken, the curvature and the signed step.
///
/// # Errors
/// `saddle` without a negative curvature ([`StaticsError::InvalidValue`]); the errors of the
/// eigensolver and of the relaxation.
pub(crate) fn step_off<M: ChainModel + ?Sized>(
    model: &M,
    saddle: &Antikink,
    sign: f64,
    options: &AntikinkOptions,
) -> Result<(Vec<f64>, usize, f64, f64), StaticsError> {
    let n = saddle.theta.len();
    let k = SymmetricMatrix::tangent_stiffness(model, &saddle.theta)?.principal(1..n - 1);
    let scale = k.inf_norm().max(f64::MIN_POSITIVE);
    let lowest = k.lowest_eigenpairs(1)?.remove(0);
    let curvature = lowest.value;
    if curvature.is_nan() || curvature >= 0.0 {
        return Err(StaticsError::InvalidValue {
            what: "the lowest curvature of the saddle to step off",
            value: curvature,
            expected: "a negative curvature (an unstable direction)",
        });
    }
    let tolerance = options.relax.tolerance;
    let length = (STEP_FORCE * tolerance * scale / -curvature).min(MAX_STEP);
    let step = sign * length;
    let mut theta = saddle.theta.clone();
    for (t, v) in theta[1..n - 1].iter_mut().zip(&lowest.vector) {
        *t += step * v;
    }
    // Stop at a quarter of the force at the step: out of the saddle's neighbourhood.
    let force = -curvature * length / scale;
    let relax_options =
        RelaxOptions { hold_ends: true, tolerance: tolerance.min(0.25 * force), ..options.relax };
    let (relaxed, steps) = relax(model, &theta, &relax_options)?;
    Ok((relaxed, steps, curvature, step))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Potential;
    use crate::runtime::RuntimeChain;
    use crate::statics::antikink::antikink_at;
    use crate::statics::walls::{Charge, domain_walls};

    /// The bond-centred antikink of a uniform chain is the Peierls-Nabarro saddle (index 1,
    /// paper Sec. V): stepped off either way, the relaxation lowers the energy and moves the
    /// wall towards the site-centred minimum on that side (19 or 20), mirror images of each other.
    #[test]
    fn a_bond_centred_antikink_is_left_towards_the_site_centred_wells_on_either_side() {
        let model = RuntimeChain::builder(40, 0.8, 1.0, 0.4).build().unwrap();
        let options = AntikinkOptions::default();
        let saddle = antikink_at(&model, 19.5, &options).unwrap();
        assert_eq!(saddle.classification.index, 1, "{saddle:?}");
        let mut ends = Vec::new();
        for sign in [1.0, -1.0] {
            let (theta, _, curvature, step) = step_off(&model, &saddle, sign, &options).unwrap();
            assert!(curvature < 0.0 && step * sign > 0.0 && step.abs() <= MAX_STEP);
            assert!(model.energy(&theta) < saddle.energy, "{sign}");
            let wall = domain_walls(&theta).into_iter().find(|w| w.charge == Charge::Antikink).unwrap();
            ends.push((wall.position, model.energy(&theta)));
        }
        // One step went left of 19.5, the other right, by the same amount and to the same energy.
        let (a, b) = (ends[0].0.min(ends[1].0), ends[0].0.max(ends[1].0));
        assert!(a < 19.5 && b > 19.5, "{ends:?}");
        assert!(((19.5 - a) - (b - 19.5)).abs() < 1e-6, "{ends:?}");
        assert!((ends[0].1 - ends[1].1).abs() < 1e-9 * ends[0].1, "{ends:?}");
    }
}
