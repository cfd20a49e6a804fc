//! Sec. V: a kink and an antikink moving along a perfect chain (`fig:ketimeplot`) and a slow
//! antikink trapped by its Peierls-Nabarro potential (`fig:akpntrapprofile`), with the parameters
//! of [`Propagation`](super::Propagation).

use rotor_chain::dynamics::launch::Direction;
use rotor_chain::dynamics::observe::{
    Propagation, damping_to_stop_at, kinetic_energy_variation, mean_speed, propagation, stopping_point,
};
use rotor_chain::dynamics::run::RunOptions;
use rotor_chain::statics::antikink::{AntikinkOptions, peierls_nabarro};
use rotor_chain::statics::continuum::ContinuumChain;
use rotor_chain::statics::walls::Charge;

use super::{chain, percent, space_time_map};
use crate::figures::{FigureError, Params};
use crate::model::{Chart, Figure, Panel, Quality, Quantity, Row, Series, Style, format_number};

/// The stretch of time `fig:ketimeplot` (b) shows, `t`.
const ZOOM: f64 = 1.0;

/// Paper Fig. `fig:ketimeplot`: the kinetic energy of the chain against time for a kink and an
/// antikink launched with [`Propagation::v0`](super::Propagation::v0) (2.4) at its `theta_bar`
/// (0.58) in a perfect chain, each followed until it comes within 8 sites of the free end it runs
/// towards.
pub fn ketimeplot(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:ketimeplot";
    let err = FigureError::on(LABEL);
    let (theta_bar, v0) = (params.propagation.theta_bar, params.propagation.v0);
    let model = chain(params, theta_bar, None).map_err(err)?;
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
    // (a) the whole run; (b) its first time unit, where the antikink's swings (about four per
    // time unit) are wide enough to read.
    let panel = |title: String, until: f64| {
        let early = |p: &Propagation| p.run.kinetic.iter().copied().filter(|&(t, _)| t <= until).collect();
        Panel::new(
            title,
            "time t",
            "kinetic energy (M a²/t²)",
            vec![
                Series::new(Quantity::Kink, "kink", early(&kink), Style::Line),
                Series::new(Quantity::Antikink, "antikink", early(&antikink), Style::Line),
            ],
        )
    };
    let panels = vec![
        Chart::Lines(panel(format!("(a) kinetic energy, θ̄ = {theta_bar}, v0 = {v0}"), f64::INFINITY)),
        Chart::Lines(panel(format!("(b) 0 ≤ t ≤ {ZOOM} of (a)"), ZOOM)),
    ];
    let travelled = |p: &Propagation| match (p.positions.first(), p.positions.last()) {
        (Some(a), Some(b)) => format!("{:.1} sites in t = {:.2}", (b.1 - a.1).abs(), b.0),
        _ => "no track".to_owned(),
    };
    let rows = vec![
        Row::words(
            format!("kink K.E. variation (max - min) / mean, θ̄ = {theta_bar}, v0 = {v0}"),
            "nearly constant",
            &percent(dk),
            format!("perfect chain, n = {}; kink ran {}", params.n, travelled(&kink)),
        ),
        Row::words(
            format!("antikink K.E. variation (max - min) / mean, θ̄ = {theta_bar}, v0 = {v0}"),
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
            format!("antikink K.E. peak-to-peak / PN barrier, θ̄ = {theta_bar}, v0 = {v0}"),
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
            "Kinetic energy vs time, kink (blue) and antikink (orange), (a) the whole run and (b) its first {ZOOM} t: \
             θ̄ = {theta_bar}, \
             v0 = {v0}, n = {}, r/a = {}, k = {}, M = {}, no impurity",
            params.n, params.r, params.k, params.mass
        ),
        panels,
        rows,
    })
}

/// Where the slow antikink of Fig. `fig:akpntrapprofile` starts: rotor `5n/6` (50 of 60), moving
/// towards rotor 0 (the caption gives no start; this one leaves it room to run 15 sites to rotor
/// 35 and more).
fn trap_start(params: &Params) -> f64 {
    (5 * params.n / 6) as f64
}

/// "Stopped": stays within 0.75 sites for 3 time units (`stopping_point` of `rotor_chain::dynamics::observe`).
const STOP_WINDOW: f64 = 3.0;
const STOP_TOLERANCE: f64 = 0.75;

/// `stopped at t = 20.30 near rotor 35.2, 14.8 sites from its start` or `not stopped: ...
/// passing rotor 35 (trap_rotor) at ...`.
fn describe_stop(p: &Propagation, trap_rotor: f64) -> String {
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
                .find(|(_, x)| *x <= trap_rotor)
                .map_or(String::new(), |(t, _)| format!(", passing rotor {trap_rotor} at t = {t:.1}"));
            format!("not stopped: at rotor {last:.1} at t = {:.1}{passed}", p.run.final_state.time)
        }
    }
}

/// Paper Fig. `fig:akpntrapprofile`: a slow antikink (`v0 = 1.1`) launched leftwards from rotor
/// `5n/6` in a perfect chain at `theta_bar = 0.575132` (where our Peierls-Nabarro barrier equals
/// the paper's 0.60): conservative, it runs on and is not trapped; with the viscous damping found
/// by a bisection (`damping_to_stop_at` of `rotor_chain::dynamics::observe`) it stops near rotor 35 around `t = 20`, as the paper
/// shows. The explanation: its washboard frequency `2 pi v / a` lies far below the phonon band,
/// so a conservative antikink radiates almost nothing (docs/dynamics.md §4). The numbers are
/// [`Propagation`](super::Propagation)'s `slow_v0`, `slow_theta_bar` and `trap_rotor`; the
/// third run is at its `theta_bar` (the paper's stated 0.58).
pub fn akpntrapprofile(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:akpntrapprofile";
    let p = &params.propagation;
    let (v0, theta_bar, stated_theta_bar, trap_rotor) =
        (p.slow_v0, p.slow_theta_bar, p.theta_bar, p.trap_rotor);
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
        trap_rotor,
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
    let stated = chain(params, stated_theta_bar, None).map_err(FigureError::on(LABEL))?;
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
    let barrier = |model| {
        peierls_nabarro(model, &AntikinkOptions::default())
            .map(|pn| pn.barrier)
            .map_err(FigureError::on(LABEL))
    };
    let (stated_barrier, barrier) = (barrier(&stated)?, barrier(&model)?);
    let rows = vec![
        Row::words(
            format!("slow antikink, θ̄ = {stated_theta_bar}, v0 = {v0}, conservative"),
            "trapped near rotor #35 around t = 20",
            &describe_stop(&at_058, trap_rotor),
            format!(
                "our PN barrier at the stated θ̄ = {stated_theta_bar} is {stated_barrier:.3}, above the launch \
                 energy {launch_energy:.3}: it never leaves its first well"
            ),
        ),
        Row::words(
            format!("slow antikink, θ̄ = {theta_bar}, v0 = {v0}, conservative"),
            "trapped near rotor #35 around t = 20",
            &describe_stop(&conservative, trap_rotor),
            format!(
                "launched leftwards from rotor {start:.0}; barrier {barrier:.4} (the paper's), launch energy \
                 {launch_energy:.3}; mean speed {early:.3} then {speed:.3} sites/t: it barely slows"
            ),
        ),
        Row::words(
            format!("slow antikink, θ̄ = {theta_bar}, v0 = {v0}, damped (γ from a bisection)"),
            "trapped near rotor #35 around t = 20 (Appendix B: no damping mentioned)",
            &format!("γ = {gamma:.3e} /t: {}", describe_stop(&damped, trap_rotor)),
            format!(
                "γ bisected in ln γ over [1e-5, 1e-1] ({iterations} halvings) for a stop at rotor {trap_rotor}; final bracket \
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
            theta_bar,
        )),
        Chart::Heat(space_time_map(format!("damped, γ = {gamma:.2e} /t"), &damped.run.space_time, theta_bar)),
        Chart::Lines(Panel {
            title: "antikink position".to_owned(),
            x_label: "time t".to_owned(),
            y_label: "wall position (rotor index)".to_owned(),
            series: vec![
                trajectory(&format!("θ̄ = {theta_bar}, conservative"), &conservative, Style::Line),
                trajectory(&format!("θ̄ = {theta_bar}, γ = {gamma:.2e}"), &damped, Style::Dashed),
                trajectory(&format!("θ̄ = {stated_theta_bar}, conservative"), &at_058, Style::LinePoints),
                Series::new(
                    Quantity::Reference,
                    format!("rotor {trap_rotor}"),
                    vec![(0.0, trap_rotor), (t_max, trap_rotor)],
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
