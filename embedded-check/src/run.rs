//! The kink run: build a kink by the branch solve, launch it along its translation mode, step it
//! with velocity Verlet, and observe wall positions and energies at fixed intervals.
//!
//! The firmware and the host harness both call [`run`] with [`Scenario::FIRMWARE`], so the two
//! cannot drift apart: the only differences left between the Cortex-M run and the host run are
//! the machine's arithmetic and its `sin`/`cos`/`atan2`/`sqrt`.

use rotor_chain::embedded::{
    ChainGeometry, Charge, DomainWalls, DynamicsError, Phase, Real, Verlet, Wall, kink_into,
    kink_launch_velocities,
};
use rotor_chain::statics::StaticsError;

/// At most this many walls are recorded per sample ([`Sample::wall_count`] counts all of them).
pub const MAX_WALLS: usize = 4;

/// What to run. Units as in docs/theory.md §3: `a = 1`, `M = 1`, time in the unit `t` of paper
/// Appendix B.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scenario {
    /// Where the kink starts: its Appendix C wall position, in rotor indices.
    pub centre: f64,
    /// Launch speed amplitude `v0` (tip speed along the translation mode, in `a / t`): the
    /// initial kinetic energy is `M v0^2 / 2`.
    pub v0: f64,
    /// Verlet time step.
    pub dt: f64,
    /// Number of steps.
    pub steps: u32,
    /// A [`Sample`] every this many steps (and at step 0 and after the last step).
    pub every: u32,
}

impl Scenario {
    /// The run of the firmware and of its check on the host, for the 16-rotor chain
    /// [`Chain16`](crate::Chain16) (`k = 1e4`, `M = 1`, `r = 0.8`, `theta_bar = 0.58`):
    ///
    /// - `centre = 4.25`: a fractional centre, so the bisection of the kink construction runs too;
    /// - `v0 = 2`: kinetic energy `M v0^2 / 2 = 2`; the kink then moves about 3.8 sites per unit
    ///   time and ends near rotor 12, inside the chain;
    /// - `dt = 2^-9 = 1.953125e-3`: a power of two, so that `step * dt` is exact and a reference
    ///   integrator reaches the same times; `omega_max dt <= 0.2` for Gershgorin's bound
    ///   `omega_max <= 101.5 / t` on this kink, the accuracy margin of `VerletOptions::DEFAULT_SAFETY`
    ///   (stability needs `< 2`);
    /// - `1024` steps (`t = 2`), a sample every `64` steps: 17 samples.
    pub const FIRMWARE: Scenario =
        Scenario { centre: 4.25, v0: 2.0, dt: 1.953125e-3, steps: 1024, every: 64 };

    /// `Ok` if every parameter is in range for a chain of `n` rotors.
    pub fn check(&self, n: usize) -> Result<(), DynamicsError> {
        let max = n.saturating_sub(1) as f64;
        if !(self.centre.is_finite() && (0.0..=max).contains(&self.centre)) {
            return Err(StaticsError::CentreOutOfRange { centre: self.centre, n, max }.into());
        }
        let rule = |ok: bool, name, value, rule| {
            if ok {
                Ok(())
            } else {
                Err(DynamicsError::InvalidSetup { options: "Scenario", name, value, rule })
            }
        };
        rule(self.v0.is_finite() && self.v0 >= 0.0, "v0", self.v0, "finite and >= 0")?;
        rule(self.dt.is_finite() && self.dt > 0.0, "dt", self.dt, "positive and finite")?;
        rule(self.every > 0, "every", f64::from(self.every), "at least 1")
    }

    /// The time after `step` steps (exact when `dt` is a power of two).
    pub fn time(&self, step: u32) -> f64 {
        f64::from(step) * self.dt
    }
}

/// The chain observed after a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample<T> {
    /// Verlet steps taken.
    pub step: u64,
    /// `step * dt`.
    pub time: f64,
    /// `sum_i I_i omega_i^2 / 2`.
    pub kinetic: T,
    /// `V(theta)`.
    pub potential: T,
    /// How many domain walls the configuration has.
    pub wall_count: usize,
    /// The first `min(wall_count, MAX_WALLS)` of them, left to right; the rest is padding.
    pub walls: [Wall<T>; MAX_WALLS],
}

impl<T: Real> Sample<T> {
    /// The recorded walls.
    pub fn walls(&self) -> &[Wall<T>] {
        &self.walls[..self.wall_count.min(MAX_WALLS)]
    }

    /// `kinetic + potential`.
    pub fn energy(&self) -> T {
        self.kinetic + self.potential
    }

    /// The same sample with every number widened to `f64` (exactly): to compare an `f32` run
    /// with an `f64` one.
    pub fn widen(&self) -> Sample<f64> {
        Sample {
            step: self.step,
            time: self.time,
            kinetic: self.kinetic.widen(),
            potential: self.potential.widen(),
            wall_count: self.wall_count,
            walls: self.walls.map(|w| Wall { position: w.position.widen(), charge: w.charge }),
        }
    }

    /// The sample of `stepper`'s state.
    pub fn of<M: ChainGeometry<T> + ?Sized, const N: usize>(
        model: &M,
        stepper: &Verlet<T, [T; N]>,
        time: f64,
    ) -> Self {
        let mut walls = [Wall { position: T::ZERO, charge: Charge::Kink }; MAX_WALLS];
        let mut wall_count = 0;
        for wall in DomainWalls::of(stepper.theta()) {
            if let Some(slot) = walls.get_mut(wall_count) {
                *slot = wall;
            }
            wall_count += 1;
        }
        Self {
            step: stepper.steps(),
            time,
            kinetic: stepper.kinetic_energy(model),
            potential: stepper.potential_energy(model),
            wall_count,
            walls,
        }
    }
}

/// The energy monitor of a whole run, from its samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary<T> {
    /// Verlet steps taken.
    pub steps: u64,
    /// `E = T + V` at step 0.
    pub energy_initial: T,
    /// `E` after the last step.
    pub energy_final: T,
    /// The largest `|E - E0|` over the samples (Verlet's bounded energy oscillation).
    pub max_energy_error: T,
}

impl<T: Real> Summary<T> {
    /// The same summary widened to `f64` (exactly).
    pub fn widen(&self) -> Summary<f64> {
        Summary {
            steps: self.steps,
            energy_initial: self.energy_initial.widen(),
            energy_final: self.energy_final.widen(),
            max_energy_error: self.max_energy_error.widen(),
        }
    }
}

/// Builds the kink of `scenario` in `model`, launches it, steps it, and hands a [`Sample`] to
/// `observer` at step 0, every `scenario.every` steps and after the last step.
pub fn run<T, M, F, const N: usize>(
    model: &M,
    scenario: &Scenario,
    mut observer: F,
) -> Result<Summary<T>, DynamicsError>
where
    T: Real,
    M: ChainGeometry<T> + ?Sized,
    F: FnMut(&Sample<T>),
{
    if model.rotor_count() != N {
        return Err(StaticsError::WrongLength { what: "theta", len: N, expected: model.rotor_count() }.into());
    }
    scenario.check(N)?;
    let mut stepper = launched_kink::<T, M, N>(model, scenario)?;
    let first = Sample::of(model, &stepper, 0.0);
    observer(&first);
    let energy_initial = first.energy();
    let mut summary =
        Summary { steps: 0, energy_initial, energy_final: energy_initial, max_energy_error: T::ZERO };
    for step in 1..=scenario.steps {
        stepper.step(model)?;
        if step % scenario.every == 0 || step == scenario.steps {
            let sample = Sample::of(model, &stepper, scenario.time(step));
            observer(&sample);
            let energy = sample.energy();
            summary.energy_final = energy;
            summary.max_energy_error = summary.max_energy_error.max((energy - energy_initial).abs());
        }
    }
    summary.steps = stepper.steps();
    Ok(summary)
}

/// The kink of `scenario` (centre, speed) with a Verlet stepper at its `dt`, before the first
/// step.
pub fn launched_kink<T, M, const N: usize>(
    model: &M,
    scenario: &Scenario,
) -> Result<Verlet<T, [T; N]>, DynamicsError>
where
    T: Real,
    M: ChainGeometry<T> + ?Sized,
{
    scenario.check(N)?;
    let mut theta = [T::ZERO; N];
    kink_into(model, T::of(scenario.centre), &mut theta)?;
    let omega = kink_launch_velocities(model, &theta, T::of(scenario.v0))?;
    Ok(Verlet::new(model, Phase { time: T::ZERO, theta, omega }, T::of(scenario.dt))?)
}
