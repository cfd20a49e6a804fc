//! Figures of the paper's dynamics (Secs. V and VI, see [`super::all`]): the kinetic energy of a
//! moving kink and antikink (`fig:ketimeplot`), Peierls-Nabarro trapping of a slow antikink
//! (`fig:akpntrapprofile`), scattering on a stiffness impurity (`fig:k-scatter`, `fig:ak-scatter`)
//! and the scattering phase diagrams (`fig:phasediagram`).
//!
//! Space-time images show the alternately measured angles `theta_i` (one sign per domain), rows
//! are output times, columns rotors. Scattering runs follow the paper's setup (Sec. VI): the
//! impurity is the middle spring `(n - 1) / 2`, the defect starts 15 sites to its right and moves
//! left ([`ScatterSetup::from_the_right`]).

use rayon::prelude::*;
use rotor_chain::RuntimeChain;
use rotor_chain::dynamics::launch::Direction;
use rotor_chain::dynamics::observe::{Propagation, kinetic_energy_variation, propagation, stopping_point};
use rotor_chain::dynamics::run::{RunOptions, propagate};
use rotor_chain::dynamics::scatter::{Outcome, ScatterSetup, Scattering, scatter};
use rotor_chain::dynamics::track::{Snapshot, SpaceTime};
use rotor_chain::statics::walls::Charge;

use rotor_chain::prelude::ParameterError;
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
const THETA_BAR_SCATTERING: f64 = 0.28;
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

/// Paper Fig. `fig:akpntrapprofile`: the space-time image of a slow antikink (`v0 = 1.1`) launched
/// leftwards from rotor `5n/6` in a perfect chain, at `theta_bar = 0.58` (our barrier 0.668 is
/// above the launch energy 0.605: it stops at once) and at `theta_bar = 0.575132` (our barrier
/// equals the paper's 0.60: it travels before the Peierls-Nabarro barrier stops it).
pub fn akpntrapprofile(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:akpntrapprofile";
    let v0 = 1.1;
    let t_max = match quality {
        Quality::Full => 60.0,
        Quality::Quick => 8.0,
    };
    let start = (5 * params.n / 6) as f64;
    let options = RunOptions { t_max, space_time: true, ..RunOptions::default() };
    let mut panels = Vec::new();
    let mut rows = Vec::new();
    for theta_bar in [THETA_BAR_PROPAGATION, THETA_BAR_PAPER_BARRIER] {
        let model = chain(params, theta_bar, None).map_err(FigureError::on(LABEL))?;
        let p = propagation(&model, Charge::Antikink, start, v0, Direction::Left, Some(4.0), &options)
            .map_err(|e| FigureError::new(LABEL, e).at("θ̄", theta_bar))?;
        let window = 3.0;
        let ours = match stopping_point(&p.positions, window, 0.75) {
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
        };
        let launched_at = p.positions.first().map_or(start, |&(_, x)| x);
        rows.push(Row::words(
            format!("slow antikink stopping point, θ̄ = {theta_bar}, v0 = {v0}"),
            "trapped near rotor #35 around t = 20",
            &ours,
            format!(
                "launched leftwards from rotor {launched_at:.1}; stopped = stays within 0.75 sites for \
                 {window:.1} time units; launch energy {:.3}",
                0.5 * params.mass * v0 * v0
            ),
        ));
        panels.push(Chart::Heat(space_time_map(
            format!("antikink, θ̄ = {theta_bar}, v0 = {v0}"),
            &p.run.space_time,
        )));
    }
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Space-time image θ_i(t) of a slow antikink (v0 = {v0}) in a perfect chain: θ̄ = \
             {THETA_BAR_PROPAGATION} and {THETA_BAR_PAPER_BARRIER} (our PN barrier = paper's 0.60), \
             n = {}, r/a = {}, k = {}",
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
/// `(4.0, 0.70)` and reflected at `(4.8, 0.20)`, `theta_bar = 0.28`.
pub fn ak_scatter(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    scatter_figure(
        "fig:ak-scatter",
        params,
        quality,
        Charge::Antikink,
        &[(4.0, 0.80, Outcome::Transmitted), (4.0, 0.70, Outcome::Trapped), (4.8, 0.20, Outcome::Reflected)],
    )
}

// --- fig:phasediagram -----------------------------------------------------------------------------

/// `count` evenly spaced values from `from` to `to`.
fn grid(from: f64, to: f64, count: usize) -> Vec<f64> {
    if count < 2 {
        return vec![from];
    }
    (0..count).map(|i| from + (to - from) * i as f64 / (count - 1) as f64).collect()
}

/// Outcomes over `v0s` (rows) and `kis` (columns), computed in parallel.
fn phase_diagram(
    params: &Params,
    charge: Charge,
    kis: &[f64],
    v0s: &[f64],
) -> Result<Vec<Vec<Outcome>>, FigureError> {
    let points: Vec<(usize, usize)> =
        (0..v0s.len()).flat_map(|row| (0..kis.len()).map(move |col| (row, col))).collect();
    let outcomes: Vec<Outcome> = points
        .par_iter()
        .map(|&(row, col)| {
            let fail =
                |e: Cause| FigureError::new("fig:phasediagram", e).at("v0", v0s[row]).at("k_i/k", kis[col]);
            let model = chain(params, THETA_BAR_SCATTERING, Some(kis[col])).map_err(|e| fail(e.into()))?;
            let setup = ScatterSetup::from_the_right(charge, v0s[row], middle_spring(params));
            scatter(&model, &setup).map(|s| s.outcome).map_err(|e| fail(e.into()))
        })
        .collect::<Result<_, FigureError>>()?;
    Ok(outcomes.chunks(kis.len()).map(<[Outcome]>::to_vec).collect())
}

fn category(outcome: Outcome) -> f64 {
    Outcome::ALL.iter().position(|&o| o == outcome).unwrap_or(Outcome::ALL.len() - 1) as f64
}

fn count(outcomes: &[Vec<Outcome>], which: &[Outcome]) -> usize {
    outcomes.iter().flatten().filter(|o| which.contains(o)).count()
}

/// Paper Fig. `fig:phasediagram`: the scattering outcome of a kink and of an antikink over the
/// impurity stiffness `k_i/k` (0.01 to 1.0) and the launch speed `v0` (0.5 to 12), `theta_bar =
/// 0.28`; 40 x 40 points in full, 6 x 6 quick.
pub fn phasediagram(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:phasediagram";
    let size = quality.pick(40, 6);
    let kis = grid(0.01, 1.0, size);
    let v0s = grid(0.5, 12.0, size);
    let mut panels = Vec::new();
    let mut diagrams = Vec::new();
    for (charge, name) in [(Charge::Kink, "kink"), (Charge::Antikink, "antikink")] {
        let outcomes = phase_diagram(params, charge, &kis, &v0s)?;
        panels.push(Chart::Heat(Heatmap {
            title: format!("{name}, θ̄ = {THETA_BAR_SCATTERING}"),
            x_label: "k_i / k".to_owned(),
            y_label: "v0 (a/t)".to_owned(),
            x: kis.clone(),
            y: v0s.clone(),
            values: outcomes.iter().map(|row| row.iter().map(|&o| category(o)).collect()).collect(),
            categories: Outcome::ALL.iter().map(|o| o.name().to_owned()).collect(),
            value_label: "outcome".to_owned(),
        }));
        diagrams.push(outcomes);
    }
    let (kink, antikink) = (&diagrams[0], &diagrams[1]);
    let counts = |d: &[Vec<Outcome>]| {
        Outcome::ALL
            .iter()
            .map(|&o| format!("{} {}", count(d, &[o]), o.name()))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let kink_bad = count(kink, &[Outcome::Trapped, Outcome::Reflected]);
    // The lowest v0 on the grid at which some antikink escapes the impurity (transmitted or
    // reflected), and the lowest at which it is transmitted through the weakest impurity (k_i/k
    // nearest 1, where the Peierls-Nabarro barrier alone can stop it).
    let lowest = |d: &[Vec<Outcome>], cols: &[usize], which: &[Outcome]| {
        d.iter().zip(&v0s).find(|(row, _)| cols.iter().any(|&c| which.contains(&row[c]))).map(|(_, &v)| v)
    };
    let all_cols: Vec<usize> = (0..kis.len()).collect();
    let escaped = lowest(antikink, &all_cols, &[Outcome::Transmitted, Outcome::Reflected]);
    let through_weakest = lowest(antikink, &[kis.len() - 1], &[Outcome::Transmitted]);
    let show = |v: Option<f64>| v.map_or("none on the grid".to_owned(), |v| format!("{v:.3}"));
    let spacing = if v0s.len() > 1 { v0s[1] - v0s[0] } else { 0.0 };
    let limit_note = if through_weakest == Some(v0s[0]) {
        format!(
            "the grid starts at v0 = {}: at θ̄ = {THETA_BAR_SCATTERING} our PN barrier does not capture even \
             that slow an antikink in t = {}; ",
            v0s[0],
            RunOptions::default().t_max
        )
    } else {
        String::new()
    };
    let rows = vec![
        Row::words(
            format!("kink phase diagram: trapped or reflected points ({size} x {size})"),
            "never trapped or reflected",
            &format!("{kink_bad} of {}", size * size),
            format!("counts: {}", counts(kink)),
        ),
        Row::words(
            format!("antikink lower limit of v0 ({size} x {size})"),
            "≈ 0.7 (below, the PN barrier captures it)",
            &format!(
                "lowest v0 with an antikink transmitted or reflected (any k_i/k): {}; transmitted at \
                 k_i/k = {:.2}: {}",
                show(escaped),
                kis[kis.len() - 1],
                show(through_weakest)
            ),
            format!("{limit_note}v0 grid spacing {spacing:.3}; counts: {}", counts(antikink)),
        ),
    ];
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Scattering phase diagrams over k_i/k (0.01..1.0) and v0 (0.5..12), {size} x {size}, kink and \
             antikink: θ̄ = {THETA_BAR_SCATTERING}, n = {}, r/a = {}, k = {}, impurity on spring {}",
            params.n,
            params.r,
            params.k,
            middle_spring(params)
        ),
        panels,
        rows,
    })
}
