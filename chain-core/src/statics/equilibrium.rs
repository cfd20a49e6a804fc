//! Finding equilibria `dV/dtheta = 0`: dissipative Newtonian dynamics (the paper's relaxation,
//! Sec. II) and a Newton polish on the gradient.
//!
//! Both work on any model with a tangent stiffness ([`Stiffness`]): a rotor chain, or a model of
//! your own. "The ends" are the first and the last degree of freedom (a chain's end rotors).
//!
//! **Newton's method** converges to the equilibrium nearest its starting point whatever its
//! index, so it finds saddles (the Peierls-Nabarro maximum) as well as minima. Each step solves
//! `(K + mu I) delta = -g` with the tangent stiffness `K` by Gaussian elimination with partial
//! pivoting (`K` is indefinite at a saddle): in O(n) for a chain's tridiagonal `K`
//! ([`SymmetricMatrix`]).
//!
//! **Near-null modes (constrained Newton).** A free chain always has a mechanism
//! (Maxwell-Calladine: n rotors, n - 1 springs), and around an antikink the two uniform domains
//! carry exponentially soft edge modes. When the antikink's tails still reach the free ends (wide
//! antikinks, small `theta_bar`), exact force balance would swing the end rotors round until they
//! are collinear with their springs (the paper's "overshooting", Sec. II), a finite motion along
//! a direction whose stiffness is below rounding. We do not follow those directions: each step
//! works in the complement of the eigenvectors whose eigenvalues lie within
//! `null_tolerance * ||K||` of zero (found in O(n) by bisection and inverse iteration), and
//! convergence is judged on the force in that complement. The force left along the near-null
//! modes is reported separately ([`Solution::edge_force`]); it is the tail tension reaching the
//! ends, `~ e^{-d / decay length}` for an antikink at distance `d` from them. This is our
//! boundary treatment: the ends are held along their soft modes, the rest of the chain is in
//! exact force balance. A symmetric starting guess has no component along the (antisymmetric)
//! translation mode, so projecting it out when it too is near-null changes nothing.
//!
//! **Constrained equilibria.** Where an off-centre defect feels a pull from the ends larger than
//! its own restoring force (a wide antikink in a short chain), no exact equilibrium exists at that
//! centring; the iteration then stagnates, and the softest free direction (the translation) is
//! held as well. The result is the equilibrium at fixed centring, a point on the adiabatic
//! trajectory of paper Sec. V, and [`Solution::held`] and [`Solution::edge_force`] say so.
//!
//! The tiny shift `mu = 1e-13 ||K||` keeps the linear solve regular, and a backtracking line
//! search on the projected force makes the iteration globally convergent from a reasonable guess.
//!
//! **Dissipative dynamics** integrates `I theta'' = -dV/dtheta - gamma I theta'` (velocity Verlet,
//! `I = M r_i^2`) until the forces are small: it slides a configuration to a nearby *minimum*,
//! which is what the paper does to the reflected kink to get a stable antikink.

use alloc::vec;
use alloc::vec::Vec;

use super::error::StaticsError;
use super::validate;
use crate::integrate::bound::omega_bound;
use crate::integrate::{MAX_STEP_BUDGET, State, Verlet};
use crate::linalg::SymmetricMatrix;
use crate::model::Stiffness;
use crate::validate::{Fields, Validate};

/// Settings of [`newton`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonOptions {
    /// Stop when `max_i |dV/dtheta_i| <= tolerance * ||K||`, i.e. when the next step would move
    /// the angles by about `tolerance` radians. Default `1e-11`.
    pub tolerance: f64,
    /// Give up after this many steps. Default 60 (quadratic convergence needs a handful).
    /// Between 0 (only the start's residual is measured) and [`NewtonOptions::MAX_ITERATIONS`].
    pub max_iterations: usize,
    /// Relative shift `mu / ||K||` of the Newton matrix. Default `1e-13` (see the module doc).
    pub shift: f64,
    /// Eigenvalues within `null_tolerance * ||K||` of zero span the near-null directions that the
    /// steps leave alone (see the module doc). Default `1e-9`.
    pub null_tolerance: f64,
    /// Hold the two end rotors where they are (Dirichlet ends): only the interior is brought into
    /// force balance, and the ends' reaction torques are reported as [`Solution::edge_force`].
    /// Default `false` (free ends).
    pub hold_ends: bool,
    /// At most this many directions are held when the iteration stagnates (see the module doc).
    /// Default 3: the two edge modes and a translation. Between 0 (none held) and
    /// [`NewtonOptions::MAX_ITERATIONS`]: the held set grows by at most one direction per step,
    /// so no iteration could hold more.
    pub max_held: usize,
}

impl NewtonOptions {
    /// The most steps [`newton`] may be given: 1000. Within its basin Newton's method doubles the
    /// correct digits at every step (quadratic convergence), so ten steps take any residual
    /// below 1 to rounding; the default 60 leaves room for the damped steps of the line search
    /// far from the solution. An iteration that has not converged after a few hundred steps is
    /// not converging, and more steps only make a stagnating run longer.
    pub const MAX_ITERATIONS: usize = 1000;
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-11,
            max_iterations: 60,
            shift: 1e-13,
            null_tolerance: 1e-9,
            hold_ends: false,
            max_held: 3,
        }
    }
}

/// Settings of [`relax`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RelaxOptions {
    /// Stop when `max_i |dV/dtheta_i| <= tolerance * ||K||`. Default `1e-4`: close enough for
    /// Newton to take over.
    pub tolerance: f64,
    /// Give up after this many time steps. Default 20000. Between 0 (the start is returned if it
    /// already meets the tolerance) and [`MAX_STEP_BUDGET`] (10^10): the steps are the damped
    /// velocity Verlet's, bounded as every integrator's.
    pub max_steps: usize,
    /// Time step as a fraction of `1 / omega_max`. Default 0.3 (velocity Verlet is stable below 2).
    pub time_step: f64,
    /// Damping rate `gamma` as a fraction of `omega_max`. Default 0.02, light enough for the soft
    /// translation mode to move, heavy enough to kill phonons in a few hundred steps.
    pub damping: f64,
    /// Hold the two end rotors still (as [`NewtonOptions::hold_ends`]). Default `false`.
    pub hold_ends: bool,
}

impl Default for RelaxOptions {
    fn default() -> Self {
        Self { tolerance: 1e-4, max_steps: 20_000, time_step: 0.3, damping: 0.02, hold_ends: false }
    }
}

/// An equilibrium found by [`newton`].
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// The angles found, radians.
    pub theta: Vec<f64>,
    /// Newton steps taken.
    pub iterations: usize,
    /// `max_i |(P dV/dtheta)_i| / ||K||` at the end, `P` projecting out the near-null modes.
    pub residual: f64,
    /// `max_i |dV/dtheta_i| / ||K||` including the held directions and end rotors: the force
    /// they carry (rounding level when nothing had to be held).
    pub edge_force: f64,
    /// How many soft directions were held (near-null edge modes, a stagnating translation).
    pub held: usize,
}

/// The rotors that move: all of them, or all but the two ends.
pub(crate) fn moving(n: usize, hold_ends: bool) -> core::ops::Range<usize> {
    if hold_ends && n > 2 { 1..n - 1 } else { 0..n }
}

/// `max(a, b)`, but NaN if either is: `f64::max` drops a NaN, which would turn a NaN force into
/// a zero residual.
fn nan_max(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() { f64::NAN } else { a.max(b) }
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| nan_max(m, x.abs()))
}

impl Validate for NewtonOptions {
    type Error = StaticsError;

    /// `tolerance > 0`, `shift >= 0`, `null_tolerance >= 0`, all finite; the counts between 0
    /// and [`NewtonOptions::MAX_ITERATIONS`]: `max_iterations = 0` only measures the start's
    /// residual, `max_held = 0` holds nothing.
    fn validate(&self) -> Result<(), StaticsError> {
        // No `..`: a field added here does not compile until it is checked.
        let Self { tolerance, max_iterations, shift, null_tolerance, hold_ends: _, max_held } = *self;
        let fields = Fields("NewtonOptions");
        fields.positive("tolerance", tolerance)?;
        let most = Self::MAX_ITERATIONS as u64;
        fields.count_in(
            "max_iterations",
            max_iterations as u64,
            0,
            most,
            "between 0 (the start's residual only) and MAX_ITERATIONS = 1000 (quadratic convergence needs a handful)",
        )?;
        fields.count_in(
            "max_held",
            max_held as u64,
            0,
            most,
            "between 0 and MAX_ITERATIONS = 1000 (one more direction is held per step at most)",
        )?;
        fields.non_negative("shift", shift)?;
        fields.non_negative("null_tolerance", null_tolerance)?;
        Ok(())
    }
}

impl Validate for RelaxOptions {
    type Error = StaticsError;

    /// `tolerance > 0`, `0 < time_step < 2` (velocity Verlet's stability limit, in `1 /
    /// omega_max`), `damping >= 0`, all finite; `max_steps` between 0 (the start is returned if
    /// it already meets the tolerance) and [`MAX_STEP_BUDGET`].
    fn validate(&self) -> Result<(), StaticsError> {
        // No `..`: a field added here does not compile until it is checked.
        let Self { tolerance, max_steps, time_step, damping, hold_ends: _ } = *self;
        let fields = Fields("RelaxOptions");
        fields.positive("tolerance", tolerance)?;
        fields.count_in(
            "max_steps",
            max_steps as u64,
            0,
            MAX_STEP_BUDGET,
            "between 0 and MAX_STEP_BUDGET = 10000000000 steps (every integrator's bound)",
        )?;
        fields.rule(
            "time_step",
            time_step,
            time_step > 0.0 && time_step < 2.0,
            "in (0, 2): velocity Verlet is stable below 2 / omega_max",
        )?;
        fields.non_negative("damping", damping)?;
        Ok(())
    }
}

/// A residual that is NaN (the model's forces or stiffness are not finite at the iterate) stops
/// the iteration with an error instead of ending the loop as if it had converged.
fn finite_residual(
    method: &'static str,
    iterations: usize,
    residual: f64,
    tolerance: f64,
) -> Result<f64, StaticsError> {
    if residual.is_nan() {
        Err(StaticsError::NoConvergence { method, iterations, residual, tolerance })
    } else {
        Ok(residual)
    }
}

/// How many eigenvalues of `K` lie within `tolerance` of zero.
fn near_null_count(k: &SymmetricMatrix, tolerance: f64) -> Result<usize, StaticsError> {
    Ok(k.count_below(tolerance)? - k.count_below(-tolerance)?)
}

/// The eigenvectors of the `count` eigenvalues of `K` nearest zero (orthonormal).
fn nearest_to_zero(k: &SymmetricMatrix, count: usize) -> Result<Vec<Vec<f64>>, StaticsError> {
    if count == 0 {
        return Ok(Vec::new());
    }
    Ok(k.eigenpairs_near(0.0, count)?.into_iter().map(|p| p.vector).collect())
}

/// The eigenvectors of `K` with eigenvalues within `tolerance` of zero (orthonormal).
fn near_null(k: &SymmetricMatrix, tolerance: f64) -> Result<Vec<Vec<f64>>, StaticsError> {
    nearest_to_zero(k, near_null_count(k, tolerance)?)
}

/// `v - sum_k (b_k . v) b_k` for an orthonormal basis `b`.
fn project_out(v: &mut [f64], basis: &[Vec<f64>]) {
    for b in basis {
        let dot: f64 = v.iter().zip(b).map(|(x, y)| x * y).sum();
        for (x, y) in v.iter_mut().zip(b) {
            *x -= dot * y;
        }
    }
}

fn projected_residual(g: &[f64], basis: &[Vec<f64>], scale: f64) -> f64 {
    let mut p = g.to_vec();
    project_out(&mut p, basis);
    max_abs(&p) / scale
}

/// Newton's method on the gradient from `theta`: the nearest equilibrium, of any index, with the
/// near-null directions (and, if asked, the end rotors) held (see the module doc).
pub fn newton<M: Stiffness + ?Sized>(
    model: &M,
    theta: &[f64],
    options: &NewtonOptions,
) -> Result<Solution, StaticsError> {
    validate::angles(model, theta)?;
    options.validate()?;
    const METHOD: &str = "Newton's method on the gradient";
    let n = model.dof_count();
    let range = moving(n, options.hold_ends);
    let mut theta = theta.to_vec();
    let mut g = vec![0.0; n];
    let mut trial = vec![0.0; n];
    let mut g_trial = vec![0.0; n];
    // Gradient and tangent stiffness in one pass ([`Stiffness::energy_gradient_stiffness_into`]),
    // at the start and at every trial point: the stiffness of an accepted trial is the next
    // iteration's (most steps are accepted at once).
    let mut k = SymmetricMatrix::for_model(model)?;
    let mut k_trial = k.clone();
    model.energy_gradient_stiffness_into(&theta, &mut g, k.values_mut());
    // Finite angles can still give non-finite forces (a model whose parameters are not finite,
    // a spring of zero length): an error, not a NaN residual.
    validate::finite("the model's gradient at theta", &g)?;
    validate::finite("the model's tangent stiffness at theta", k.values())?;
    let scale = k.inf_norm().max(f64::MIN_POSITIVE);
    let mut held = near_null(&k.principal(range.clone()), options.null_tolerance * scale)?;
    let mut residual = projected_residual(&g[range.clone()], &held, scale);
    let mut previous = f64::INFINITY;
    let mut iterations = 0;
    while finite_residual(METHOD, iterations, residual, options.tolerance)? > options.tolerance {
        if iterations == options.max_iterations {
            return Err(StaticsError::NoConvergence {
                method: METHOD,
                iterations,
                residual,
                tolerance: options.tolerance,
            });
        }
        iterations += 1;
        let moving = k.principal(range.clone());
        // The held set only grows (a borderline eigenvalue must not flip in and out), and the
        // residual is re-measured in the new basis so the line search compares like with like.
        // When a step barely helps, the softest free direction is held too: there is no exact
        // equilibrium along it (a soft translation pulled by the ends), and the constrained one
        // is the point of the adiabatic trajectory at this centring.
        let stagnating = iterations > 1 && residual > 0.5 * previous;
        let grow = usize::from(stagnating && held.len() < options.max_held);
        let count = (held.len() + grow).max(near_null_count(&moving, options.null_tolerance * scale)?);
        previous = residual;
        held = nearest_to_zero(&moving, count)?;
        residual = projected_residual(&g[range.clone()], &held, scale);
        if residual <= options.tolerance {
            break;
        }
        let mut rhs: Vec<f64> = g[range.clone()].iter().map(|x| -x).collect();
        project_out(&mut rhs, &held);
        let mut delta = moving.solve_shifted(-options.shift * scale, &rhs)?;
        project_out(&mut delta, &held);
        // Backtracking on the projected force: the full step, halved until it decreases.
        let mut alpha = 1.0;
        loop {
            trial.copy_from_slice(&theta);
            for (t, d) in trial[range.clone()].iter_mut().zip(&delta) {
                *t += alpha * d;
            }
            model.energy_gradient_stiffness_into(&trial, &mut g_trial, k_trial.values_mut());
            let r = projected_residual(&g_trial[range.clone()], &held, scale);
            if r < residual || alpha < 1e-6 {
                core::mem::swap(&mut theta, &mut trial);
                core::mem::swap(&mut g, &mut g_trial);
                core::mem::swap(&mut k, &mut k_trial);
                residual = r;
                break;
            }
            alpha *= 0.5;
        }
    }
    let edge_force = max_abs(&g) / scale;
    validate::finite("the equilibrium found by Newton's method", &theta)?;
    Ok(Solution { theta, iterations, residual, edge_force, held: held.len() })
}

/// Dissipative Newtonian dynamics from rest at `theta` (paper Sec. II), until the forces fall
/// below the tolerance. Returns the relaxed angles and the number of time steps taken.
///
/// The steps are those of the damped velocity Verlet of [`Verlet`] (the damping applied as an
/// exact decay of the velocities), with the step and the damping scaled by the integrators' bound
/// on the fastest mode ([`omega_bound`]), and the end degrees of freedom held if asked.
pub fn relax<M: Stiffness + ?Sized>(
    model: &M,
    theta: &[f64],
    options: &RelaxOptions,
) -> Result<(Vec<f64>, usize), StaticsError> {
    validate::angles(model, theta)?;
    options.validate()?;
    let n = model.dof_count();
    let no_convergence = |iterations: usize, residual: f64| StaticsError::NoConvergence {
        method: "dissipative dynamics",
        iterations,
        residual,
        tolerance: options.tolerance,
    };
    // The integrators' bound on the fastest mode: omega_max <= sqrt(||K|| / I_min).
    let bound = omega_bound(model, theta).map_err(|_| no_convergence(0, f64::NAN))?;
    let scale = bound.norm.max(f64::MIN_POSITIVE);
    let dt = options.time_step / bound.omega;
    let gamma = options.damping * bound.omega;
    let range = moving(n, options.hold_ends);
    let rates = vec![gamma; n];
    let mut stepper = Verlet::damped(model, State::at_rest(theta.to_vec()), dt, &rates)
        .map_err(|_| no_convergence(0, f64::NAN))?;
    for i in (0..n).filter(|i| !range.contains(i)) {
        stepper.hold(i);
    }
    let mut step = 0;
    loop {
        let residual = max_abs(&stepper.gradient()[range.clone()]) / scale;
        if residual <= options.tolerance {
            return Ok((stepper.into_state().theta, step));
        }
        if !residual.is_finite() || step == options.max_steps {
            return Err(no_convergence(step, residual));
        }
        step += 1;
        // Verlet counts its own time; relaxation only needs the configuration.
        if stepper.step_to(model, step as f64 * dt).is_err() {
            return Err(no_convergence(step, f64::NAN));
        }
    }
}

/// At most this many refinement steps in [`polish`]: from Newton's tolerance (`1e-11`) to the
/// rounding floor (`~1e-16`) takes one or two quadratically convergent steps.
pub const POLISH_STEPS: usize = 4;

/// Refines an equilibrium found by [`newton`] to the rounding floor of the gradient: projected
/// Newton steps (the near-null directions of `options` left alone, as in [`newton`]; nothing
/// newly held) while each one lowers the projected residual, at most [`POLISH_STEPS`] of them.
///
/// Why: Newton's tolerance (`1e-11 ||K||` on the force) leaves an error `~1e-11 ||K|| / lambda`
/// in the stiff directions, and a curvature far below `||K||` moves with the configuration at
/// first order: at `theta_bar = 0.2` (n = 60, held ends) the antikink's translation curvature
/// `4e-7` came out 1.4 % off at Newton's tolerance and within `1e-4` of an independent
/// computation after the polish (tests/statics_nonuniform.rs).
///
/// # Errors
/// As [`newton`] (a non-finite model at the iterate).
pub fn polish<M: Stiffness + ?Sized>(
    model: &M,
    solution: Solution,
    options: &NewtonOptions,
) -> Result<Solution, StaticsError> {
    options.validate()?;
    let n = model.dof_count();
    validate::angles(model, &solution.theta)?;
    let range = moving(n, options.hold_ends);
    let mut theta = solution.theta;
    let mut g = vec![0.0; n];
    let mut k = SymmetricMatrix::for_model(model)?;
    model.energy_gradient_stiffness_into(&theta, &mut g, k.values_mut());
    validate::finite("the model's gradient at theta", &g)?;
    validate::finite("the model's tangent stiffness at theta", k.values())?;
    let scale = k.inf_norm().max(f64::MIN_POSITIVE);
    let moving_k = k.principal(range.clone());
    let held = near_null(&moving_k, options.null_tolerance * scale)?;
    let mut residual = projected_residual(&g[range.clone()], &held, scale);
    let mut steps = 0;
    let mut trial = theta.clone();
    let mut g_trial = vec![0.0; n];
    let mut k_trial = k.clone();
    while steps < POLISH_STEPS {
        let moving_k = k.principal(range.clone());
        let mut rhs: Vec<f64> = g[range.clone()].iter().map(|x| -x).collect();
        project_out(&mut rhs, &held);
        let mut delta = moving_k.solve_shifted(-options.shift * scale, &rhs)?;
        project_out(&mut delta, &held);
        trial.copy_from_slice(&theta);
        for (t, d) in trial[range.clone()].iter_mut().zip(&delta) {
            *t += d;
        }
        model.energy_gradient_stiffness_into(&trial, &mut g_trial, k_trial.values_mut());
        let r = projected_residual(&g_trial[range.clone()], &held, scale);
        if r.is_nan() || r >= residual {
            break;
        }
        core::mem::swap(&mut theta, &mut trial);
        core::mem::swap(&mut g, &mut g_trial);
        core::mem::swap(&mut k, &mut k_trial);
        residual = r;
        steps += 1;
    }
    validate::finite("the equilibrium polished by Newton's method", &theta)?;
    Ok(Solution {
        theta,
        iterations: solution.iterations + steps,
        residual,
        edge_force: max_abs(&g) / scale,
        held: solution.held,
    })
}
