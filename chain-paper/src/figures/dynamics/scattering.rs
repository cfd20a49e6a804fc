//! Sec. VI: single scattering runs on a stiffness impurity, as space-time images (`fig:k-scatter`,
//! `fig:ak-scatter`), and the transmitted antikink's speed after against before the impurity;
//! the runs and ranges are [`Scattering`](super::Scattering)'s.

use chain_sweep::Axis;
use rayon::prelude::*;
use rotor_chain::dynamics::observe::{mean_speed, passage_speeds, propagation};
use rotor_chain::dynamics::run::{RunOptions, propagate};
use rotor_chain::dynamics::scatter::{Outcome, ScatterSetup, Scattering, scatter};
use rotor_chain::dynamics::track::{Snapshot, SpaceTime};
use rotor_chain::statics::walls::Charge;

use super::{chain, middle_spring, percent, space_time_map};
use crate::figures::{Cause, FigureError, Params};
use crate::model::{Chart, Figure, Panel, Quality, Quantity, Row, Series, Style};

/// The outcomes the paper reports (Sec. VI, Figs. `fig:k-scatter`, `fig:ak-scatter`), for the
/// summary rows: `(defect, v0, k_i/k, outcome)`.
const PAPER_OUTCOMES: [(Charge, f64, f64, Outcome); 5] = [
    (Charge::Kink, 4.0, 0.10, Outcome::Transmitted),
    (Charge::Kink, 9.6, 0.01, Outcome::Split),
    (Charge::Antikink, 4.0, 0.80, Outcome::Transmitted),
    (Charge::Antikink, 4.0, 0.70, Outcome::Trapped),
    (Charge::Antikink, 4.8, 0.20, Outcome::Reflected),
];

/// The outcome the paper reports for `charge` at `(v0, k_i/k)`, if it reports one.
fn paper_outcome(charge: Charge, v0: f64, ki: f64) -> Option<Outcome> {
    PAPER_OUTCOMES.iter().find(|p| p.0 == charge && p.1 == v0 && p.2 == ki).map(|p| p.3)
}

/// One scattering experiment of Sec. VI, with its space-time image continued after the outcome is
/// decided for `after` times the time it took (so the products can be seen moving apart).
struct Event {
    result: Scattering,
    image: SpaceTime,
    /// The interior walls at the image's last time, e.g. `kink 12.3, antikink 29.5`.
    walls_at_end: String,
}

/// The interior walls of a snapshot, left to right.
fn describe_walls(snapshot: Option<&Snapshot>) -> String {
    let Some(s) = snapshot else { return "none".to_owned() };
    let walls: Vec<String> = s
        .walls
        .iter()
        .zip(&s.at_boundary)
        .filter(|(_, b)| !**b)
        .map(|(w, _)| {
            let name = if w.charge == Charge::Kink { "kink" } else { "antikink" };
            format!("{name} {:.1}", w.position)
        })
        .collect();
    if walls.is_empty() { "none".to_owned() } else { walls.join(", ") }
}

fn scatter_event(
    params: &Params,
    charge: Charge,
    v0: f64,
    ki_ratio: f64,
    after: f64,
) -> Result<Event, Cause> {
    let model = chain(params, params.scattering.theta_bar, Some(ki_ratio))?;
    let mut setup = ScatterSetup::from_the_right(charge, v0, middle_spring(params));
    setup.run.space_time = true;
    let result = scatter(&model, &setup)?;
    let mut image = result.run.space_time.clone();
    let mut walls_at_end = describe_walls(result.run.tracker.snapshots.last());
    let state = result.run.final_state.clone();
    if after > 0.0 {
        let t_max = state.time * (1.0 + after);
        let options = RunOptions { t_max, space_time: true, ..setup.run };
        let more = propagate(&model, state, &options, &mut |_| false)?;
        // The continuation's first output is the scattering run's last.
        for (t, theta) in more.space_time.times.iter().zip(&more.space_time.theta).skip(1) {
            image.push(*t, theta);
        }
        walls_at_end = describe_walls(more.tracker.snapshots.last());
    }
    Ok(Event { result, image, walls_at_end })
}

/// A scattering figure: one space-time image and one row per `(v0, k_i/k)`.
fn scatter_figure(
    label: &'static str,
    params: &Params,
    quality: Quality,
    charge: Charge,
    points: &[(f64, f64)],
) -> Result<Figure, FigureError> {
    let theta_bar = params.scattering.theta_bar;
    let name = match charge {
        Charge::Kink => "kink",
        Charge::Antikink => "antikink",
    };
    // The image continues after the decision for half as long again (full) or a quarter (quick),
    // so the products are seen moving apart.
    let after = match quality {
        Quality::Full => 0.5,
        Quality::Quick => 0.25,
    };
    let events: Vec<Result<Event, Cause>> =
        points.par_iter().map(|&(v0, ki)| scatter_event(params, charge, v0, ki, after)).collect();
    let mut panels = Vec::new();
    let mut rows = Vec::new();
    for (&(v0, ki), event) in points.iter().zip(events) {
        let event = event.map_err(|e| FigureError::new(label, e).at("v0", v0).at("k_i/k", ki))?;
        let ours = event.result.outcome;
        let paper = paper_outcome(charge, v0, ki);
        rows.push(Row::words(
            format!("{name} on an impurity, v0 = {v0}, k_i/k = {ki}, θ̄ = {theta_bar}"),
            paper.map_or("not in the paper", Outcome::name),
            ours.name(),
            format!(
                "decided at t = {:.2}{}; walls at the image's end (t = {:.2}): {}",
                event.result.decided_at,
                if paper.is_none_or(|p| p == ours) { "" } else { " (differs from the paper)" },
                event.image.times.last().copied().unwrap_or(0.0),
                event.walls_at_end
            ),
        ));
        panels.push(Chart::Heat(space_time_map(
            format!("{name}, v0 = {v0}, k_i/k = {ki}: {}", ours.name()),
            &event.image,
            theta_bar,
        )));
    }
    Ok(Figure {
        label,
        caption: format!(
            "Space-time images θ_i(t) of {} {name} scattering on an impurity of stiffness k_i (spring {}, \
             incoming from the right): θ̄ = {theta_bar}, n = {}, r/a = {}, k = {}, M = {}",
            if name.starts_with('a') { "an" } else { "a" },
            middle_spring(params),
            params.n,
            params.r,
            params.k,
            params.mass
        ),
        panels,
        rows,
    })
}

/// Paper Fig. `fig:k-scatter`: a kink transmitted at `(v0, k_i/k) = (4.0, 0.10)` and split at
/// `(9.6, 0.01)`, `theta_bar = 0.28` ([`Scattering::kink_runs`](super::Scattering::kink_runs)).
pub fn k_scatter(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    scatter_figure("fig:k-scatter", params, quality, Charge::Kink, &params.scattering.kink_runs)
}

/// Paper Fig. `fig:ak-scatter`: an antikink transmitted at `(v0, k_i/k) = (4.0, 0.80)`, trapped at
/// `(4.0, 0.70)` and reflected at `(4.8, 0.20)`, `theta_bar = 0.28`; and the paper's "for `k_i/k`
/// near 1, the antikink gets transmitted with energy dissipation and thus slows down": the
/// speed after the impurity over the speed before, against `k_i/k`. The runs and ranges are
/// [`Scattering`](super::Scattering)'s `antikink_runs`, `slowing_ki` and `slowing_v0s`.
pub fn ak_scatter(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:ak-scatter";
    let s = &params.scattering;
    let mut figure = scatter_figure(LABEL, params, quality, Charge::Antikink, &s.antikink_runs)?;
    let kis: Vec<f64> = Axis::linspace(s.slowing_ki.0, s.slowing_ki.1, quality.pick(25, 5))
        .map_err(FigureError::on(LABEL))?
        .values()
        .to_vec();
    let v0s = &s.slowing_v0s;
    let cases: Vec<(f64, f64)> = v0s.iter().flat_map(|&v0| kis.iter().map(move |&ki| (v0, ki))).collect();
    let ratios: Vec<Option<f64>> = cases
        .par_iter()
        .map(|&(v0, ki)| slowing(params, v0, ki))
        .collect::<Result<_, Cause>>()
        .map_err(FigureError::on(LABEL))?;
    let series: Vec<Series> = v0s
        .iter()
        .enumerate()
        .map(|(k, v0)| {
            let points = kis
                .iter()
                .zip(&ratios[k * kis.len()..(k + 1) * kis.len()])
                .filter_map(|(&ki, r)| r.map(|r| (ki, r)))
                .collect();
            Series::new(
                Quantity::Parameter { index: k, of: v0s.len() },
                format!("v0 = {v0}"),
                points,
                Style::LinePoints,
            )
        })
        .collect();
    let at = |v0: f64, ki: f64| slowing(params, v0, ki).map_err(FigureError::on(LABEL));
    let show = |r: Option<f64>| r.map_or("not transmitted".to_owned(), |r| format!("{r:.3}"));
    let (paper_point, control, stiffer) = (at(4.0, 0.8)?, at(4.0, 1.0)?, at(8.0, 1.2)?);
    figure.rows.push(Row::words(
        format!("transmitted antikink speed after / before the impurity, v0 = 4, k_i/k = 0.8, θ̄ = {}", s.theta_bar),
        "slows down (energy dissipation) for k_i/k near 1",
        &show(paper_point),
        format!(
            "speeds fitted more than 8 sites before and after the impurity; k_i = k: {} (no impurity, no slowing); \
             v0 = 8, k_i/k = 1.2: {}",
            show(control),
            show(stiffer)
        ),
    ));
    // Ratios above 1: set against the antikink's own speed swing along a perfect chain.
    let above: Vec<(f64, f64, f64)> = cases
        .iter()
        .zip(&ratios)
        .filter_map(|(&(v0, ki), r)| r.filter(|&r| r > 1.0).map(|r| (v0, ki, r)))
        .collect();
    if let Some(&(v0, ki, most)) = above.iter().max_by(|a, b| a.2.total_cmp(&b.2)) {
        let swing = speed_swing(params, v0).map_err(FigureError::on(LABEL))?;
        let against = match swing {
            Some(swing) if most - 1.0 <= swing => format!(
                "within the swing of the antikink's own speed along a perfect chain at that v0 ({}: its \
                 translation trades energy with its internal motion, which a nearly neutral impurity shifts)",
                percent(swing)
            ),
            Some(swing) => {
                format!("beyond the swing of its own speed along a perfect chain ({})", percent(swing))
            }
            None => "its speed along a perfect chain could not be fitted".to_owned(),
        };
        figure.caption.push_str(&format!(
            ". Speed ratio above 1 at {} points, at most {most:.4} (v0 = {v0}, k_i/k = {ki:.3}): {against}",
            above.len()
        ));
    }
    figure.panels.push(Chart::Lines(Panel {
        title: "transmitted antikink: speed after / before".to_owned(),
        x_label: "k_i / k".to_owned(),
        y_label: "v_out / v_in".to_owned(),
        series,
        log_y: false,
    }));
    Ok(figure)
}

/// Stretches of the path over which [`speed_swing`] fits a speed, in sites.
const SWING_STRETCH: f64 = 3.0;

/// `(max - min) / mean` of the speeds of an antikink launched as in the scattering runs along a
/// perfect chain, each fitted over [`SWING_STRETCH`] sites, from its start to the end zone
/// (`clear` sites from the end): how much its speed varies with no impurity at all. `None` with
/// fewer than two stretches.
fn speed_swing(params: &Params, v0: f64) -> Result<Option<f64>, Cause> {
    let model = chain(params, params.scattering.theta_bar, None)?;
    let setup = ScatterSetup::from_the_right(Charge::Antikink, v0, middle_spring(params));
    let options = RunOptions { t_max: 20.0, ..RunOptions::default() };
    let p = propagation(&model, setup.charge, setup.start, v0, setup.direction, Some(setup.reach), &options)?;
    let mut speeds = Vec::new();
    let mut high = setup.start - 1.0;
    while high - SWING_STRETCH > setup.clear {
        let stretch: Vec<(f64, f64)> =
            p.positions.iter().copied().filter(|&(_, x)| x <= high && x > high - SWING_STRETCH).collect();
        if let (Some(first), Some(last)) = (stretch.first(), stretch.last()) {
            speeds.extend(mean_speed(&stretch, first.0, last.0).map(f64::abs));
        }
        high -= SWING_STRETCH;
    }
    let mean = speeds.iter().sum::<f64>() / speeds.len().max(1) as f64;
    let (lo, hi) = speeds.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &v| (a.min(v), b.max(v)));
    Ok((speeds.len() >= 2 && mean > 0.0).then(|| (hi - lo) / mean))
}

/// `v_out / v_in` of an antikink launched as in the paper's scattering runs at `(v0, k_i/k)`:
/// `None` unless it was transmitted and seen long enough on both sides.
fn slowing(params: &Params, v0: f64, ki_ratio: f64) -> Result<Option<f64>, Cause> {
    let model = chain(params, params.scattering.theta_bar, Some(ki_ratio))?;
    // The paper's scattering setup: where the antikink starts, how near walls count, the margins.
    let setup = ScatterSetup::from_the_right(Charge::Antikink, v0, middle_spring(params));
    let options = RunOptions { t_max: 20.0, ..RunOptions::default() };
    let p = propagation(&model, setup.charge, setup.start, v0, setup.direction, Some(setup.reach), &options)?;
    let (v_in, v_out) = passage_speeds(
        &p.positions,
        setup.impurity as f64 + 0.5,
        setup.clear,
        (params.n - 1) as f64,
        setup.clear,
        0.1,
    );
    Ok(v_in.zip(v_out).map(|(a, b)| b / a))
}
