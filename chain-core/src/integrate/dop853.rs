//! Adaptive integration of `I_i thetadd_i = -dV/dtheta_i - gamma I_i thetadot_i` with DOP853, the
//! explicit Runge-Kutta pair of order 8(5,3) of Dormand and Prince (Hairer, Norsett and Wanner,
//! *Solving Ordinary Differential Equations I*, 2nd ed., Secs. II.4-II.6; coefficients in
//! `tableau.rs`), on the first-order system `y = (theta, omega)`,
//! `y' = f(y) = (omega, -I^-1 dV/dtheta - gamma omega)`.
//!
//! - **Steps.** Twelve stages, the last one shared with the next step (FSAL: `f(y_new)` is the
//!   next step's first stage), so an accepted step costs 12 gradient evaluations.
//! - **Error.** The error of each step is estimated from an embedded 5th-order and 3rd-order
//!   solution, combined as in Hairer's code DOP853:
//!   `err = h ||e5||^2 / sqrt(||e5||^2 + 0.01 ||e3||^2)` in the root-mean-square norm with weights
//!   `1 / (atol + rtol max(|y_i|, |y_new_i|))`; a step is accepted when `err <= 1`.
//! - **Step size.** A PI controller (HNW II Sec. IV.2, Gustafsson's "Lund stabilization"),
//!   `h_new = h * 0.9 * err^-alpha * err_prev^beta` with `beta = 0.04`, `alpha = 1/8 - 0.2 beta`
//!   (Hairer's parametrization), the ratio kept in `[1/3, 6]` and no growth right after a
//!   rejection. On a moving kink the step is limited by the fastest phonons (`h omega_max ~ 0.6`),
//!   where the pure `err^{-1/8}` rule (Hairer's DOP853 default, `beta = 0`) oscillates: it
//!   rejected 200-460 of 4000-5500 steps on a smooth moving kink, and `beta = 0.04` one, for a
//!   third less time. (A kink launched by `dynamics::launch` and reflected at a free end still
//!   sees ~370 rejections in ~5250 steps, all after the reflection.)
//!   The first step is chosen by Hairer's `hinit` (HNW I Sec. II.4) unless given.
//! - **Dense output.** Three more stages give the 7th-order continuous extension of HNW I Sec.
//!   II.6, evaluated at the requested output times inside a step (computed only for steps that
//!   contain one), so outputs never shorten the steps.
//!
//! Energy is not conserved exactly by a Runge-Kutta method: the error drifts roughly linearly in
//! time at a rate set by the tolerance. At the default tolerances it stays below `1e-9` of the
//! energy of a moving kink over the paper's `t = 20` (tests/integrate.rs); for much longer
//! conservative runs prefer [`verlet`](super::verlet()).

use alloc::vec;
use alloc::vec::Vec;

use super::tableau::{A, B, BHH, D, E5};
use super::{
    DEFAULT_ENERGY_LIMIT, Flow, IntegrateError, Integrator, Monitor, Report, Schedule, Sponge, State,
    check_energy_limit, check_positive, check_step_budget, damping_rates, inverse_inertia, not_finite,
};
use crate::model::Potential;
use crate::validate::{Fields, Validate};

/// Settings of [`adaptive`]. Times in the unit `t` of paper Appendix B.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveOptions {
    /// Relative tolerance of each step (applied to angles and angular velocities alike).
    /// Default `1e-10`: with DOP853's 8th order a decade of tolerance costs only a third more
    /// steps, and together with `atol` it holds the energy of the paper's moving kink (60 rotors,
    /// `k = 1e4`, `v0 = 2.4`, `t = 20`) to `2e-10` relative, five times inside the `1e-9` the
    /// scattering runs need (measured: `1e-9` and `1e-10` for both tolerances give `2e-8` and
    /// `1.7e-9`).
    pub rtol: f64,
    /// Absolute tolerance, in radians and radians per `t`; must be positive (rotors at rest have
    /// zero velocity, so a purely relative test would divide by zero). Default `1e-11`, a decade
    /// below `rtol`: most of the chain is quiet (rotors near `+-theta_bar` carrying phonons of
    /// tiny amplitude), and its errors, which only `atol` controls, add up in the energy.
    pub atol: f64,
    /// The first step; `None` (default) chooses it by Hairer's rule (one extra evaluation).
    pub initial_step: Option<f64>,
    /// The longest step. Default `f64::INFINITY`: the error control alone decides, and outputs
    /// come from the dense output, so they need no step limit.
    pub max_step: f64,
    /// Fail with [`IntegrateError::StepSizeTooSmall`] when the controller wants a shorter step.
    /// Default `0`: only steps lost to rounding (`0.1 h <= eps |t|`) fail, as in Hairer's code; a
    /// fixed floor would depend on the stiffness.
    pub min_step: f64,
    /// Give up after this many steps, accepted and rejected. Default 100 000 (Hairer's default):
    /// a paper-length run of 60 rotors at `k = 1e4` takes about 5000. Between 1 and
    /// [`MAX_STEP_BUDGET`](super::MAX_STEP_BUDGET) (10^10), every integrator's bound.
    pub max_steps: usize,
    /// Damping rate `gamma >= 0` of every rotor, in `1 / t`. Default 0 (Newtonian dynamics).
    pub damping: f64,
    /// Absorbing ends: extra damping on the last rotors at each end. Default `None`.
    pub sponge: Option<Sponge>,
    /// The largest relative energy change before the run stops with
    /// [`IntegrateError::EnergyNotConserved`] (checked at every output). Default
    /// [`DEFAULT_ENERGY_LIMIT`]; infinite switches it off.
    pub energy_limit: f64,
    /// A bound on the fastest mode's angular frequency at the start, in `1 / t`
    /// ([`omega_bound`](super::bound::omega_bound), from the tangent stiffness): a run that could
    /// not fit [`AdaptiveOptions::max_steps`] at DOP853's stability limit is then refused before
    /// its first step ([`IntegrateError::StepBudget`]). Default `None`: the run is bounded by
    /// `max_steps` alone (a model with only a [`Potential`] has no stiffness to bound it from);
    /// the dynamics' runs fill it in.
    pub omega_max: Option<f64>,
}

impl Default for AdaptiveOptions {
    fn default() -> Self {
        Self {
            rtol: super::Method::DOP853_RTOL,
            atol: super::Method::DOP853_ATOL,
            initial_step: None,
            max_step: f64::INFINITY,
            min_step: 0.0,
            max_steps: 100_000,
            damping: 0.0,
            sponge: None,
            energy_limit: DEFAULT_ENERGY_LIMIT,
            omega_max: None,
        }
    }
}

impl Validate for AdaptiveOptions {
    type Error = IntegrateError;

    /// Every field in its range: `rtol >= 0`, `atol > 0`, `initial_step > 0`, `max_step > 0`
    /// (infinite: no limit), `0 <= min_step <= max_step`, `max_steps` between 1 and
    /// [`MAX_STEP_BUDGET`](super::MAX_STEP_BUDGET), `damping >= 0`, the
    /// sponge's, `omega_max > 0`, `energy_limit > 0` (infinite: no check); every finite one
    /// finite.
    fn validate(&self) -> Result<(), IntegrateError> {
        // No `..`: a field added here does not compile until it is checked.
        let Self {
            rtol,
            atol,
            initial_step,
            max_step,
            min_step,
            max_steps,
            damping,
            sponge,
            energy_limit,
            omega_max,
        } = *self;
        let fields = Fields("AdaptiveOptions");
        fields.non_negative("rtol", rtol)?;
        fields.positive("atol", atol)?;
        if let Some(h) = initial_step {
            fields.positive("initial_step", h)?;
        }
        fields.rule("max_step", max_step, max_step > 0.0, "positive (infinite: no limit)")?;
        let ok = min_step >= 0.0 && min_step.is_finite() && min_step <= max_step;
        fields.rule("min_step", min_step, ok, "non-negative, finite and at most max_step")?;
        check_step_budget(fields, "max_steps", max_steps as u64)?;
        fields.non_negative("damping", damping)?;
        if let Some(sponge) = sponge {
            sponge.validate()?;
        }
        if let Some(omega) = omega_max {
            fields.positive("omega_max", omega)?;
        }
        check_energy_limit(fields, energy_limit)
    }
}

/// A generous bound on `h omega` for DOP853 to be stable on an oscillation (its stability region
/// reaches about 4-6 along the imaginary axis): used only to refuse runs that cannot fit their
/// step budget.
const STABILITY_LIMIT: f64 = 6.0;

/// Safety factor on the predicted step (Hairer's default).
const SAFETY: f64 = 0.9;
/// Bounds on `h_new / h` (Hairer's defaults for DOP853).
const MIN_RATIO: f64 = 0.333;
const MAX_RATIO: f64 = 6.0;
/// The PI controller's exponents (module doc).
const BETA: f64 = 0.04;
const ALPHA: f64 = 1.0 / 8.0 - 0.2 * BETA;

/// Integrates `state` with DOP853 (module doc) up to the last of `outputs`, calling `observer`
/// with the state at each output time (from the dense output inside a step, exactly at a step's
/// end). `outputs` must not decrease and must not precede `state.time`; an output equal to the
/// start time sees the initial state.
///
/// On return `state` holds the last state the observer saw: the one at the last output, or where
/// it stopped the run. On [`IntegrateError::StepSizeTooSmall`], [`IntegrateError::TooManySteps`]
/// and [`IntegrateError::NotFinite`] it holds the last accepted step, from which a run can resume.
pub fn adaptive<M: Potential + ?Sized>(
    model: &M,
    state: &mut State,
    outputs: &[f64],
    options: &AdaptiveOptions,
    observer: &mut dyn FnMut(&State) -> Flow,
) -> Result<Report, IntegrateError> {
    state.check(model)?;
    options.validate()?;
    check_outputs(state.time, outputs)?;
    run(model, state, &|k| outputs[k], outputs.len(), options, observer)
}

/// [`adaptive`] with the output times given by `output(k)`, `k < count` (checked by the caller).
fn run<M: Potential + ?Sized>(
    model: &M,
    state: &mut State,
    output: &dyn Fn(usize) -> f64,
    count: usize,
    options: &AdaptiveOptions,
    observer: &mut dyn FnMut(&State) -> Flow,
) -> Result<Report, IntegrateError> {
    let rates = damping_rates(model.dof_count(), options.damping, options.sponge)?;
    let damped = rates.iter().any(|&r| r > 0.0);
    let mut monitor = Monitor::new(model, state, damped, options.energy_limit)?;
    let f = EquationsOfMotion { model, inverse_inertia: inverse_inertia(model)?, damping: rates };
    let mut next = 0;
    while next < count && output(next) <= state.time {
        if monitor.output(model, state, observer)? {
            return Ok(monitor.report);
        }
        next += 1;
    }
    if next == count {
        return Ok(monitor.report);
    }
    let t_end = output(count - 1);
    // An explicit Runge-Kutta method needs h omega_max below its stability limit (about 6 for
    // DOP853 on oscillations, generously): a run that would need more steps than its budget at
    // that step is refused before it starts, instead of after max_steps.
    if let Some(omega) = options.omega_max {
        let needed = (t_end - state.time) * omega / STABILITY_LIMIT;
        if needed > options.max_steps as f64 {
            return Err(IntegrateError::StepBudget {
                steps: needed,
                dt: STABILITY_LIMIT / omega,
                span: t_end - state.time,
                budget: options.max_steps as u64,
            });
        }
    }

    let mut w = Stepper::new(state);
    let mut t = state.time;
    f.eval(&w.y, &mut w.k[0]);
    f.check(t, &w.k[0])?;
    let mut h = match options.initial_step {
        Some(h) => h,
        None => w.initial_step(&f, options),
    };
    let mut err_previous = 1e-4;
    let mut rejected_last = false;
    let mut attempts = 0;
    loop {
        h = h.min(options.max_step);
        if h < options.min_step || 0.1 * h <= t.abs() * f64::EPSILON {
            w.unpack_y(t, state);
            return Err(IntegrateError::StepSizeTooSmall { time: t, step: h });
        }
        if attempts == options.max_steps {
            w.unpack_y(t, state);
            return Err(IntegrateError::TooManySteps { time: t, steps: attempts });
        }
        attempts += 1;
        // Stretch a step that would end just short of the end, rather than leave a sliver.
        let last = 1.01 * h >= t_end - t;
        if last {
            h = t_end - t;
        }
        let err = w.attempt(&f, h, options);
        // A non-finite estimate (an overflow, a NaN force inside the step) is a rejection, and
        // `f64::min` ignores the NaN below, so the step is cut by the largest factor.
        if err.is_nan() || err > 1.0 {
            monitor.report.rejected += 1;
            rejected_last = true;
            h /= (1.0 / MIN_RATIO).min(libm::pow(err, ALPHA) / SAFETY);
            continue;
        }
        let t_new = if last { t_end } else { t + h };
        let (y_new, f_new) = (&w.y_new, &mut w.k[12]);
        f.eval(y_new, f_new);
        if let Err(e) = f.check(t_new, &w.k[12]) {
            w.unpack_y_new(t_new, state);
            return Err(e);
        }
        monitor.report.steps += 1;
        let mut dense_ready = false;
        while next < count && output(next) <= t_new {
            let time = output(next);
            if time == t_new {
                w.unpack_y_new(time, state);
            } else {
                if !dense_ready {
                    w.prepare_dense(&f, h);
                    dense_ready = true;
                }
                w.interpolate((time - t) / h, time, state);
            }
            if monitor.output(model, state, observer)? {
                return Ok(monitor.report);
            }
            next += 1;
        }
        if last {
            return Ok(monitor.report);
        }
        let mut ratio =
            (libm::pow(err, -ALPHA) * libm::pow(err_previous, BETA) * SAFETY).clamp(MIN_RATIO, MAX_RATIO);
        if rejected_last {
            ratio = ratio.min(1.0);
        }
        err_previous = err.max(1e-4);
        rejected_last = false;
        t = t_new;
        w.advance();
        h *= ratio;
    }
}

impl Integrator for AdaptiveOptions {
    fn name(&self) -> &'static str {
        "dop853"
    }

    /// The outputs come from the dense output; they never shorten the steps.
    fn integrate<M: Potential + ?Sized>(
        &self,
        model: &M,
        state: &mut State,
        schedule: &Schedule,
        observer: &mut dyn FnMut(&State) -> Flow,
    ) -> Result<Report, IntegrateError> {
        state.check(model)?;
        self.validate()?;
        check_positive("Schedule", "interval", schedule.interval)?;
        let start = state.time;
        let last = schedule.time(start, schedule.count);
        if !last.is_finite() {
            return Err(IntegrateError::NotFinite {
                what: "outputs",
                time: start,
                index: schedule.count,
                value: last,
            });
        }
        // The last output exactly at the schedule's end, the others at their multiples.
        let output = |k: usize| if k == schedule.count { last } else { schedule.time(start, k) };
        run(model, state, &output, schedule.count + 1, self, observer)
    }
}

/// Output times: finite, not decreasing, not before `start`.
fn check_outputs(start: f64, outputs: &[f64]) -> Result<(), IntegrateError> {
    let mut previous = start;
    for (index, &time) in outputs.iter().enumerate() {
        if !time.is_finite() {
            return Err(IntegrateError::NotFinite { what: "outputs", time: start, index, value: time });
        }
        if time < previous {
            return Err(IntegrateError::OutputsOutOfOrder { index, time, previous });
        }
        previous = time;
    }
    Ok(())
}

/// The equations of motion as a first-order system in `y = (theta, omega)`.
struct EquationsOfMotion<'a, M: ?Sized> {
    model: &'a M,
    inverse_inertia: Vec<f64>,
    /// The damping rate of each rotor.
    damping: Vec<f64>,
}

impl<M: Potential + ?Sized> EquationsOfMotion<'_, M> {
    /// `dy = (omega, -I^-1 dV/dtheta - gamma omega)`.
    fn eval(&self, y: &[f64], dy: &mut [f64]) {
        let n = self.inverse_inertia.len();
        let (theta, omega) = y.split_at(n);
        let (velocity, acceleration) = dy.split_at_mut(n);
        velocity.copy_from_slice(omega);
        self.model.gradient_into(theta, acceleration);
        for (((a, w), c), g) in
            acceleration.iter_mut().zip(omega).zip(&self.inverse_inertia).zip(&self.damping)
        {
            *a = -*a * c - g * w;
        }
    }

    /// `Err(NotFinite)` if `f(y)` has a non-finite acceleration (its velocities are the state's).
    fn check(&self, time: f64, dy: &[f64]) -> Result<(), IntegrateError> {
        not_finite("acceleration", time, &dy[self.inverse_inertia.len()..])
    }
}

/// The state `y`, the trial `y_new`, the stages `k_0..k_15` and the dense output's coefficients,
/// allocated once per run.
struct Stepper {
    y: Vec<f64>,
    y_new: Vec<f64>,
    stage: Vec<f64>,
    /// `sum_j b_j k_j`, so `y_new = y + h * increment`.
    increment: Vec<f64>,
    err5: Vec<f64>,
    err3: Vec<f64>,
    k: Vec<Vec<f64>>,
    /// `F_0..F_6` of the interpolant `y + s (F_0 + (1-s) (F_1 + s (F_2 + (1-s) (F_3 + ...))))`.
    dense: [Vec<f64>; 7],
}

fn square(x: f64) -> f64 {
    x * x
}

/// Elements per block of the linear combinations: a block of the output stays in L1 cache while
/// the stages stream past, so a large chain reads each stage once per combination.
const BLOCK: usize = 256;

/// `out = base + scale sum_j w_j k_j` (with `base = 0` if `None`), block by block.
fn combine(out: &mut [f64], base: Option<&[f64]>, scale: f64, row: &[(usize, f64)], k: &[Vec<f64>]) {
    for (b, out) in out.chunks_mut(BLOCK).enumerate() {
        let range = b * BLOCK..b * BLOCK + out.len();
        match base {
            Some(base) => out.copy_from_slice(&base[range.clone()]),
            None => out.fill(0.0),
        }
        for &(j, w) in row {
            let a = scale * w;
            for (o, x) in out.iter_mut().zip(&k[j][range.clone()]) {
                *o += a * x;
            }
        }
    }
}

/// `out = base + h sum_j a_j k_j`: a stage's argument.
fn stage_point(out: &mut [f64], base: &[f64], h: f64, row: &[(usize, f64)], k: &[Vec<f64>]) {
    combine(out, Some(base), h, row, k);
}

/// `out = scale * sum_j w_j k_j`.
fn weighted_sum(out: &mut [f64], scale: f64, row: &[(usize, f64)], k: &[Vec<f64>]) {
    combine(out, None, scale, row, k);
}

impl Stepper {
    fn new(state: &State) -> Self {
        let y: Vec<f64> = state.theta.iter().chain(&state.omega).copied().collect();
        let zeros = || vec![0.0; y.len()];
        Self {
            y_new: zeros(),
            stage: zeros(),
            increment: zeros(),
            err5: zeros(),
            err3: zeros(),
            k: (0..16).map(|_| zeros()).collect(),
            dense: core::array::from_fn(|_| zeros()),
            y,
        }
    }

    /// Hairer's starting step (HNW I Sec. II.4, "Starting step size"): a step with
    /// `h^8 max(||f'||, ||f||) = 0.01`, from one explicit Euler step of length `0.01 ||y||/||f||`.
    fn initial_step<M: Potential + ?Sized>(
        &mut self,
        f: &EquationsOfMotion<'_, M>,
        options: &AdaptiveOptions,
    ) -> f64 {
        let dim = self.y.len() as f64;
        let scale = |y: f64| options.atol + options.rtol * y.abs();
        let rms = |sum: f64| crate::math::sqrt(sum / dim);
        let norm_f = rms(self.y.iter().zip(&self.k[0]).map(|(y, f)| square(f / scale(*y))).sum());
        let norm_y = rms(self.y.iter().map(|y| square(y / scale(*y))).sum());
        let mut h = if norm_f <= 1e-5 || norm_y <= 1e-5 { 1e-6 } else { 0.01 * norm_y / norm_f };
        h = h.min(options.max_step);
        stage_point(&mut self.stage, &self.y, h, &[(0, 1.0)], &self.k);
        f.eval(&self.stage, &mut self.k[1]);
        let second: f64 = self
            .y
            .iter()
            .zip(&self.k[0])
            .zip(&self.k[1])
            .map(|((y, f0), f1)| square((f1 - f0) / scale(*y)))
            .sum();
        let derivative = (rms(second) / h).max(norm_f);
        let h1 =
            if derivative <= 1e-15 { (h * 1e-3).max(1e-6) } else { libm::pow(0.01 / derivative, 1.0 / 8.0) };
        (100.0 * h).min(h1).min(options.max_step)
    }

    /// Stages 1-11 of a step of size `h` from `y` (with `k_0 = f(y)`), the trial `y_new`, and the
    /// scaled error estimate (`<= 1` to accept).
    fn attempt<M: Potential + ?Sized>(
        &mut self,
        f: &EquationsOfMotion<'_, M>,
        h: f64,
        options: &AdaptiveOptions,
    ) -> f64 {
        for (s, row) in A.iter().enumerate().take(12).skip(1) {
            stage_point(&mut self.stage, &self.y, h, row, &self.k);
            f.eval(&self.stage, &mut self.k[s]);
        }
        weighted_sum(&mut self.increment, 1.0, B, &self.k);
        weighted_sum(&mut self.err5, 1.0, E5, &self.k);
        weighted_sum(&mut self.err3, 1.0, BHH, &self.k);
        let (mut sum5, mut sum3) = (0.0, 0.0);
        for i in 0..self.y.len() {
            let (y, increment) = (self.y[i], self.increment[i]);
            let y_new = y + h * increment;
            self.y_new[i] = y_new;
            let weight = 1.0 / (options.atol + options.rtol * y.abs().max(y_new.abs()));
            sum5 += square(self.err5[i] * weight);
            sum3 += square((increment - self.err3[i]) * weight);
        }
        let denominator = sum5 + 0.01 * sum3;
        let denominator = if denominator > 0.0 { denominator } else { 1.0 };
        h * sum5 / crate::math::sqrt(self.y.len() as f64 * denominator)
    }

    /// The interpolant of the accepted step `y -> y_new` of size `h` (needs `k_12 = f(y_new)`).
    fn prepare_dense<M: Potential + ?Sized>(&mut self, f: &EquationsOfMotion<'_, M>, h: f64) {
        for (s, row) in A.iter().enumerate().skip(13) {
            stage_point(&mut self.stage, &self.y, h, row, &self.k);
            f.eval(&self.stage, &mut self.k[s]);
        }
        let [f0, f1, f2, rest @ ..] = &mut self.dense;
        for i in 0..self.y.len() {
            let difference = self.y_new[i] - self.y[i];
            let spline = h * self.k[0][i] - difference;
            f0[i] = difference;
            f1[i] = spline;
            f2[i] = difference - h * self.k[12][i] - spline;
        }
        for (out, row) in rest.iter_mut().zip(&D) {
            weighted_sum(out, h, row, &self.k);
        }
    }

    /// The dense output at `y + s h`, `0 <= s <= 1`, written to `state` at `time`.
    fn interpolate(&self, s: f64, time: f64, state: &mut State) {
        let s1 = 1.0 - s;
        let c = &self.dense;
        let at = |i: usize| {
            let tail = c[3][i] + s * (c[4][i] + s1 * (c[5][i] + s * c[6][i]));
            self.y[i] + s * (c[0][i] + s1 * (c[1][i] + s * (c[2][i] + s1 * tail)))
        };
        let n = state.theta.len();
        for (i, theta) in state.theta.iter_mut().enumerate() {
            *theta = at(i);
        }
        for (i, omega) in state.omega.iter_mut().enumerate() {
            *omega = at(n + i);
        }
        state.time = time;
    }

    /// Accept the step: `y_new` becomes `y` and `f(y_new)` the next first stage (FSAL).
    fn advance(&mut self) {
        core::mem::swap(&mut self.y, &mut self.y_new);
        self.k.swap(0, 12);
    }

    fn unpack_y(&self, time: f64, state: &mut State) {
        unpack(&self.y, time, state);
    }

    fn unpack_y_new(&self, time: f64, state: &mut State) {
        unpack(&self.y_new, time, state);
    }
}

fn unpack(y: &[f64], time: f64, state: &mut State) {
    let (theta, omega) = y.split_at(state.theta.len());
    state.theta.copy_from_slice(theta);
    state.omega.copy_from_slice(omega);
    state.time = time;
}
