//! Propagating a launched defect: the integrator, the wall tracker, the kinetic-energy series and
//! the space-time image, with an early stop once the caller has seen enough.

use alloc::vec::Vec;

use super::DynamicsError;
use super::integrate::{Flow, Report, State, VerletOptions, kinetic_energy, verlet};
use super::track::{Snapshot, SpaceTime, Tracker};
use crate::model::ChainModel;

/// Settings of a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunOptions {
    /// Stop at this time if nothing stopped the run before. Default 20 (the paper's runs).
    pub t_max: f64,
    /// Time between outputs (tracking, energies). Default 0.01.
    pub output_interval: f64,
    /// Verlet step; `None` picks a tenth of the stability limit from the tangent stiffness
    /// ([`VerletOptions::DEFAULT_SAFETY`]).
    pub dt: Option<f64>,
    /// Viscous damping `gamma` (0: conservative). Default 0.
    pub damping: f64,
    /// Keep the angles at every output for a space-time image. Default `false`.
    pub space_time: bool,
}

impl Default for RunOptions {
    fn default() -> Self {
        Self { t_max: 20.0, output_interval: 0.01, dt: None, damping: 0.0, space_time: false }
    }
}

/// What a run recorded.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    pub tracker: Tracker,
    /// `(t, kinetic energy)` at every output (paper Fig. `fig:ketimeplot`).
    pub kinetic: Vec<(f64, f64)>,
    pub space_time: SpaceTime,
    pub report: Report,
    pub final_state: State,
}

/// Runs `state` with velocity Verlet, recording at every output and asking `stop` after each
/// snapshot whether to end the run.
pub fn propagate<M: ChainModel + ?Sized>(
    model: &M,
    mut state: State,
    options: &RunOptions,
    stop: &mut dyn FnMut(&Snapshot) -> bool,
) -> Result<Run, DynamicsError> {
    let dt = match options.dt {
        Some(dt) => dt,
        None => VerletOptions::stable_for(model, &state.theta, VerletOptions::DEFAULT_SAFETY)?.dt,
    };
    // A whole number of steps per output, and a whole number of outputs up to the end, so every
    // output lands on a multiple of the output interval.
    let every = libm::ceil(options.output_interval / dt).max(1.0) as usize;
    let dt = options.output_interval / every as f64;
    let t_end = state.time
        + libm::ceil((options.t_max - state.time) / options.output_interval) * options.output_interval;
    let mut tracker = Tracker::new(&state.theta);
    let mut kinetic = Vec::new();
    let mut space_time = SpaceTime::default();
    // Verlet calls the observer on the initial state and after every `every` steps.
    let report =
        verlet(model, &mut state, t_end, &VerletOptions { dt, damping: options.damping }, every, &mut |s| {
            kinetic.push((s.time, kinetic_energy(model, &s.omega)));
            if options.space_time {
                space_time.push(s.time, &s.theta);
            }
            if stop(tracker.record(s.time, &s.theta)) { Flow::Stop } else { Flow::Continue }
        })?;
    Ok(Run { tracker, kinetic, space_time, report, final_state: state })
}
