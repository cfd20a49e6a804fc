//! Sec. II: the kink and the antikink drawn (`fig:kconfig`, `fig:akconfig`), their cobweb plots
//! (`fig:kcobweb`, `fig:akcobweb`), and the antikink's profile against the continuum and its
//! spring stretch (`fig:aktheta`). The paper states no number in these figures.

use rotor_chain::statics::StaticsError;
use rotor_chain::statics::antikink::{Antikink, AntikinkOptions, peierls_nabarro};
use rotor_chain::statics::cobweb::cobweb;
use rotor_chain::statics::kink::{kink, reflected_kink};
use rotor_chain::statics::walls::Charge;
use rotor_chain::{ChainModel, RuntimeChain};

use super::{profile, uniform_levels};
use crate::figures::{FigureError, Params, chain, continuum, grid};
use crate::model::{ChainDrawing, Chart, Figure, Panel, Quality, Quantity, Series, Style};
use rotor_chain::ChainGeometry;
use rotor_chain::SpringNetwork;

/// Half-width of the cobweb plot's window (rad): wide enough to show the constraint curve turning
/// back beyond `+-theta_bar` (its vertical tangent is at `theta_{i+1} = 0.70`).
const COBWEB_RANGE: f64 = 0.8;

/// Points of a curve.
type Curve = Vec<(f64, f64)>;

/// Spring `p`'s rest-length curve in the window `[-range, range]^2`, well resolved where it is
/// flat and where it is steep: `(x, F(x))` by the map where its slope is below 1 (`x + y <= 0`),
/// `(F^-1(y), y)` by the inverse map where it is above. Split where the map's two roots meet (the
/// vertical tangent beyond `+theta_bar`) into the flipper branch `F` and the other branch.
fn constraint_curve<M: ChainModel>(model: &M, p: usize, range: f64, samples: usize) -> (Curve, Curve) {
    let mut flipper: Vec<(f64, f64)> = grid(-range, range, samples)
        .into_iter()
        .filter_map(|x| model.next_angles(p, x).ok().map(|[y, _]| (x, y)))
        .filter(|&(x, y)| x + y <= 0.0 && y.abs() <= range)
        .collect();
    let steep: Vec<(f64, f64)> = grid(-range, range, samples)
        .into_iter()
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

fn pairs(points: &[[f64; 2]]) -> Vec<(f64, f64)> {
    points.iter().map(|&[x, y]| (x, y)).collect()
}

/// The cobweb panel in the paper's notation: spring `p`'s constraint curve (black; the other
/// branch dashed where it enters the window), the grey diagonal, the red staircase, blue rotor
/// points and red spring points.
fn cobweb_panel<M: ChainModel>(
    title: &str,
    model: &M,
    p: usize,
    theta: &[f64],
    q: Quality,
) -> Result<Chart, StaticsError> {
    let samples = q.pick(241, 61);
    let web = cobweb(model, p, theta, COBWEB_RANGE, 2)?;
    let (flipper, other) = constraint_curve(model, p, COBWEB_RANGE, samples);
    let mut series =
        vec![Series::new(Quantity::Constraint, "springs at rest (flipper branch)", flipper, Style::Line)];
    if other.len() > 1 {
        series.push(Series::new(Quantity::Constraint, "other branch", other, Style::Dashed));
    }
    series.extend([
        Series::new(Quantity::Diagonal, "θ_{i+1} = θ_i", pairs(&web.diagonal), Style::Line),
        Series::new(Quantity::Spring, "iteration", pairs(&web.staircase), Style::Dashed),
        Series::new(Quantity::Rotor, "rotor points", pairs(&web.rotors), Style::Points),
        Series::new(Quantity::Spring, "spring points", pairs(&web.springs), Style::Points),
    ]);
    Ok(Panel::new(title, "θ_i (rad)", "θ_{i+1} (rad)", series).into())
}

/// The panel of a profile `theta_i` with the levels `+-theta_bar`.
fn profile_panel(title: &str, name: &str, theta: &[f64], theta_bar: f64, extra: Vec<Series>) -> Chart {
    let mut series = vec![Series::new(Quantity::Rotor, name, profile(theta), Style::LinePoints)];
    series.extend(extra);
    series.extend(uniform_levels(theta.len(), theta_bar));
    Panel::new(title, "rotor index i", "θ_i (rad)", series).into()
}

/// Fig. `fig:kcobweb`: the zero-energy kink centred in a chain of [`Cobweb::rotors`] (16; on its
/// middle spring), drawn (`fig:kconfig`), its profile, and its cobweb plot on that spring's
/// constraint curve.
///
/// [`Cobweb::rotors`]: super::Cobweb::rotors
pub fn kcobweb(p: &Params, q: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:kcobweb";
    let (n, theta_bar) = (p.cobweb.rotors, p.cobweb.theta_bar);
    let model = chain(p, n, theta_bar).map_err(FigureError::on(LABEL))?;
    let centre = (n - 1) as f64 / 2.0;
    let theta = kink(&model, centre).map_err(FigureError::on(LABEL))?;
    let drawing = ChainDrawing::new("(a) kink: springs at rest", &model, &theta, 0..n)
        .map_err(FigureError::on(LABEL))?;
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Kink configuration (a), its profile (b) and cobweb plot (c), springs at rest: n = {n}, r/a = {}, \
             θ̄ = {theta_bar}, centre {centre}",
            p.r
        ),
        panels: vec![
            drawing.into(),
            profile_panel("(b) kink profile", "kink", &theta, theta_bar, Vec::new()),
            cobweb_panel("(c) cobweb plot", &model, n / 2 - 1, &theta, q).map_err(FigureError::on(LABEL))?,
        ],
        rows: Vec::new(),
    })
}

/// The antikink of Figs. `fig:akcobweb` and `fig:aktheta`: the Peierls-Nabarro minimum of the
/// chain of [`Params::cobweb`] (16 rotors at `theta_bar = 0.58`), ends held.
fn cobweb_antikink(p: &Params, label: &'static str) -> Result<(RuntimeChain, Antikink), FigureError> {
    let model = chain(p, p.cobweb.rotors, p.cobweb.theta_bar).map_err(FigureError::on(label))?;
    let minimum = peierls_nabarro(&model, &AntikinkOptions::default())
        .map_err(FigureError::on(label))?
        .minimum()
        .clone();
    Ok((model, minimum))
}

/// Fig. `fig:akcobweb`: the antikink (Peierls-Nabarro minimum, ends held) drawn (`fig:akconfig`),
/// its profile with the paper's starting guess (the reflected kink), and its cobweb plot, whose
/// spring points leave the constraint curve near the core.
pub fn akcobweb(p: &Params, q: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:akcobweb";
    let (model, antikink) = cobweb_antikink(p, LABEL)?;
    let n = model.rotor_count();
    let start = reflected_kink(&model, antikink.centre).map_err(FigureError::on(LABEL))?;
    let spring = (antikink.centre.floor() as usize).min(n - 2);
    let drawing = ChainDrawing::new("(a) antikink: springs stretched", &model, &antikink.theta, 0..n)
        .map_err(FigureError::on(LABEL))?;
    // Rings: the start lies within a dot's size of the minimum on most rotors.
    let guess = Series::new(Quantity::Antikink, "reflected kink (start)", profile(&start), Style::Rings);
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Antikink at the Peierls-Nabarro minimum, ends held at ∓θ̄: configuration (a), profile (b) and cobweb \
             plot (c): n = {n}, r/a = {}, θ̄ = {}, centre {:.2}",
            p.r, p.cobweb.theta_bar, antikink.centre
        ),
        panels: vec![
            drawing.into(),
            profile_panel(
                "(b) antikink profile",
                "antikink",
                &antikink.theta,
                p.cobweb.theta_bar,
                vec![guess],
            ),
            cobweb_panel("(c) cobweb plot", &model, spring, &antikink.theta, q)
                .map_err(FigureError::on(LABEL))?,
        ],
        rows: Vec::new(),
    })
}

/// Fig. `fig:aktheta`: (a) the antikink of Fig. `fig:akcobweb` against the continuum profile
/// `theta = asin(u / r)`, `u = ubar tanh((x - x0)/w)` (Eq. `eq:kinksolution`) centred on it;
/// (b) the stretch `l_p - lbar` of every spring.
pub fn aktheta(p: &Params, q: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:aktheta";
    let (model, antikink) = cobweb_antikink(p, LABEL)?;
    let n = model.rotor_count();
    let theory = continuum(p, p.cobweb.theta_bar).map_err(FigureError::on(LABEL))?;
    let end = (n - 1) as f64;
    let curve = grid(0.0, end, q.pick(20, 4) * (n - 1) + 1)
        .into_iter()
        .map(|x| (x, theory.angle(Charge::Antikink, x, antikink.centre)))
        .collect();
    let mut lengths = vec![0.0; n - 1];
    model.spring_lengths_into(&antikink.theta, &mut lengths);
    let stretch = lengths.iter().enumerate().map(|(s, l)| (s as f64, l - model.rest_length(s))).collect();
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Antikink profile against the continuum wall (a) and spring stretch (b): n = {n}, r/a = {}, \
             θ̄ = {}, ends held, w = {:.4} a",
            p.r,
            p.cobweb.theta_bar,
            theory.width()
        ),
        panels: vec![
            Panel::new(
                "(a) θ profile",
                "rotor index i",
                "θ_i (rad)",
                vec![
                    Series::new(Quantity::Rotor, "lattice", profile(&antikink.theta), Style::Points),
                    Series::new(Quantity::Continuum, "continuum", curve, Style::Line),
                ],
            )
            .into(),
            Panel::new(
                "(b) spring stretch",
                "spring index p (joins rotors p and p+1)",
                "l_p − l̄ (a)",
                vec![Series::new(Quantity::Spring, "stretch", stretch, Style::LinePoints)],
            )
            .into(),
        ],
        rows: Vec::new(),
    })
}
