//! Cobweb analysis of the branch map (paper Sec. II, Fig. `fig:kcobweb`).
//!
//! Spring `p` at rest defines a curve in the `(theta_p, theta_{p+1})` plane; its flipper branch is
//! a map `theta_{p+1} = F(theta_p)` whose fixed points on the diagonal are the uniform states
//! `+-theta_bar`. Linearising at a fixed point, `theta_{i+1} - theta_bar = F'(theta_bar)(theta_i - theta_bar)`:
//! the fixed point repels if `|F'| > 1` and attracts if `|F'| < 1`, and deformations decay over
//! `|1 / ln F'|` sites. For equal rotors, implicit differentiation of Eq. (`eq:instantlength`)
//! gives `F'(theta_bar) = (a + 2 r sin theta_bar)/(a - 2 r sin theta_bar)`; numerically the slope
//! is `-(dl/dtheta_p)/(dl/dtheta_{p+1})`, read off the generated compatibility matrix.

use alloc::vec;
use alloc::vec::Vec;

use super::error::StaticsError;
use super::validate;
use crate::model::ChainModel;

/// Whether a fixed point attracts or repels forward iteration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stability {
    /// `|F'| < 1`: deformations shrink under the map.
    Attracting,
    /// `|F'| > 1`: deformations grow under the map.
    Repelling,
    /// `|F'| = 1` within rounding.
    Marginal,
}

/// A fixed point of spring `p`'s branch map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedPoint {
    /// The fixed point `-theta_bar` or `+theta_bar`, radians.
    pub theta: f64,
    /// `F'` at the fixed point.
    pub slope: f64,
    /// Whether the branch map attracts or repels there.
    pub stability: Stability,
    /// `|1 / ln F'|`, in sites.
    pub decay_length: f64,
}

/// `F'(theta_bar)` of a chain with equal rotors, in closed form.
pub fn slope_closed_form(a: f64, r: f64, theta_bar: f64) -> f64 {
    let s = 2.0 * r * libm::sin(theta_bar);
    (a + s) / (a - s)
}

/// The slope `F'` of spring `p`'s map at `(theta_p, theta_{p+1})` from the generated code:
/// on the constraint `l_p = l0_p`, `dtheta_{p+1}/dtheta_p = -(dl/dtheta_p)/(dl/dtheta_{p+1})`.
///
/// # Errors
/// [`StaticsError::Branch`] (`NoSuchSpring`) for a spring `p` the chain does not have;
/// [`StaticsError::NotFinite`] for a non-finite angle.
pub fn branch_slope<M: ChainModel + ?Sized>(
    model: &M,
    p: usize,
    theta_p: f64,
    theta_next: f64,
) -> Result<f64, StaticsError> {
    validate::spring(model, p)?;
    validate::finite("theta_p, theta_{p+1}", &[theta_p, theta_next])?;
    let n = model.rotor_count();
    let mut theta = vec![0.0; n];
    theta[p] = theta_p;
    theta[p + 1] = theta_next;
    let (left, right) = super::counting::compatibility(model, &theta);
    // C = dl / d(r theta): undo the rotor lengths to get dl/dtheta.
    Ok(-(left[p] * model.rotor_length(p)) / (right[p] * model.rotor_length(p + 1)))
}

/// Classifies a slope.
pub fn stability(slope: f64) -> Stability {
    let m = slope.abs();
    if (m - 1.0).abs() < 1e-12 {
        Stability::Marginal
    } else if m > 1.0 {
        Stability::Repelling
    } else {
        Stability::Attracting
    }
}

/// The two fixed points `-theta_bar`, `+theta_bar` of spring `p`'s flipper branch (refined by
/// Newton's method on `F(theta) - theta`, so springs with their own rest length are handled).
pub fn fixed_points<M: ChainModel + ?Sized>(model: &M, p: usize) -> Result<[FixedPoint; 2], StaticsError> {
    validate::spring(model, p)?;
    let tb = validate::theta_bar(model)?;
    let mut out =
        [FixedPoint { theta: 0.0, slope: 0.0, stability: Stability::Marginal, decay_length: 0.0 }; 2];
    for (slot, start) in out.iter_mut().zip([-tb, tb]) {
        let mut t = start;
        for _ in 0..50 {
            let f = model.next_angles(p, t)?[0];
            let slope = branch_slope(model, p, t, f)?;
            let step = (f - t) / (slope - 1.0);
            t -= step;
            if step.abs() <= 1e-15 * (1.0 + t.abs()) {
                break;
            }
        }
        let f = model.next_angles(p, t)?[0];
        let slope = branch_slope(model, p, t, f)?;
        *slot = FixedPoint {
            theta: t,
            slope,
            stability: stability(slope),
            decay_length: (1.0 / libm::log(slope.abs())).abs(),
        };
    }
    Ok(out)
}

/// Everything needed to draw a cobweb plot of a profile (Fig. `fig:kcobweb`).
#[derive(Clone, Debug, PartialEq)]
pub struct Cobweb {
    /// The flipper branch `(theta_p, F(theta_p))` of the constraint curve, sampled.
    pub flipper_branch: Vec<[f64; 2]>,
    /// The other branch of the constraint curve.
    pub other_branch: Vec<[f64; 2]>,
    /// The diagonal `theta_{p+1} = theta_p`, as its two end points.
    pub diagonal: [[f64; 2]; 2],
    /// Rotor points `(theta_i, theta_i)`.
    pub rotors: Vec<[f64; 2]>,
    /// Spring points `(theta_i, theta_{i+1})`.
    pub springs: Vec<[f64; 2]>,
    /// The staircase `(theta_1, theta_1) -> (theta_1, theta_2) -> (theta_2, theta_2) -> ...`.
    pub staircase: Vec<[f64; 2]>,
}

/// The most samples of the constraint curve [`cobweb`] takes.
pub const MAX_COBWEB_SAMPLES: usize = 1_000_000;

/// The cobweb of `theta` drawn on spring `p`'s constraint curve, sampled at `samples` angles
/// over `[-range, range]` (angles where the branch solve has no real root are left out).
///
/// # Errors
/// A spring `p` the chain does not have, `theta` not one finite angle per rotor, `range` not
/// finite and positive, or more than [`MAX_COBWEB_SAMPLES`] samples.
pub fn cobweb<M: ChainModel + ?Sized>(
    model: &M,
    p: usize,
    theta: &[f64],
    range: f64,
    samples: usize,
) -> Result<Cobweb, StaticsError> {
    validate::spring(model, p)?;
    validate::angles(model, theta)?;
    validate::positive("range", range)?;
    validate::at_most("samples", samples, MAX_COBWEB_SAMPLES)?;
    let mut flipper_branch = Vec::new();
    let mut other_branch = Vec::new();
    for s in 0..samples {
        let t = -range + 2.0 * range * s as f64 / (samples.max(2) - 1) as f64;
        if let Ok([f, g]) = model.next_angles(p, t) {
            flipper_branch.push([t, f]);
            other_branch.push([t, g]);
        }
    }
    let mut staircase = Vec::with_capacity(2 * theta.len());
    for w in theta.windows(2) {
        staircase.push([w[0], w[0]]);
        staircase.push([w[0], w[1]]);
    }
    if let Some(&last) = theta.last() {
        staircase.push([last, last]);
    }
    Ok(Cobweb {
        flipper_branch,
        other_branch,
        diagonal: [[-range, -range], [range, range]],
        rotors: theta.iter().map(|&t| [t, t]).collect(),
        springs: theta.windows(2).map(|w| [w[0], w[1]]).collect(),
        staircase,
    })
}
