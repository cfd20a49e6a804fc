//! Figures of Secs. II-V (see [`super::all`]): the kink and antikink cobweb plots, the antikink
//! profile and spring stretch, the antikink energy against `theta_bar`, the two Peierls-Nabarro
//! equilibria, and the barrier against the antikink's width and against the chain's length.
//!
//! Units are those of the paper (Appendix B): `a = 1`, so `k a^2` is `params.k`. Energies in the
//! summary rows are absolute (`M a^2 / t^2`, as the paper prints them); energies on the axes are in
//! `k a^2`. The antikink is always the equilibrium with its end rotors held at `-+theta_bar`
//! (`docs/statics.md` §3, "Boundary treatment").

use rotor_chain::statics::antikink::{
    Antikink, AntikinkOptions, PeierlsNabarro, barrier_vs_size, peierls_nabarro,
};
use rotor_chain::statics::cobweb::cobweb;
use rotor_chain::statics::continuum::{ContinuumChain, PN_ASYMPTOTIC_LOG_SLOPE};
use rotor_chain::statics::kink::{kink, reflected_kink};
use rotor_chain::statics::walls::Charge;
use rotor_chain::{ChainModel, RuntimeChain};

use super::{FigureError, FigureFn, Params};
use crate::model::{Chart, Figure, Panel, Quality, Row, Series, Style};

/// This module's figures, in the paper's order.
pub fn figures() -> Vec<(&'static str, FigureFn)> {
    vec![
        ("fig:kcobweb", kcobweb as FigureFn),
        ("fig:akcobweb", akcobweb),
        ("fig:aktheta", aktheta),
        ("fig:akenergy", akenergy),
        ("fig:akconfigpn", akconfigpn),
        ("fig:logvpn-theta", logvpn_theta),
        ("fig:logvpn-size", logvpn_size),
    ]
}

/// The equilibrium angle of the paper's figures (Secs. II, V).
const THETA_BAR: f64 = 0.58;
/// The chain of the cobweb pictures: the paper's core "rotors 8 and 9", "8th spring" (Sec. II).
const COBWEB_ROTORS: usize = 16;
/// Half-width of the cobweb plot's window (rad): wide enough to show the constraint curve turning
/// back beyond `+-theta_bar` (its vertical tangent is at `theta_{i+1} = 0.70`).
const COBWEB_RANGE: f64 = 0.8;
/// The paper's Sec. V energies (absolute, `k = 1e4`): minimum, saddle, barrier.
const PAPER_MINIMUM: f64 = 1359.15;
const PAPER_SADDLE: f64 = 1359.75;
const PAPER_BARRIER: f64 = 0.60;
/// The paper's fitted slope of `ln V_PNB` against `w/a` (Fig. `fig:logvpn-theta`).
const PAPER_LOG_SLOPE: f64 = -10.6;
/// The equilibrium angle of the finite-size study (Fig. `fig:logvpn-size`).
const SIZE_THETA_BAR: f64 = 0.40;

/// The paper's chain with `n` rotors at `theta_bar` (`a = 1`).
fn chain(p: &Params, n: usize, theta_bar: f64, label: &'static str) -> Result<RuntimeChain, FigureError> {
    RuntimeChain::builder(n, p.r, p.k, theta_bar).mass(p.mass).build().map_err(FigureError::on(label))
}

/// The continuum theory of the same chain.
fn continuum(p: &Params, theta_bar: f64, label: &'static str) -> Result<ContinuumChain, FigureError> {
    ContinuumChain::new(1.0, p.r, theta_bar, p.k, p.mass).map_err(FigureError::on(label))
}

/// The minimum and saddle of the antikink in the middle of `n` rotors, ends held.
fn pn(p: &Params, n: usize, theta_bar: f64, label: &'static str) -> Result<PeierlsNabarro, FigureError> {
    peierls_nabarro(&chain(p, n, theta_bar, label)?, &AntikinkOptions::default())
        .map_err(FigureError::on(label))
}

/// `k a^2` with `a = 1`.
fn ka2(p: &Params) -> f64 {
    p.k
}

/// `n` evenly spaced values from `from` to `to`.
fn linspace(from: f64, to: f64, n: usize) -> impl Iterator<Item = f64> {
    let step = if n > 1 { (to - from) / (n - 1) as f64 } else { 0.0 };
    (0..n).map(move |j| from + step * j as f64)
}

/// `from, from + step, ...` up to `to` (inclusive to rounding).
fn grid(from: f64, to: f64, step: f64) -> Vec<f64> {
    let count = ((to - from) / step + 1e-9).floor() as usize + 1;
    (0..count).map(|j| from + step * j as f64).collect()
}

fn lines(title: &str, x_label: &str, y_label: &str, series: Vec<Series>) -> Chart {
    Chart::Lines(Panel {
        title: title.to_owned(),
        x_label: x_label.to_owned(),
        y_label: y_label.to_owned(),
        series,
        log_y: false,
    })
}

/// `(i, theta_i)`.
fn profile(theta: &[f64]) -> Vec<(f64, f64)> {
    theta.iter().enumerate().map(|(i, &t)| (i as f64, t)).collect()
}

fn pairs(points: &[[f64; 2]]) -> Vec<(f64, f64)> {
    points.iter().map(|&[x, y]| (x, y)).collect()
}

/// Horizontal lines at `+-theta_bar` across `n` rotors.
fn uniform_levels(n: usize, theta_bar: f64) -> [Series; 2] {
    let end = (n - 1) as f64;
    [
        Series::new("+theta_bar", vec![(0.0, theta_bar), (end, theta_bar)], Style::Dashed),
        Series::new("-theta_bar", vec![(0.0, -theta_bar), (end, -theta_bar)], Style::Dashed),
    ]
}

/// Points of a curve.
type Curve = Vec<(f64, f64)>;

/// Spring `p`'s rest-length curve in the window `[-range, range]^2`, well resolved where it is
/// flat and where it is steep: `(x, F(x))` by the map where its slope is below 1 (`x + y <= 0`),
/// `(F^-1(y), y)` by the inverse map where it is above. Split where the map's two roots meet (the
/// vertical tangent beyond `+theta_bar`) into the flipper branch `F` and the other branch.
fn constraint_curve<M: ChainModel>(model: &M, p: usize, range: f64, samples: usize) -> (Curve, Curve) {
    let mut flipper: Vec<(f64, f64)> = linspace(-range, range, samples)
        .filter_map(|x| model.next_angles(p, x).ok().map(|[y, _]| (x, y)))
        .filter(|&(x, y)| x + y <= 0.0 && y.abs() <= range)
        .collect();
    let steep: Vec<(f64, f64)> = linspace(-range, range, samples)
        .filter_map(|y| model.previous_angles(p, y).ok().map(|[x, _]| (x, y)))
        .filter(|&(x, y)| x + y > 0.0 && x.abs() <= range)
        .collect();
    let turn = steep.iter().enumerate().max_by(|a, b| a.1.0.total_cmp(&b.1.0)).map(|(i, _)| i);
    let other = match turn {
        Some(turn) => {
            flipper.extend_from_slice(&steep[..=turn]);
            steep[turn..].to_vec()
        }
        None => Vec::new(),
    };
    (flipper, other)
}

/// The cobweb panel: spring `p`'s constraint curve (flipper branch solid, the other branch dashed
/// where it enters the window), the diagonal, the staircase, rotor and spring points.
fn cobweb_panel<M: ChainModel>(
    title: &str,
    model: &M,
    p: usize,
    theta: &[f64],
    q: Quality,
) -> Result<Chart, rotor_chain::statics::StaticsError> {
    let samples = q.pick(241, 61);
    let web = cobweb(model, p, theta, COBWEB_RANGE, 2)?;
    let (flipper, other) = constraint_curve(model, p, COBWEB_RANGE, samples);
    let mut series = vec![Series::new("flipper branch", flipper, Style::Line)];
    if other.len() > 1 {
        series.push(Series::new("other branch", other, Style::Dashed));
    }
    series.extend([
        Series::new("diagonal", pairs(&web.diagonal), Style::Line),
        Series::new("staircase", pairs(&web.staircase), Style::Line),
        Series::new("rotors", pairs(&web.rotors), Style::Points),
        Series::new("springs", pairs(&web.springs), Style::Points),
    ]);
    Ok(lines(title, "θ_i (rad)", "θ_{i+1} (rad)", series))
}

/// Fig. `fig:kcobweb`: the zero-energy kink centred in a 16-rotor chain (on its middle spring) and
/// its cobweb plot on that spring's constraint curve. The paper states no number here.
pub fn kcobweb(p: &Params, q: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:kcobweb";
    let n = COBWEB_ROTORS;
    let model = chain(p, n, THETA_BAR, LABEL)?;
    let centre = (n - 1) as f64 / 2.0;
    let theta = kink(&model, centre).map_err(FigureError::on(LABEL))?;
    let mut config = vec![Series::new("kink", profile(&theta), Style::LinePoints)];
    config.extend(uniform_levels(n, THETA_BAR));
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Kink configuration (a) and cobweb plot (b), springs at rest: n = {n}, r/a = {}, θ̄ = {THETA_BAR}, \
             centre {centre}",
            p.r
        ),
        panels: vec![
            lines("(a) kink", "rotor index i", "θ_i (rad)", config),
            cobweb_panel("(b) cobweb plot", &model, n / 2 - 1, &theta, q).map_err(FigureError::on(LABEL))?,
        ],
        rows: Vec::new(),
    })
}

/// The antikink of Figs. `fig:akcobweb` and `fig:aktheta`: the Peierls-Nabarro minimum of the
/// 16-rotor chain at `theta_bar = 0.58`, ends held.
fn cobweb_antikink(p: &Params, label: &'static str) -> Result<(RuntimeChain, Antikink), FigureError> {
    let model = chain(p, COBWEB_ROTORS, THETA_BAR, label)?;
    let minimum = peierls_nabarro(&model, &AntikinkOptions::default())
        .map_err(FigureError::on(label))?
        .minimum()
        .clone();
    Ok((model, minimum))
}

/// Fig. `fig:akcobweb`: the antikink (Peierls-Nabarro minimum, ends held) and its cobweb plot,
/// whose spring points leave the constraint curve near the core. Panel (a) also shows the
/// paper's starting guess, the reflected kink. The paper states no number here.
pub fn akcobweb(p: &Params, q: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:akcobweb";
    let (model, antikink) = cobweb_antikink(p, LABEL)?;
    let n = model.rotor_count();
    let start = reflected_kink(&model, antikink.centre).map_err(FigureError::on(LABEL))?;
    let spring = (antikink.centre.floor() as usize).min(n - 2);
    let mut config = vec![
        Series::new("antikink", profile(&antikink.theta), Style::LinePoints),
        Series::new("reflected kink", profile(&start), Style::Dashed),
    ];
    config.extend(uniform_levels(n, THETA_BAR));
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Antikink at the Peierls-Nabarro minimum, ends held at ∓θ̄ (a), and its cobweb plot (b): n = {n}, \
             r/a = {}, θ̄ = {THETA_BAR}, centre {:.2}",
            p.r, antikink.centre
        ),
        panels: vec![
            lines("(a) antikink", "rotor index i", "θ_i (rad)", config),
            cobweb_panel("(b) cobweb plot", &model, spring, &antikink.theta, q)
                .map_err(FigureError::on(LABEL))?,
        ],
        rows: Vec::new(),
    })
}

/// Fig. `fig:aktheta`: (a) the antikink of Fig. `fig:akcobweb` against the continuum profile
/// `theta = asin(u / r)`, `u = ubar tanh((x - x0)/w)` (Eq. `eq:kinksolution`) centred on it;
/// (b) the stretch `l_p - lbar` of every spring. The paper states no number here.
pub fn aktheta(p: &Params, q: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:aktheta";
    let (model, antikink) = cobweb_antikink(p, LABEL)?;
    let n = model.rotor_count();
    let theory = continuum(p, THETA_BAR, LABEL)?;
    let end = (n - 1) as f64;
    let curve = linspace(0.0, end, q.pick(20, 4) * (n - 1) + 1)
        .map(|x| (x, theory.angle(Charge::Antikink, x, antikink.centre)))
        .collect();
    let mut lengths = vec![0.0; n - 1];
    model.spring_lengths_into(&antikink.theta, &mut lengths);
    let stretch = lengths.iter().enumerate().map(|(s, l)| (s as f64, l - model.rest_length(s))).collect();
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Antikink profile against the continuum wall (a) and spring stretch (b): n = {n}, r/a = {}, \
             θ̄ = {THETA_BAR}, ends held, w = {:.4} a",
            p.r,
            theory.width()
        ),
        panels: vec![
            lines(
                "(a) θ profile",
                "rotor index i",
                "θ_i (rad)",
                vec![
                    Series::new("lattice", profile(&antikink.theta), Style::Points),
                    Series::new("continuum", curve, Style::Line),
                ],
            ),
            lines(
                "(b) spring stretch",
                "spring index p (joins rotors p and p+1)",
                "l_p − l̄ (a)",
                vec![Series::new("stretch", stretch, Style::LinePoints)],
            ),
        ],
        rows: Vec::new(),
    })
}

/// Fig. `fig:akenergy`: the antikink's energy (the Peierls-Nabarro minimum) against `theta_bar`,
/// `n = params.n`, with Eq. (`eq:akenergy`).
pub fn akenergy(p: &Params, q: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:akenergy";
    let thetas = match q {
        Quality::Full => grid(0.05, 0.65, 0.025),
        Quality::Quick => vec![0.1, 0.3, 0.5, 0.65],
    };
    let lattice = thetas
        .iter()
        .map(|&t| Ok((t, pn(p, p.n, t, LABEL)?.minimum().energy / ka2(p))))
        .collect::<Result<Vec<_>, FigureError>>()?;
    let (lo, hi) = (thetas[0], thetas[thetas.len() - 1]);
    let curve = linspace(lo, hi, q.pick(121, 31))
        .map(|t| Ok((t, continuum(p, t, LABEL)?.antikink_energy() / ka2(p))))
        .collect::<Result<Vec<_>, FigureError>>()?;
    let ours = pn(p, p.n, THETA_BAR, LABEL)?.minimum().energy;
    let theory = continuum(p, THETA_BAR, LABEL)?.antikink_energy();
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Antikink energy (Peierls-Nabarro minimum, ends held) against θ̄, lattice and Eq. (akenergy): \
             n = {}, r/a = {}",
            p.n, p.r
        ),
        panels: vec![lines(
            "antikink energy",
            "θ̄ (rad)",
            "V / (k a²)",
            vec![
                Series::new("lattice", lattice, Style::Points),
                Series::new("continuum", curve, Style::Line),
            ],
        )],
        rows: vec![Row::number(
            format!("antikink energy (M a²/t²), θ̄ = {THETA_BAR}, n = {}, k = {}", p.n, p.k),
            PAPER_MINIMUM,
            ours,
            Some(theory),
            "the paper's Sec. V minimum; θ̄ = 0.575132 reproduces 1359.15 and the paper's saddle and barrier \
             (docs/statics.md §3, fig:akconfigpn)",
        )],
    })
}

/// `theta_bar` at which the Peierls-Nabarro minimum of `n` rotors has energy `target`, by secant
/// iteration from the paper's 0.58.
fn fit_theta_bar(p: &Params, target: f64, label: &'static str) -> Result<f64, FigureError> {
    let f = |t: f64| -> Result<f64, FigureError> { Ok(pn(p, p.n, t, label)?.minimum().energy - target) };
    let (mut t0, mut t1) = (THETA_BAR - 0.01, THETA_BAR);
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
/// (rotor-centred) and (b) the saddle (spring-centred), `n = params.n`, `theta_bar = 0.58`.
pub fn akconfigpn(p: &Params, _q: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:akconfigpn";
    let barrier = pn(p, p.n, THETA_BAR, LABEL)?;
    let (minimum, saddle) = (barrier.minimum(), barrier.saddle());
    let theory = continuum(p, THETA_BAR, LABEL)?;
    let fitted = fit_theta_bar(p, PAPER_MINIMUM, LABEL)?;
    let refit = pn(p, p.n, fitted, LABEL)?;
    let panel = |title: &str, a: &Antikink, name: &str| {
        let mut series = vec![Series::new(name, profile(&a.theta), Style::LinePoints)];
        series.extend(uniform_levels(p.n, THETA_BAR));
        lines(
            &format!(
                "{title}, index {}, centre {:.2}, V = {:.4}",
                a.classification.index, a.centre, a.energy
            ),
            "rotor index i",
            "θ_i (rad)",
            series,
        )
    };
    let resolved = if barrier.resolved { "" } else { " (NOT resolved: no index-0/index-1 pair)" };
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Antikink equilibria, (a) minimum and (b) saddle: n = {}, r/a = {}, θ̄ = {THETA_BAR}, k = {}, M = {}, \
             ends held",
            p.n, p.r, p.k, p.mass
        ),
        panels: vec![panel("(a) minimum", minimum, "minimum"), panel("(b) saddle", saddle, "saddle")],
        rows: vec![
            Row::number(
                format!("antikink PN minimum energy (M a²/t²), θ̄ = {THETA_BAR}, n = {}", p.n),
                PAPER_MINIMUM,
                minimum.energy,
                Some(theory.antikink_energy()),
                "continuum: Eq. (akenergy); ours is the rotor-centred equilibrium, index 0",
            ),
            Row::number(
                format!("antikink PN saddle energy (M a²/t²), θ̄ = {THETA_BAR}, n = {}", p.n),
                PAPER_SADDLE,
                saddle.energy,
                None,
                format!("spring-centred equilibrium, index {}", saddle.classification.index),
            ),
            Row::number(
                format!("PN barrier V_saddle − V_min (M a²/t²), θ̄ = {THETA_BAR}, n = {}", p.n),
                PAPER_BARRIER,
                barrier.barrier,
                Some(theory.pn_barrier()),
                format!(
                    "continuum: our peak-to-peak derivation (Eq. PNB2 as printed gives half, {:.4}){resolved}; \
                     θ̄ = {fitted:.6}, fitted to V_min = {PAPER_MINIMUM}, gives saddle {:.4} and barrier {:.4}",
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

/// Fig. `fig:logvpn-theta`: `ln(V_PNB / (k a^2))` against `w/a` for `theta_bar` in 0.35..0.65
/// (where the barrier is resolved at `n = 60`), with its fitted line and the continuum barrier,
/// derived and as printed (Eq. `eq:PNB2`).
pub fn logvpn_theta(p: &Params, q: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:logvpn-theta";
    let (lo, hi) = (0.35, 0.65);
    let thetas = match q {
        Quality::Full => grid(lo, hi, 0.025),
        Quality::Quick => vec![0.35, 0.45, 0.55, 0.65],
    };
    let mut lattice = Vec::new();
    let mut ratios = Vec::new();
    let mut unresolved = Vec::new();
    for &t in &thetas {
        let barrier = pn(p, p.n, t, LABEL)?;
        let theory = continuum(p, t, LABEL)?;
        if barrier.resolved && barrier.barrier > 0.0 {
            lattice.push((theory.width(), (barrier.barrier / ka2(p)).ln()));
            ratios.push(theory.pn_barrier() / barrier.barrier);
        } else {
            unresolved.push(t);
        }
    }
    if lattice.len() < 2 {
        return Err(FigureError::new(LABEL, format!("fewer than two resolved barriers over θ̄ = {thetas:?}")));
    }
    let fit = least_squares(&lattice);
    let (mut derived, mut printed) = (Vec::new(), Vec::new());
    for t in linspace(lo, hi, q.pick(121, 31)) {
        let theory = continuum(p, t, LABEL)?;
        derived.push((theory.width(), (theory.pn_barrier() / ka2(p)).ln()));
        printed.push((theory.width(), (theory.pn_barrier_as_printed() / ka2(p)).ln()));
    }
    let local = continuum(p, 0.5, LABEL)?.pn_log_slope();
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
        panels: vec![lines(
            "PN barrier",
            "w / a",
            "ln(V_PNB / (k a²))",
            vec![
                Series::new("lattice", lattice.clone(), Style::Points),
                Series::new("fit", fit_line(&lattice, fit), Style::Dashed),
                Series::new("continuum derived", derived, Style::Line),
                Series::new("continuum Eq. PNB2", printed, Style::Dashed),
            ],
        )],
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

/// Fig. `fig:logvpn-size`: `ln|Delta V_PNB|` against the number of rotors at `theta_bar = 0.40`,
/// `Delta V_PNB = V_PNB(n) - V_PNB(params.n)`, with the fitted decay and the rate `ln F'(0.40)`
/// expected from the tails reaching the ends.
pub fn logvpn_size(p: &Params, q: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:logvpn-size";
    let mut sizes: Vec<usize> = match q {
        Quality::Full => (16..=36).collect(),
        Quality::Quick => vec![16, 18, 20, 22, 24],
    };
    sizes.push(p.n);
    let build = |n: usize| RuntimeChain::builder(n, p.r, p.k, SIZE_THETA_BAR).mass(p.mass).build();
    let barriers =
        barrier_vs_size(&sizes, build, &AntikinkOptions::default()).map_err(FigureError::on(LABEL))?;
    let (_, reference) = barriers[barriers.len() - 1];
    let energy = pn(p, p.n, SIZE_THETA_BAR, LABEL)?.minimum().energy;
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
        return Err(FigureError::new(
            LABEL,
            format!("fewer than two differences above rounding ({floor:.1e})"),
        ));
    }
    let fit = least_squares(&resolved);
    let (first, last) = (resolved[0].0, resolved[resolved.len() - 1].0);
    let rate = continuum(p, SIZE_THETA_BAR, LABEL)?.cobweb_slope().ln();
    // The rate ln F' drawn through the centroid of the resolved points.
    let (mx, my) = (
        resolved.iter().map(|q| q.0).sum::<f64>() / resolved.len() as f64,
        resolved.iter().map(|q| q.1).sum::<f64>() / resolved.len() as f64,
    );
    let expected = fit_line(&resolved, (-rate, my + rate * mx));
    let mut series = vec![
        Series::new("lattice", resolved.clone(), Style::Points),
        Series::new("fit", fit_line(&resolved, fit), Style::Dashed),
        Series::new("rate ln F'", expected, Style::Line),
    ];
    if !rounding.is_empty() {
        series.push(Series::new("rounding level", rounding, Style::Points));
    }
    let mut row = Row::words(
        format!("finite-size decay of ΔV_PNB, θ̄ = {SIZE_THETA_BAR}, n = {first}–{last} (above rounding)"),
        "exponential",
        &format!("exponential, {:.3} per rotor", -fit.0),
        format!(
            "continuum: ln F'(θ̄) = 1/ξ, the tails reach the ends with amplitude F'^(-n/2) and the energy is \
             quadratic in them; reference n = {}",
            p.n
        ),
    );
    row.continuum = Some(format!("{rate:.3} per rotor"));
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Finite-size correction ΔV_PNB = V_PNB(n) − V_PNB({}) against n: r/a = {}, θ̄ = {SIZE_THETA_BAR}, \
             ends held",
            p.n, p.r
        ),
        panels: vec![lines("finite size", "number of rotors n", "ln|ΔV_PNB / (k a²)|", series)],
        rows: vec![row],
    })
}
