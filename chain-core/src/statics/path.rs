//! The antikink's adiabatic path (paper Sec. V): its lowest energy `E(c)` with its centre held at
//! any `c`, not only at the rotor and spring centrings, and the descent along `c` to the bottom
//! of a well.
//!
//! **The centre as a constraint.** The Appendix C wall coordinate of an antikink whose sign change
//! lies between rotors `i` and `i + 1` is `c = i + theta_i / (theta_i - theta_{i+1})`
//! ([`super::walls`]). Holding it at `c = i + f` (`0 <= f <= 1`) is the *linear* constraint
//! `(1 - f) theta_i + f theta_{i+1} = 0`. We eliminate the angle with the larger coefficient,
//! `theta_e = s theta_q` (`q` its neighbour in the pair, `|s| <= 1`): in the remaining angles
//! the energy's Hessian is `T^T K T`, still tridiagonal (the eliminated rotor's neighbours become
//! neighbours), so each constrained Newton step is one O(n) solve, and its Sturm count is the
//! Morse index of the path point in the directions that keep the centre.
//!
//! **The slope.** At a constrained equilibrium the gradient is parallel to the constraint's
//! normal `a`, `g = lambda a`, and differentiating `a(c) . theta(c) = 0` gives
//! `dE/dc = g . theta' = -lambda (theta_{i+1} - theta_i)`: the exact derivative of the path
//! energy, from one solve. Where it vanishes the gradient vanishes, so the path point is a free
//! equilibrium of the chain.
//!
//! **The descent** ([`descend`]) steps along `c` by [`PATH_STEP`] downhill from a start until the
//! slope changes sign, then closes that bracket on the slope's zero by regula falsi (Illinois),
//! each point warm-started from the nearest one solved. Why this is needed: on a chain with
//! impurities the Peierls-Nabarro wells are shifted off the rotor and spring centrings, so
//! Newton's method from a symmetric guess at a centring finds no equilibrium there (docs/statics.md
//! "Chains that are not uniform"); along the path the well is a zero of one smooth function.
//!
//! Only with held ends ([`super::antikink::Ends::Held`]): with free ends the domains' near-null edge
//! modes make `T^T K T` singular to rounding.

use alloc::vec;
use alloc::vec::Vec;

use super::antikink::AntikinkOptions;
use super::classify::rounding_tolerance;
use super::equilibrium::POLISH_STEPS;
use super::error::StaticsError;
use super::walls::{Charge, domain_walls};
use crate::linalg::SymmetricMatrix;
use crate::model::ChainModel;

/// The descent's step along the centre, in sites. Why 1/8: a Peierls-Nabarro well is half a site
/// wide between its two saddles on a uniform chain and an impurity only narrows the wells on its
/// slope, so a step of an eighth puts at least two path points in every well it crosses.
pub const PATH_STEP: f64 = 0.125;

/// The descent stops when the bracket on the slope's zero is narrower than this (sites): far below
/// where the free Newton polish that follows needs to start.
pub const PATH_RESOLUTION: f64 = 1e-9;

/// At most this many regula-falsi steps close a bracket: Illinois converges superlinearly, and 80
/// halvings alone would reach below [`PATH_RESOLUTION`] from a bracket of [`PATH_STEP`].
pub const MAX_REFINEMENTS: usize = 80;

/// A point of the adiabatic path: the antikink of lowest energy near a guess with its centre held.
#[derive(Clone, Debug, PartialEq)]
pub struct PathPoint {
    /// The centre held (Appendix C wall coordinate, in rotor indices).
    pub centre: f64,
    /// The angles, radians (end rotors held at `-theta_bar`, `+theta_bar`).
    pub theta: Vec<f64>,
    /// Potential energy `V = E(c)`.
    pub energy: f64,
    /// `dE/dc`, energy per site (see the module doc); zero at a free equilibrium.
    pub slope: f64,
    /// Negative eigenvalues of the Hessian in the directions that keep the centre (below
    /// `-64 n eps ||K||`): 0 where the path is a valley floor.
    pub index: usize,
    /// Constrained Newton steps taken.
    pub iterations: usize,
    /// `max |T^T dV/dtheta| / ||K||` at the end: the force left in the directions that keep the
    /// centre (the constraint's own force is `dE/dc`).
    pub residual: f64,
}

/// The constrained pair: the rotors `(i, i + 1)` whose sign change is held at `c = i + f`.
struct Constraint {
    i: usize,
    f: f64,
    /// The eliminated rotor and its partner: `theta[eliminated] = s theta[partner]`.
    eliminated: usize,
    partner: usize,
    s: f64,
}

impl Constraint {
    fn new(c: f64, first: usize, last: usize) -> Self {
        let i = (libm::floor(c) as usize).clamp(first, last - 1);
        let f = c - i as f64;
        let (eliminated, partner, s) =
            if f <= 0.5 { (i, i + 1, -f / (1.0 - f)) } else { (i + 1, i, -(1.0 - f) / f) };
        Self { i, f, eliminated, partner, s }
    }

    /// Projects `theta` onto the constraint along its normal `a = (1 - f) e_i + f e_{i+1}`.
    fn project(&self, theta: &mut [f64]) {
        let (a0, a1) = (1.0 - self.f, self.f);
        let t = (a0 * theta[self.i] + a1 * theta[self.i + 1]) / (a0 * a0 + a1 * a1);
        theta[self.i] -= t * a0;
        theta[self.i + 1] -= t * a1;
    }

    /// `dE/dc` from the gradient at a constrained equilibrium (module doc).
    fn slope(&self, theta: &[f64], g: &[f64]) -> f64 {
        let (a0, a1) = (1.0 - self.f, self.f);
        let lambda = (a0 * g[self.i] + a1 * g[self.i + 1]) / (a0 * a0 + a1 * a1);
        -lambda * (theta[self.i + 1] - theta[self.i])
    }
}

/// The reduced gradient `T^T g` and tridiagonal Hessian `T^T K T` on the moving rotors
/// `first..=last` without the eliminated one, in order; `rows` lists their rotor indices.
fn reduce(
    k: &SymmetricMatrix,
    g: &[f64],
    con: &Constraint,
    rows: &[usize],
) -> Result<(Vec<f64>, SymmetricMatrix), StaticsError> {
    let (diag, off) = k.bands().ok_or(StaticsError::InvalidValue {
        what: "the stiffness layout of the model",
        value: f64::NAN,
        expected: "a chain's tridiagonal tangent stiffness",
    })?;
    let entry = |a: usize, b: usize| match a.abs_diff(b) {
        0 => diag[a],
        1 => off[a.min(b)],
        _ => 0.0,
    };
    let (e, q, s) = (con.eliminated, con.partner, con.s);
    // (T^T K T)_{ab} = K_ab + s (d_aq K_eb + d_bq K_ae) + s^2 d_aq d_bq K_ee.
    let reduced = |a: usize, b: usize| {
        let mut v = entry(a, b);
        if a == q {
            v += s * entry(e, b);
        }
        if b == q {
            v += s * entry(a, e);
        }
        if a == q && b == q {
            v += s * s * diag[e];
        }
        v
    };
    let gr = rows.iter().map(|&a| g[a] + if a == q { s * g[e] } else { 0.0 }).collect();
    let d: Vec<f64> = rows.iter().map(|&a| reduced(a, a)).collect();
    let o: Vec<f64> = rows.windows(2).map(|w| reduced(w[0], w[1])).collect();
    Ok((gr, SymmetricMatrix::tridiagonal(&d, &o)?))
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m: f64, x| if x.is_nan() || m.is_nan() { f64::NAN } else { m.max(x.abs()) })
}

/// The point of the adiabatic path at `centre`: Newton's method on the energy with the antikink's
/// centre held (module doc), from `guess` (any configuration with one antikink near `centre`; it
/// is first projected onto the constraint), to `options.newton.tolerance` on the reduced force.
///
/// # Errors
/// `centre` outside `[1, n - 2]` or ends not held ([`StaticsError::InvalidValue`]); a guess of the
/// wrong length or not finite; [`StaticsError::NoConvergence`] after
/// `options.newton.max_iterations` steps; [`StaticsError::DefectLost`] when the result holds other
/// walls than the one antikink at `centre`.
pub fn at_centre<M: ChainModel + ?Sized>(
    model: &M,
    guess: &[f64],
    centre: f64,
    options: &AntikinkOptions,
) -> Result<PathPoint, StaticsError> {
    super::validate::angles(model, guess)?;
    let n = model.rotor_count();
    if options.ends != super::antikink::Ends::Held {
        return Err(StaticsError::InvalidValue {
            what: "the ends of a chain for the antikink's adiabatic path",
            value: f64::NAN,
            expected: "held ends (Ends::Held): free ends carry near-null edge modes",
        });
    }
    let (first, last) = (1, n.saturating_sub(2));
    if !(n >= 4 && centre >= first as f64 && centre <= last as f64) {
        return Err(StaticsError::InvalidValue {
            what: "the centre of a point of the antikink's adiabatic path",
            value: centre,
            expected: "a wall position in [1, n - 2] (between the held end rotors), n >= 4",
        });
    }
    let newton = &options.newton;
    let con = Constraint::new(centre, first, last);
    let rows: Vec<usize> = (first..=last).filter(|&a| a != con.eliminated).collect();
    let mut theta = guess.to_vec();
    let tb = model.theta_bar();
    (theta[0], theta[n - 1]) = (-tb, tb);
    con.project(&mut theta);
    let mut g = vec![0.0; n];
    let mut k = SymmetricMatrix::for_model(model)?;
    let mut trial = theta.clone();
    let mut g_trial = g.clone();
    let mut k_trial = k.clone();
    model.energy_gradient_stiffness_into(&theta, &mut g, k.values_mut());
    super::validate::finite("the model's gradient at theta", &g)?;
    let scale = k.inf_norm().max(f64::MIN_POSITIVE);
    let (mut gr, mut kr) = reduce(&k, &g, &con, &rows)?;
    let mut residual = max_abs(&gr) / scale;
    let mut iterations = 0;
    // To the tolerance, then polished to the rounding floor (as `equilibrium::polish`, at most
    // POLISH_STEPS steps while each lowers the force): the slope of a wide antikink's path is
    // small (`~1e-7` per site at `theta_bar = 0.2`), and the force left at the tolerance would
    // blur it.
    let mut polished = 0;
    loop {
        let converged = residual <= newton.tolerance;
        if converged && polished == POLISH_STEPS {
            break;
        }
        if !converged && (iterations == newton.max_iterations || residual.is_nan()) {
            return Err(StaticsError::NoConvergence {
                method: "Newton's method at a fixed antikink centre",
                iterations,
                residual,
                tolerance: newton.tolerance,
            });
        }
        let rhs: Vec<f64> = gr.iter().map(|x| -x).collect();
        let delta = kr.solve_shifted(-newton.shift * scale, &rhs)?;
        // Backtracking on the reduced force, as in `equilibrium::newton`; a polishing step is
        // taken whole or not at all.
        let mut alpha = 1.0;
        let mut accepted = false;
        loop {
            trial.copy_from_slice(&theta);
            for (&a, d) in rows.iter().zip(&delta) {
                trial[a] += alpha * d;
                if a == con.partner {
                    trial[con.eliminated] += alpha * con.s * d;
                }
            }
            con.project(&mut trial);
            model.energy_gradient_stiffness_into(&trial, &mut g_trial, k_trial.values_mut());
            let (gt, kt) = reduce(&k_trial, &g_trial, &con, &rows)?;
            let r = max_abs(&gt) / scale;
            if r < residual || (!converged && alpha < 1e-6) {
                core::mem::swap(&mut theta, &mut trial);
                core::mem::swap(&mut g, &mut g_trial);
                core::mem::swap(&mut k, &mut k_trial);
                (gr, kr, residual) = (gt, kt, r);
                accepted = true;
                break;
            }
            if converged || alpha < 1e-6 {
                break;
            }
            alpha *= 0.5;
        }
        if converged {
            if !accepted {
                break;
            }
            polished += 1;
        } else {
            iterations += 1;
        }
    }
    super::validate::finite("the antikink at a fixed centre", &theta)?;
    let walls = domain_walls(&theta);
    let antikinks = walls.iter().filter(|w| w.charge == Charge::Antikink).count();
    let held = walls.first().map_or(f64::NAN, |w| w.position);
    let off = (held - centre).abs();
    if walls.len() != 1 || antikinks != 1 || off.is_nan() || off > 1e-9 * centre.max(1.0) {
        return Err(StaticsError::DefectLost {
            expected: "antikink",
            kinks: walls.len() - antikinks,
            antikinks,
        });
    }
    let index = kr.count_below(-rounding_tolerance(kr.dim()) * kr.inf_norm())?;
    Ok(PathPoint {
        centre,
        energy: model.energy(&theta),
        slope: con.slope(&theta, &g),
        theta,
        index,
        iterations,
        residual,
    })
}

/// Where [`descend`] ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Descent {
    /// The bottom of a well: the path point where `dE/dc` changes sign from negative to positive,
    /// to [`PATH_RESOLUTION`]. Its gradient vanishes to the constrained Newton's tolerance, so it
    /// is the starting point of a free Newton polish.
    Bottom(PathPoint),
    /// The last point of a path that ends while still falling: one [`MIN_STEP`] further no antikink
    /// with its centre held keeps its one wall (next to a soft impurity a kink-antikink pair
    /// nucleates on it) or Newton's method finds none (a fold of the path).
    End(PathPoint),
}

/// The shortest step [`descend`] tries before it calls the path ended ([`Descent::End`]).
pub const MIN_STEP: f64 = PATH_STEP / 64.0;

/// Descends the adiabatic path from the antikink `start` (one antikink, any configuration near
/// equilibrium) downhill in steps of [`PATH_STEP`] (halved down to [`MIN_STEP`] where a step finds
/// no path point) until the slope changes sign, then closes that bracket on its zero.
///
/// The descent stays within `reach` sites of the start's centre and inside `[1, n - 2]`.
///
/// # Errors
/// [`StaticsError::DescentLeftRegion`] when the energy still falls at the edge of that region
/// (the start, the region, where the descent reached, its energy and slope);
/// [`StaticsError::InvalidValue`] for a negative or NaN `reach` or fewer than 4 rotors; the errors
/// of [`at_centre`] at the start.
pub fn descend<M: ChainModel + ?Sized>(
    model: &M,
    start: &[f64],
    reach: f64,
    options: &AntikinkOptions,
) -> Result<Descent, StaticsError> {
    super::validate::angles(model, start)?;
    let from = domain_walls(start)
        .iter()
        .find(|w| w.charge == Charge::Antikink)
        .map(|w| w.position)
        .ok_or(StaticsError::DefectLost { expected: "antikink", kinks: 0, antikinks: 0 })?;
    let n = model.rotor_count() as f64;
    if !(reach >= 0.0 && n >= 4.0) {
        return Err(StaticsError::InvalidValue {
            what: "the reach of the antikink's descent (and the chain's rotor count)",
            value: reach,
            expected: "a reach >= 0 sites on a chain of at least 4 rotors (a wall between held ends)",
        });
    }
    let (lo, hi) = ((from - reach).max(1.0), (from + reach).min(n - 2.0));
    let from = from.clamp(lo, hi);
    let mut p = at_centre(model, start, from, options)?;
    // A start exactly at a stationary point goes right: past a maximum the slope falls on, at a
    // minimum the first step brackets it.
    let dir = if p.slope > 0.0 { -1.0 } else { 1.0 };
    // Each accepted step moves at least MIN_STEP (or reaches an edge of the region, after which
    // the next target is the point itself), so the region is crossed in a bounded number of steps.
    for _ in 0..libm::ceil((hi - lo) / MIN_STEP) as usize + 2 {
        let target = (p.centre + dir * PATH_STEP).clamp(lo, hi);
        if target == p.centre {
            return Err(StaticsError::DescentLeftRegion {
                start: from,
                lo,
                hi,
                reached: p.centre,
                energy: p.energy,
                slope: p.slope,
            });
        }
        let Some(q) = next_point(model, &p, target, options)? else {
            return Ok(Descent::End(p));
        };
        if dir * q.slope >= 0.0 {
            return refine(model, p, q, options).map(Descent::Bottom);
        }
        p = q;
    }
    Ok(Descent::End(p))
}

/// The next point of the path from `p` toward `target`: held at `target`, else half the way, a
/// quarter, ... down to [`MIN_STEP`]; `None` where none of them is a point of `p`'s branch
/// (Newton's method does not converge, a pair nucleates, or it converged to an equilibrium of
/// another branch, [`continues`]): the path ends at `p`. The one step of the descent and of the
/// path scan (`path_scan`), at most 7 tries for a step of [`PATH_STEP`].
///
/// # Errors
/// The errors of [`at_centre`] other than a lost antikink or Newton's method not converging.
pub(crate) fn next_point<M: ChainModel + ?Sized>(
    model: &M,
    p: &PathPoint,
    target: f64,
    options: &AntikinkOptions,
) -> Result<Option<PathPoint>, StaticsError> {
    let n = model.rotor_count();
    let mut step = target - p.centre;
    let mut c = target;
    loop {
        match at_centre(model, &p.theta, c, options) {
            Ok(q) if continues(p, &q, n) => return Ok(Some(q)),
            Ok(_) | Err(StaticsError::NoConvergence { .. } | StaticsError::DefectLost { .. }) => {}
            Err(e) => return Err(e),
        }
        // Not `!(>)`: a NaN step ends the path too.
        if step.abs() <= MIN_STEP || step.is_nan() {
            return Ok(None);
        }
        step *= 0.5;
        c = p.centre + step;
    }
}

/// Whether `q`, a point of the path found from `p` (Newton's method warm-started there), lies on
/// `p`'s branch. On the branch, `E(q) - E(p)` is the integral of `dE/dc` over the step: between
/// the step times the smaller and the larger of the two end slopes where the slope is monotone
/// over the step, and here allowed their spread again on either side (a slope that is not
/// monotone over an eighth of a site), plus the energies' rounding (`64 n eps |E|`). A change far
/// outside is another equilibrium with the centre held: n = 40, `theta_bar = 0.4`, spring 19 at
/// `0.3k`, where the path folds at c = 16.6 (Newton's method fails there and a pair nucleates for
/// a few steps beyond), a halved step from 16.56 converged to a configuration of energy 4166 (the
/// antikink's 468), whose bracket led the descent to an index-1 saddle of that branch. A NaN
/// energy or slope is not on the branch either.
fn continues(p: &PathPoint, q: &PathPoint, n: usize) -> bool {
    let dc = q.centre - p.centre;
    let (a, b) = (p.slope * dc, q.slope * dc);
    let (low, high) = (a.min(b), a.max(b));
    let spread = high - low;
    let rounding = 64.0 * n as f64 * f64::EPSILON * p.energy.abs().max(q.energy.abs());
    let change = q.energy - p.energy;
    change >= low - spread - rounding && change <= high + spread + rounding
}

/// Closes the bracket `(a, b)` (slopes of opposite signs) on the zero of the slope by regula
/// falsi with the Illinois halving, at most [`MAX_REFINEMENTS`] steps.
pub(crate) fn refine<M: ChainModel + ?Sized>(
    model: &M,
    mut a: PathPoint,
    mut b: PathPoint,
    options: &AntikinkOptions,
) -> Result<PathPoint, StaticsError> {
    let mut side = 0i8;
    let (mut wa, mut wb) = (a.slope, b.slope);
    for _ in 0..MAX_REFINEMENTS {
        if b.slope == 0.0 || (b.centre - a.centre).abs() <= PATH_RESOLUTION {
            break;
        }
        let c = (a.centre * wb - b.centre * wa) / (wb - wa);
        let c = if c.is_finite() && c > a.centre.min(b.centre) && c < a.centre.max(b.centre) {
            c
        } else {
            0.5 * (a.centre + b.centre)
        };
        let guess = if (c - a.centre).abs() < (c - b.centre).abs() { &a.theta } else { &b.theta };
        let m = at_centre(model, guess, c, options)?;
        let slope = m.slope;
        if (slope > 0.0) == (b.slope > 0.0) {
            (b, wb) = (m, slope);
            if side == 1 {
                wa *= 0.5;
            }
            side = 1;
        } else {
            (a, wa) = (m, slope);
            if side == -1 {
                wb *= 0.5;
            }
            side = -1;
        }
    }
    Ok(if a.slope.abs() < b.slope.abs() { a } else { b })
}
