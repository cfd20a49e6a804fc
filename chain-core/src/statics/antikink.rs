//! The antikink and its Peierls-Nabarro barrier (paper Sec. II, III, V; Figs. `fig:akcobweb`,
//! `fig:aktheta`, `fig:akenergy`, `fig:akconfigpn`, `fig:logvpn-theta`, `fig:logvpn-size`).
//!
//! **Construction.** The paper reflects the kink's spring points across the diagonal of the
//! cobweb plot ([`super::kink::reflected_kink`]) and relaxes the result with dissipative Newtonian
//! dynamics; we then polish with Newton's method on the gradient ([`super::equilibrium`]).
//!
//! **Minimum and saddle.** A discrete antikink is in equilibrium only where its profile is locally
//! symmetric: centred on a rotor or centred on a spring. One centring is a minimum of the energy,
//! the other a saddle of index 1, and the Peierls-Nabarro barrier is their energy difference
//! (Sec. V). Both are found by Newton's method from the reflected kink built *symmetrically*
//! about the wanted centre: the symmetric guess has no component along the antisymmetric
//! translation mode, so Newton stays on that centring whether it is the minimum or the saddle,
//! and the Sturm count of the tangent stiffness says which it is.
//!
//! **Robustness.** Wide antikinks (small `theta_bar`) have exponentially small barriers and the
//! free ends carry exponentially soft edge modes, so plain minimisation drifts (toward a kink
//! entering from an end, which can annihilate the antikink). Newton from a symmetric guess never
//! follows those flat directions, and the domain walls of the result are counted: an answer
//! without exactly one antikink is an error, not a result.
//!
//! **Boundary treatment.** With free ends an antikink can be in exact equilibrium only if the end
//! rotors are collinear with their springs: force balance on an end rotor makes its spring's
//! tension vanish unless the spring points at its pivot, and a vanishing tension propagates
//! inward. So wherever the antikink's tails reach the ends, exact free-end equilibrium swings the
//! end rotors round (the paper's "overshooting", Sec. II, Fig. `fig:aktheta`), a large motion
//! along directions far softer than the antikink itself (at `theta_bar = 0.1`, n = 60 they even
//! have negative curvature at the uniform ends). The paper "fixed the boundary conditions to ensure
//! that the antikink is in mechanical equilibrium". We do the same, explicitly ([`Ends::Held`],
//! the default): the end rotors are held at `-theta_bar` and `+theta_bar`, every other rotor is in
//! exact force balance, and the ends' reaction torques are reported ([`Antikink::edge_force`]).
//! Where the tails are below rounding at the ends (`theta_bar = 0.58`, n = 60: `F'^-30 ~ 1e-35`)
//! this is the free-end equilibrium to the last digit. [`Ends::Free`] is available; it holds only
//! the near-null directions (see [`super::equilibrium`]).

use alloc::vec::Vec;

use super::classify::{Classification, EquilibriumKind, classify, rounding_tolerance};
use super::equilibrium::{NewtonOptions, RelaxOptions, newton, polish, relax};
use super::error::StaticsError;
use super::kink::reflected_kink;
use super::path::{Descent, PathPoint, descend};
use super::step_off::{MAX_STEP_OFFS, StepOff, step_off};
use super::walls::{Charge, domain_walls};
use crate::linalg::SymmetricMatrix;
use crate::model::ChainModel;
use crate::validate::{Fields, Validate};

/// How the chain's ends are treated (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Ends {
    /// The end rotors are held at `-theta_bar` and `+theta_bar`; every other rotor is in exact
    /// force balance. The default.
    #[default]
    Held,
    /// Free ends; near-null edge modes are held by the constrained Newton step instead.
    Free,
}

/// Settings of the antikink analyses.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct AntikinkOptions {
    /// Settings of the Newton polish.
    pub newton: NewtonOptions,
    /// Settings of the dissipative relaxation.
    pub relax: RelaxOptions,
    /// Relative tolerance for counting eigenvalues as zero ([`classify`]). Default `None`: the
    /// rounding error of the computation, [`rounding_tolerance`]`(n)` (`64 n eps`), so that a
    /// resolved soft curvature (the translation at small `theta_bar`) is never called zero.
    pub zero_tolerance: Option<f64>,
    /// How the chain's ends are treated. Default [`Ends::Held`].
    pub ends: Ends,
}

impl Validate for AntikinkOptions {
    type Error = StaticsError;

    /// The Newton and relaxation settings ([`NewtonOptions`]'s and [`RelaxOptions`]'s rules),
    /// `zero_tolerance` finite and `>= 0`.
    fn validate(&self) -> Result<(), StaticsError> {
        // No `..`: a field added here does not compile until it is checked.
        let Self { newton, relax, zero_tolerance, ends: _ } = *self;
        newton.validate()?;
        relax.validate()?;
        if let Some(tolerance) = zero_tolerance {
            Fields("AntikinkOptions").non_negative("zero_tolerance", tolerance)?;
        }
        Ok(())
    }
}

impl AntikinkOptions {
    fn hold(&self) -> bool {
        self.ends == Ends::Held
    }
}

/// The reflected kink centred at `centre`, with the end rotors at `-theta_bar` and `+theta_bar`
/// when the ends are held.
fn initial_guess<M: ChainModel + ?Sized>(
    model: &M,
    centre: f64,
    options: &AntikinkOptions,
) -> Result<Vec<f64>, StaticsError> {
    options.validate()?;
    let mut guess = reflected_kink(model, centre)?;
    if options.hold() {
        let n = guess.len();
        let tb = model.theta_bar();
        guess[0] = -tb;
        guess[n - 1] = tb;
    }
    Ok(guess)
}

/// A found centre farther than this (in sites) from the centring asked for is not an
/// equilibrium there: half the distance between neighbouring centrings.
pub const MOVED: f64 = 0.25;

/// An antikink equilibrium.
#[derive(Clone, Debug, PartialEq)]
pub struct Antikink {
    /// The angles, radians, one per rotor.
    pub theta: Vec<f64>,
    /// The centring asked for (an integer or a half-integer; for [`antikink_relaxed`], the
    /// centring it ended at, or the centre where the descent along the adiabatic path found the
    /// well, [`super::path`]). [`Antikink::moved`] compares it with `centre`.
    pub requested: f64,
    /// Potential energy `V`.
    pub energy: f64,
    /// The antikink's position (Appendix C wall coordinate).
    pub centre: f64,
    /// Minimum or saddle, from the tangent stiffness.
    pub classification: Classification,
    /// Newton steps of the polish.
    pub newton_iterations: usize,
    /// Dissipative-dynamics time steps (0 when not relaxed).
    pub relax_steps: usize,
    /// `max |dV/dtheta| / ||K||` at the end, near-null directions held ([`super::equilibrium`]).
    pub residual: f64,
    /// `max_i |dV/dtheta_i| / ||K||` over every rotor, the held directions and the end rotors
    /// included: the force they carry (rounding level when nothing had to be held, and equal to
    /// `residual` when nothing held carries more than the free rotors' residual).
    pub edge_force: f64,
    /// How many soft directions Newton's method held ([`super::equilibrium::Solution::held`]).
    /// With a held translation the result is the equilibrium at fixed centring, a point of the
    /// adiabatic trajectory, not a free equilibrium.
    pub held: usize,
    /// The saddles [`antikink_relaxed`] stepped off on its way, in order, each with where the
    /// descent from it went ([`super::step_off`]); empty for every other analysis.
    pub step_offs: Vec<StepOff>,
}

impl Antikink {
    fn from_solution<M: ChainModel + ?Sized>(
        model: &M,
        requested: f64,
        solution: super::equilibrium::Solution,
        relax_steps: usize,
        options: &AntikinkOptions,
    ) -> Result<Self, StaticsError> {
        let super::equilibrium::Solution { theta, iterations: newton_iterations, residual, edge_force, held } =
            solution;
        let walls = domain_walls(&theta);
        let antikinks: Vec<f64> =
            walls.iter().filter(|w| w.charge == Charge::Antikink).map(|w| w.position).collect();
        if antikinks.len() != 1 || walls.len() != 1 {
            return Err(StaticsError::DefectLost {
                expected: "antikink",
                kinks: walls.len() - antikinks.len(),
                antikinks: antikinks.len(),
            });
        }
        // With held ends the stability is that of the moving rotors.
        let k = SymmetricMatrix::tangent_stiffness(model, &theta)?;
        let k = k.principal(super::equilibrium::moving(theta.len(), options.hold()));
        let relative = options.zero_tolerance.unwrap_or_else(|| rounding_tolerance(k.dim()));
        let classification = classify(&k, relative)?;
        Ok(Self {
            energy: model.energy(&theta),
            requested,
            centre: antikinks[0],
            theta,
            classification,
            newton_iterations,
            relax_steps,
            residual,
            edge_force,
            held,
            step_offs: Vec::new(),
        })
    }

    /// Whether the tangent stiffness shows a saddle.
    pub fn is_saddle(&self) -> bool {
        matches!(self.classification.kind, EquilibriumKind::Saddle { .. })
    }

    /// Whether the antikink found is centred more than [`MOVED`] from the centring asked for:
    /// there is no equilibrium at that centring.
    pub fn moved(&self) -> bool {
        let distance = (self.centre - self.requested).abs();
        distance.is_nan() || distance > MOVED
    }

    /// A free equilibrium (nothing held) at the centring asked for.
    pub fn is_free(&self) -> bool {
        self.held == 0 && !self.moved()
    }

    /// A Peierls-Nabarro minimum: a free equilibrium of Morse index 0.
    pub fn is_free_minimum(&self) -> bool {
        self.is_free() && self.classification.index == 0
    }
}

/// The antikink equilibrium centred at `centre` (an integer: on a rotor; a half-integer: on a
/// spring), by Newton's method from the symmetric reflected kink, polished to rounding
/// ([`polish`]). Minimum or saddle, as the classification says. Where the translation had to be
/// held (`held > 0`: the ends' pull on a wide antikink beats the Peierls-Nabarro force there) the
/// result is the equilibrium at fixed centring, a point of the adiabatic trajectory, with
/// `edge_force` the force that takes. Any other centre is an error (`InvalidValue`): no
/// equilibrium sits between the two centrings.
///
/// # Errors
/// [`StaticsError::NotAnEquilibrium`] when the antikink found is centred more than [`MOVED`] from
/// `centre` (requested and found centre, index and held directions): no equilibrium there, as
/// next to an impurity whose force beats the Peierls-Nabarro pinning
/// ([`peierls_nabarro`]'s landscape lists the equilibria near it).
pub fn antikink_at<M: ChainModel + ?Sized>(
    model: &M,
    centre: f64,
    options: &AntikinkOptions,
) -> Result<Antikink, StaticsError> {
    let found = solve_centring(model, centre, options)?;
    if found.moved() {
        return Err(StaticsError::NotAnEquilibrium {
            requested: centre,
            found: found.centre,
            index: found.classification.index,
            held: found.held,
        });
    }
    Ok(found)
}

/// [`antikink_at`] without the check that the antikink stayed at `centre` (the landscape scan
/// records where it went).
pub(crate) fn solve_centring<M: ChainModel + ?Sized>(
    model: &M,
    centre: f64,
    options: &AntikinkOptions,
) -> Result<Antikink, StaticsError> {
    if centre.is_finite() && 2.0 * centre != libm::round(2.0 * centre) {
        return Err(StaticsError::InvalidValue {
            what: "centre",
            value: centre,
            expected: "an integer (rotor-centred) or a half-integer (spring-centred) rotor index",
        });
    }
    let guess = initial_guess(model, centre, options)?;
    let newton_options = NewtonOptions { hold_ends: options.hold(), ..options.newton };
    let solution = polish(model, newton(model, &guess, &newton_options)?, &newton_options)?;
    Antikink::from_solution(model, centre, solution, 0, options)
}

/// The paper's construction: the reflected kink centred at `centre`, relaxed by dissipative
/// Newtonian dynamics, then polished by Newton's method; the result is a Peierls-Nabarro
/// **minimum** (a free equilibrium of Morse index 0), or an error that says what was found.
///
/// The relaxation slides the antikink into a minimum only where the Peierls-Nabarro force beats
/// the relaxation's tolerance (measured: `theta_bar >= 0.45` at n = 60); a wider antikink, or one
/// started on a saddle, stops where it is, and the polish then returns the saddle or a
/// fixed-centring point. From there the antikink descends its adiabatic path
/// ([`super::path::descend`]: its lowest energy with the centre held, at any centre, not only the
/// centrings) anywhere between the held end rotors, to where `dE/dc` changes sign, and a free Newton
/// polish from that point gives the equilibrium, classified by the Sturm count of its tangent
/// stiffness. In a uniform chain that is the neighbouring centring; next to an impurity the well
/// lies between the centrings (n = 40, `theta_bar = 0.4`, the middle spring at `2k`, from 15: at
/// 13.9714, where no centring is an equilibrium, docs/statics.md "Chains that are not uniform").
/// Where the path ends on a slope (one more step would nucleate a kink-antikink pair at a soft
/// impurity ahead) the relaxation is run again from its last point.
///
/// Where that equilibrium is a free saddle (the path's stationary point with a direction across
/// the path unstable) the search steps off it along its unstable eigenvector, both ways, by damped
/// relaxation ([`super::step_off`], which says why), follows each side down as above and keeps
/// the side that ends at a free minimum (the lower if both do); at most
/// [`super::step_off::MAX_STEP_OFFS`] times. Each saddle left and where its descent went are in
/// [`Antikink::step_offs`].
///
/// With [`Ends::Free`] there is no descent: the near-null edge modes of the two domains are held
/// and counted in the index, so the lower of the two centrings next to where the relaxation
/// stopped is returned as it is.
///
/// # Errors
/// [`StaticsError::DescentLeftRegion`] when the energy still falls next to a held end rotor
/// (centre 1 or `n - 2`: the start, the region, the centre reached, its energy and slope: where
/// the antikink went);
/// [`StaticsError::NoMinimum`] when the equilibrium at the bottom is not a free minimum (never a
/// saddle called a minimum: a saddle that neither side of a step-off leaves, or the last after
/// [`super::step_off::MAX_STEP_OFFS`] step-offs), with its centre, index and held directions; the
/// errors of the relaxation, of the path and of Newton's method (a step-off whose both sides fail:
/// the first side's error, as an antikink lost or a descent that left its region).
/// # Example
///
/// ```
/// use rotor_chain::RuntimeChain;
/// use rotor_chain::statics::antikink::{AntikinkOptions, antikink_relaxed};
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let chain = RuntimeChain::builder(60, 0.8, 1.0e4, 0.58).build()?;
/// let antikink = antikink_relaxed(&chain, 29.5, &AntikinkOptions::default())?; // starts on the saddle
/// assert!(antikink.is_free_minimum());
/// assert!((antikink.centre - antikink.centre.round()).abs() < 1e-9); // ends rotor-centred
/// # Ok(())
/// # }
/// ```
pub fn antikink_relaxed<M: ChainModel + ?Sized>(
    model: &M,
    centre: f64,
    options: &AntikinkOptions,
) -> Result<Antikink, StaticsError> {
    // With free ends the domains' edge modes are held and enter the index (at `theta_bar = 0.5`
    // they can be slightly negative), so "a free minimum" is not defined: the lower centring is
    // returned, as its `held` and classification say.
    if options.ends == Ends::Free {
        return relaxed_nearest(model, centre, options);
    }
    let start = relaxed_polished(model, centre, options)?;
    if start.is_free_minimum() {
        return Ok(start);
    }
    let mut found = descend_polished(model, &start.theta, start.relax_steps, options)?;
    // A descent that stops at a saddle steps off it along its unstable direction, both ways
    // (`super::step_off`); each step-off ends lower than the saddle, so the search cannot cycle.
    let mut step_offs = Vec::new();
    while found.held == 0 && found.classification.index >= 1 && step_offs.len() < MAX_STEP_OFFS {
        let (next, record) = leave_saddle(model, &found, options)?;
        step_offs.push(record);
        found = next;
        if found.is_free_minimum() {
            break;
        }
    }
    if found.is_free_minimum() {
        found.step_offs = step_offs;
        return Ok(found);
    }
    Err(StaticsError::NoMinimum {
        near: centre,
        found: found.centre,
        index: found.classification.index,
        held: found.held,
    })
}

/// The free Newton options of the descent: with the ends held and nothing held that the
/// classification resolves (the translation at `theta_bar = 0.2`, n = 60, is `6e-11 ||K||`,
/// below Newton's default null tolerance but far above rounding).
fn free_newton<M: ChainModel + ?Sized>(model: &M, options: &AntikinkOptions) -> NewtonOptions {
    let n = model.rotor_count();
    let resolved = options.zero_tolerance.unwrap_or_else(|| rounding_tolerance(n.saturating_sub(2)));
    NewtonOptions { hold_ends: true, null_tolerance: resolved, ..options.newton }
}

/// The descent of [`antikink_relaxed`] from `theta` (one antikink, at or next to an equilibrium):
/// the adiabatic path to the bottom of its well (or, where the path ends on a slope, the
/// relaxation from its last point), polished by free Newton and classified. `relax_steps` are the
/// time steps already taken.
fn descend_polished<M: ChainModel + ?Sized>(
    model: &M,
    theta: &[f64],
    relax_steps: usize,
    options: &AntikinkOptions,
) -> Result<Antikink, StaticsError> {
    let n = model.rotor_count();
    match descend(model, theta, n as f64, options)? {
        Descent::Bottom(bottom) => {
            let mut found = polished_on_path(model, bottom, options)?;
            found.relax_steps = relax_steps;
            Ok(found)
        }
        // The path ends on a slope (a pair would nucleate at a soft impurity ahead): the paper's
        // relaxation from its last point slides on down.
        Descent::End(last) => {
            let (relaxed, steps) =
                relax(model, &last.theta, &RelaxOptions { hold_ends: true, ..options.relax })?;
            let free = free_newton(model, options);
            let solution = polish(model, newton(model, &relaxed, &free)?, &free)?;
            let mut found = Antikink::from_solution(model, f64::NAN, solution, relax_steps + steps, options)?;
            found.requested = found.centre;
            Ok(found)
        }
    }
}

/// The free equilibrium at the bottom (or top) of a well of the adiabatic path, `point` (where
/// `dE/dc` vanishes, [`super::path::refine`]): polished by free Newton and classified by the Sturm
/// count of its tangent stiffness, with `point.centre` as the centre it was found at
/// (`requested`).
pub(crate) fn polished_on_path<M: ChainModel + ?Sized>(
    model: &M,
    point: PathPoint,
    options: &AntikinkOptions,
) -> Result<Antikink, StaticsError> {
    let free = free_newton(model, options);
    let solution = polish(model, newton(model, &point.theta, &free)?, &free)?;
    Antikink::from_solution(model, point.centre, solution, 0, options)
}

/// A point of the adiabatic path as an [`Antikink`] at its centre with the centre held
/// (`held = 1`, `residual` the force left in the directions that keep the centre, `edge_force`
/// the whole force, the centre's included), classified by its tangent stiffness as
/// [`antikink_at`]'s fixed-centring points are.
pub(crate) fn on_path<M: ChainModel + ?Sized>(
    model: &M,
    point: PathPoint,
    options: &AntikinkOptions,
) -> Result<Antikink, StaticsError> {
    let k = SymmetricMatrix::tangent_stiffness(model, &point.theta)?;
    let scale = k.inf_norm().max(f64::MIN_POSITIVE);
    let mut g = alloc::vec![0.0; point.theta.len()];
    model.gradient_into(&point.theta, &mut g);
    let edge_force =
        g.iter().fold(0.0f64, |m, x| if x.is_nan() || m.is_nan() { f64::NAN } else { m.max(x.abs()) });
    let solution = super::equilibrium::Solution {
        theta: point.theta,
        iterations: point.iterations,
        residual: point.residual,
        edge_force: edge_force / scale,
        held: 1,
    };
    Antikink::from_solution(model, point.centre, solution, 0, options)
}

/// Steps off the free saddle `saddle` both ways ([`super::step_off`]) and follows each side down:
/// free Newton from the relaxed configuration, and where that is not a free minimum the descent
/// of [`descend_polished`]. Keeps the side that ends at a free minimum, the lower if both do
/// (else the lower end); a side that comes back to the saddle (its centre within `1e-6` sites
/// and not lower) or fails is dropped.
///
/// # Errors
/// When neither side leaves the saddle: the first side's error, or [`StaticsError::NoMinimum`]
/// at the saddle.
fn leave_saddle<M: ChainModel + ?Sized>(
    model: &M,
    saddle: &Antikink,
    options: &AntikinkOptions,
) -> Result<(Antikink, StepOff), StaticsError> {
    let free = free_newton(model, options);
    let mut best: Option<(Antikink, StepOff)> = None;
    let mut first_error = None;
    for sign in [1.0, -1.0] {
        let side = step_off(model, saddle, sign, options).and_then(|(relaxed, steps, curvature, step)| {
            let steps = saddle.relax_steps + steps;
            let solution = polish(model, newton(model, &relaxed, &free)?, &free)?;
            let mut end = Antikink::from_solution(model, f64::NAN, solution, steps, options)?;
            end.requested = end.centre;
            if !end.is_free_minimum() {
                end = descend_polished(model, &end.theta, steps, options)?;
            }
            Ok((end, curvature, step))
        });
        let (end, curvature, step) = match side {
            Ok(side) => side,
            Err(e) => {
                first_error.get_or_insert(e);
                continue;
            }
        };
        if (end.centre - saddle.centre).abs() <= 1e-6 && end.energy >= saddle.energy {
            continue;
        }
        let record = StepOff {
            saddle: saddle.centre,
            theta: saddle.theta.clone(),
            saddle_energy: saddle.energy,
            index: saddle.classification.index,
            curvature,
            step,
            reached: end.centre,
            energy: end.energy,
        };
        let better = match &best {
            None => true,
            Some((b, _)) => (end.is_free_minimum(), -end.energy) > (b.is_free_minimum(), -b.energy),
        };
        if better {
            best = Some((end, record));
        }
    }
    best.ok_or_else(|| {
        first_error.unwrap_or(StaticsError::NoMinimum {
            near: saddle.centre,
            found: saddle.centre,
            index: saddle.classification.index,
            held: saddle.held,
        })
    })
}

/// The paper's relaxation of the reflected kink centred at `centre`, polished by Newton's method,
/// with the centring it reached as `requested`.
fn relaxed_polished<M: ChainModel + ?Sized>(
    model: &M,
    centre: f64,
    options: &AntikinkOptions,
) -> Result<Antikink, StaticsError> {
    let guess = initial_guess(model, centre, options)?;
    let (relaxed, steps) =
        relax(model, &guess, &RelaxOptions { hold_ends: options.hold(), ..options.relax })?;
    let newton_options = NewtonOptions { hold_ends: options.hold(), ..options.newton };
    let solution = polish(model, newton(model, &relaxed, &newton_options)?, &newton_options)?;
    let mut polished = Antikink::from_solution(model, f64::NAN, solution, steps, options)?;
    // What the relaxation reached is its own centring.
    polished.requested = libm::round(2.0 * polished.centre) / 2.0;
    Ok(polished)
}

/// The relaxation and polish of [`antikink_relaxed`], and where that is not a free minimum the
/// lower of the two centrings next to it, whatever it is: the launches' static antikink
/// (`dynamics::launch`), which near an end may be a fixed-centring point or a saddle, as `held`
/// and the classification say (docs/dynamics.md §2).
pub(crate) fn relaxed_nearest<M: ChainModel + ?Sized>(
    model: &M,
    centre: f64,
    options: &AntikinkOptions,
) -> Result<Antikink, StaticsError> {
    let polished = relaxed_polished(model, centre, options)?;
    let steps = polished.relax_steps;
    if polished.classification.index == 0 && polished.is_free() {
        return Ok(polished);
    }
    let n = model.rotor_count() as f64;
    let rotor = libm::round(polished.centre).clamp(1.0, (n - 2.0).max(1.0));
    let spring = if polished.centre >= rotor { rotor + 0.5 } else { rotor - 0.5 };
    let (a, b) = (solve_centring(model, rotor, options)?, solve_centring(model, spring, options)?);
    let mut best = if a.energy <= b.energy { a } else { b };
    best.relax_steps = steps;
    Ok(best)
}

/// The antikink near a requested place: the two centrings there and, on a chain with impurities
/// or where those two are not a minimum and a saddle, the landscape around them
/// ([`super::landscape`]).
#[derive(Clone, Debug, PartialEq)]
pub struct PeierlsNabarro {
    /// The antikink solved at the rotor centring (`(n - 1) / 2` rounded down for
    /// [`peierls_nabarro`]); it may have moved (`moved()`): no equilibrium there. Where the
    /// symmetric guess there splits into a pair (next to a stiff impurity), the free equilibrium
    /// the adiabatic path descends to from that centring, `requested` the centring.
    pub rotor_centred: Antikink,
    /// The antikink solved at the neighbouring spring centring.
    pub spring_centred: Antikink,
    /// The Peierls-Nabarro barrier `V_saddle - V_minimum` (`|V_rotor - V_spring|`), meaningful
    /// when `resolved`.
    pub barrier: f64,
    /// Whether the two centrings stayed where they were asked for (neither `moved()`), exactly
    /// one a minimum (index 0) and one a saddle (index 1). For very wide antikinks the barrier is below
    /// what double precision resolves and both may look alike; the barrier is then an upper
    /// estimate. On a chain with impurities the two centrings may not be equilibria at all.
    pub resolved: bool,
    /// The landscape within [`super::landscape::LANDSCAPE_REACH`] sites of the requested place
    /// ([`super::landscape::scan`]), in order of centre: on a chain with impurities every
    /// centring as the point of the adiabatic path there (`held = 1`) and every free equilibrium
    /// of the path ([`Antikink::is_free`]) with its Morse index, on or between the centrings; on
    /// a uniform chain every centring solved at fixed centring. Only the two centrings when the
    /// chain is uniform and they are `resolved`.
    pub landscape: Vec<Antikink>,
    /// The pinning (negative) or repulsion (positive) energy of each impurity spring within the
    /// landscape ([`super::landscape::ImpurityEnergy`]).
    pub impurities: Vec<super::landscape::ImpurityEnergy>,
}

impl PeierlsNabarro {
    /// The Peierls-Nabarro minimum at the requested place: of the two centrings, those with Morse
    /// index 0 that stayed where they were asked for, the lower (with `held > 0`, at small
    /// `theta_bar` in a short chain, it is the minimum at fixed centring, as `held` says; where the
    /// held ends confine a very wide antikink, both centrings slide to the middle and the one
    /// that is there is the minimum).
    ///
    /// # Errors
    /// [`StaticsError::NoMinimum`] when neither is (a saddle, a held point, an antikink that moved
    /// away, as next to a stiff impurity): the landscape lists the minima nearby.
    pub fn minimum(&self) -> Result<&Antikink, StaticsError> {
        self.pair()
            .filter(|a| a.classification.index == 0 && !a.moved())
            .min_by(|a, b| a.energy.total_cmp(&b.energy))
            .ok_or_else(|| self.no(self.lower()))
    }

    /// The saddle at the requested place: of the two centrings, those of index at least 1 that
    /// stayed where they were asked for, the higher.
    ///
    /// # Errors
    /// [`StaticsError::NotAnEquilibrium`] otherwise (the higher centring, where the antikink went,
    /// its index and held directions).
    pub fn saddle(&self) -> Result<&Antikink, StaticsError> {
        self.pair()
            .filter(|a| a.classification.index >= 1 && !a.moved())
            .max_by(|a, b| a.energy.total_cmp(&b.energy))
            .ok_or_else(|| {
                let higher = if core::ptr::eq(self.lower(), &self.rotor_centred) {
                    &self.spring_centred
                } else {
                    &self.rotor_centred
                };
                StaticsError::NotAnEquilibrium {
                    requested: higher.requested,
                    found: higher.centre,
                    index: higher.classification.index,
                    held: higher.held,
                }
            })
    }

    fn pair(&self) -> impl Iterator<Item = &Antikink> {
        [&self.rotor_centred, &self.spring_centred].into_iter()
    }

    /// The free minima of the landscape (index 0, nothing held, not moved).
    pub fn minima(&self) -> impl Iterator<Item = &Antikink> {
        self.landscape.iter().filter(|a| a.is_free_minimum())
    }

    /// The free saddles of the landscape (index at least 1, nothing held, not moved).
    pub fn saddles(&self) -> impl Iterator<Item = &Antikink> {
        self.landscape.iter().filter(|a| a.is_free() && a.classification.index >= 1)
    }

    fn lower(&self) -> &Antikink {
        if self.rotor_centred.energy <= self.spring_centred.energy {
            &self.rotor_centred
        } else {
            &self.spring_centred
        }
    }

    fn no(&self, found: &Antikink) -> StaticsError {
        StaticsError::NoMinimum {
            near: self.rotor_centred.requested,
            found: found.centre,
            index: found.classification.index,
            held: found.held,
        }
    }
}

/// The fewest rotors [`peierls_nabarro`] accepts: the spring-centred antikink at `m + 1/2`
/// (`m = (n - 1) / 2`) needs rotors `m - 1` to `m + 2`, a rotor beyond its two core rotors on
/// each side; on 3 rotors both centrings relax to the same state and the "barrier" would be 0.
pub const PEIERLS_NABARRO_MIN_ROTORS: usize = 4;

/// The Peierls-Nabarro barrier of `model` (paper Sec. V): the antikink centred on the middle
/// rotor and on the neighbouring spring, and their energy difference; on a chain with impurities
/// (or where those two are not a minimum and a saddle) also the landscape around them and the
/// impurities' pinning or repulsion energies ([`peierls_nabarro_near`]).
/// # Example
///
/// ```
/// use rotor_chain::prelude::*;
/// use rotor_chain::statics::antikink::{AntikinkOptions, peierls_nabarro};
///
/// #[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
/// pub struct Chain;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let pn = peierls_nabarro(&Chain, &AntikinkOptions::default())?;
/// assert!(pn.resolved);
/// assert_eq!(pn.minimum()?.classification.index, 0);  // rotor-centred: the minimum
/// assert_eq!(pn.saddle()?.classification.index, 1);   // spring-centred: the saddle
/// assert!((pn.barrier - (pn.saddle()?.energy - pn.minimum()?.energy)).abs() < 1e-12);
/// # Ok(())
/// # }
/// ```
pub fn peierls_nabarro<M: ChainModel + ?Sized>(
    model: &M,
    options: &AntikinkOptions,
) -> Result<PeierlsNabarro, StaticsError> {
    let n = model.rotor_count();
    if n < PEIERLS_NABARRO_MIN_ROTORS {
        return Err(StaticsError::InvalidValue {
            what: "the rotor count of a chain for the Peierls-Nabarro barrier",
            value: n as f64,
            expected: "at least 4: a rotor beyond the core on each side of both centrings (n = 3 has one \
                       antikink state, so no barrier)",
        });
    }
    peierls_nabarro_near(model, ((n - 1) / 2) as f64, options)
}

/// [`peierls_nabarro`] at the rotor centring `rotor` (an integer) and the spring to its right.
///
/// On a chain with impurities the landscape comes from the adiabatic path
/// ([`super::landscape::scan`]), and a centring whose symmetric guess splits into a kink-antikink
/// pair (n = 40, spring 19 at `5k`, `theta_bar = 0.4`: both middle centrings) is reported as
/// where the path descends from it ([`PeierlsNabarro::rotor_centred`]): there the minima nearest
/// the impurity are at 13.956134 and 25.043866, the path ends 0.94 sites short of the impurity's
/// centring (at 18.561142, a pair nucleates one step on), and the repulsion measured there is
/// 171.90 (docs/statics.md "Chains that are not uniform").
///
/// # Errors
/// `rotor` not an integer in `[1, n - 3]`; the errors of [`antikink_at`] other than
/// [`StaticsError::NotAnEquilibrium`] (a centring that moved is part of the landscape) and, on a
/// chain with impurities, other than [`StaticsError::DefectLost`] where the path reaches or passes
/// near the centring; those of [`super::landscape::scan`].
pub fn peierls_nabarro_near<M: ChainModel + ?Sized>(
    model: &M,
    rotor: f64,
    options: &AntikinkOptions,
) -> Result<PeierlsNabarro, StaticsError> {
    let n = model.rotor_count();
    let max = n.saturating_sub(3).max(1) as f64;
    if !(rotor >= 1.0 && rotor <= max && rotor == libm::round(rotor)) {
        return Err(StaticsError::InvalidValue {
            what: "rotor",
            value: rotor,
            expected: "an integer rotor index in [1, n - 3]",
        });
    }
    let impurity_springs = super::landscape::impurity_springs(model);
    // Next to a stiff impurity the symmetric guess splits into a kink-antikink pair (5k, n = 40,
    // theta_bar = 0.4 to 0.6): that centring is then filled in from the path below.
    let centring = |c: f64| match solve_centring(model, c, options) {
        Err(lost @ StaticsError::DefectLost { .. }) if !impurity_springs.is_empty() => Ok(Err(lost)),
        other => other.map(Ok),
    };
    let (rotor_centred, spring_centred) = (centring(rotor)?, centring(rotor + 0.5)?);
    let resolved = match (&rotor_centred, &spring_centred) {
        (Ok(r), Ok(s)) => {
            let (a, b) = (r.classification.index, s.classification.index);
            !r.moved() && !s.moved() && ((a == 0 && b == 1) || (a == 1 && b == 0))
        }
        _ => false,
    };
    let (landscape, impurities, path) = match (&rotor_centred, &spring_centred) {
        (Ok(r), Ok(s)) if resolved && impurity_springs.is_empty() => {
            (alloc::vec![r.clone(), s.clone()], Vec::new(), None)
        }
        _ => super::landscape::scan_with_path(model, rotor + 0.25, &impurity_springs, options)?,
    };
    // A lost centring is kept only on a chain with impurities, which is scanned; where the path
    // did not reach it, the loss is the error.
    let fill = |found: Result<Antikink, StaticsError>, c: f64| match (found, &path) {
        (Ok(a), _) => Ok(a),
        (Err(lost), Some(path)) => went_along_path(model, path, c, options)?.ok_or(lost),
        (Err(lost), None) => Err(lost),
    };
    let (rotor_centred, spring_centred) = (fill(rotor_centred, rotor)?, fill(spring_centred, rotor + 0.5)?);
    let barrier = (rotor_centred.energy - spring_centred.energy).abs();
    Ok(PeierlsNabarro { rotor_centred, spring_centred, barrier, resolved, landscape, impurities })
}

/// Where the antikink held at the centring `c` goes along the path `path`: from the path point at
/// `c` (or, where the path ends before `c`, as next to a stiff impurity, the one nearest it) the
/// first free equilibrium downhill (the side `dE/dc` falls toward), with `c` as `requested`, so
/// [`Antikink::moved`] says that no equilibrium is at `c`; that path point itself when it is one
/// (`dE/dc = 0`) or when no equilibrium lies downhill in the window; `None` without a path.
fn went_along_path<M: ChainModel + ?Sized>(
    model: &M,
    path: &super::path_scan::PathScan,
    c: f64,
    options: &AntikinkOptions,
) -> Result<Option<Antikink>, StaticsError> {
    let Some(at) = path.at(c).or_else(|| path.nearest(c)) else {
        return Ok(None);
    };
    let c_at = at.centre;
    let downhill = path.equilibria.iter().filter(|e| (e.centre - c_at) * -at.slope > 0.0);
    let mut went = if at.slope > 0.0 {
        downhill.max_by(|a, b| a.centre.total_cmp(&b.centre))
    } else {
        downhill.min_by(|a, b| a.centre.total_cmp(&b.centre))
    }
    .cloned()
    .map_or_else(|| on_path(model, at.clone(), options), Ok)?;
    went.requested = c;
    Ok(Some(went))
}

/// The finite-size study of the barrier (Fig. `fig:logvpn-size`): the barrier of the chain that
/// `build(n)` returns, for every `n` in `sizes`.
pub fn barrier_vs_size<M: ChainModel>(
    sizes: &[usize],
    build: impl Fn(usize) -> Result<M, crate::error::ParameterError>,
    options: &AntikinkOptions,
) -> Result<Vec<(usize, f64)>, StaticsError> {
    sizes.iter().map(|&n| peierls_nabarro(&build(n)?, options).map(|pn| (n, pn.barrier))).collect()
}
