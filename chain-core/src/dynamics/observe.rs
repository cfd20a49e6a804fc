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
    /// The whole run.
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

/// The least-squares slope `dx/dt` of the samples `(t, x)` with `t` in `[t_from, t_to]`, in sites
/// per time unit; `None` with fewer than two samples or no spread in `t`.
pub fn mean_speed(positions: &[(f64, f64)], t_from: f64, t_to: f64) -> Option<f64> {
    let window: Vec<&(f64, f64)> = positions.iter().filter(|(t, _)| *t >= t_from && *t <= t_to).collect();
    if window.len() < 2 {
        return None;
    }
    let count = window.len() as f64;
    let (mean_t, mean_x) = window.iter().fold((0.0, 0.0), |(a, b), (t, x)| (a + t / count, b + x / count));
    let (mut stt, mut stx) = (0.0, 0.0);
    for (t, x) in window {
        stt += (t - mean_t) * (t - mean_t);
        stx += (t - mean_t) * (x - mean_x);
    }
    (stt > 0.0).then(|| stx / stt)
}

/// The speeds of a defect before and after it passed an impurity centred at `x_imp`: fitted
/// (see [`mean_speed`]) while it was farther than `clear` from the impurity on its incoming side,
/// and on its far side from `clear` until `margin` sites from the end it is heading for. `None`
/// for a side it was not seen on for at least `min_time`.
pub fn passage_speeds(
    positions: &[(f64, f64)],
    x_imp: f64,
    clear: f64,
    last_rotor: f64,
    margin: f64,
    min_time: f64,
) -> (Option<f64>, Option<f64>) {
    let Some(&(_, start)) = positions.first() else { return (None, None) };
    let side = if start > x_imp { 1.0 } else { -1.0 };
    let far_end = if side > 0.0 { 0.0 } else { last_rotor };
    let incoming: Vec<(f64, f64)> =
        positions.iter().copied().take_while(|(_, x)| (x - x_imp) * side > clear).collect();
    let outgoing: Vec<(f64, f64)> = positions
        .iter()
        .copied()
        .skip_while(|(_, x)| (x - x_imp) * side > -clear)
        .take_while(|(_, x)| (x - far_end).abs() > margin)
        .collect();
    let fit = |samples: &[(f64, f64)]| match (samples.first(), samples.last()) {
        (Some(a), Some(b)) if b.0 - a.0 >= min_time => mean_speed(samples, a.0, b.0).map(f64::abs),
        _ => None,
    };
    (fit(&incoming), fit(&outgoing))
}

/// What [`damping_to_stop_at`] found.
#[derive(Clone, Debug, PartialEq)]
pub struct DampingSearch {
    /// The damping rate `gamma` (in `1 / t`) of the last bracket's upper end: the smallest found
    /// that stops the defect before the target.
    pub damping: f64,
    /// When and where the defect stopped with that damping ([`stopping_point`]).
    pub stopped_at: (f64, f64),
    /// The bracket `[below, above]` left after the search: with `below` the defect stops past the
    /// target (or not at all), with `above` before it.
    pub bracket: (f64, f64),
    /// Bisection steps taken.
    pub iterations: usize,
    /// The run with [`DampingSearch::damping`].
    pub propagation: Propagation,
}

/// The uniform damping rate `gamma` at which a `charge` defect launched at `start` with speed
/// `v0` towards `direction` stops (stays within `tolerance` sites for `window` time units, see
/// [`stopping_point`]) at `target`: a bisection on `ln gamma` within `bracket`, `iterations`
/// halvings. More damping stops the defect sooner, so the distance travelled falls with `gamma`;
/// the Peierls-Nabarro wells make it fall in steps of one site, and the search ends on the step
/// that brackets the target. Used for paper Fig. `fig:akpntrapprofile`, whose trapped antikink
/// needs a damping the paper does not mention (docs/dynamics.md §4).
#[allow(clippy::too_many_arguments)]
pub fn damping_to_stop_at<M: ChainModel + ?Sized>(
    model: &M,
    charge: Charge,
    start: f64,
    v0: f64,
    direction: Direction,
    target: f64,
    bracket: (f64, f64),
    iterations: usize,
    window: f64,
    tolerance: f64,
    options: &RunOptions,
) -> Result<DampingSearch, DynamicsError> {
    let (mut low, mut high) = bracket;
    if !(low > 0.0 && high > low && high.is_finite()) {
        return Err(DynamicsError::InvalidSetup {
            options: "damping_to_stop_at",
            name: "bracket",
            value: low,
            rule: "0 < low < high, finite",
        });
    }
    let goal = (target - start).abs();
    // The distance the defect travels before it stops (infinite if it does not), where and when
    // it stopped, and the run.
    type Travel = (f64, Option<(f64, f64)>, Propagation);
    let travel = |gamma: f64| -> Result<Travel, DynamicsError> {
        let options = RunOptions { damping: gamma, ..*options };
        let p = propagation(model, charge, start, v0, direction, Some(4.0), &options)?;
        Ok(match stopping_point(&p.positions, window, tolerance) {
            Some((t, d)) => {
                let x = p.positions.iter().find(|(s, _)| *s >= t).map_or(f64::NAN, |&(_, x)| x);
                (d, Some((t, x)), p)
            }
            None => (f64::INFINITY, None, p),
        })
    };
    if travel(low)?.0 <= goal {
        return Err(DynamicsError::InvalidSetup {
            options: "damping_to_stop_at",
            name: "bracket low",
            value: low,
            rule: "so small that the defect passes the target",
        });
    }
    let mut best = travel(high)?;
    if best.0 > goal {
        return Err(DynamicsError::InvalidSetup {
            options: "damping_to_stop_at",
            name: "bracket high",
            value: high,
            rule: "so large that the defect stops before the target",
        });
    }
    for _ in 0..iterations {
        let mid = crate::math::sqrt(low * high);
        let result = travel(mid)?;
        if result.0 > goal {
            low = mid;
        } else {
            high = mid;
            best = result;
        }
    }
    let (_, stopped, propagation) = best;
    Ok(DampingSearch {
        damping: high,
        stopped_at: stopped.unwrap_or((f64::NAN, f64::NAN)),
        bracket: (low, high),
        iterations,
        propagation,
    })
}

/// Whether a defect stays one wall as it runs along a perfect chain (paper Sec. VI: "the maximum
/// initial velocity with which we can launch an antikink is around 12. Above this, the antikink
/// itself becomes unstable and tends to quickly disintegrate").
#[derive(Clone, Debug, PartialEq)]
pub struct Stability {
    /// The most walls not born at a free end seen at once.
    pub most_walls: usize,
    /// When three walls or more were first seen, if ever.
    pub first_extra: Option<f64>,
    /// The longest time three walls or more were seen without a break.
    pub longest_extra: f64,
    /// Where the launched defect was at the end of the observation.
    pub reached: f64,
}

/// Launches `charge` at `start` with `v0` towards `direction` in `model` and counts its walls
/// (walls born at a free end left out, [`super::scatter::Follower`]) until it comes within
/// `margin` sites of the end ahead, or `options.t_max`.
pub fn stability<M: ChainModel + ?Sized>(
    model: &M,
    charge: Charge,
    start: f64,
    v0: f64,
    direction: Direction,
    margin: f64,
    options: &RunOptions,
) -> Result<Stability, DynamicsError> {
    use super::scatter::{Follower, Origin};
    let n = model.rotor_count();
    let last = n.saturating_sub(1) as f64;
    let launched = launch(model, charge, start, v0, direction)?;
    // A wall unseen for five outputs has vanished (0.05 t at the default interval): in outputs, so
    // that a run in another time unit (its interval scaled with it) follows the same walls.
    let mut follower = Follower::new(n, 4.0, 3.0, 5.0 * options.output_interval);
    let mut result =
        Stability { most_walls: 0, first_extra: None, longest_extra: 0.0, reached: launched.position };
    let mut since: Option<f64> = None;
    let mut nearest = launched.position;
    let mut stop = |s: &super::track::Snapshot| -> bool {
        follower.update(s);
        let walls: Vec<f64> =
            follower.walls.iter().filter(|w| w.origin != Origin::End).map(|w| w.position).collect();
        result.most_walls = result.most_walls.max(walls.len());
        if walls.len() >= 3 {
            result.first_extra.get_or_insert(s.time);
            let t0 = *since.get_or_insert(s.time);
            result.longest_extra = result.longest_extra.max(s.time - t0);
        } else {
            since = None;
        }
        if let Some(x) = s.interior(charge).min_by(|a, b| (a - nearest).abs().total_cmp(&(b - nearest).abs()))
        {
            nearest = x;
        }
        result.reached = nearest;
        match direction {
            Direction::Left => nearest < margin,
            Direction::Right => nearest > last - margin,
        }
    };
    propagate(model, launched.state, options, &mut stop)?;
    Ok(result)
}
