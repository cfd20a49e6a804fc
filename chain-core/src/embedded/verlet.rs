//! Velocity Verlet (kick-drift-kick) for `I_i thetadd_i = -dV/dtheta_i`, in fixed-size arrays, in
//! the chain's float type: the one stepper of `f64` and `f32` chains (each macro chain's
//! `verlet()` returns it) and of the firmware.
//!
//! One step of length `dt`:
//!
//! ```text
//! omega += -dt/2 I^-1 dV/dtheta(theta)     (kick)
//! theta += dt omega                         (drift)
//! omega += -dt/2 I^-1 dV/dtheta(theta)     (kick)
//! ```
//!
//! second order, time-reversible and symplectic, so the energy error oscillates with bounded
//! amplitude instead of drifting (Hairer, Lubich and Wanner, *Geometric Numerical Integration*,
//! Secs. I.1.4 and IX.8). The gradient at the end of a step is the one the next step starts with:
//! a step costs **one gradient evaluation** and two sweeps over the rotors.
//!
//! The arithmetic is that of `dynamics::integrate::verlet` without damping, in the same order, so
//! that the two produce the same trajectory (a test compares them); that integrator adds damping,
//! absorbing ends and output schedules, and keeps its state in `Vec`s.

use super::{EmbeddedError, FloatChain, Real};

/// A chain's state `theta`, `omega = dtheta/dt` and the integrator's cached gradient.
#[derive(Clone, Debug)]
pub struct Verlet<T, const N: usize> {
    theta: [T; N],
    omega: [T; N],
    /// `dV/dtheta` at `theta`.
    gradient: [T; N],
    /// `dt / (2 I_i)`: the kick's factor, folded once.
    half_kick: [T; N],
    dt: T,
    steps: u32,
}

impl<T: Real, const N: usize> Verlet<T, N> {
    /// A stepper at `(theta, omega)` with step `dt` (in the time unit `t` of paper Appendix B).
    /// Stability needs `omega_max dt < 2` for the chain's fastest phonon (`dynamics`'
    /// `VerletOptions::stable_for` picks `dt` from a bound on it).
    pub fn new<M: FloatChain<T> + ?Sized>(
        model: &M,
        theta: [T; N],
        omega: [T; N],
        dt: T,
    ) -> Result<Self, EmbeddedError> {
        if model.rotor_count() != N {
            return Err(EmbeddedError::WrongRotorCount { rotors: model.rotor_count(), expected: N });
        }
        if !(dt > T::ZERO && dt.is_finite()) {
            return Err(EmbeddedError::InvalidParameter {
                name: "dt",
                value: dt.widen(),
                rule: "positive and finite",
            });
        }
        let mut half_kick = [T::ZERO; N];
        for (i, c) in half_kick.iter_mut().enumerate() {
            let inertia = model.inertia(i);
            if !(inertia > T::ZERO && inertia.is_finite()) {
                return Err(EmbeddedError::BadInertia { index: i, inertia: inertia.widen() });
            }
            *c = T::of(0.5) * dt * (T::ONE / inertia);
        }
        let mut stepper = Self { theta, omega, gradient: [T::ZERO; N], half_kick, dt, steps: 0 };
        stepper.check_finite("theta", &stepper.theta)?;
        stepper.check_finite("omega", &stepper.omega)?;
        model.gradient_into(&stepper.theta, &mut stepper.gradient);
        stepper.check_finite("gradient", &stepper.gradient)?;
        Ok(stepper)
    }

    /// One velocity-Verlet step. A state that is no longer finite is an error (and stays in the
    /// stepper for inspection).
    pub fn step<M: FloatChain<T> + ?Sized>(&mut self, model: &M) -> Result<(), EmbeddedError> {
        let dt = self.dt;
        for (((t, w), g), c) in
            self.theta.iter_mut().zip(&mut self.omega).zip(&self.gradient).zip(&self.half_kick)
        {
            *w -= *c * *g;
            *t += dt * *w;
        }
        model.gradient_into(&self.theta, &mut self.gradient);
        let mut finite = true;
        for ((w, g), c) in self.omega.iter_mut().zip(&self.gradient).zip(&self.half_kick) {
            *w -= *c * *g;
            finite &= w.is_finite();
        }
        self.steps = self.steps.saturating_add(1);
        if !finite {
            // A NaN force gives a NaN velocity; an unstable step grows both until they overflow.
            self.check_finite("theta", &self.theta)?;
            self.check_finite("omega", &self.omega)?;
        }
        Ok(())
    }

    /// Angles `theta_i`.
    pub fn theta(&self) -> &[T; N] {
        &self.theta
    }

    /// Angular velocities `omega_i = dtheta_i/dt`.
    pub fn omega(&self) -> &[T; N] {
        &self.omega
    }

    /// `dV/dtheta` at the current angles.
    pub fn gradient(&self) -> &[T; N] {
        &self.gradient
    }

    /// The time step.
    pub fn dt(&self) -> T {
        self.dt
    }

    /// Steps taken (saturating at `u32::MAX`).
    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// Kinetic energy `T = sum_i I_i omega_i^2 / 2`.
    pub fn kinetic_energy<M: FloatChain<T> + ?Sized>(&self, model: &M) -> T {
        T::of(0.5) * self.omega.iter().enumerate().fold(T::ZERO, |s, (i, &w)| s + model.inertia(i) * w * w)
    }

    /// Potential energy `V(theta)`.
    pub fn potential_energy<M: FloatChain<T> + ?Sized>(&self, model: &M) -> T {
        model.energy(&self.theta)
    }

    /// The energy `E = T + V` now, checked against `reference` (the energy right after the
    /// launch, say): [`EmbeddedError::EnergyDrift`] if `|E - reference| > tolerance`, else `E`.
    ///
    /// [`step`](Self::step) checks only that the state stays finite. A `dt` past the stability
    /// limit (`omega_max dt >= 2` for the chain's fastest phonon) makes the energy grow step
    /// after step while every number stays finite: the 16-rotor kink of docs/embedded.md,
    /// launched with `E = 2`, has `E = 3e12` after 100 steps at `dt = 10` and `1e14` after 10^4,
    /// without a NaN (measured). Verlet's error at a stable
    /// step is a bounded oscillation of order `(omega dt)^2` times the energy (Hairer, Lubich and
    /// Wanner, Sec. IX.8), so a tolerance of a few percent of the launch energy separates the two.
    /// It costs one energy evaluation (less than a step); call it every few hundred steps, as
    /// `dynamics` does at its outputs with its 10 % `energy_limit`.
    pub fn check_energy<M: FloatChain<T> + ?Sized>(
        &self,
        model: &M,
        reference: T,
        tolerance: T,
    ) -> Result<T, EmbeddedError> {
        let energy = self.kinetic_energy(model) + self.potential_energy(model);
        // Written so that a NaN energy, reference or tolerance fails too.
        if (energy - reference).abs() <= tolerance {
            Ok(energy)
        } else {
            Err(EmbeddedError::EnergyDrift {
                step: self.steps,
                energy: energy.widen(),
                reference: reference.widen(),
                tolerance: tolerance.widen(),
                dt: self.dt.widen(),
            })
        }
    }

    fn check_finite(&self, what: &'static str, v: &[T; N]) -> Result<(), EmbeddedError> {
        match v.iter().position(|x| !x.is_finite()) {
            Some(index) => {
                Err(EmbeddedError::NotFinite { what, step: self.steps, index, value: v[index].widen() })
            }
            None => Ok(()),
        }
    }
}
