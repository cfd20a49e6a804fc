//! Sec. VII-B, the linkage limit: the potential and phase portraits of kink 1 with the chain
//! drawn (`fig:defectiveKL`), two-kink orbits with the configuration at their start
//! (`fig:orbit`), and the `(E, l0)` diagram (`fig:ELdiagram`).

use rotor_chain::RuntimeChain;
use rotor_chain::statics::linkage::{
    LinkageChain, LinkageError, PhaseState, Region, TrajectoryPoint, el_diagram,
};

use crate::figures::{Cause, FigureError, Params, continuum, grid};
use crate::model::{
    ChainDrawing, Chart, Figure, Heatmap, Panel, Quality, Quantity, Row, Series, Style, format_number,
};

fn linkage(params: &Params, l0: f64) -> Result<LinkageChain, Cause> {
    let l = &params.linkage;
    Ok(LinkageChain::new(continuum(params, l.theta_bar)?, l.rotors, l0)?)
}

/// The real-space chain of the linkage limit with its kinks at `(x1, x2)`: two sub-chains of
/// `m` rotors joined by the impurity spring (rest length `l0`), the angles of
/// `LinkageChain::chain_profile` (Appendix C). The bars' small stretch is that of the continuum
/// profile the linkage limit uses.
fn linkage_drawing(
    params: &Params,
    model: &LinkageChain,
    x: (f64, f64),
    title: String,
) -> Result<Chart, Cause> {
    let m = model.rotors();
    let chain = RuntimeChain::builder(2 * m, params.r, params.k, params.linkage.theta_bar)
        .mass(params.mass)
        .spring_rest_length(m - 1, model.impurity_rest_length())
        .build()?;
    let theta = model.chain_profile(x.0, x.1);
    Ok(ChainDrawing::new(title, &chain, &theta, 0..2 * m)?.into())
}

/// The range of the kink coordinate, `[-(m + 1), m + 1]` (Appendix C: `0` at the far end's
/// collinear point, `m` at the head, `m + 1` where the head rotor is collinear with its bar).
fn coordinate_range(model: &LinkageChain) -> (f64, f64) {
    let end = model.head_position() + 1.0;
    (-end, end)
}

/// The heat map of `V(x1, x2; l0)`, clipped at `cap` (the paper trims a corner for visibility).
fn potential_map(model: &LinkageChain, title: String, points: usize, cap: f64) -> Chart {
    let (from, to) = coordinate_range(model);
    let xs = grid(from, to, points);
    let values =
        xs.iter().map(|&x2| xs.iter().map(|&x1| model.potential(x1, x2).min(cap)).collect()).collect();
    Chart::Heat(Heatmap {
        title,
        x_label: "x1 (a)".to_owned(),
        y_label: "x2 (a)".to_owned(),
        x: xs.clone(),
        y: xs,
        values,
        categories: Vec::new(),
        value_label: "V (M a²/t²)".to_owned(),
        log_x: false,
        colour_limit: None,
    })
}

/// Fig. `fig:defectiveKL` (b): the potential of kink 1 with kink 2 at `x2 = 0` and its phase
/// portraits, below, near and above `l_critical`, and the two-kink potential below it.
pub fn defective_kl(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:defectiveKL";
    let theta_bar = params.linkage.theta_bar;
    let [l0_below, l0_near, l0_above] = params.linkage.rest_lengths;
    let linkage_rotors = params.linkage.rotors;
    let cont = continuum(params, theta_bar).map_err(FigureError::on(LABEL))?;
    let l_c = cont.l_critical();
    let below = linkage(params, l0_below).map_err(FigureError::on(LABEL))?;
    let (from, to) = coordinate_range(&below);
    let xs = grid(from, to, quality.pick(721, 145));
    let mut panels = Vec::new();
    for (tag, l0) in [("below", l0_below), ("near", l0_near), ("above", l0_above)] {
        let model = linkage(params, l0).map_err(|e| FigureError::new(LABEL, e).at("l0", l0))?;
        let e_c = model.critical_energy();
        // V(x1, 0) up to 3 E_c: the walls at the heads rise to 1e3, which would hide the well of
        // depth 0.13 near l_critical.
        let cap = 3.0 * e_c;
        let profile: Vec<(f64, f64)> = model
            .potential_profile(&xs)
            .into_iter()
            .filter(|[_, v]| *v <= cap)
            .map(|[x, v]| (x, v))
            .collect();
        let name = if l0 < l_c { "E_c" } else { "E_min" };
        panels.push(Chart::from(Panel::new(
            format!(
                "V(x1, 0), l0 = {l0:.2} ({tag} l_critical), {name} = {}; V ≤ 3 {name}",
                format_number(e_c)
            ),
            "x1 (a)",
            "V (M a²/t²)",
            vec![Series::new(Quantity::Potential, "V(x1 0)", profile, Style::Line)],
        )));
        // Two energies: inside and outside the separatrix below l_critical, two above the least
        // energy E_min = E_c above it.
        // Below the separatrix bound (blue), above unbound (orange); the higher of two unbound
        // energies dashed.
        let energies: Vec<(String, f64, Quantity, Style)> = if l0 < l_c {
            vec![
                ("E=0.5Ec".to_owned(), 0.5 * e_c, Quantity::Bound, Style::Line),
                ("E=1.5Ec".to_owned(), 1.5 * e_c, Quantity::Unbound, Style::Line),
            ]
        } else {
            vec![
                ("E=1.5Emin".to_owned(), 1.5 * e_c, Quantity::Unbound, Style::Line),
                ("E=2.5Emin".to_owned(), 2.5 * e_c, Quantity::Unbound, Style::Dashed),
            ]
        };
        let mut series = Vec::new();
        for (name, energy, quantity, style) in energies {
            let curves = model.level_curves(energy, &xs);
            let several = curves.len() > 1;
            for (j, curve) in curves.into_iter().enumerate() {
                let mut pts: Vec<(f64, f64)> = curve.into_iter().map(|[x, p]| (x, p)).collect();
                if let Some(&first) = pts.first() {
                    pts.push(first);
                }
                let label = if several { format!("{name} #{}", j + 1) } else { name.clone() };
                series.push(Series::new(quantity, label, pts, style));
            }
        }
        panels.push(Chart::from(Panel::new(
            format!("phase portrait of kink 1 (x2 = 0), l0 = {l0:.2}"),
            "x1 (a)",
            "p1 (M a/t)",
            series,
        )));
    }
    let e_c = below.critical_energy();
    panels.push(potential_map(
        &below,
        format!("V(x1, x2; l0 = {l0_below:.2}), clipped at 1.5 E_c = {}", format_number(1.5 * e_c)),
        quality.pick(181, 37),
        1.5 * e_c,
    ));
    let x_eq = below.equilibria().iter().filter(|e| e.stable).map(|e| e.x).fold(f64::NAN, f64::max);
    let title =
        format!("(a) the chain at x1 = x_eq = {x_eq:.2}, x2 = 0, l0 = {l0_below:.2} (impurity outlined)");
    panels.insert(0, linkage_drawing(params, &below, (x_eq, 0.0), title).map_err(FigureError::on(LABEL))?);
    let rows = vec![Row::number(
        format!("kink-1 equilibrium x_eq (x2 = 0), l0 = {l0_below} < l_critical"),
        "8",
        x_eq,
        None,
        "the paper gives x_eq ≈ ±8 for an unstated l0 < l_critical; ours grows to 8.20 at l0 = 2.0 \
         and merges into 0 as l0 → l_critical (pitchfork)",
    )];
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Linkage limit, two sub-chains of {linkage_rotors} rotors, θ̄ = {theta_bar}, r/a = {}, k = {}, \
             M = {}: the chain (a), V(x1, 0) and phase portraits of kink 1 at l0 = {l0_below:.2}, {l0_near:.2}, \
             {l0_above:.2} (l_critical = {l_c:.4}), and V(x1, x2) at l0 = {l0_below:.2}",
            params.r, params.k, params.mass
        ),
        panels,
        rows,
    })
}

/// A state at `(x1, x2)` whose momenta point along `direction` with `H = energy`.
fn start(model: &LinkageChain, x: [f64; 2], direction: [f64; 2], energy: f64) -> PhaseState {
    let kinetic = (energy - model.potential(x[0], x[1])).max(0.0);
    let per_unit = direction[0] * direction[0] / (2.0 * model.kink_mass(x[0]))
        + direction[1] * direction[1] / (2.0 * model.kink_mass(x[1]));
    let s = if per_unit > 0.0 { (kinetic / per_unit).sqrt() } else { 0.0 };
    PhaseState { x1: x[0], x2: x[1], p1: s * direction[0], p2: s * direction[1] }
}

/// Points of the curve `V(x1, x2) = energy` on a grid over the coordinate range: where `V - E`
/// changes sign between neighbours of a row or a column, linearly interpolated.
fn contour(model: &LinkageChain, energy: f64, points: usize) -> Vec<(f64, f64)> {
    let (from, to) = coordinate_range(model);
    let xs = grid(from, to, points);
    let f: Vec<Vec<f64>> =
        xs.iter().map(|&y| xs.iter().map(|&x| model.potential(x, y) - energy).collect()).collect();
    let cross = |a: f64, b: f64, fa: f64, fb: f64| a + (b - a) * fa / (fa - fb);
    let mut out = Vec::new();
    for (r, row) in f.iter().enumerate() {
        for c in 0..points {
            if c + 1 < points && row[c] * row[c + 1] < 0.0 {
                out.push((cross(xs[c], xs[c + 1], row[c], row[c + 1]), xs[r]));
            }
            if r + 1 < points && row[c] * f[r + 1][c] < 0.0 {
                out.push((xs[c], cross(xs[r], xs[r + 1], row[c], f[r + 1][c])));
            }
        }
    }
    out
}

/// `(a)`, `(b)`, ...: the panel letter of the `index`-th panel (from 0).
fn letter(index: usize) -> String {
    format!("({})", char::from(b'a' + (index % 26) as u8))
}

/// One case of Fig. `fig:orbit`.
struct OrbitCase {
    title: &'static str,
    l0: f64,
    /// The energy, from the model.
    energy: fn(&LinkageChain) -> f64,
    position: [f64; 2],
    direction: [f64; 2],
}

/// Fig. `fig:orbit`: two-kink trajectories in the `(x1, x2)` plane.
pub fn orbit(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:orbit";
    let theta_bar = params.linkage.theta_bar;
    let [l0_below, _, l0_above] = params.linkage.rest_lengths;
    let linkage_rotors = params.linkage.rotors;
    let l_c = continuum(params, theta_bar).map_err(FigureError::on(LABEL))?.l_critical();
    let (dt, steps) = (4.0e-4, quality.pick(50_000, 3_000));
    let stride = (steps / 2_000).max(1);
    let cases = [
        OrbitCase {
            title: "(e) l0 < l_critical, E = 0.7 E_c",
            l0: l0_below,
            energy: |m| 0.7 * m.critical_energy(),
            position: [6.6, 4.0],
            direction: [1.0, 0.0],
        },
        OrbitCase {
            title: "(f) l0 < l_critical, E = 1.2 E_c",
            l0: l0_below,
            energy: |m| 1.2 * m.critical_energy(),
            position: [6.0, 5.0],
            direction: [-1.0, -0.6],
        },
        OrbitCase {
            title: "(g) l0 = l_critical (E_c = 0), E = 20",
            l0: l_c,
            energy: |_| 20.0,
            position: [2.0, -3.0],
            direction: [1.0, 0.6],
        },
        OrbitCase {
            title: "(h) l0 > l_critical, E = E_min + 20",
            l0: l0_above,
            energy: |m| m.critical_energy() + 20.0,
            position: [2.0, -3.0],
            direction: [1.0, 0.6],
        },
    ];
    let (mut drawings, mut panels) = (Vec::new(), Vec::new());
    let mut rows = Vec::new();
    let mut drifts = Vec::new();
    for case in &cases {
        let model = linkage(params, case.l0).map_err(|e| FigureError::new(LABEL, e).at("l0", case.l0))?;
        let energy = (case.energy)(&model);
        let state = start(&model, case.position, case.direction, energy);
        let run = model.trajectory(state, dt, steps, stride).map_err(FigureError::on(LABEL))?;
        let e0 = run[0].energy;
        drifts.push(run.iter().map(|p| (p.energy - e0).abs()).fold(0.0, f64::max) / e0.abs().max(1e-300));
        let region = model.region(e0).map_err(FigureError::on(LABEL))?;
        let region_name = format!("{region:?}").to_lowercase();
        let path: Vec<(f64, f64)> = run.iter().map(|p: &TrajectoryPoint| (p.x1, p.x2)).collect();
        panels.push(Chart::from(Panel::new(
            format!("{}: l0 = {:.4}, E = {}, {}", case.title, case.l0, format_number(e0), region_name),
            "x1 (a)",
            "x2 (a)",
            vec![
                Series::new(Quantity::Trajectory, "trajectory", path, Style::Line),
                Series::new(
                    Quantity::Reference,
                    "V = E",
                    contour(&model, e0, quality.pick(161, 41)),
                    Style::Points,
                ),
                Series::new(
                    Quantity::Configuration,
                    "start (drawn above)",
                    vec![(state.x1, state.x2)],
                    Style::Points,
                ),
            ],
        )));
        // The drawings come first, (a) to (d); each names the trajectory it starts, (e) to (h).
        let tag = &case.title[..case.title.find(')').map_or(0, |i| i + 1)];
        let title = format!(
            "{} the chain at the start of {tag}, x1 = {:.2}, x2 = {:.2}",
            letter(drawings.len()),
            state.x1,
            state.x2
        );
        drawings.push(
            linkage_drawing(params, &model, (state.x1, state.x2), title).map_err(FigureError::on(LABEL))?,
        );
        // Annulus: the kinks are never both near their far ends at once.
        let inner = run.iter().map(|p| p.x1.abs().max(p.x2.abs())).fold(f64::INFINITY, f64::min);
        let (paper, note) = match region {
            Region::Annulus => (
                "square annulus: the kinks take turns",
                "the kinks never both leave the impurity: max(|x1|, |x2|) stays near x_eq",
            ),
            Region::Disk => (
                "square disk: both kinks may leave the impurity",
                "both kinks reach their far ends (x = 0) at the same time",
            ),
            Region::Forbidden => ("forbidden", ""),
        };
        if case.l0 < l_c {
            rows.push(Row::words(
                format!("two-kink orbit, l0 = {}, E/E_c = {:.1}", case.l0, e0 / model.critical_energy()),
                paper,
                &format!("{region_name}; min over t of max(|x1|, |x2|) = {}", format_number(inner)),
                note,
            ));
        }
    }
    let worst = drifts.iter().copied().fold(0.0, f64::max);
    drawings.extend(panels);
    let panels = drawings;
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Two-kink trajectories on V(x1, x2; l0) (e-h) and the chain at each start (a-d; the red dot of e-h), \
             {linkage_rotors}-rotor sub-chains, θ̄ = {theta_bar}, \
             r/a = {}, k = {}, M = {}; {steps} symplectic steps of dt = {dt} (max |ΔE|/E = {})",
            params.r,
            params.k,
            params.mass,
            format_number(worst)
        ),
        panels,
        rows,
    })
}

/// Fig. `fig:ELdiagram`: the `(E, l0)` diagram.
pub fn el_diagram_figure(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:ELdiagram";
    let theta_bar = params.linkage.theta_bar;
    let cont = continuum(params, theta_bar).map_err(FigureError::on(LABEL))?;
    let (l_c, bar) = (cont.l_critical(), cont.rest_length());
    let (from, to) = ((bar + 0.03).max(1.7), 2.9);
    let l0s = grid(from, to, quality.pick(241, 49));
    let curve = el_diagram(&cont, &l0s).map_err(FigureError::on(LABEL))?;
    let e_max = curve.iter().map(|p| p[1]).fold(0.0, f64::max) * 1.1;
    let left: Vec<(f64, f64)> = curve.iter().filter(|p| p[0] <= l_c).map(|p| (p[0], p[1])).collect();
    let right: Vec<(f64, f64)> = curve.iter().filter(|p| p[0] >= l_c).map(|p| (p[0], p[1])).collect();
    let energies = grid(0.0, e_max, quality.pick(201, 41));
    let categories = [Region::Annulus, Region::Disk, Region::Forbidden];
    let values = energies
        .iter()
        .map(|&e| {
            l0s.iter()
                .map(|&l0| {
                    let region = Region::classify(&cont, l0, e)?;
                    Ok(categories.iter().position(|&c| c == region).unwrap_or(0) as f64)
                })
                .collect::<Result<Vec<f64>, LinkageError>>()
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(FigureError::on(LABEL))?;
    // Region labels: one representative point of each region.
    let mid_left = 0.5 * (from + l_c);
    let mid_right = 0.5 * (l_c + to);
    let (e_left, e_right) = (cont.critical_energy(mid_left), cont.critical_energy(mid_right));
    let panels = vec![
        Chart::from(Panel::new(
            "(a) the critical energies against l0",
            "l0 / a",
            "E (M a²/t²)",
            vec![
                Series::new(Quantity::Continuum, "E_c (annulus below; disk above)", left, Style::Line),
                Series::new(Quantity::Continuum, "E_min (forbidden below)", right, Style::Dashed),
                Series::new(
                    Quantity::Reference,
                    "l0 = l_critical",
                    vec![(l_c, 0.0), (l_c, e_max)],
                    Style::Dashed,
                ),
                Series::new(Quantity::Annulus, "annulus", vec![(mid_left, 0.5 * e_left)], Style::Points),
                Series::new(Quantity::Disk, "disk", vec![(mid_left, 0.5 * (e_left + e_max))], Style::Points),
                Series::new(
                    Quantity::Forbidden,
                    "forbidden",
                    vec![(mid_right, 0.5 * e_right)],
                    Style::Points,
                ),
            ],
        )),
        Chart::Heat(Heatmap {
            title: "(b) the region of each (l0, E)".to_owned(),
            x_label: "l0 / a".to_owned(),
            y_label: "E (M a²/t²)".to_owned(),
            x: l0s.clone(),
            y: energies,
            values,
            categories: vec!["annulus".to_owned(), "disk".to_owned(), "forbidden".to_owned()],
            value_label: "region".to_owned(),
            log_x: false,
            colour_limit: None,
        }),
    ];
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "(E, l0) diagram of the linkage limit: (a) E_c = k (l0 − l_critical)²/2 below l_critical, E_min \
             above, and one dot in each region in its colour of (b), which marks every (l0, E) annulus, disk or \
             forbidden; l_critical = {l_c:.4}, l̄ = {bar:.4}, θ̄ = {theta_bar}, r/a = {}, k = {}",
            params.r, params.k
        ),
        panels,
        rows: Vec::new(),
    })
}
