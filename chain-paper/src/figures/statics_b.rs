//! Figures of the paper's linear modes and bond-length impurity (Secs. IV and VII, see
//! [`super::all`]): the localised modes of the kink and the antikink (`fig:mode-config`,
//! `fig:w-th`), the zero, soft and tensional modes of a long middle spring (`fig:longbar`), and
//! the linkage limit: the two-kink potential and phase portraits (`fig:defectiveKL`), two-kink
//! orbits (`fig:orbit`) and the `(E, l0)` diagram (`fig:ELdiagram`).
//!
//! Frequencies are given in the paper's unit `(r/a) sqrt(k/M)` (Sec. VII-A), energies in
//! `M a^2 / t^2` (with `a = 1`), positions in lattice spacings `a`.

use rotor_chain::RuntimeChain;
use rotor_chain::prelude::ChainModel;
use rotor_chain::statics::antikink::{AntikinkOptions, peierls_nabarro};
use rotor_chain::statics::continuum::ContinuumChain;
use rotor_chain::statics::counting::maxwell_calladine;
use rotor_chain::statics::equilibrium::{NewtonOptions, norm, stiffness};
use rotor_chain::statics::impurity::{critical_length, impurity_analysis, two_kink_configuration};
use rotor_chain::statics::kink::kink;
use rotor_chain::statics::linkage::{LinkageChain, PhaseState, Region, TrajectoryPoint, el_diagram};
use rotor_chain::statics::modes::{Mode, ModeKind, ModeOptions, modes};
use rotor_chain::statics::walls::domain_walls;

use super::{FigureError, FigureFn, Params};
use crate::model::{Chart, Figure, Heatmap, Panel, Quality, Row, Series, Style, format_number};

/// This module's figures, in the paper's order.
pub fn figures() -> Vec<(&'static str, FigureFn)> {
    vec![
        ("fig:mode-config", mode_config),
        ("fig:w-th", w_th),
        ("fig:longbar", longbar),
        ("fig:defectiveKL", defective_kl),
        ("fig:orbit", orbit),
        ("fig:ELdiagram", el_diagram_figure),
    ]
}

/// The equilibrium angle of Figs. `fig:mode-config`, `fig:longbar` and Sec. VII-B.
const THETA_BAR: f64 = 0.58;
/// The impurity's rest length of Fig. `fig:longbar`.
const LONGBAR_L0: f64 = 2.30;
/// Rotors per sub-chain of the linkage limit (Fig. `fig:defect-chain-conf`).
const LINKAGE_ROTORS: usize = 8;
/// Impurity rest lengths of the linkage figures: below, near (just below) and above `l_critical`.
const L0_BELOW: f64 = 2.15;
const L0_NEAR: f64 = 2.30;
const L0_ABOVE: f64 = 2.40;
/// The least chain length of Fig. `fig:w-th`: the walls at `theta_bar = 0.05` (`w = 12.5 a`) must
/// not feel the ends, which at `n = 60` lift the antikink's translation frequency to `1e-3`.
const W_TH_ROTORS: usize = 240;
/// Rotors shown either side of a defect in Fig. `fig:mode-config`.
const MODE_WINDOW: usize = 12;

/// The paper's frequency unit `(r/a) sqrt(k/M)` (`a = 1`), in `1/t`.
fn unit(params: &Params) -> f64 {
    params.r * (params.k / params.mass).sqrt()
}

fn chain(params: &Params, n: usize, theta_bar: f64) -> Result<RuntimeChain, String> {
    RuntimeChain::builder(n, params.r, params.k, theta_bar)
        .mass(params.mass)
        .build()
        .map_err(|e| e.to_string())
}

fn continuum(params: &Params, theta_bar: f64) -> Result<ContinuumChain, String> {
    ContinuumChain::new(1.0, params.r, theta_bar, params.k, params.mass).map_err(|e| e.to_string())
}

/// The middle spring of an `n`-rotor chain, the impurity of Sec. VII-A.
fn middle_spring(n: usize) -> usize {
    (n - 1) / 2
}

/// `v` scaled so that its largest component is `+1` (sign fixed for reproducible plots).
fn normalised(v: &[f64]) -> Vec<f64> {
    let peak = v.iter().copied().max_by(|a, b| a.abs().total_cmp(&b.abs())).unwrap_or(0.0);
    if peak == 0.0 { v.to_vec() } else { v.iter().map(|x| x / peak).collect() }
}

/// `(i, v_i)` for `i` in `range`.
fn indexed(v: &[f64], range: std::ops::Range<usize>) -> Vec<(f64, f64)> {
    range.filter_map(|i| v.get(i).map(|&x| (i as f64, x))).collect()
}

/// `"+0.7 %"`.
fn percent(x: f64) -> String {
    format!("{:+.1} %", 100.0 * x)
}

fn lines(title: impl Into<String>, x_label: &str, y_label: &str, series: Vec<Series>, log_y: bool) -> Chart {
    Chart::Lines(Panel {
        title: title.into(),
        x_label: x_label.to_owned(),
        y_label: y_label.to_owned(),
        series,
        log_y,
    })
}

// ------------------------------------------------------------------------------------------------
// Sec. IV: localised modes of the kink and the antikink.

/// The centred kink and the antikink minimum (ends held, as it is computed) with their lowest
/// modes.
struct DefectModes {
    kink_theta: Vec<f64>,
    kink_modes: Vec<Mode>,
    antikink_theta: Vec<f64>,
    antikink_modes: Vec<Mode>,
}

fn defect_modes(model: &RuntimeChain, n: usize) -> Result<DefectModes, String> {
    let lowest = ModeOptions { count: Some(6), ..ModeOptions::default() };
    let kink_theta = kink(model, (n as f64 - 1.0) / 2.0).map_err(|e| e.to_string())?;
    let kink_modes = modes(model, &kink_theta, &lowest).map_err(|e| e.to_string())?;
    // A tight Newton tolerance: at small theta_bar the default 1e-11 leaves a residual whose
    // third-order coupling shows as a spurious translation curvature (1e-5 (r/a)sqrt(k/M) at 0.05).
    let options = AntikinkOptions {
        newton: NewtonOptions { tolerance: 1e-14, ..NewtonOptions::default() },
        ..AntikinkOptions::default()
    };
    let pn = peierls_nabarro(model, &options).map_err(|e| e.to_string())?;
    let antikink_theta = pn.minimum().theta.clone();
    let held = ModeOptions { hold_ends: true, ..lowest };
    let antikink_modes = modes(model, &antikink_theta, &held).map_err(|e| e.to_string())?;
    Ok(DefectModes { kink_theta, kink_modes, antikink_theta, antikink_modes })
}

fn first_of(list: &[Mode], kind: ModeKind) -> Option<&Mode> {
    list.iter().find(|m| m.kind == kind)
}

/// The smallest frequency we count as resolved at `theta`: ten times `sqrt(eps ||K|| / (M r^2))`,
/// the rounding of a double-precision `omega^2` (a margin of 100 in `omega^2`); below it a
/// frequency is zero at machine precision.
fn frequency_resolution(model: &RuntimeChain, theta: &[f64], params: &Params) -> f64 {
    let (diag, off) = stiffness(model, theta);
    10.0 * (f64::EPSILON * norm(&diag, &off) / (params.mass * params.r * params.r)).sqrt()
}

/// `"0.8936 (r/a)√(k/M)"`, or `"0 (rounding)"` below the resolution `floor` (both in `1/t`).
fn frequency_label(omega: f64, floor: f64, unit: f64) -> String {
    if omega <= floor {
        "0 (rounding)".to_owned()
    } else {
        format!("{} (r/a)√(k/M)", format_number(omega / unit))
    }
}

/// Fig. `fig:mode-config`: the translation and shape modes of the kink and the antikink.
pub fn mode_config(params: &Params, _quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:mode-config";
    let n = params.n;
    let model = chain(params, n, THETA_BAR).map_err(FigureError::on(LABEL))?;
    let DefectModes { kink_theta, kink_modes, antikink_theta, antikink_modes } =
        defect_modes(&model, n).map_err(FigureError::on(LABEL))?;
    let u = unit(params);
    let mut panels = Vec::new();
    let cases = [
        ("(a) kink translation", &kink_theta, &kink_modes, ModeKind::Translation),
        ("(b) kink shape", &kink_theta, &kink_modes, ModeKind::Shape),
        ("(c) antikink translation", &antikink_theta, &antikink_modes, ModeKind::Translation),
        ("(d) antikink shape", &antikink_theta, &antikink_modes, ModeKind::Shape),
    ];
    for (title, theta, list, kind) in cases {
        let mode =
            first_of(list, kind).ok_or_else(|| FigureError::new(LABEL, format!("{title}: no such mode")))?;
        let centre = domain_walls(theta).first().map_or(n as f64 / 2.0, |w| w.position);
        let from = (centre.round() as usize).saturating_sub(MODE_WINDOW);
        let to = (centre.round() as usize + MODE_WINDOW + 1).min(n);
        let profile: Vec<f64> = theta.iter().map(|t| t / THETA_BAR).collect();
        let omega = frequency_label(mode.frequency, frequency_resolution(&model, theta, params), u);
        panels.push(lines(
            format!("{title} mode, ω = {omega}, wall at {centre:.2}"),
            "rotor index i",
            "mode component (max 1); θ_i / θbar",
            vec![
                Series::new("mode", indexed(&normalised(&mode.shape), from..to), Style::LinePoints),
                Series::new("θ_i/θbar", indexed(&profile, from..to), Style::Dashed),
            ],
            false,
        ));
    }
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Translation and shape modes of the kink (a, b) and the antikink minimum (c, d; ends held), \
             n = {n}, r/a = {}, θbar = {THETA_BAR}, k = {}, M = {}; rotors within {MODE_WINDOW} of the wall \
             shown",
            params.r, params.k, params.mass
        ),
        panels,
        rows: Vec::new(),
    })
}

/// One `theta_bar` of Fig. `fig:w-th`: kink and antikink translation and shape frequencies (in
/// `1/t`, `None` when zero at machine precision) and the continuum shape mode.
struct LocalisedModes {
    theta_bar: f64,
    kink_translation: Option<f64>,
    kink_shape: Option<f64>,
    antikink_translation: Option<f64>,
    antikink_shape: Option<f64>,
    continuum_shape: f64,
}

fn localised_modes(params: &Params, n: usize, theta_bar: f64) -> Result<LocalisedModes, String> {
    let model = chain(params, n, theta_bar)?;
    let DefectModes { kink_theta, kink_modes, antikink_theta, antikink_modes } = defect_modes(&model, n)?;
    let resolved = |theta: &[f64], list: &[Mode], kind| {
        let floor = frequency_resolution(&model, theta, params);
        first_of(list, kind).map(|m| m.frequency).filter(|&w| w > floor)
    };
    Ok(LocalisedModes {
        theta_bar,
        kink_translation: resolved(&kink_theta, &kink_modes, ModeKind::Translation),
        kink_shape: resolved(&kink_theta, &kink_modes, ModeKind::Shape),
        antikink_translation: resolved(&antikink_theta, &antikink_modes, ModeKind::Translation),
        antikink_shape: resolved(&antikink_theta, &antikink_modes, ModeKind::Shape),
        continuum_shape: continuum(params, theta_bar)?.shape_mode_frequency(),
    })
}

/// Fig. `fig:w-th`: localised-mode frequencies of the kink and the antikink against `theta_bar`.
pub fn w_th(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:w-th";
    let thetas: Vec<f64> = match quality {
        Quality::Full => (0..=24).map(|j| 0.05 + 0.025 * j as f64).collect(),
        Quality::Quick => vec![0.05, 0.1, 0.3, 0.5, 0.65],
    };
    let u = unit(params);
    let n = params.n.max(W_TH_ROTORS);
    let data: Vec<LocalisedModes> = thetas
        .iter()
        .map(|&t| localised_modes(params, n, t))
        .collect::<Result<_, _>>()
        .map_err(FigureError::on(LABEL))?;
    let points = |get: &dyn Fn(&LocalisedModes) -> Option<f64>| -> Vec<(f64, f64)> {
        data.iter().filter_map(|d| get(d).map(|w| (d.theta_bar, w / u))).filter(|p| p.1 > 0.0).collect()
    };
    let curve: Vec<(f64, f64)> = (0..=60)
        .map(|j| 0.05 + 0.6 * j as f64 / 60.0)
        .map(|t| continuum(params, t).map(|c| (t, c.shape_mode_frequency() / u)))
        .collect::<Result<_, _>>()
        .map_err(FigureError::on(LABEL))?;
    let panel = |title: &str, shape: Vec<(f64, f64)>, translation: Vec<(f64, f64)>| {
        lines(
            title,
            "θbar (rad)",
            "ω / ((r/a)√(k/M))",
            // A translation mode that is zero at every theta_bar (the kink's) has no point.
            // The continuum first, so the colours agree between the panels.
            [
                Series::new("continuum shape", curve.clone(), Style::Line),
                Series::new("shape", shape, Style::Points),
                Series::new("translation", translation, Style::Points),
            ]
            .into_iter()
            .filter(|s| !s.points.is_empty())
            .collect(),
            true,
        )
    };
    let panels = vec![
        panel("(a) kink", points(&|d| d.kink_shape), points(&|d| d.kink_translation)),
        panel("(b) antikink", points(&|d| d.antikink_shape), points(&|d| d.antikink_translation)),
    ];

    // Rows at theta_bar = 0.1 (the paper: agreement with the continuum at small theta_bar) and 0.58.
    let small = localised_modes(params, n, 0.1).map_err(FigureError::on(LABEL))?;
    let mut rows = Vec::new();
    for (name, ours) in [("kink", small.kink_shape), ("antikink", small.antikink_shape)] {
        let ours = ours.ok_or_else(|| FigureError::new(LABEL, format!("{name}: no shape mode at 0.1")))?;
        let row = Row::words(
            format!("{name} shape-mode frequency at θ̄ = 0.1, n = {n} ((r/a)√(k/M))"),
            "agrees with continuum",
            &format!(
                "{} vs continuum {} ({})",
                format_number(ours / u),
                format_number(small.continuum_shape / u),
                percent(ours / small.continuum_shape - 1.0)
            ),
            "the paper shows the agreement graphically (Fig. w-th), no number; we compare with \
             Eq. (continuumtheoryfrequency2)",
        );
        rows.push(Row { continuum: Some(format_number(small.continuum_shape / u)), ..row });
    }
    let range = format!("θ̄ = {:.3}..{:.3}", thetas[0], thetas[thetas.len() - 1]);
    let kink_resolved: Vec<f64> =
        data.iter().filter(|d| d.kink_translation.is_some()).map(|d| d.theta_bar).collect();
    rows.push(Row::words(
        format!("kink translation-mode frequency, {range}, n = {n}"),
        "zero at machine precision",
        &if kink_resolved.is_empty() {
            "zero (below 10 sqrt(ε‖K‖/(Mr²))) at every θ̄".to_owned()
        } else {
            format!("resolved at θ̄ = {kink_resolved:?}")
        },
        "ω² of order ε‖K‖: rounding",
    ));
    // The antikink: zero below some theta_bar, finite above.
    let zero_up_to = data.iter().take_while(|d| d.antikink_translation.is_none()).last().map(|d| d.theta_bar);
    let first_resolved = data.iter().find_map(|d| d.antikink_translation.map(|w| (d.theta_bar, w)));
    rows.push(Row::words(
        format!("antikink translation-mode frequency, {range}, n = {n}"),
        "effectively zero for θ̄ < 0.1, finite above",
        &match (zero_up_to, first_resolved) {
            (Some(z), Some((t, w))) => format!(
                "zero up to θ̄ = {z:.3}; first resolved at θ̄ = {t:.3}: {} (r/a)√(k/M)",
                format_number(w / u)
            ),
            (None, Some((t, w))) => {
                format!("resolved at every θ̄, {} (r/a)√(k/M) at θ̄ = {t:.3}", format_number(w / u))
            }
            (_, None) => "zero at every θ̄".to_owned(),
        },
        "zero: below 10 sqrt(ε‖K‖/(Mr²)); at n = 60 the ends lift it to ~1e-4 at θ̄ = 0.1 \
         (docs/statics.md §5)",
    ));
    let mid = localised_modes(params, n, THETA_BAR).map_err(FigureError::on(LABEL))?;
    if let (Some(t), Some(s)) = (mid.antikink_translation, mid.antikink_shape) {
        rows.push(Row::words(
            "antikink ω_t / ω_s at θ̄ = 0.58",
            "finite, significantly smaller than ω_s",
            &format!("{} / {} = {}", format_number(t / u), format_number(s / u), format_number(t / s)),
            "the antikink's translation is pinned by its Peierls-Nabarro potential",
        ));
    }
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Localised-mode frequencies of (a) the kink and (b) the antikink against θbar (shape, \
             translation; zero at machine precision omitted), n = {n}, r/a = {}, k = {}, M = {}; line: \
             continuum Eq. (continuumtheoryfrequency2)",
            params.r, params.k, params.mass
        ),
        panels,
        rows,
    })
}

// ------------------------------------------------------------------------------------------------
// Sec. VII-A: a long middle spring.

/// Fig. `fig:longbar`: zero mode, soft mode and soft tensional mode of a long middle spring.
pub fn longbar(params: &Params, _quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:longbar";
    let n = params.n;
    let p = middle_spring(n);
    let build = |l0: f64| {
        RuntimeChain::builder(n, params.r, params.k, THETA_BAR)
            .mass(params.mass)
            .spring(p, Some(params.k), Some(l0))
            .build()
            .map_err(FigureError::on(LABEL))
    };
    let model = build(LONGBAR_L0)?;
    let analysis = impurity_analysis(&model, p).map_err(FigureError::on(LABEL))?;
    let u = unit(params);
    let cont = continuum(params, THETA_BAR).map_err(FigureError::on(LABEL))?;
    let (zero, soft) = (&analysis.modes[0], &analysis.modes[1]);
    let profile: Vec<f64> = analysis.theta.iter().map(|t| t / THETA_BAR).collect();
    let mode_panel = |title: String, mode: &Mode| {
        lines(
            title,
            "rotor index i",
            "mode component (max 1); θ_i / θbar",
            vec![
                Series::new("mode", indexed(&normalised(&mode.shape), 0..n), Style::LinePoints),
                Series::new("θ_i/θbar", indexed(&profile, 0..n), Style::Dashed),
            ],
            false,
        )
    };
    let tensions = normalised(&analysis.tensional.tensions);
    let floor = frequency_resolution(&model, &analysis.theta, params);
    let panels = vec![
        mode_panel(format!("(a) zero mode, ω = {}", frequency_label(zero.frequency, floor, u)), zero),
        mode_panel(format!("(b) soft mode, ω = {}", frequency_label(soft.frequency, floor, u)), soft),
        lines(
            format!(
                "(c) soft tensional mode, eigenvalue of CCᵀ = {}",
                format_number(analysis.tensional.eigenvalue)
            ),
            "spring index p",
            "tension (max 1)",
            vec![Series::new("tension", indexed(&tensions, 0..tensions.len()), Style::LinePoints)],
            false,
        ),
    ];

    let kink_shape = {
        let plain = chain(params, n, THETA_BAR).map_err(FigureError::on(LABEL))?;
        let theta = kink(&plain, (n as f64 - 1.0) / 2.0).map_err(FigureError::on(LABEL))?;
        let list = modes(&plain, &theta, &ModeOptions { count: Some(4), ..ModeOptions::default() })
            .map_err(FigureError::on(LABEL))?;
        first_of(&list, ModeKind::Shape).map_or(f64::NAN, |m| m.frequency / u)
    };
    let at_critical = {
        let critical = build(analysis.critical_length)?;
        let theta = two_kink_configuration(&critical, p).map_err(FigureError::on(LABEL))?;
        maxwell_calladine(&critical, &theta, None).map_err(FigureError::on(LABEL))?
    };
    let plural =
        |count: usize, word: &str, many: &str| format!("{count} {}", if count == 1 { word } else { many });
    let count = |zero: usize, selfs: usize| {
        format!(
            "{}, {}",
            plural(zero, "zero mode", "zero modes"),
            plural(selfs, "self-stress", "self-stresses")
        )
    };
    let rows = vec![
        Row::number(
            "l_critical / a (θ̄ = 0.58, r/a = 0.8)",
            2.31,
            critical_length(&model, p).map_err(FigureError::on(LABEL))?,
            Some(cont.l_critical()),
            "2.3051 rounds to the paper's 2.31",
        ),
        Row::number(
            "soft-mode frequency at l0 = 2.30 ((r/a)√(k/M))",
            7.7e-9,
            soft.frequency / u,
            None,
            "7.7e-9 is below the resolution of ω from a double-precision ω² (≈2e-8) and would need \
             l_critical − l0 ≈ 2e-9, not the paper's 0.005; ours scales as 4.1 (l_critical − l0) \
             (docs/statics.md §7)",
        ),
        Row::number(
            "lbar / a (θ̄ = 0.58, r/a = 0.8)",
            1.68,
            model.rest_length(0),
            Some(cont.rest_length()),
            "sqrt(a² + 4r² cos²θ̄) = 1.6707 rounds to 1.67, not 1.68; 1.68 would need θ̄ = 0.5666 \
             (docs/statics.md §3)",
        ),
        Row {
            continuum: Some(format_number(cont.shape_mode_frequency() / u)),
            ..Row::words(
                "kink shape-mode frequency, θ̄ = 0.58 ((r/a)√(k/M))",
                "of the order 1e-2",
                &format_number(kink_shape),
                "the caption's 1e-2 disagrees with both our lattice value and the continuum, \
                 Eq. (continuumtheoryfrequency2)",
            )
        },
        Row::words(
            "Maxwell-Calladine counting at l0 = 2.30",
            "1 zero mode, 0 self-stresses",
            &count(analysis.counting.zero_modes.len(), analysis.counting.self_stresses.len()),
            "",
        ),
        Row::words(
            format!("Maxwell-Calladine counting at l0 = l_critical, n = {n}"),
            "2 zero modes, 1 self-stress",
            &count(at_critical.zero_modes.len(), at_critical.self_stresses.len()),
            "for short chains (n = 16) the self-stress is truncated at F'^(-n/2) and counts as 0",
        ),
    ];
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Zero mode (a), soft mode (b) and soft tensional mode (c) with a long middle spring (spring {p}, \
             l0/a = {LONGBAR_L0:.2}, same stiffness), n = {n}, θbar = {THETA_BAR}, r/a = {}, k = {}, M = {}",
            params.r, params.k, params.mass
        ),
        panels,
        rows,
    })
}

// ------------------------------------------------------------------------------------------------
// Sec. VII-B: the linkage limit.

fn linkage(params: &Params, l0: f64) -> Result<LinkageChain, String> {
    LinkageChain::new(continuum(params, THETA_BAR)?, LINKAGE_ROTORS, l0).map_err(|e| e.to_string())
}

/// `count` points from `from` to `to`.
fn grid(from: f64, to: f64, count: usize) -> Vec<f64> {
    (0..count).map(|j| from + (to - from) * j as f64 / (count - 1) as f64).collect()
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
    })
}

/// Fig. `fig:defectiveKL` (b): the potential of kink 1 with kink 2 at `x2 = 0` and its phase
/// portraits, below, near and above `l_critical`, and the two-kink potential below it.
pub fn defective_kl(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:defectiveKL";
    let cont = continuum(params, THETA_BAR).map_err(FigureError::on(LABEL))?;
    let l_c = cont.l_critical();
    let below = linkage(params, L0_BELOW).map_err(FigureError::on(LABEL))?;
    let (from, to) = coordinate_range(&below);
    let xs = grid(from, to, quality.pick(721, 145));
    let mut panels = Vec::new();
    for (tag, l0) in [("below", L0_BELOW), ("near", L0_NEAR), ("above", L0_ABOVE)] {
        let model = linkage(params, l0).map_err(FigureError::on(LABEL))?;
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
        panels.push(lines(
            format!(
                "V(x1, 0), l0 = {l0:.2} ({tag} l_critical), {name} = {}; V ≤ 3 {name}",
                format_number(e_c)
            ),
            "x1 (a)",
            "V (M a²/t²)",
            vec![Series::new("V(x1 0)", profile, Style::Line)],
            false,
        ));
        // Two energies: inside and outside the separatrix below l_critical, two above the least
        // energy E_min = E_c above it.
        let energies: Vec<(String, f64)> = if l0 < l_c {
            [0.5, 1.5].iter().map(|&f| (format!("E={f}Ec"), f * e_c)).collect()
        } else {
            [1.5, 2.5].iter().map(|&f| (format!("E={f}Emin"), f * e_c)).collect()
        };
        let mut series = Vec::new();
        for (name, energy) in energies {
            let curves = model.level_curves(energy, &xs);
            let several = curves.len() > 1;
            for (j, curve) in curves.into_iter().enumerate() {
                let mut pts: Vec<(f64, f64)> = curve.into_iter().map(|[x, p]| (x, p)).collect();
                if let Some(&first) = pts.first() {
                    pts.push(first);
                }
                let label = if several { format!("{name} #{}", j + 1) } else { name.clone() };
                series.push(Series::new(label, pts, Style::Line));
            }
        }
        panels.push(lines(
            format!("phase portrait of kink 1 (x2 = 0), l0 = {l0:.2}"),
            "x1 (a)",
            "p1 (M a/t)",
            series,
            false,
        ));
    }
    let e_c = below.critical_energy();
    panels.push(potential_map(
        &below,
        format!("V(x1, x2; l0 = {L0_BELOW:.2}), clipped at 1.5 E_c = {}", format_number(1.5 * e_c)),
        quality.pick(181, 37),
        1.5 * e_c,
    ));
    let x_eq = below.equilibria().iter().filter(|e| e.stable).map(|e| e.x).fold(f64::NAN, f64::max);
    let rows = vec![Row::number(
        format!("kink-1 equilibrium x_eq (x2 = 0), l0 = {L0_BELOW} < l_critical"),
        8.0,
        x_eq,
        None,
        "the paper gives x_eq ≈ ±8 for an unstated l0 < l_critical; ours grows to 8.20 at l0 = 2.0 \
         and merges into 0 as l0 → l_critical (pitchfork)",
    )];
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Linkage limit, two sub-chains of {LINKAGE_ROTORS} rotors, θbar = {THETA_BAR}, r/a = {}, k = {}, \
             M = {}: V(x1, 0) and phase portraits of kink 1 at l0 = {L0_BELOW:.2}, {L0_NEAR:.2}, \
             {L0_ABOVE:.2} (l_critical = {l_c:.4}), and V(x1, x2) at l0 = {L0_BELOW:.2}",
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
    let l_c = continuum(params, THETA_BAR).map_err(FigureError::on(LABEL))?.l_critical();
    let (dt, steps) = (4.0e-4, quality.pick(50_000, 3_000));
    let stride = (steps / 2_000).max(1);
    let cases = [
        OrbitCase {
            title: "(a) l0 < l_critical, E = 0.7 E_c",
            l0: L0_BELOW,
            energy: |m| 0.7 * m.critical_energy(),
            position: [6.6, 4.0],
            direction: [1.0, 0.0],
        },
        OrbitCase {
            title: "(b) l0 < l_critical, E = 1.2 E_c",
            l0: L0_BELOW,
            energy: |m| 1.2 * m.critical_energy(),
            position: [6.0, 5.0],
            direction: [-1.0, -0.6],
        },
        OrbitCase {
            title: "(c) l0 = l_critical (E_c = 0), E = 20",
            l0: l_c,
            energy: |_| 20.0,
            position: [2.0, -3.0],
            direction: [1.0, 0.6],
        },
        OrbitCase {
            title: "(d) l0 > l_critical, E = E_min + 20",
            l0: L0_ABOVE,
            energy: |m| m.critical_energy() + 20.0,
            position: [2.0, -3.0],
            direction: [1.0, 0.6],
        },
    ];
    let mut panels = Vec::new();
    let mut rows = Vec::new();
    let mut drifts = Vec::new();
    for case in &cases {
        let model = linkage(params, case.l0).map_err(FigureError::on(LABEL))?;
        let energy = (case.energy)(&model);
        let state = start(&model, case.position, case.direction, energy);
        let run = model.trajectory(state, dt, steps, stride).map_err(FigureError::on(LABEL))?;
        let e0 = run[0].energy;
        drifts.push(run.iter().map(|p| (p.energy - e0).abs()).fold(0.0, f64::max) / e0.abs().max(1e-300));
        let region = model.region(e0).map_err(FigureError::on(LABEL))?;
        let region_name = format!("{region:?}").to_lowercase();
        let path: Vec<(f64, f64)> = run.iter().map(|p: &TrajectoryPoint| (p.x1, p.x2)).collect();
        panels.push(lines(
            format!("{}: l0 = {:.4}, E = {}, {}", case.title, case.l0, format_number(e0), region_name),
            "x1 (a)",
            "x2 (a)",
            vec![
                Series::new("trajectory", path, Style::Line),
                Series::new("V = E", contour(&model, e0, quality.pick(161, 41)), Style::Points),
                Series::new("start", vec![(state.x1, state.x2)], Style::Points),
            ],
            false,
        ));
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
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Two-kink trajectories on V(x1, x2; l0), {LINKAGE_ROTORS}-rotor sub-chains, θbar = {THETA_BAR}, \
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
    let cont = continuum(params, THETA_BAR).map_err(FigureError::on(LABEL))?;
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
                .collect::<Result<Vec<f64>, rotor_chain::statics::linkage::LinkageError>>()
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(FigureError::on(LABEL))?;
    // Region labels: one representative point of each region.
    let mid_left = 0.5 * (from + l_c);
    let mid_right = 0.5 * (l_c + to);
    let (e_left, e_right) = (cont.critical_energy(mid_left), cont.critical_energy(mid_right));
    let panels = vec![
        lines(
            "(E, l0) diagram",
            "l0 / a",
            "E (M a²/t²)",
            vec![
                Series::new("E_c (annulus below; disk above)", left, Style::Line),
                Series::new("E_min (forbidden below)", right, Style::Line),
                Series::new("l0 = l_critical", vec![(l_c, 0.0), (l_c, e_max)], Style::Dashed),
                Series::new("annulus", vec![(mid_left, 0.5 * e_left)], Style::Points),
                Series::new("disk", vec![(mid_left, 0.5 * (e_left + e_max))], Style::Points),
                Series::new("forbidden", vec![(mid_right, 0.5 * e_right)], Style::Points),
            ],
            false,
        ),
        Chart::Heat(Heatmap {
            title: "accessible region (Region::classify)".to_owned(),
            x_label: "l0 / a".to_owned(),
            y_label: "E (M a²/t²)".to_owned(),
            x: l0s.clone(),
            y: energies,
            values,
            categories: vec!["annulus".to_owned(), "disk".to_owned(), "forbidden".to_owned()],
            value_label: "region".to_owned(),
        }),
    ];
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "(E, l0) diagram of the linkage limit: E_c = k (l0 − l_critical)²/2, l_critical = {l_c:.4}, \
             lbar = {bar:.4}, θbar = {THETA_BAR}, r/a = {}, k = {}",
            params.r, params.k
        ),
        panels,
        rows: Vec::new(),
    })
}
