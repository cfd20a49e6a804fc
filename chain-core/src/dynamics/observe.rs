//! Observables of a propagating defect (paper Sec. V): its trajectory, the kinetic energy
//! (Fig. `fig:ketimeplot`), Peierls-Nabarro trapping of a slow antikink (Fig.
//! `fig:akpntrapprofile`), and reflection at a free end.

use alloc::vec::Vec;

use super::DynamicsError;
use super::launch::{Direction, launch};
use super::run::{Run, RunOptions, propagate};
use crate::model::ChainModel;
use crate::statics::walls::Charge;

/// A defect launched in a perfect chain, followed wall by wall.
#[derive(Clone, Debug, PartialEq)]
pub struct Propagation {
    /// `(t, x)`: the interior wall of the launched charge nearest to its previous position.
    pub positions: Vec<(f64, f64)>,
    pub run: Run,
}

/// Launches `charge` at `start` with speed `v0` towards `direction` and follows it until `t_max`
/// or until `stop_at_end` sites from a free end.
pub fn propagation<M: ChainModel + ?Sized>(
    model: &M,
    charge: Charge,
    start: f64,
    v0: f64,
    direction: Direction,
    stop_at_end: Option<f64>,
    options: &RunOptions,
) -> Result<Propagation, DynamicsError> {
    let n = model.rotor_count() as f64;
    let launched = launch(model, charge, start, v0, direction)?;
    let mut positions: Vec<(f64, f64)> = Vec::new();
    let mut last = launched.position;
    let mut stop = |s: &super::track::Snapshot| -> bool {
        let nearest = s.interior(charge).min_by(|a, b| (a - last).abs().total_cmp(&(b - last).abs()));
        if let Some(x) = nearest {
            last = x;
            positions.push((s.time, x));
        }
        matches!(stop_at_end, Some(m) if last < m || last > n - 1.0 - m)
    };
    let run = propagate(model, launched.state, options, &mut stop)?;
    Ok(Propagation { positions, run })
}

/// `(max - min) / mean` of the kinetic energy between `t_from` and `t_to` (paper Fig.
/// `fig:ketimeplot`: small for the kink, large for the antikink).
pub fn kinetic_energy_variation(run: &Run, t_from: f64, t_to: f64) -> f64 {
    let window: Vec<f64> =
        run.kinetic.iter().filter(|(t, _)| *t >= t_from && *t <= t_to).map(|(_, k)| *k).collect();
    if window.is_empty() {
        return 0.0;
    }
    let (min, max) =
        window.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &k| (a.min(k), b.max(k)));
    let mean = window.iter().sum::<f64>() / window.len() as f64;
    (max - min) / mean
}

/// Where a defect stopped: the first time after which its position stays within `tolerance`
/// sites for `window` time units, and the distance it travelled from its start until then
/// (paper Fig. `fig:akpntrapprofile`). `None` if it never stops.
pub fn stopping_point(positions: &[(f64, f64)], window: f64, tolerance: f64) -> Option<(f64, f64)> {
    let start = positions.first()?.1;
    for (i, &(t0, x0)) in positions.iter().enumerate() {
        let later: Vec<&(f64, f64)> = positions[i..].iter().take_while(|(t, _)| *t <= t0 + window).collect();
        let spans = later.last().is_some_and(|(t, _)| *t >= t0 + window * 0.999);
        if spans && later.iter().all(|(_, x)| (x - x0).abs() <= tolerance) {
            return Some((t0, (x0 - start).abs()));
        }
    }
    None
}
