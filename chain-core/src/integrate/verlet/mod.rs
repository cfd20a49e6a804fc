//! Velocity Verlet (kick-drift-kick) for `I_i thetadd_i = -dV/dtheta_i - gamma I_i thetadot_i`.
//!
//! The vector field splits into three exactly solvable flows: the drift `thetadot = omega`, the
//! kick `omegadot = -I^-1 dV/dtheta`, and the decay `omegadot = -gamma omega`, solved by
//! `omega -> e^{-gamma t} omega`. One step of length `dt` composes them symmetrically (Strang):
//!
//! ```text
//! decay(dt/2) kick(dt/2) drift(dt) kick(dt/2) decay(dt/2)
//! ```
//!
//! so it is second order and time-reversible (Hairer, Lubich and Wanner, *Geometric Numerical
//! Integration*, Secs. I.1.4 and II.5). Without damping the decay is the identity (the factor is
//! exactly 1.0), and what is left is the Stormer-Verlet map: symplectic, so it conserves a
//! modified energy `E + O(dt^2)` and the energy error oscillates with bounded amplitude instead
//! of drifting, over exponentially long times (GNI Sec. IX.8). With damping, applying the decay
//! exactly makes each step contract the symplectic form by exactly `e^{-gamma dt}`, as the true
//! flow does (a conformally symplectic integrator), and the phonon damping rate is exact at any
//! `dt`.
//!
//! The gradient at the end of a step is the one the next step starts with, so a step costs one
//! evaluation of the gradient (with the energy in the same pass,
//! [`Potential::energy_and_gradient_into`], when the run reports energies) and two O(n)
//! sweeps. Stability needs `omega_max dt < 2` for the fastest mode; [`VerletOptions::stable_for`]
//! picks `dt` from a bound on `omega_max` ([`omega_bound`](super::bound::omega_bound)).
//!
//! **One stepper.** [`Verlet`] is generic over the float type (`f64`, or `f32` for a chain
//! declared with `float = f32`) and over the storage ([`Storage`]: a `Vec`, or an array for a
//! microcontroller without a heap). It serves the runs ([`verlet`], through the [`Integrator`](super::Integrator)
//! trait), the statics' dissipative relaxation (damping, held degrees of freedom) and the
//! firmware (each `#[rotor_chain]` chain's `verlet()`), with the same arithmetic in the same order.

#[cfg(feature = "alloc")]
mod options;

#[cfg(feature = "alloc")]
pub use options::{VerletOptions, verlet};

use super::state::{Phase, Storage};
use super::{IntegrateError, check_option, not_finite};
use crate::model::Potential;
use crate::real::Real;

/// Velocity Verlet on a state: the one implementation of the (damped) Verlet map of the module
/// doc. `T` is the float type, `S` the storage ([`Storage`]: `Vec<T>` or `[T; N]`).
///
/// # Example: a chain on a microcontroller, no heap
///
/// ```
/// use rotor_chain::prelude::*;
/// use rotor_chain::integrate::{Phase, Verlet};
///
/// #[rotor_chain(n = 16, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
/// struct Chain;
///
/// let mut theta = [0.58f64; 16];
/// theta[8] = 0.5;                                         // a small disturbance
/// let mut v = Verlet::new(&Chain, Phase { time: 0.0, theta, omega: [0.0; 16] }, 1e-4)?;
/// let e0 = v.kinetic_energy(&Chain) + v.potential_energy(&Chain);
/// for _ in 0..1000 {
///     v.step(&Chain)?;
/// }
/// v.check_energy(&Chain, e0, 1e-2 * e0)?;                  // Verlet's error stays bounded
/// assert_eq!(v.steps(), 1000);
/// # Ok::<(), rotor_chain::integrate::IntegrateError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Verlet<T, S> {
    state: Phase<T, S>,
    /// The time of the first state: [`Verlet::step`] sets `t0 + steps dt`, free of accumulated
    /// rounding.
    t0: T,
    /// `dV/dtheta` at the current state.
    gradient: S,
    /// `dt / (2 I_i)`, the kick's factor folded once; 0 for a held degree of freedom.
    half_kick: S,
    /// `exp(-gamma_i dt / 2)`; `None` without damping (the steps then skip the decay).
    decay: Option<S>,
    /// `V` at the current state, when each step evaluates it with the gradient.
    potential: Option<T>,
    dt: T,
    steps: u64,
}

impl<T: Real, S: Storage<T>> Verlet<T, S> {
    /// A stepper at `state` (checked) with step `dt`, no damping, one gradient evaluation per step
    /// ([`Potential::gradient_into`]; the energy only when asked). Stability needs
    /// `omega_max dt < 2` for the model's fastest mode ([`VerletOptions::stable_for`] picks `dt`
    /// from a bound on it).
    ///
    /// # Errors
    /// A state that does not fit the model or is not finite, a `dt` that is not positive and
    /// finite, an inertia that is not positive and finite with a finite inverse, or a gradient
    /// that is not finite at the start.
    pub fn new<M: Potential<T> + ?Sized>(
        model: &M,
        state: Phase<T, S>,
        dt: T,
    ) -> Result<Self, IntegrateError> {
        Self::build(model, state, dt, None, false)
    }

    /// A stepper with damping rates `gamma_i >= 0` (one per degree of freedom, in `1 / t`; the
    /// decay applied exactly) that evaluates the potential energy with every gradient
    /// ([`Potential::energy_and_gradient_into`], one pass), as the runs and the relaxation need.
    ///
    /// # Errors
    /// As [`Verlet::new`], or rates of the wrong length or not finite and `>= 0`.
    pub fn damped<M: Potential<T> + ?Sized>(
        model: &M,
        state: Phase<T, S>,
        dt: T,
        rates: &[T],
    ) -> Result<Self, IntegrateError> {
        Self::build(model, state, dt, Some(rates), true)
    }

    fn build<M: Potential<T> + ?Sized>(
        model: &M,
        state: Phase<T, S>,
        dt: T,
        rates: Option<&[T]>,
        track_potential: bool,
    ) -> Result<Self, IntegrateError> {
        state.check(model)?;
        check_option("Verlet", "dt", dt.widen(), dt > T::ZERO && dt.is_finite(), "positive and finite")?;
        let n = model.dof_count();
        let mut half_kick = S::filled(n, T::ZERO).ok_or(IntegrateError::WrongLength {
            what: "the stepper's storage",
            len: state.theta.as_ref().len(),
            expected: n,
        })?;
        for (i, c) in half_kick.as_mut().iter_mut().enumerate() {
            let inertia = model.inertia(i);
            let inverse = T::ONE / inertia;
            // A subnormal inertia is positive and finite, but its inverse overflows.
            if !(inertia > T::ZERO && inertia.is_finite() && inverse.is_finite()) {
                return Err(IntegrateError::BadInertia { index: i, inertia: inertia.widen() });
            }
            *c = T::of(0.5) * dt * inverse;
        }
        let decay = match rates {
            None => None,
            Some(rates) => {
                if rates.len() != n {
                    return Err(IntegrateError::WrongLength {
                        what: "damping rates",
                        len: rates.len(),
                        expected: n,
                    });
                }
                if let Some(&bad) = rates.iter().find(|r| !(**r >= T::ZERO && r.is_finite())) {
                    return Err(IntegrateError::InvalidOption {
                        options: "Verlet::damped",
                        name: "damping",
                        value: bad.widen(),
                        rule: "non-negative and finite",
                    });
                }
                let mut decay = half_kick.clone();
                for (d, g) in decay.as_mut().iter_mut().zip(rates) {
                    *d = (-T::of(0.5) * *g * dt).exp();
                }
                Some(decay)
            }
        };
        let mut gradient = half_kick.clone();
        let potential = if track_potential {
            Some(model.energy_and_gradient_into(state.theta.as_ref(), gradient.as_mut()))
        } else {
            model.gradient_into(state.theta.as_ref(), gradient.as_mut());
            None
        };
        not_finite("gradient", state.time.widen(), gradient.as_ref())?;
        Ok(Self { t0: state.time, state, gradient, half_kick, decay, potential, dt, steps: 0 })
    }

    /// Holds degree of freedom `i` still: its rate becomes 0 and no force moves it (a Dirichlet
    /// end).
    ///
    /// # Panics
    /// If `i` is not a degree of freedom of the state.
    pub fn hold(&mut self, i: usize) {
        self.half_kick.as_mut()[i] = T::ZERO;
        self.state.omega.as_mut()[i] = T::ZERO;
    }

    /// One step of `dt`; the state's time becomes `t0 + steps dt` (no accumulated rounding).
    ///
    /// # Errors
    /// As [`Verlet::step_to`].
    pub fn step<M: Potential<T> + ?Sized>(&mut self, model: &M) -> Result<(), IntegrateError> {
        let time = self.t0 + T::of(self.steps.saturating_add(1) as f64) * self.dt;
        self.step_to(model, time)
    }

    /// One step of `dt`, after which the state's time is `time` (the caller counts the steps).
    ///
    /// # Errors
    /// A rate that is no longer finite (a NaN force, or a step so far past the stability limit
    /// that the motion overflowed), [`IntegrateError::NotFinite`]; the state shows the step that
    /// went wrong.
    pub fn step_to<M: Potential<T> + ?Sized>(&mut self, model: &M, time: T) -> Result<(), IntegrateError> {
        let dt = self.dt;
        let theta = self.state.theta.as_mut();
        let omega = self.state.omega.as_mut();
        let (gradient, half_kick) = (self.gradient.as_mut(), self.half_kick.as_ref());
        // Kick and drift. With damping the decay brackets the kicks (Strang); without it the
        // multiplications by 1 are skipped, which leaves the same bits.
        match &self.decay {
            None => {
                for (((t, w), g), c) in
                    theta.iter_mut().zip(omega.iter_mut()).zip(gradient.iter()).zip(half_kick)
                {
                    *w -= *c * *g;
                    *t += dt * *w;
                }
            }
            Some(decay) => {
                let wgc = omega.iter_mut().zip(gradient.iter()).zip(half_kick).zip(decay.as_ref());
                for (t, (((w, g), c), d)) in theta.iter_mut().zip(wgc) {
                    *w = *w * *d - *c * *g;
                    *t += dt * *w;
                }
            }
        }
        match self.potential {
            Some(_) => self.potential = Some(model.energy_and_gradient_into(theta, gradient)),
            None => model.gradient_into(theta, gradient),
        }
        let mut finite = true;
        match &self.decay {
            None => {
                for ((w, g), c) in omega.iter_mut().zip(gradient.iter()).zip(half_kick) {
                    *w -= *c * *g;
                    finite &= w.is_finite();
                }
            }
            Some(decay) => {
                for (((w, g), c), d) in
                    omega.iter_mut().zip(gradient.iter()).zip(half_kick).zip(decay.as_ref())
                {
                    *w = (*w - *c * *g) * *d;
                    finite &= w.is_finite();
                }
            }
        }
        self.steps = self.steps.saturating_add(1);
        self.state.time = time;
        if !finite {
            not_finite("theta", time.widen(), self.state.theta.as_ref())?;
            not_finite("omega", time.widen(), self.state.omega.as_ref())?;
        }
        Ok(())
    }

    /// The state after the steps taken so far.
    pub fn state(&self) -> &Phase<T, S> {
        &self.state
    }

    /// The state, giving up the stepper.
    pub fn into_state(self) -> Phase<T, S> {
        self.state
    }

    /// The degrees of freedom `theta`.
    pub fn theta(&self) -> &S {
        &self.state.theta
    }

    /// Their rates `omega = dtheta/dt`.
    pub fn omega(&self) -> &S {
        &self.state.omega
    }

    /// `dV/dtheta` at the current state.
    pub fn gradient(&self) -> &S {
        &self.gradient
    }

    /// The time step.
    pub fn dt(&self) -> T {
        self.dt
    }

    /// Steps taken (saturating).
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Kinetic energy `sum_i I_i omega_i^2 / 2`.
    pub fn kinetic_energy<M: Potential<T> + ?Sized>(&self, model: &M) -> T {
        kinetic_energy(model, self.state.omega.as_ref())
    }

    /// Potential energy `V(theta)`: the one evaluated with the last gradient when the stepper
    /// tracks it ([`Verlet::damped`]), else evaluated now.
    pub fn potential_energy<M: Potential<T> + ?Sized>(&self, model: &M) -> T {
        self.potential.unwrap_or_else(|| model.energy(self.state.theta.as_ref()))
    }

    /// The energy `E = T + V` now, checked against `reference` (the energy right after the
    /// launch, say): [`IntegrateError::EnergyDrift`] if `|E - reference| > tolerance`, else `E`.
    ///
    /// [`Verlet::step`] checks only that the state stays finite. A `dt` past the stability limit
    /// (`omega_max dt >= 2` for the model's fastest phonon) makes the energy grow step after step
    /// while every number stays finite: the 16-rotor kink of docs/embedded.md, launched with
    /// `E = 2`, has `E = 3e12` after 100 steps at `dt = 10` and `1e14` after 10^4, without a NaN
    /// (measured). Verlet's error at a stable step is a bounded oscillation of order
    /// `(omega dt)^2` times the energy (Hairer, Lubich and Wanner, Sec. IX.8), so a tolerance of a
    /// few percent of the launch energy separates the two. It costs one energy evaluation when
    /// the stepper does not track the energy; call it every few hundred steps, as the runs do at
    /// their outputs with their 10 % energy limit.
    pub fn check_energy<M: Potential<T> + ?Sized>(
        &self,
        model: &M,
        reference: T,
        tolerance: T,
    ) -> Result<T, IntegrateError> {
        let energy = self.kinetic_energy(model) + self.potential_energy(model);
        // Written so that a NaN energy, reference or tolerance fails too.
        if (energy - reference).abs() <= tolerance {
            Ok(energy)
        } else {
            Err(IntegrateError::EnergyDrift {
                step: self.steps,
                energy: energy.widen(),
                reference: reference.widen(),
                tolerance: tolerance.widen(),
                dt: self.dt.widen(),
            })
        }
    }
}

/// `T = sum_i I_i omega_i^2 / 2`.
///
/// # Panics
/// If `omega` has fewer than `dof_count()` entries (a programming error, as for the slice
/// methods of [`Potential`]; [`Phase::check`] tells beforehand).
pub fn kinetic_energy<T: Real, M: Potential<T> + ?Sized>(model: &M, omega: &[T]) -> T {
    let n = model.dof_count();
    T::of(0.5) * omega[..n].iter().enumerate().fold(T::ZERO, |s, (i, &w)| s + model.inertia(i) * w * w)
}
