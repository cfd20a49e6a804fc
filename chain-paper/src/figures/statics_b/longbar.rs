//! Sec. VII-A: a long middle spring (`fig:longbar`): its zero mode, soft mode and soft tensional
//! mode, drawn on the chain and plotted, and the paper's numbers about them.

use rotor_chain::RuntimeChain;
use rotor_chain::statics::counting::maxwell_calladine;
use rotor_chain::statics::impurity::{impurity_analysis, two_kink_configuration};
use rotor_chain::statics::kink::kink;
use rotor_chain::statics::modes::{Mode, ModeKind, ModeOptions, modes};

use super::{first_of, frequency_label, frequency_resolution, indexed, middle_spring, normalised, unit};
use crate::drawing::window;
use crate::figures::{FigureError, Params, chain, continuum};
use crate::model::{
    ChainDrawing, Chart, Figure, Panel, Quality, Quantity, Row, Series, Style, format_number,
};
use rotor_chain::SpringNetwork;

/// Rotors drawn either side of the impurity.
const DRAWN: usize = 7;

/// Fig. `fig:longbar`: zero mode, soft mode and soft tensional mode of a long middle spring
/// ([`Params::long_bar`]: rest length 2.30 at `theta_bar = 0.58`).
pub fn longbar(params: &Params, _quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:longbar";
    let n = params.n;
    let (theta_bar, rest_length) = (params.long_bar.theta_bar, params.long_bar.rest_length);
    let p = middle_spring(n);
    let build = |l0: f64| {
        RuntimeChain::builder(n, params.r, params.k, theta_bar)
            .mass(params.mass)
            .spring(p, Some(params.k), Some(l0))
            .build()
            .map_err(FigureError::on(LABEL))
    };
    let model = build(rest_length)?;
    let analysis = impurity_analysis(&model, p).map_err(FigureError::on(LABEL))?;
    let u = unit(params);
    let cont = continuum(params, theta_bar).map_err(FigureError::on(LABEL))?;
    let (zero, soft) = (&analysis.modes[0], &analysis.modes[1]);
    let profile: Vec<f64> = analysis.theta.iter().map(|t| t / theta_bar).collect();
    let mode_panel = |title: String, mode: &Mode| -> Chart {
        Panel::new(
            title,
            "rotor index i",
            "mode component (max 1); θ_i / θ̄",
            vec![
                Series::new(
                    Quantity::Mode,
                    "mode",
                    indexed(&normalised(&mode.shape), 0..n),
                    Style::LinePoints,
                ),
                Series::new(Quantity::Rotor, "θ_i / θ̄", indexed(&profile, 0..n), Style::Dashed),
            ],
        )
        .into()
    };
    let tensions = normalised(&analysis.tensional.tensions);
    let floor = frequency_resolution(&model, &analysis.theta, params);
    let (zero_title, soft_title, tension_title) = (
        format!("(a) zero mode, ω = {}", frequency_label(zero.frequency, floor, u)),
        format!("(b) soft mode, ω = {}", frequency_label(soft.frequency, floor, u)),
        format!(
            "(c) soft tensional mode, eigenvalue of CCᵀ = {}",
            format_number(analysis.tensional.eigenvalue)
        ),
    );
    let shown = window(p as f64 + 0.5, DRAWN, n);
    let span = format!(" (rotors {}–{})", shown.start, shown.end - 1);
    let drawing = |title: &str| {
        ChainDrawing::new(format!("{title}{span}"), &model, &analysis.theta, shown.clone())
            .map_err(FigureError::on(LABEL))
    };
    let panels = vec![
        drawing(&zero_title)?.with_mode(&zero.shape).map_err(FigureError::on(LABEL))?.into(),
        drawing(&soft_title)?.with_mode(&soft.shape).map_err(FigureError::on(LABEL))?.into(),
        drawing(&tension_title)?
            .with_tensions(&analysis.tensional.tensions)
            .map_err(FigureError::on(LABEL))?
            .into(),
        mode_panel(zero_title.clone(), zero),
        mode_panel(soft_title.clone(), soft),
        Panel::new(
            tension_title.clone(),
            "spring index p",
            "tension (max 1)",
            vec![Series::new(
                Quantity::Mode,
                "tension",
                indexed(&tensions, 0..tensions.len()),
                Style::LinePoints,
            )],
        )
        .into(),
    ];

    let kink_shape = {
        let plain = chain(params, n, theta_bar).map_err(FigureError::on(LABEL))?;
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
            format!("l_critical / a (θ̄ = {theta_bar}, r/a = {})", params.r),
            "2.31",
            analysis.critical_length,
            Some(cont.l_critical()),
            "2.3051 rounds to the paper's 2.31",
        ),
        Row::number(
            format!("soft-mode frequency at l0 = {rest_length:.2} ((r/a)√(k/M))"),
            "7.7e-9",
            soft.frequency / u,
            None,
            "7.7e-9 would need l_critical − l0 ≈ 2e-9, not the paper's 0.005; ours scales as \
             4.1 (l_critical − l0) (docs/statics.md §7)",
        )
        .resolution(
            floor / u,
            "10 √(ε‖K‖/(M r²)), the least ω resolved from a double-precision ω² for this chain",
        ),
        Row::number(
            format!("l̄ / a (θ̄ = {theta_bar}, r/a = {})", params.r),
            "1.68",
            model.rest_length(0),
            Some(cont.rest_length()),
            "sqrt(a² + 4r² cos²θ̄) = 1.6707 rounds to 1.67, not 1.68; 1.68 would need θ̄ = 0.5666 \
             (docs/statics.md §3)",
        ),
        Row::words(
            format!("kink shape-mode frequency, θ̄ = {theta_bar} ((r/a)√(k/M))"),
            "of the order 1e-2",
            &format_number(kink_shape),
            "the caption's 1e-2 disagrees with both our lattice value and the continuum, \
             Eq. (continuumtheoryfrequency2)",
        )
        .with_continuum(format_number(cont.shape_mode_frequency() / u)),
        Row::words(
            format!("Maxwell-Calladine counting at l0 = {rest_length:.2}"),
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
             l0/a = {rest_length:.2}, same stiffness, outlined), drawn and plotted: n = {n}, θ̄ = {theta_bar}, r/a = {}, k = {}, M = {}",
            params.r, params.k, params.mass
        ),
        panels,
        rows,
    })
}
