//! Sec. IV: the translation and shape modes of the kink and the antikink, drawn on the chain
//! and plotted (`fig:mode-config`), and their frequencies against `theta_bar` (`fig:w-th`).

use rotor_chain::RuntimeChain;
use rotor_chain::statics::antikink::{AntikinkOptions, peierls_nabarro};
use rotor_chain::statics::equilibrium::NewtonOptions;
use rotor_chain::statics::kink::kink;
use rotor_chain::statics::modes::{Mode, ModeKind, ModeOptions, modes};
use rotor_chain::statics::walls::domain_walls;

use super::{first_of, frequency_label, frequency_resolution, indexed, normalised, unit};
use crate::drawing::window;
use crate::figures::{Cause, FigureError, Params, chain, continuum, grid};
use crate::model::{
    ChainDrawing, Chart, Figure, Panel, Quality, Quantity, Row, Series, Style, format_number,
};

/// Rotors plotted either side of a defect in Fig. `fig:mode-config`.
const MODE_WINDOW: usize = 12;
/// Rotors drawn either side of a defect in Fig. `fig:mode-config`.
const DRAWN: usize = 6;
/// How many of the lowest modes are searched for the translation and shape modes.
const LOWEST: usize = 6;

/// `"+0.7 %"`.
fn percent(x: f64) -> String {
    format!("{:+.1} %", 100.0 * x)
}

/// The centred kink and the antikink minimum (ends held, as it is computed) with their lowest
/// modes.
struct DefectModes {
    kink_theta: Vec<f64>,
    kink_modes: Vec<Mode>,
    antikink_theta: Vec<f64>,
    antikink_modes: Vec<Mode>,
}

fn defect_modes(model: &RuntimeChain, n: usize) -> Result<DefectModes, Cause> {
    let lowest = ModeOptions { count: Some(LOWEST), ..ModeOptions::default() };
    let kink_theta = kink(model, (n as f64 - 1.0) / 2.0)?;
    let kink_modes = modes(model, &kink_theta, &lowest)?;
    // A tight Newton tolerance: at small theta_bar the default 1e-11 leaves a residual whose
    // third-order coupling shows as a spurious translation curvature (1e-5 (r/a)sqrt(k/M) at 0.05).
    let options = AntikinkOptions {
        newton: NewtonOptions { tolerance: 1e-14, ..NewtonOptions::default() },
        ..AntikinkOptions::default()
    };
    let pn = peierls_nabarro(model, &options)?;
    let antikink_theta = pn.minimum()?.theta.clone();
    let held = ModeOptions { hold_ends: true, ..lowest };
    let antikink_modes = modes(model, &antikink_theta, &held)?;
    Ok(DefectModes { kink_theta, kink_modes, antikink_theta, antikink_modes })
}

/// Fig. `fig:mode-config`: the translation and shape modes of the kink and the antikink.
pub fn mode_config(params: &Params, _quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:mode-config";
    let (n, theta_bar) = (params.n, params.modes.theta_bar);
    let model = chain(params, n, theta_bar).map_err(FigureError::on(LABEL))?;
    let DefectModes { kink_theta, kink_modes, antikink_theta, antikink_modes } =
        defect_modes(&model, n).map_err(FigureError::on(LABEL))?;
    let u = unit(params);
    let (mut drawings, mut plots) = (Vec::new(), Vec::new());
    // Each mode is drawn (panels a-d) and plotted (e-h): a letter of its own for every panel.
    let cases = [
        ("a", "e", "kink translation", "kink", &kink_theta, &kink_modes, ModeKind::Translation),
        ("b", "f", "kink shape", "kink", &kink_theta, &kink_modes, ModeKind::Shape),
        (
            "c",
            "g",
            "antikink translation",
            "antikink",
            &antikink_theta,
            &antikink_modes,
            ModeKind::Translation,
        ),
        ("d", "h", "antikink shape", "antikink", &antikink_theta, &antikink_modes, ModeKind::Shape),
    ];
    for (drawn, plotted_letter, title, defect, theta, list, kind) in cases {
        let mode = first_of(list, kind).ok_or_else(|| {
            let kind = if kind == ModeKind::Shape { "shape" } else { "translation" };
            FigureError::new(LABEL, Cause::NoSuchMode { defect, kind, searched: LOWEST })
        })?;
        let centre = domain_walls(theta).first().map_or(n as f64 / 2.0, |w| w.position);
        let profile: Vec<f64> = theta.iter().map(|t| t / theta_bar).collect();
        let omega = frequency_label(mode.frequency, frequency_resolution(&model, theta, params), u);
        let shown = window(centre, DRAWN, n);
        let drawing = ChainDrawing::new(
            format!("({drawn}) {title} mode, ω = {omega} (rotors {}–{})", shown.start, shown.end - 1),
            &model,
            theta,
            shown,
        )
        .and_then(|d| d.with_mode(&mode.shape))
        .map_err(FigureError::on(LABEL))?;
        drawings.push(Chart::from(drawing));
        let plotted = window(centre, MODE_WINDOW, n);
        plots.push(Chart::from(Panel::new(
            format!("({plotted_letter}) {title}: components, wall at {centre:.2}"),
            "rotor index i",
            "mode component (max 1); θ_i / θ̄",
            vec![
                Series::new(
                    Quantity::Mode,
                    "mode",
                    indexed(&normalised(&mode.shape), plotted.clone()),
                    Style::LinePoints,
                ),
                Series::new(Quantity::Rotor, "θ_i / θ̄", indexed(&profile, plotted), Style::Dashed),
            ],
        )));
    }
    drawings.extend(plots);
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Translation and shape modes of the kink (a, b; e, f) and the antikink minimum (c, d; g, h; ends \
             held), drawn (a-d, arrows: each tip's displacement) and plotted (e-h): n = {n}, r/a = {}, θ̄ = {theta_bar}, k = {}, M = {}",
            params.r, params.k, params.mass
        ),
        panels: drawings,
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

fn localised_modes(params: &Params, n: usize, theta_bar: f64) -> Result<LocalisedModes, FigureError> {
    const LABEL: &str = "fig:w-th";
    let fail = |e: Cause| FigureError::new(LABEL, e).at("θ̄", theta_bar);
    let model = chain(params, n, theta_bar).map_err(|e| fail(e.into()))?;
    let DefectModes { kink_theta, kink_modes, antikink_theta, antikink_modes } =
        defect_modes(&model, n).map_err(fail)?;
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
        continuum_shape: continuum(params, theta_bar).map_err(|e| fail(e.into()))?.shape_mode_frequency(),
    })
}

/// Fig. `fig:w-th`: localised-mode frequencies of the kink and the antikink against `theta_bar`
/// over [`Modes::theta_range`](super::Modes::theta_range).
pub fn w_th(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:w-th";
    let (from, to) = params.modes.theta_range;
    let thetas: Vec<f64> = grid(from, to, quality.pick(25, 5));
    let u = unit(params);
    let n = params.n.max(params.modes.w_th_rotors);
    let data: Vec<LocalisedModes> =
        thetas.iter().map(|&t| localised_modes(params, n, t)).collect::<Result<_, _>>()?;
    let points = |get: &dyn Fn(&LocalisedModes) -> Option<f64>| -> Vec<(f64, f64)> {
        data.iter().filter_map(|d| get(d).map(|w| (d.theta_bar, w / u))).filter(|p| p.1 > 0.0).collect()
    };
    let curve: Vec<(f64, f64)> = grid(from, to, 61)
        .into_iter()
        .map(|t| continuum(params, t).map(|c| (t, c.shape_mode_frequency() / u)))
        .collect::<Result<_, _>>()
        .map_err(FigureError::on(LABEL))?;
    let panel = |title: &str, shape: Vec<(f64, f64)>, translation: Vec<(f64, f64)>| {
        Chart::from(
            Panel::new(
                title,
                "θ̄ (rad)",
                "ω / ((r/a)√(k/M))",
                // A translation mode that is zero at every theta_bar (the kink's) has no point.
                [
                    Series::new(Quantity::Continuum, "continuum shape", curve.clone(), Style::Line),
                    Series::new(Quantity::Mode, "shape ω_s", shape, Style::Points),
                    Series::new(Quantity::Mode, "translation ω_t", translation, Style::OpenPoints),
                ]
                .into_iter()
                .filter(|s| !s.points.is_empty())
                .collect(),
            )
            .log_y(),
        )
    };
    let panels = vec![
        panel("(a) kink", points(&|d| d.kink_shape), points(&|d| d.kink_translation)),
        panel("(b) antikink", points(&|d| d.antikink_shape), points(&|d| d.antikink_translation)),
    ];

    // Rows at theta_bar = 0.1 (the paper: agreement with the continuum at small theta_bar) and 0.58.
    let small = localised_modes(params, n, 0.1)?;
    let mut rows = Vec::new();
    for (name, ours) in [("kink", small.kink_shape), ("antikink", small.antikink_shape)] {
        let ours = ours.ok_or_else(|| {
            FigureError::new(LABEL, Cause::NoSuchMode { defect: name, kind: "shape", searched: LOWEST })
                .at("θ̄", 0.1)
        })?;
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
        rows.push(row.with_continuum(format_number(small.continuum_shape / u)));
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
    let mid = localised_modes(params, n, params.modes.theta_bar)?;
    if let (Some(t), Some(s)) = (mid.antikink_translation, mid.antikink_shape) {
        rows.push(Row::words(
            format!("antikink ω_t / ω_s at θ̄ = {}", params.modes.theta_bar),
            "finite, significantly smaller than ω_s",
            &format!("{} / {} = {}", format_number(t / u), format_number(s / u), format_number(t / s)),
            "the antikink's translation is pinned by its Peierls-Nabarro potential",
        ));
    }
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Localised-mode frequencies of (a) the kink and (b) the antikink against θ̄ (filled: shape, \
             open: translation; zero at machine precision omitted), n = {n}, r/a = {}, k = {}, M = {}; line: \
             continuum Eq. (continuumtheoryfrequency2)",
            params.r, params.k, params.mass
        ),
        panels,
        rows,
    })
}
