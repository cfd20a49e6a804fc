//! Secs. III and V: the antikink's energy against `theta_bar` (`fig:akenergy`), its two
//! Peierls-Nabarro equilibria drawn and plotted (`fig:akconfigpn`), and the barrier against the
//! antikink's width (`fig:logvpn-theta`) and the chain's length (`fig:logvpn-size`).

use rotor_chain::RuntimeChain;
use rotor_chain::statics::antikink::{Antikink, AntikinkOptions, barrier_vs_size};
use rotor_chain::statics::continuum::PN_ASYMPTOTIC_LOG_SLOPE;

use super::{ka2, pn, profile, uniform_levels};
use crate::drawing::window;
use crate::figures::{Cause, FigureError, Params, chain, continuum, grid};
use crate::model::{ChainDrawing, Chart, Figure, Panel, Quality, Quantity, Row, Series, Style};
use rotor_chain::ChainGeometry;

/// The paper's Sec. V energies (absolute, `k = 1e4`): minimum, saddle, barrier, as printed.
const PAPER_MINIMUM: &str = "1359.15";
const PAPER_SADDLE: &str = "1359.75";
const PAPER_BARRIER: &str = "0.60";
/// The paper's fitted slope of `ln V_PNB` against `w/a` (Fig. `fig:logvpn-theta`).
const PAPER_LOG_SLOPE: &str = "-10.6";
/// Rotors drawn either side of the antikink's centre in Fig. `fig:akconfigpn`.
const DRAWN: usize = 7;

/// Fig. `fig:akenergy`: the antikink's energy (the Peierls-Nabarro minimum) against `theta_bar`
/// over [`Barrier::energy_range`], `n = params.n`, with Eq. (`eq:akenergy`); the summary row at
/// [`Barrier::theta_bar`].
///
/// [`Barrier::energy_range`]: super::Barrier::energy_range
/// [`Barrier::theta_bar`]: super::Barrier::theta_bar
pub fn akenergy(p: &Params, q: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:akenergy";
    let (from, to) = p.barrier.energy_range;
    let thetas = grid(from, to, q.pick(25, 4));
    let fail = |t: f64| move |e: rotor_chain::statics::StaticsError| FigureError::new(LABEL, e).at("θ̄", t);
    let lattice = thetas
        .iter()
        .map(|&t| Ok((t, pn(p, p.n, t).map_err(fail(t))?.minimum().energy / ka2(p))))
        .collect::<Result<Vec<_>, FigureError>>()?;
    let (lo, hi) = (thetas[0], thetas[thetas.len() - 1]);
    let curve = grid(lo, hi, q.pick(121, 31))
        .into_iter()
        .map(|t| Ok((t, continuum(p, t).map_err(FigureError::on(LABEL))?.antikink_energy() / ka2(p))))
        .collect::<Result<Vec<_>, FigureError>>()?;
    let theta_bar = p.barrier.theta_bar;
    let ours = pn(p, p.n, theta_bar).map_err(fail(theta_bar))?.minimum().energy;
    let theory = continuum(p, theta_bar).map_err(FigureError::on(LABEL))?.antikink_energy();
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Antikink energy (Peierls-Nabarro minimum, ends held) against θ̄, lattice and Eq. (akenergy): \
             n = {}, r/a = {}",
            p.n, p.r
        ),
        panels: vec![
            Panel::new(
                "antikink energy",
                "θ̄ (rad)",
                "V / (k a²)",
                vec![
                    Series::new(Quantity::Lattice, "lattice", lattice, Style::Points),
                    Series::new(Quantity::Continuum, "continuum", curve, Style::Line),
                ],
            )
            .into(),
        ],
        rows: vec![Row::number(
            format!("antikink energy (M a²/t²), θ̄ = {theta_bar}, n = {}, k = {}", p.n, p.k),
            PAPER_MINIMUM,
            ours,
            Some(theory),
            "the paper's Sec. V minimum; θ̄ = 0.575132 reproduces 1359.15 and the paper's saddle and barrier \
             (docs/statics.md §3, fig:akconfigpn)",
        )],
    })
}

/// `theta_bar` at which the Peierls-Nabarro minimum of `n` rotors has energy `target`, by secant
/// iteration from [`Barrier::theta_bar`](super::Barrier::theta_bar) (the paper's 0.58).
fn fit_theta_bar(p: &Params, target: f64, label: &'static str) -> Result<f64, FigureError> {
    let f = |t: f64| -> Result<f64, FigureError> {
        Ok(pn(p, p.n, t).map_err(|e| FigureError::new(label, e).at("θ̄", t))?.minimum().energy - target)
    };
    let (mut t0, mut t1) = (p.barrier.theta_bar - 0.01, p.barrier.theta_bar);
    let (mut f0, mut f1) = (f(t0)?, f(t1)?);
    for _ in 0..20 {
        if f1.abs() < 1e-9 * target.abs() || f1 == f0 {
            break;
        }
        let t2 = t1 - f1 * (t1 - t0) / (f1 - f0);
        (t0, f0) = (t1, f1);
        t1 = t2;
        f1 = f(t1)?;
    }
    Ok(t1)
}

/// Fig. `fig:akconfigpn`: the two Peierls-Nabarro equilibria of the antikink, (a) the minimum
/// (rotor-centred) and (b) the saddle (spring-centred), `n = params.n`, at
/// [`Barrier::theta_bar`](super::Barrier::theta_bar) (0.58).
pub fn akconfigpn(p: &Params, _q: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:akconfigpn";
    let theta_bar = p.barrier.theta_bar;
    let model = chain(p, p.n, theta_bar).map_err(FigureError::on(LABEL))?;
    let barrier = pn(p, p.n, theta_bar).map_err(FigureError::on(LABEL))?;
    let (minimum, saddle) = (barrier.minimum(), barrier.saddle());
    let theory = continuum(p, theta_bar).map_err(FigureError::on(LABEL))?;
    let paper_minimum: f64 = PAPER_MINIMUM.parse().unwrap_or(f64::NAN);
    let fitted = fit_theta_bar(p, paper_minimum, LABEL)?;
    let refit = pn(p, p.n, fitted).map_err(|e| FigureError::new(LABEL, e).at("θ̄", fitted))?;
    let title = |tag: &str, a: &Antikink| {
        format!("{tag}, index {}, centre {:.2}, V = {:.4}", a.classification.index, a.centre, a.energy)
    };
    let drawing = |tag: &str, a: &Antikink| -> Result<ChainDrawing, FigureError> {
        let rotors = window(a.centre, DRAWN, model.rotor_count());
        ChainDrawing::new(
            format!("{} (rotors {}–{})", title(tag, a), rotors.start, rotors.end - 1),
            &model,
            &a.theta,
            rotors,
        )
        .map_err(FigureError::on(LABEL))
    };
    // One stretch scale for both, so that the two equilibria compare by colour.
    let mut drawings = [drawing("(a) minimum", minimum)?, drawing("(b) saddle", saddle)?];
    ChainDrawing::share_stretch_scale(&mut drawings);
    let [minimum_drawing, saddle_drawing] = drawings;
    let panel = |tag: &str, a: &Antikink, name: &str| -> Chart {
        let mut series = vec![Series::new(Quantity::Rotor, name, profile(&a.theta), Style::LinePoints)];
        series.extend(uniform_levels(p.n, theta_bar));
        Panel::new(title(tag, a), "rotor index i", "θ_i (rad)", series).into()
    };
    let resolved = if barrier.resolved { "" } else { " (NOT resolved: no index-0/index-1 pair)" };
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Antikink equilibria, minimum (a, c) and saddle (b, d), drawn and as profiles: n = {}, r/a = {}, θ̄ = {theta_bar}, k = {}, M = {}, \
             ends held",
            p.n, p.r, p.k, p.mass
        ),
        panels: vec![
            minimum_drawing.into(),
            saddle_drawing.into(),
            panel("(c) minimum", minimum, "minimum"),
            panel("(d) saddle", saddle, "saddle"),
        ],
        rows: vec![
            Row::number(
                format!("antikink PN minimum energy (M a²/t²), θ̄ = {theta_bar}, n = {}", p.n),
                PAPER_MINIMUM,
                minimum.energy,
                Some(theory.antikink_energy()),
                "continuum: Eq. (akenergy); ours is the rotor-centred equilibrium, index 0",
            ),
            Row::number(
                format!("antikink PN saddle energy (M a²/t²), θ̄ = {theta_bar}, n = {}", p.n),
                PAPER_SADDLE,
                saddle.energy,
                None,
                format!("spring-centred equilibrium, index {}", saddle.classification.index),
            ),
            Row::number(
                format!("PN barrier V_saddle − V_min (M a²/t²), θ̄ = {theta_bar}, n = {}", p.n),
                PAPER_BARRIER,
                barrier.barrier,
                Some(theory.pn_barrier()),
                format!(
                    "continuum: our peak-to-peak derivation (Eq. PNB2 as printed gives half, {:.4}){resolved}; \
                     θ̄ = {fitted:.7}, fitted to V_min = {PAPER_MINIMUM}, gives saddle {:.4} and barrier {:.4}",
                    theory.pn_barrier_as_printed(),
                    refit.saddle().energy,
                    refit.barrier
                ),
            ),
        ],
    })
}

/// The least-squares line through `points`: `(slope, intercept)`.
fn least_squares(points: &[(f64, f64)]) -> (f64, f64) {
    let n = points.len() as f64;
    let mx = points.iter().map(|q| q.0).sum::<f64>() / n;
    let my = points.iter().map(|q| q.1).sum::<f64>() / n;
    let sxy: f64 = points.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum();
    let sxx: f64 = points.iter().map(|q| (q.0 - mx) * (q.0 - mx)).sum();
    let slope = sxy / sxx;
    (slope, my - slope * mx)
}

/// The fitted line over the `x` range of `points`.
fn fit_line(points: &[(f64, f64)], (slope, intercept): (f64, f64)) -> Vec<(f64, f64)> {
    let lo = points.iter().map(|q| q.0).fold(f64::INFINITY, f64::min);
    let hi = points.iter().map(|q| q.0).fold(f64::NEG_INFINITY, f64::max);
    vec![(lo, slope * lo + intercept), (hi, slope * hi + intercept)]
}

/// Fig. `fig:logvpn-theta`: `ln(V_PNB / (k a^2))` against `w/a` for `theta_bar` over
/// [`Barrier::width_range`](super::Barrier::width_range) (0.35..0.65, where the barrier is
/// resolved at `n = 60`), with its fitted line and the continuum barrier, derived and as printed
/// (Eq. `eq:PNB2`).
pub fn logvpn_theta(p: &Params, q: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:logvpn-theta";
    let (lo, hi) = p.barrier.width_range;
    let thetas = grid(lo, hi, q.pick(13, 4));
    let mut lattice = Vec::new();
    let mut ratios = Vec::new();
    let mut unresolved = Vec::new();
    for &t in &thetas {
        let barrier = pn(p, p.n, t).map_err(|e| FigureError::new(LABEL, e).at("θ̄", t))?;
        let theory = continuum(p, t).map_err(FigureError::on(LABEL))?;
        if barrier.resolved && barrier.barrier > 0.0 {
            lattice.push((theory.width(), (barrier.barrier / ka2(p)).ln()));
            ratios.push(theory.pn_barrier() / barrier.barrier);
        } else {
            unresolved.push(t);
        }
    }
    if lattice.len() < 2 {
        let found = lattice.len();
        return Err(FigureError::new(
            LABEL,
            Cause::TooFewPoints { what: "resolved PN barriers", found, needed: 2 },
        ));
    }
    let fit = least_squares(&lattice);
    let (mut derived, mut printed) = (Vec::new(), Vec::new());
    for t in grid(lo, hi, q.pick(121, 31)) {
        let theory = continuum(p, t).map_err(FigureError::on(LABEL))?;
        derived.push((theory.width(), (theory.pn_barrier() / ka2(p)).ln()));
        printed.push((theory.width(), (theory.pn_barrier_as_printed() / ka2(p)).ln()));
    }
    let local = continuum(p, 0.5).map_err(FigureError::on(LABEL))?.pn_log_slope();
    let (least, most) = ratios.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &r| (a.min(r), b.max(r)));
    let skipped = if unresolved.is_empty() {
        String::new()
    } else {
        format!("; unresolved, left out: θ̄ = {unresolved:?}")
    };
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Peierls-Nabarro barrier against the antikink width, lattice (θ̄ = {lo}–{hi}) and continuum: n = {}, \
             r/a = {}, ends held",
            p.n, p.r
        ),
        panels: vec![
            Panel::new(
                "PN barrier",
                "w / a",
                "ln(V_PNB / (k a²))",
                vec![
                    Series::new(Quantity::Lattice, "lattice", lattice.clone(), Style::Points),
                    Series::new(Quantity::Fit, "fit", fit_line(&lattice, fit), Style::Dashed),
                    Series::new(Quantity::Continuum, "continuum derived", derived, Style::Line),
                    Series::new(Quantity::Continuum, "continuum Eq. PNB2", printed, Style::Dashed),
                ],
            )
            .into(),
        ],
        rows: vec![
            Row::number(
                format!("slope of ln(V_PNB/(k a²)) against w/a, θ̄ = {lo}–{hi}, n = {}", p.n),
                PAPER_LOG_SLOPE,
                fit.0,
                Some(PN_ASYMPTOTIC_LOG_SLOPE),
                format!(
                    "continuum: −π², the large-w asymptote; its local slope at θ̄ = 0.5 is {local:.3}; {} \
                     resolved points{skipped}",
                    lattice.len()
                ),
            ),
            Row::words(
                format!("continuum / lattice PN barrier, θ̄ = {lo}–{hi}"),
                "differ by at least one order of magnitude",
                &format!("continuum {least:.0} to {most:.0} times above"),
                "continuum: our peak-to-peak barrier; Eq. (PNB2) as printed is half of it",
            ),
        ],
    })
}

/// Fig. `fig:logvpn-size`: `ln|Delta V_PNB|` against the number of rotors at
/// [`Barrier::size_theta_bar`](super::Barrier::size_theta_bar) (0.40), `Delta V_PNB = V_PNB(n) -
/// V_PNB(params.n)` for `n` over [`Barrier::sizes`](super::Barrier::sizes), with the fitted decay
/// and the rate `ln F'(theta_bar)` expected from the tails reaching the ends.
pub fn logvpn_size(p: &Params, q: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:logvpn-size";
    let size_theta_bar = p.barrier.size_theta_bar;
    let (first, last) = p.barrier.sizes;
    // Quick: every other length of the first nine.
    let mut sizes: Vec<usize> = match q {
        Quality::Full => (first..=last).collect(),
        Quality::Quick => (first..=last.min(first + 8)).step_by(2).collect(),
    };
    sizes.push(p.n);
    let build = |n: usize| RuntimeChain::builder(n, p.r, p.k, size_theta_bar).mass(p.mass).build();
    let barriers =
        barrier_vs_size(&sizes, build, &AntikinkOptions::default()).map_err(FigureError::on(LABEL))?;
    let (_, reference) = barriers[barriers.len() - 1];
    let energy = pn(p, p.n, size_theta_bar).map_err(FigureError::on(LABEL))?.minimum().energy;
    // Differences below this are rounding in the two energies of each barrier (measured: from
    // n = 27 on they scatter between 2 and 8 eps V_min instead of falling further).
    let floor = 20.0 * f64::EPSILON * energy / ka2(p);
    let (mut resolved, mut rounding) = (Vec::new(), Vec::new());
    for &(n, barrier) in &barriers[..barriers.len() - 1] {
        let delta = ((barrier - reference) / ka2(p)).abs();
        if delta > floor {
            resolved.push((n as f64, delta.ln()));
        } else if delta > 0.0 {
            rounding.push((n as f64, delta.ln()));
        }
    }
    if resolved.len() < 2 {
        let found = resolved.len();
        return Err(FigureError::new(
            LABEL,
            Cause::TooFewPoints { what: "ΔV_PNB above rounding", found, needed: 2 },
        ));
    }
    let fit = least_squares(&resolved);
    let (first, last) = (resolved[0].0, resolved[resolved.len() - 1].0);
    let rate = continuum(p, size_theta_bar).map_err(FigureError::on(LABEL))?.cobweb_slope().ln();
    // The rate ln F' drawn through the centroid of the resolved points.
    let (mx, my) = (
        resolved.iter().map(|q| q.0).sum::<f64>() / resolved.len() as f64,
        resolved.iter().map(|q| q.1).sum::<f64>() / resolved.len() as f64,
    );
    let expected = fit_line(&resolved, (-rate, my + rate * mx));
    let mut series = vec![
        Series::new(Quantity::Lattice, "lattice", resolved.clone(), Style::Points),
        Series::new(Quantity::Fit, "fit", fit_line(&resolved, fit), Style::Dashed),
        Series::new(Quantity::Continuum, "rate ln F'", expected, Style::Line),
    ];
    if !rounding.is_empty() {
        series.push(Series::new(Quantity::Rounding, "rounding level", rounding, Style::Points));
    }
    let row = Row::words(
        format!("finite-size decay of ΔV_PNB, θ̄ = {size_theta_bar}, n = {first}–{last} (above rounding)"),
        "exponential",
        &format!("exponential, {:.3} per rotor", -fit.0),
        format!(
            "continuum: ln F'(θ̄) = 1/ξ, the tails reach the ends with amplitude F'^(-n/2) and the energy is \
             quadratic in them; reference n = {}",
            p.n
        ),
    );
    let row = row.with_continuum(format!("{rate:.3} per rotor"));
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Finite-size correction ΔV_PNB = V_PNB(n) − V_PNB({}) against n: r/a = {}, θ̄ = {size_theta_bar}, \
             ends held",
            p.n, p.r
        ),
        panels: vec![Panel::new("finite size", "number of rotors n", "ln|ΔV_PNB / (k a²)|", series).into()],
        rows: vec![row],
    })
}
