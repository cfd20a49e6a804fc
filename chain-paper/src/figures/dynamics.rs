//! Figures of the paper's dynamics (Secs. V and VI, see [`super::all`]): the kinetic energy of a
//! moving kink and antikink (`fig:ketimeplot`), Peierls-Nabarro trapping of a slow antikink
//! (`fig:akpntrapprofile`), scattering on a stiffness impurity (`fig:k-scatter`, `fig:ak-scatter`)
//! and the scattering phase diagrams (`fig:phasediagram`).
//!
//! Space-time images show the alternately measured angles `theta_i` (one sign per domain), rows
//! are output times, columns rotors. Scattering runs follow the paper's setup (Sec. VI): the
//! impurity is the middle spring `(n - 1) / 2`, the defect starts 15 sites to its right and moves
//! left ([`ScatterSetup::from_the_right`]).

use chain_sweep::scattering::{Defect, PhaseDiagram};
use chain_sweep::{Axis, Grid, compute_grid};
use rayon::prelude::*;
use rotor_chain::RuntimeChain;
use rotor_chain::dynamics::launch::Direction;
use rotor_chain::dynamics::observe::{
    Propagation, damping_to_stop_at, kinetic_energy_variation, mean_speed, passage_speeds, propagation,
    stability, stopping_point,
};
use rotor_chain::dynamics::run::{RunOptions, propagate};
use rotor_chain::dynamics::scatter::{Outcome, ScatterSetup, Scattering, scatter};
use rotor_chain::dynamics::track::{Snapshot, SpaceTime};
use rotor_chain::statics::continuum::ContinuumChain;
use rotor_chain::statics::walls::Charge;

use rotor_chain::ParameterError;
use rotor_chain::statics::antikink::{AntikinkOptions, peierls_nabarro};

use super::{Cause, FigureError, FigureFn, Params};
use crate::model::{Chart, Figure, Heatmap, Panel, Quality, Quantity, Row, Series, Style, format_number};

/// This module's figures, in the paper's order.
pub fn figures() -> Vec<(&'static str, FigureFn)> {
    vec![
        ("fig:ketimeplot", ketimeplot),
        ("fig:akpntrapprofile", akpntrapprofile),
        ("fig:k-scatter", k_scatter),
        ("fig:ak-scatter", ak_scatter),
        ("fig:phasediagram", phasediagram),
    ]
}

/// The equilibrium angle of Sec. V (Figs. `fig:ketimeplot`, `fig:akpntrapprofile`).
const THETA_BAR_PROPAGATION: f64 = 0.58;
/// The angle at which our Peierls-Nabarro barrier equals the paper's 0.60 (docs/statics.md).
const THETA_BAR_PAPER_BARRIER: f64 = 0.575132;
/// Where the paper's slow antikink is trapped (Fig. `fig:akpntrapprofile`).
const PAPER_TRAP_ROTOR: f64 = 35.0;
/// The equilibrium angle of Sec. VI (scattering).
pub(crate) const THETA_BAR_SCATTERING: f64 = 0.28;
/// The most rows of a space-time image.
const MAX_IMAGE_ROWS: usize = 400;

fn chain(params: &Params, theta_bar: f64, impurity: Option<f64>) -> Result<RuntimeChain, ParameterError> {
    let mut builder = RuntimeChain::builder(params.n, params.r, params.k, theta_bar).mass(params.mass);
    if let Some(ki_ratio) = impurity {
        builder = builder.spring(middle_spring(params), Some(ki_ratio * params.k), None);
    }
    builder.build()
}

/// The impurity spring of Sec. VI: the middle one.
fn middle_spring(params: &Params) -> usize {
    (params.n - 1) / 2
}

/// `0.97 %`.
fn percent(x: f64) -> String {
    format!("{:.2} %", 100.0 * x)
}

/// The space-time image of `image`, at most [`MAX_IMAGE_ROWS`] rows (every `stride`-th output).
fn space_time_map(title: String, image: &SpaceTime) -> Heatmap {
    let stride = image.times.len().div_ceil(MAX_IMAGE_ROWS).max(1);
    let rows: Vec<usize> = (0..image.times.len()).step_by(stride).collect();
    let n = image.theta.first().map_or(0, Vec::len);
    Heatmap {
        title,
        x_label: "rotor index i".to_owned(),
        y_label: "time t".to_owned(),
        x: (0..n).map(|i| i as f64).collect(),
        y: rows.iter().map(|&r| image.times[r]).collect(),
        values: rows.iter().map(|&r| image.theta[r].clone()).collect(),
        categories: Vec::new(),
        value_label: "θ (rad)".to_owned(),
    }
}

// --- fig:ketimeplot -------------------------------------------------------------------------------

/// Paper Fig. `fig:ketimeplot`: the kinetic energy of the chain against time for a kink and an
/// antikink launched with `v0 = 2.4` at `theta_bar = 0.58` in a perfect chain, each followed until
/// it comes within 8 sites of the free end it runs towards.
pub fn ketimeplot(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:ketimeplot";
    let err = FigureError::on(LABEL);
    let v0 = 2.4;
    let model = chain(params, THETA_BAR_PROPAGATION, None).map_err(err)?;
    let t_max = match quality {
        Quality::Full => 20.0,
        Quality::Quick => 3.0,
    };
    let options = RunOptions { t_max, ..RunOptions::default() };
    let start = 0.75 * params.n as f64;
    let run = |charge| {
        propagation(&model, charge, start, v0, Direction::Left, Some(8.0), &options)
            .map_err(|e| FigureError::new(LABEL, e).at("v0", v0))
    };
    let (kink, antikink) = (run(Charge::Kink)?, run(Charge::Antikink)?);
    let barrier =
        peierls_nabarro(&model, &AntikinkOptions::default()).map_err(FigureError::on(LABEL))?.barrier;
    let t_end = |p: &Propagation| p.positions.last().map_or(0.0, |&(t, _)| t);
    let dk = kinetic_energy_variation(&kink.run, 0.0, t_end(&kink));
    let da = kinetic_energy_variation(&antikink.run, 0.0, t_end(&antikink));
    let peak_to_peak = |p: &Propagation| {
        let window = p.run.kinetic.iter().filter(|(t, _)| *t <= t_end(p)).map(|(_, k)| *k);
        let (min, max) = window.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), k| (a.min(k), b.max(k)));
        max - min
    };
    let panel = Panel {
        title: format!("kinetic energy, θ̄ = {THETA_BAR_PROPAGATION}, v0 = {v0}"),
        x_label: "time t".to_owned(),
        y_label: "kinetic energy (M a²/t²)".to_owned(),
        series: vec![
            Series::new(Quantity::Kink, "kink", kink.run.kinetic.clone(), Style::Line),
            Series::new(Quantity::Antikink, "antikink", antikink.run.kinetic.clone(), Style::Dashed),
        ],
        log_y: false,
    };
    let travelled = |p: &Propagation| match (p.positions.first(), p.positions.last()) {
        (Some(a), Some(b)) => format!("{:.1} sites in t = {:.2}", (b.1 - a.1).abs(), b.0),
        _ => "no track".to_owned(),
    };
    let rows = vec![
        Row::words(
            format!("kink K.E. variation (max - min) / mean, θ̄ = {THETA_BAR_PROPAGATION}, v0 = {v0}"),
            "nearly constant",
            &percent(dk),
            format!("perfect chain, n = {}; kink ran {}", params.n, travelled(&kink)),
        ),
        Row::words(
            format!("antikink K.E. variation (max - min) / mean, θ̄ = {THETA_BAR_PROPAGATION}, v0 = {v0}"),
            "changes significantly",
            &percent(da),
            format!(
                "antikink ran {}; {:.1} times the kink's",
                travelled(&antikink),
                da / dk.max(f64::MIN_POSITIVE)
            ),
        ),
        // Like with like: our swing against our barrier; the paper's barrier against its swing,
        // which it calls consistent but does not print.
        Row::words(
            format!("antikink K.E. peak-to-peak / PN barrier, θ̄ = {THETA_BAR_PROPAGATION}, v0 = {v0}"),
            "≈ 1: its barrier 0.60 is 'consistent with' its K.E. fluctuations",
            &format!(
                "{} / {} = {:.2}",
                format_number(peak_to_peak(&antikink)),
                format_number(barrier),
                peak_to_peak(&antikink) / barrier
            ),
            "both ours: the swing of this run and the PN barrier of the same chain; the paper prints no swing",
        ),
    ];
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Kinetic energy vs time, kink (solid) and antikink (dashed): θ̄ = {THETA_BAR_PROPAGATION}, \
             v0 = {v0}, n = {}, r/a = {}, k = {}, M = {}, no impurity",
            params.n, params.r, params.k, params.mass
        ),
        panels: vec![Chart::Lines(panel)],
        rows,
    })
}

// --- fig:akpntrapprofile --------------------------------------------------------------------------

/// Where the slow antikink of Fig. `fig:akpntrapprofile` starts: rotor `5n/6` (50 of 60), moving
/// towards rotor 0 (the caption gives no start; this one leaves it room to run 15 sites to rotor
/// 35 and more).
fn trap_start(params: &Params) -> f64 {
    (5 * params.n / 6) as f64
}

/// "Stopped": stays within 0.75 sites for 3 time units ([`stopping_point`]).
const STOP_WINDOW: f64 = 3.0;
const STOP_TOLERANCE: f64 = 0.75;

/// `stopped at t = 20.30 near rotor 35.2, 14.8 sites from its start` or `not stopped: ...`.
fn describe_stop(p: &Propagation) -> String {
    match stopping_point(&p.positions, STOP_WINDOW, STOP_TOLERANCE) {
        Some((t, distance)) => {
            let at = p.positions.iter().find(|(s, _)| *s >= t).map_or(f64::NAN, |&(_, x)| x);
            format!("stopped at t = {t:.2} near rotor {at:.1}, {distance:.1} sites from its start")
        }
        None => {
            let last = p.positions.last().map_or(f64::NAN, |&(_, x)| x);
            let passed = p
                .positions
                .iter()
                .find(|(_, x)| *x <= PAPER_TRAP_ROTOR)
                .map_or(String::new(), |(t, _)| format!(", passing rotor 35 at t = {t:.1}"));
            format!("not stopped: at rotor {last:.1} at t = {:.1}{passed}", p.run.final_state.time)
        }
    }
}

/// Paper Fig. `fig:akpntrapprofile`: a slow antikink (`v0 = 1.1`) launched leftwards from rotor
/// `5n/6` in a perfect chain at `theta_bar = 0.575132` (where our Peierls-Nabarro barrier equals
/// the paper's 0.60): conservative, it runs on and is not trapped; with the viscous damping found
/// by a bisection ([`damping_to_stop_at`]) it stops near rotor 35 around `t = 20`, as the paper
/// shows. The explanation: its washboard frequency `2 pi v / a` lies far below the phonon band,
/// so a conservative antikink radiates almost nothing (docs/dynamics.md §4).
pub fn akpntrapprofile(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:akpntrapprofile";
    let v0 = 1.1;
    let theta_bar = THETA_BAR_PAPER_BARRIER;
    let start = trap_start(params);
    let (t_max, iterations) = match quality {
        Quality::Full => (40.0, 14),
        Quality::Quick => (26.0, 4),
    };
    let model = chain(params, theta_bar, None).map_err(FigureError::on(LABEL))?;
    let options = RunOptions { t_max, output_interval: 0.02, space_time: true, ..RunOptions::default() };
    let conservative = propagation(&model, Charge::Antikink, start, v0, Direction::Left, Some(4.0), &options)
        .map_err(FigureError::on(LABEL))?;
    // The search compares stopping points only; no image needed.
    let search_options = RunOptions { space_time: false, output_interval: 0.05, ..options };
    let search = damping_to_stop_at(
        &model,
        Charge::Antikink,
        start,
        v0,
        Direction::Left,
        PAPER_TRAP_ROTOR,
        (1e-5, 1e-1),
        iterations,
        STOP_WINDOW,
        STOP_TOLERANCE,
        &search_options,
    )
    .map_err(FigureError::on(LABEL))?;
    let gamma = search.damping;
    let damped_options = RunOptions { damping: gamma, ..options };
    let damped =
        propagation(&model, Charge::Antikink, start, v0, Direction::Left, Some(4.0), &damped_options)
            .map_err(FigureError::on(LABEL))?;
    // At the paper's stated 0.58 our barrier (0.668) is above the launch energy (0.605).
    let stated = chain(params, THETA_BAR_PROPAGATION, None).map_err(FigureError::on(LABEL))?;
    let short =
        RunOptions { t_max: quality.pick(20, 8) as f64, output_interval: 0.05, ..RunOptions::default() };
    let at_058 = propagation(&stated, Charge::Antikink, start, v0, Direction::Left, Some(4.0), &short)
        .map_err(FigureError::on(LABEL))?;

    // The washboard frequency of the conservative antikink against the phonon band.
    let t_end = conservative.positions.last().map_or(0.0, |&(t, _)| t);
    let speed = mean_speed(&conservative.positions, 0.5 * t_end, t_end).map_or(f64::NAN, f64::abs);
    let early = mean_speed(&conservative.positions, 0.1 * t_end, 0.3 * t_end).map_or(f64::NAN, f64::abs);
    let washboard = 2.0 * std::f64::consts::PI * speed;
    let band = ContinuumChain::new(1.0, params.r, theta_bar, params.k, params.mass)
        .map_err(FigureError::on(LABEL))?
        .phonon_band_edges();
    let launch_energy = 0.5 * params.mass * v0 * v0;
    let rows = vec![
        Row::words(
            format!("slow antikink, θ̄ = {THETA_BAR_PROPAGATION}, v0 = {v0}, conservative"),
            "trapped near rotor #35 around t = 20",
            &describe_stop(&at_058),
            format!(
                "our PN barrier at the stated θ̄ = 0.58 is 0.668, above the launch energy {launch_energy:.3}: it never \
                 leaves its first well"
            ),
        ),
        Row::words(
            format!("slow antikink, θ̄ = {theta_bar}, v0 = {v0}, conservative"),
            "trapped near rotor #35 around t = 20",
            &describe_stop(&conservative),
            format!(
                "launched leftwards from rotor {start:.0}; barrier 0.6023 (the paper's), launch energy \
                 {launch_energy:.3}; mean speed {early:.3} then {speed:.3} sites/t: it barely slows"
            ),
        ),
        Row::words(
            format!("slow antikink, θ̄ = {theta_bar}, v0 = {v0}, damped (γ from a bisection)"),
            "trapped near rotor #35 around t = 20 (Appendix B: no damping mentioned)",
            &format!("γ = {gamma:.3e} /t: {}", describe_stop(&damped)),
            format!(
                "γ bisected in ln γ over [1e-5, 1e-1] ({iterations} halvings) for a stop at rotor 35; final bracket \
                 [{:.4e}, {:.4e}]; stopped = within {STOP_TOLERANCE} sites for {STOP_WINDOW} t",
                search.bracket.0, search.bracket.1
            ),
        ),
        Row::words(
            format!("washboard frequency 2πv/a of the conservative antikink vs phonon band, θ̄ = {theta_bar}"),
            "radiation slows the antikink until the PN barrier traps it",
            &format!("{washboard:.2} /t, band {:.1}-{:.1} /t", band[0], band[1]),
            format!(
                "v = {speed:.3} sites/t; the band starts {:.0} times higher, so only the {:.0}th harmonic of the PN \
                 potential could radiate: a conservative antikink keeps its speed",
                band[0] / washboard,
                (band[0] / washboard).ceil()
            ),
        ),
    ];
    let trajectory = |name: &str, p: &Propagation, style| {
        Series::new(Quantity::Antikink, name, p.positions.clone(), style)
    };
    let panels = vec![
        Chart::Heat(space_time_map(
            format!("conservative, θ̄ = {theta_bar}, v0 = {v0}"),
            &conservative.run.space_time,
        )),
        Chart::Heat(space_time_map(format!("damped, γ = {gamma:.2e} /t"), &damped.run.space_time)),
        Chart::Lines(Panel {
            title: "antikink position".to_owned(),
            x_label: "time t".to_owned(),
            y_label: "wall position (rotor index)".to_owned(),
            series: vec![
                trajectory(&format!("θ̄ = {theta_bar}, conservative"), &conservative, Style::Line),
                trajectory(&format!("θ̄ = {theta_bar}, γ = {gamma:.2e}"), &damped, Style::Dashed),
                trajectory(&format!("θ̄ = {THETA_BAR_PROPAGATION}, conservative"), &at_058, Style::LinePoints),
                Series::new(
                    Quantity::Reference,
                    "rotor 35",
                    vec![(0.0, PAPER_TRAP_ROTOR), (t_max, PAPER_TRAP_ROTOR)],
                    Style::Dashed,
                ),
            ],
            log_y: false,
        }),
    ];
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Slow antikink (v0 = {v0}) from rotor {start:.0} in a perfect chain, θ̄ = {theta_bar} (our PN barrier = \
             paper's 0.60): conservative, and with the damping γ = {gamma:.2e} found by bisection; n = {}, r/a = {}, \
             k = {}",
            params.n, params.r, params.k
        ),
        panels,
        rows,
    })
}

// --- fig:k-scatter and fig:ak-scatter -------------------------------------------------------------

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
    let model = chain(params, THETA_BAR_SCATTERING, Some(ki_ratio))?;
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

/// A scattering figure: one space-time image and one row per `(v0, k_i/k, paper's outcome)`.
fn scatter_figure(
    label: &'static str,
    params: &Params,
    quality: Quality,
    charge: Charge,
    points: &[(f64, f64, Outcome)],
) -> Result<Figure, FigureError> {
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
        points.par_iter().map(|&(v0, ki, _)| scatter_event(params, charge, v0, ki, after)).collect();
    let mut panels = Vec::new();
    let mut rows = Vec::new();
    for (&(v0, ki, paper), event) in points.iter().zip(events) {
        let event = event.map_err(|e| FigureError::new(label, e).at("v0", v0).at("k_i/k", ki))?;
        let ours = event.result.outcome;
        rows.push(Row::words(
            format!("{name} on an impurity, v0 = {v0}, k_i/k = {ki}, θ̄ = {THETA_BAR_SCATTERING}"),
            paper.name(),
            ours.name(),
            format!(
                "decided at t = {:.2}{}; walls at the image's end (t = {:.2}): {}",
                event.result.decided_at,
                if ours == paper { "" } else { " (differs from the paper)" },
                event.image.times.last().copied().unwrap_or(0.0),
                event.walls_at_end
            ),
        ));
        panels.push(Chart::Heat(space_time_map(
            format!("{name}, v0 = {v0}, k_i/k = {ki}: {}", ours.name()),
            &event.image,
        )));
    }
    Ok(Figure {
        label,
        caption: format!(
            "Space-time images θ_i(t) of a {name} scattering on a soft spring (impurity on spring {}, \
             incoming from the right): θ̄ = {THETA_BAR_SCATTERING}, n = {}, r/a = {}, k = {}, M = {}",
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
/// `(9.6, 0.01)`, `theta_bar = 0.28`.
pub fn k_scatter(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    scatter_figure(
        "fig:k-scatter",
        params,
        quality,
        Charge::Kink,
        &[(4.0, 0.10, Outcome::Transmitted), (9.6, 0.01, Outcome::Split)],
    )
}

/// Paper Fig. `fig:ak-scatter`: an antikink transmitted at `(v0, k_i/k) = (4.0, 0.80)`, trapped at
/// `(4.0, 0.70)` and reflected at `(4.8, 0.20)`, `theta_bar = 0.28`; and the paper's "for `k_i/k`
/// near 1, the antikink gets transmitted with energy dissipation and thus slows down": the
/// speed after the impurity over the speed before, against `k_i/k`.
pub fn ak_scatter(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:ak-scatter";
    let mut figure = scatter_figure(
        LABEL,
        params,
        quality,
        Charge::Antikink,
        &[(4.0, 0.80, Outcome::Transmitted), (4.0, 0.70, Outcome::Trapped), (4.8, 0.20, Outcome::Reflected)],
    )?;
    let kis: Vec<f64> =
        Axis::linspace(0.7, 1.3, quality.pick(25, 5)).map_err(FigureError::on(LABEL))?.values().to_vec();
    let v0s = [2.0, 4.0, 8.0];
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
        format!("transmitted antikink speed after / before the impurity, v0 = 4, k_i/k = 0.8, θ̄ = {THETA_BAR_SCATTERING}"),
        "slows down (energy dissipation) for k_i/k near 1",
        &show(paper_point),
        format!(
            "speeds fitted more than 8 sites before and after the impurity; k_i = k: {} (no impurity, no slowing); \
             v0 = 8, k_i/k = 1.2: {}",
            show(control),
            show(stiffer)
        ),
    ));
    figure.panels.push(Chart::Lines(Panel {
        title: "transmitted antikink: speed after / before".to_owned(),
        x_label: "k_i / k".to_owned(),
        y_label: "v_out / v_in".to_owned(),
        series,
        log_y: false,
    }));
    Ok(figure)
}

/// `v_out / v_in` of an antikink launched as in the paper's scattering runs at `(v0, k_i/k)`:
/// `None` unless it was transmitted and seen long enough on both sides.
fn slowing(params: &Params, v0: f64, ki_ratio: f64) -> Result<Option<f64>, Cause> {
    let model = chain(params, THETA_BAR_SCATTERING, Some(ki_ratio))?;
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

// --- fig:phasediagram -----------------------------------------------------------------------------

/// The label of a point that failed (energy budget, unreadable walls): shown, never hidden.
pub(crate) const FAILED: &str = "failed";

/// One phase diagram over `grid` (x: `k_i/k`, y: `v0`), computed by chain-sweep's
/// [`PhaseDiagram::compute_point`] in parallel: `labels[j][i]` for `v0 = ys[j]`, `k_i/k = xs[i]`.
pub(crate) fn phase_diagram(
    params: &Params,
    defect: Defect,
    grid: &Grid,
) -> Result<Vec<Vec<Option<Outcome>>>, Cause> {
    let mut d = PhaseDiagram::new(params.n, params.r, params.k, THETA_BAR_SCATTERING, defect)?;
    d.mass = params.mass;
    d.check()?;
    let points = compute_grid(grid, |ki, v0| d.compute_point(ki, v0), None)?;
    let mut labels = vec![vec![None; grid.xs().len()]; grid.ys().len()];
    for p in points {
        labels[p.index.1][p.index.0] = p.outcome.ok().map(|r| r.outcome);
    }
    Ok(labels)
}

/// A phase-diagram label's colour index: its place in [`Outcome::ALL`], then [`FAILED`].
pub(crate) fn category(outcome: Option<Outcome>) -> f64 {
    match outcome {
        Some(o) => Outcome::ALL.iter().position(|&x| x == o).unwrap_or(0) as f64,
        None => Outcome::ALL.len() as f64,
    }
}

fn count(labels: &[Vec<Option<Outcome>>], which: Option<Outcome>) -> usize {
    labels.iter().flatten().filter(|&&o| o == which).count()
}

/// `1536 transmitted, 55 split, ...`: every label that occurs, with its count.
pub(crate) fn label_counts(labels: &[Vec<Option<Outcome>>]) -> Vec<String> {
    Outcome::ALL
        .iter()
        .map(|&o| (count(labels, Some(o)), o.name()))
        .chain([(count(labels, None), FAILED)])
        .filter(|(c, _)| *c > 0)
        .map(|(c, name)| format!("{c} {name}"))
        .collect()
}

/// [`label_counts`] and the share of undecided points: `..., undecided 0.0 %`.
fn counts(labels: &[Vec<Option<Outcome>>]) -> String {
    let total = labels.iter().map(Vec::len).sum::<usize>().max(1);
    let mut parts = label_counts(labels);
    let undecided = count(labels, Some(Outcome::Undecided));
    parts.push(format!("undecided {:.1} %", 100.0 * undecided as f64 / total as f64));
    parts.join(", ")
}

/// The colour categories of a phase diagram: every outcome in [`Outcome::ALL`]'s order, then
/// [`FAILED`] (as [`category`] numbers them).
pub(crate) fn outcome_categories() -> Vec<String> {
    Outcome::ALL.iter().map(|o| o.name()).chain([FAILED]).map(str::to_owned).collect()
}

/// The boundary between two regimes along each `v0` row: where the longest run of `left` labels
/// (scanning in `k_i/k`) is directly followed by `right`, at the geometric mean of the two
/// `k_i/k`. Returns `(k_i/k, v0)` for every row that has one.
fn boundary(
    labels: &[Vec<Option<Outcome>>],
    xs: &[f64],
    ys: &[f64],
    left: Outcome,
    right: Outcome,
) -> Vec<(f64, f64)> {
    labels
        .iter()
        .zip(ys)
        .filter_map(|(row, &v0)| {
            // The longest run of `left`: (start, end exclusive).
            let mut best: Option<(usize, usize)> = None;
            let mut i = 0;
            while i < row.len() {
                if row[i] == Some(left) {
                    let start = i;
                    while i < row.len() && row[i] == Some(left) {
                        i += 1;
                    }
                    if best.is_none_or(|(s, e)| i - start > e - s) {
                        best = Some((start, i));
                    }
                } else {
                    i += 1;
                }
            }
            let (_, end) = best?;
            (end < row.len() && row[end] == Some(right)).then(|| ((xs[end - 1] * xs[end]).sqrt(), v0))
        })
        .collect()
}

/// Three significant digits: `0.0134`, `12.3`, `-45.6`.
fn sig3(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.digits$}")
}

/// The least-squares slope `dv0 / d(k_i/k)` of boundary points, and how many there were.
fn slope(points: &[(f64, f64)]) -> Option<(f64, usize)> {
    if points.len() < 3 {
        return None;
    }
    let n = points.len() as f64;
    let (mx, my) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (sxx, sxy) =
        points.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + (x - mx) * (x - mx), b + (x - mx) * (y - my)));
    (sxx > 0.0).then(|| (sxy / sxx, points.len()))
}

/// A summary row for the boundary `left | right`.
fn boundary_row(
    name: &str,
    labels: &[Vec<Option<Outcome>>],
    grid: &Grid,
    (left, right): (Outcome, Outcome),
    paper: &str,
    note: &str,
) -> Row {
    let points = boundary(labels, grid.xs(), grid.ys(), left, right);
    let ours = match slope(&points) {
        Some((s, rows)) => {
            let (lo, hi) =
                points.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.0), b.max(p.0)));
            let sign = if s > 0.0 { "positive" } else { "negative" };
            format!(
                "{sign} slope, dv0/d(k_i/k) = {} over {rows} rows; k_i/k from {} to {}",
                sig3(s),
                sig3(lo),
                sig3(hi)
            )
        }
        None => format!("no boundary found ({} rows)", points.len()),
    };
    Row::words(format!("{name}: boundary {} | {}", left.name(), right.name()), paper, &ours, note.to_owned())
}

/// `trapped 2.5-3.6, transmitted 3.7-3.9, ...`: the runs of equal outcomes along `v0s`.
fn alternation(outcomes: &[Option<Outcome>], v0s: &[f64]) -> String {
    let mut parts: Vec<String> = Vec::new();
    let mut k = 0;
    while k < outcomes.len() {
        let mut end = k;
        while end + 1 < outcomes.len() && outcomes[end + 1] == outcomes[k] {
            end += 1;
        }
        let name = outcomes[k].map_or(FAILED, Outcome::name);
        parts.push(if end == k {
            format!("{name} {:.2}", v0s[k])
        } else {
            format!("{name} {:.2}-{:.2}", v0s[k], v0s[end])
        });
        k = end + 1;
    }
    parts.join(", ")
}

/// The antikink of the paper's scattering chain run along a perfect chain at each `v0`: the most
/// walls seen at once and the longest time it had three or more (paper: "above v0 = 12 the
/// antikink itself becomes unstable and tends to quickly disintegrate").
fn stability_scan(params: &Params, v0s: &[f64]) -> Result<Vec<(f64, usize, f64)>, FigureError> {
    let fail = |e: Cause, v0: f64| FigureError::new("fig:phasediagram", e).at("v0", v0);
    let model = chain(params, THETA_BAR_SCATTERING, None).map_err(|e| fail(e.into(), f64::NAN))?;
    let setup = ScatterSetup::from_the_right(Charge::Antikink, 0.0, middle_spring(params));
    let options = RunOptions { t_max: 5.0, ..RunOptions::default() };
    v0s.par_iter()
        .map(|&v0| {
            stability(&model, setup.charge, setup.start, v0, setup.direction, setup.clear, &options)
                .map(|s| (v0, s.most_walls, s.longest_extra))
                .map_err(|e| fail(e.into(), v0))
        })
        .collect()
}

/// Paper Fig. `fig:phasediagram`: the scattering outcome of a kink and of an antikink over the
/// impurity stiffness `k_i/k` (0.01 to 3, evenly spaced in the logarithm, so that both the soft
/// impurities of the kink's split and the stiff ones of the antikink's upper reflection regime
/// are resolved) and the launch speed `v0` (0.5 to 12), `theta_bar = 0.28`; 40 x 40 points in
/// full, 6 x 6 quick. Each point is chain-sweep's ([`PhaseDiagram::compute_point`]), the one
/// the `phase-diagram` tool computes. With the antikink's stability against `v0` up to 25.
pub fn phasediagram(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:phasediagram";
    let fail = FigureError::on(LABEL);
    let size = quality.pick(40, 6);
    let kis = Axis::geomspace(0.01, 3.0, size).map_err(FigureError::on(LABEL))?;
    let v0s = Axis::linspace(0.5, 12.0, size).map_err(FigureError::on(LABEL))?;
    let grid = Grid::new(kis, v0s).map_err(FigureError::on(LABEL))?;
    let categories = outcome_categories();
    let mut panels = Vec::new();
    let mut diagrams = Vec::new();
    for defect in [Defect::Kink, Defect::Antikink] {
        let labels = phase_diagram(params, defect, &grid).map_err(&fail)?;
        panels.push(Chart::Heat(Heatmap {
            title: format!("{}, θ̄ = {THETA_BAR_SCATTERING}", defect.name()),
            x_label: "log₁₀(k_i / k)".to_owned(),
            y_label: "v0 (a/t)".to_owned(),
            x: grid.xs().iter().map(|x| x.log10()).collect(),
            y: grid.ys().to_vec(),
            values: labels.iter().map(|row| row.iter().map(|&o| category(o)).collect()).collect(),
            categories: categories.clone(),
            value_label: "outcome".to_owned(),
        }));
        diagrams.push(labels);
    }
    let (kink, antikink) = (&diagrams[0], &diagrams[1]);
    let stable_v0s: Vec<f64> =
        Axis::linspace(10.0, 25.0, quality.pick(31, 4)).map_err(FigureError::on(LABEL))?.values().to_vec();
    let scan = stability_scan(params, &stable_v0s)?;
    panels.push(Chart::Lines(Panel {
        title: "antikink in a perfect chain: walls against v0".to_owned(),
        x_label: "v0 (a/t)".to_owned(),
        y_label: "most walls at once; longest time with 3+ walls (t × 10)".to_owned(),
        series: vec![
            Series::new(
                Quantity::Antikink,
                "most walls",
                scan.iter().map(|&(v, w, _)| (v, w as f64)).collect(),
                Style::LinePoints,
            ),
            Series::new(
                Quantity::Antikink,
                "longest time with 3+ walls × 10",
                scan.iter().map(|&(v, _, t)| (v, 10.0 * t)).collect(),
                Style::Dashed,
            ),
        ],
        log_y: false,
    }));
    let single_up_to = scan.iter().take_while(|s| s.1 <= 1).last().map_or(f64::NAN, |s| s.0);
    let first_extra =
        scan.iter().find(|s| s.1 >= 3).map_or("none up to 25".to_owned(), |s| format!("{}", s.0));
    let lasting =
        scan.iter().find(|s| s.2 >= 0.25).map_or("none up to 25".to_owned(), |s| format!("{}", s.0));
    let grid_note = format!("k_i/k 0.01..3 log-spaced, v0 0.5..12, {size} x {size}");
    // The paper's alternating window: outcomes along v0 at k_i/k = 0.75.
    let window_v0s = Axis::linspace(2.5, 5.0, quality.pick(26, 6)).map_err(FigureError::on(LABEL))?;
    let column = Grid::new(Axis::from_values(vec![0.75]).map_err(FigureError::on(LABEL))?, window_v0s)
        .map_err(FigureError::on(LABEL))?;
    let window = phase_diagram(params, Defect::Antikink, &column).map_err(&fail)?;
    let runs = alternation(&window.iter().map(|row| row[0]).collect::<Vec<_>>(), column.ys());
    let rows = vec![
        Row::words(
            format!("kink phase diagram: trapped or reflected points ({size} x {size})"),
            "never trapped or reflected",
            &format!(
                "{} of {}",
                count(kink, Some(Outcome::Trapped)) + count(kink, Some(Outcome::Reflected)),
                size * size
            ),
            format!("{grid_note}; {}", counts(kink)),
        ),
        boundary_row(
            "kink",
            kink,
            &grid,
            (Outcome::Split, Outcome::Transmitted),
            "positive slope (a faster kink splits on a stiffer impurity)",
            "boundary points at the geometric mean of the two k_i/k of each v0 row",
        ),
        Row::words(
            format!("antikink phase diagram: regimes ({size} x {size})"),
            "reflected (soft), trapped, transmitted, reflected (stiff)",
            &counts(antikink),
            format!(
                "{grid_note}; free ends; annihilated = by a wall from a free end before anything settled"
            ),
        ),
        boundary_row(
            "antikink",
            antikink,
            &grid,
            (Outcome::Transmitted, Outcome::Reflected),
            "positive slope (upper reflection regime, k_i > k)",
            "the higher the barrier, the faster the antikink must be to pass",
        ),
        boundary_row(
            "antikink",
            antikink,
            &grid,
            (Outcome::Trapped, Outcome::Transmitted),
            "negative slope",
            "a softer impurity makes the antikink lose more energy",
        ),
        boundary_row(
            "antikink",
            antikink,
            &grid,
            (Outcome::Reflected, Outcome::Trapped),
            "positive slope (lower reflection regime)",
            "reflected below, trapped above in k_i/k",
        ),
        Row::words(
            "antikink outcomes along v0 at k_i/k = 0.75 (alternating regimes)".to_owned(),
            "a small range of alternating transmitted / trapped regimes around k_i/k = 0.75, v0 = 3.6",
            &runs,
            format!(
                "v0 from 2.5 to 5 in {} steps; the 40 x 40 grid is too coarse to show it",
                column.ys().len()
            ),
        ),
        Row::words(
            "antikink stability against v0, perfect chain, θ̄ = 0.28".to_owned(),
            "disintegrates above v0 ≈ 12",
            &format!(
                "one wall up to v0 = {single_up_to}; extra walls from v0 = {first_extra}; lasting ≥ 0.25 t from {lasting}"
            ),
            format!(
                "launched from rotor {:.0} towards rotor 0 and followed to 8 sites from the end (or t = 5), walls from \
                 the free ends left out; v0 = {:.1}..{:.1}",
                ScatterSetup::from_the_right(Charge::Antikink, 0.0, middle_spring(params)).start,
                stable_v0s[0],
                stable_v0s[stable_v0s.len() - 1]
            ),
        ),
    ];
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Scattering phase diagrams over k_i/k (0.01..3, log-spaced) and v0 (0.5..12), {size} x {size}, kink and \
             antikink; antikink walls against v0 up to 25: θ̄ = {THETA_BAR_SCATTERING}, n = {}, r/a = {}, k = {}, \
             impurity on spring {}, free ends",
            params.n,
            params.r,
            params.k,
            middle_spring(params)
        ),
        panels,
        rows,
    })
}
