//! Sec. VI, Fig. `fig:phasediagram`: the scattering phase diagrams of the kink and the antikink
//! over the impurity stiffness and the launch speed ([`crate::outcomes`]), the boundaries'
//! slopes, the alternating window and the antikink's stability against `v0`; the grid and ranges
//! are [`Scattering`](super::Scattering)'s.

use chain_sweep::scattering::{Defect, Ends, Method, PhaseDiagram};
use chain_sweep::{Axis, Grid, compute_grid};
use rayon::prelude::*;
use rotor_chain::dynamics::observe::stability;
use rotor_chain::dynamics::run::RunOptions;
use rotor_chain::dynamics::scatter::{Outcome, ScatterSetup};
use rotor_chain::statics::walls::Charge;

use super::{chain, middle_spring};
use crate::figures::{Cause, FigureError, Params};
use crate::model::{Chart, Figure, Panel, Quality, Quantity, Row, Series, Style};
use crate::outcomes::{Cell, FAILED, OutcomeGrid, UNRESOLVED};

/// The phase diagram of `defect` for the chain of `params` at
/// [`Scattering::theta_bar`](super::Scattering::theta_bar): the paper's free ends and Verlet.
fn settings(params: &Params, defect: Defect) -> Result<PhaseDiagram, Cause> {
    let mut d = PhaseDiagram::new(params.n, params.r, params.k, params.scattering.theta_bar, defect)?;
    d.mass = params.mass;
    d.check()?;
    Ok(d)
}

/// One phase diagram over `grid` (x: `k_i/k`, y: `v0`) of the chain of `params` at
/// [`Scattering::theta_bar`](super::Scattering::theta_bar), computed by chain-sweep's
/// `PhaseDiagram::compute_point` in parallel, every point cross-checked with DOP853 if
/// `cross_check` (points whose outcome is not the impurity's alone are
/// [`Cell::Unresolved`] either way).
pub(crate) fn phase_diagram(
    params: &Params,
    defect: Defect,
    grid: &Grid,
    cross_check: bool,
) -> Result<OutcomeGrid, Cause> {
    let d = PhaseDiagram { cross_check, ..settings(params, defect)? };
    let points = compute_grid(grid, |ki, v0| d.compute_point(ki, v0), None)?;
    Ok(OutcomeGrid::new(grid, &points)?)
}

/// A cell's label as the caption names it.
fn cell_name(cell: &Cell) -> &'static str {
    match cell {
        Cell::Outcome(o) => o.name(),
        Cell::Unresolved { .. } => UNRESOLVED,
        Cell::Failed(_) => FAILED,
        _ => "not computed",
    }
}

/// What the isolated cells of `outcomes` ([`OutcomeGrid::isolated`], the diagram of `defect`;
/// unresolved cells, which say why themselves, left out) are: each point is run again with DOP853 and with absorbing ends (the checks of
/// docs/dynamics.md §6). A label both keep is a real outcome in a window narrower than the grid's
/// spacing; one that changes depends on rounding and on what the free ends send back (the late
/// events of a chaotic run). Empty when no cell is isolated.
fn isolated_cells(params: &Params, defect: Defect, outcomes: &OutcomeGrid) -> Result<Vec<String>, Cause> {
    let mut cells = outcomes.isolated();
    cells.retain(|&(i, j)| !matches!(outcomes.cells()[j][i], Cell::Unresolved { .. }));
    let dop853 = PhaseDiagram { integrator: Method::dop853(), ..settings(params, defect)? };
    let absorbing = PhaseDiagram { ends: Ends::Absorbing, ..settings(params, defect)? };
    cells
        .par_iter()
        .map(|&(i, j)| {
            let (ki, v0) = (outcomes.ki()[i], outcomes.v0()[j]);
            let label = cell_name(&outcomes.cells()[j][i]);
            let again = |d: &PhaseDiagram| d.compute_point(ki, v0).map_or(FAILED, |r| r.outcome.name());
            let (with_dop853, with_absorbing) = (again(&dop853), again(&absorbing));
            let verdict = if with_dop853 == label && with_absorbing == label {
                "the same with DOP853 and with absorbing ends: a window narrower than the grid's spacing".to_owned()
            } else {
                format!("{with_dop853} with DOP853, {with_absorbing} with absorbing ends: depends on rounding and the free ends")
            };
            Ok(format!("{} {label} at k_i/k = {ki:.3}, v0 = {v0:.2} ({verdict})", defect.name()))
        })
        .collect()
}

fn count(labels: &[Vec<Option<Outcome>>], which: Option<Outcome>) -> usize {
    labels.iter().flatten().filter(|&&o| o == which).count()
}

/// `1536 transmitted, 55 split, 8 unresolved, ...`: every label that occurs, with its count.
pub(crate) fn label_counts(outcomes: &OutcomeGrid) -> Vec<String> {
    Outcome::ALL
        .iter()
        .map(|&o| (outcomes.count(o), o.name()))
        .chain([(outcomes.unresolved(), UNRESOLVED), (outcomes.failed(), FAILED)])
        .filter(|(c, _)| *c > 0)
        .map(|(c, name)| format!("{c} {name}"))
        .collect()
}

/// [`label_counts`] and the shares of undecided and unresolved points: `..., undecided 0.0 %,
/// unresolved 0.5 %`.
fn counts(outcomes: &OutcomeGrid) -> String {
    let total = outcomes.cells().iter().map(Vec::len).sum::<usize>().max(1);
    let share = |c: usize| 100.0 * c as f64 / total as f64;
    let mut parts = label_counts(outcomes);
    parts.push(format!("undecided {:.1} %", share(outcomes.count(Outcome::Undecided))));
    parts.push(format!("unresolved {:.1} %", share(outcomes.unresolved())));
    parts.join(", ")
}

/// What "unresolved" means in the diagrams' rows and caption.
fn unresolved_note(cross_check: bool) -> &'static str {
    if cross_check {
        "Verlet and DOP853 decide differently, or a wall from a free end reached the impurity before the \
         decision"
    } else {
        "a wall from a free end reached the impurity before the decision (not cross-checked with DOP853)"
    }
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
    let model = chain(params, params.scattering.theta_bar, None).map_err(|e| fail(e.into(), f64::NAN))?;
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
/// full, 6 x 6 quick (all of them [`Scattering`](super::Scattering)'s). Each point is
/// chain-sweep's (`PhaseDiagram::compute_point`), the one the `phase-diagram` tool computes.
/// With the antikink's stability against `v0` up to 25.
pub fn phasediagram(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    const LABEL: &str = "fig:phasediagram";
    let fail = FigureError::on(LABEL);
    let s = &params.scattering;
    let theta_bar = s.theta_bar;
    let size = quality.pick(s.points, s.points.min(6));
    let ((ki_from, ki_to), (v0_from, v0_to)) = (s.ki_range, s.v0_range);
    let kis = Axis::geomspace(ki_from, ki_to, size).map_err(FigureError::on(LABEL))?;
    let v0s = Axis::linspace(v0_from, v0_to, size).map_err(FigureError::on(LABEL))?;
    let grid = Grid::new(kis, v0s).map_err(FigureError::on(LABEL))?;
    let mut panels = Vec::new();
    let mut diagrams = Vec::new();
    let mut isolated = Vec::new();
    let mut grids = Vec::new();
    for (tag, defect) in [("(a)", Defect::Kink), ("(b)", Defect::Antikink)] {
        let outcomes = phase_diagram(params, defect, &grid, s.cross_check).map_err(&fail)?;
        panels.push(Chart::Heat(outcomes.heatmap(format!("{tag} {}, θ̄ = {theta_bar}", defect.name()))));
        isolated.extend(isolated_cells(params, defect, &outcomes).map_err(&fail)?);
        diagrams.push(outcomes.labels());
        grids.push(outcomes);
    }
    let (kink, antikink) = (&diagrams[0], &diagrams[1]);
    let (stable_from, stable_to) = s.stability_v0;
    let stable_v0s: Vec<f64> = Axis::linspace(stable_from, stable_to, quality.pick(31, 4))
        .map_err(FigureError::on(LABEL))?
        .values()
        .to_vec();
    let scan = stability_scan(params, &stable_v0s)?;
    panels.push(Chart::Lines(Panel::new(
        "(c) antikink in a perfect chain: most walls at once",
        "v0 (a/t)",
        "walls",
        vec![Series::new(
            Quantity::Antikink,
            "most walls",
            scan.iter().map(|&(v, w, _)| (v, w as f64)).collect(),
            Style::LinePoints,
        )],
    )));
    panels.push(Chart::Lines(Panel::new(
        "(d) antikink in a perfect chain: time with 3 or more walls",
        "v0 (a/t)",
        "longest time with 3+ walls (t)",
        vec![Series::new(
            Quantity::Antikink,
            "longest time with 3+ walls",
            scan.iter().map(|&(v, _, t)| (v, t)).collect(),
            Style::LinePoints,
        )],
    )));
    let single_up_to = scan.iter().take_while(|s| s.1 <= 1).last().map_or(f64::NAN, |s| s.0);
    let none = format!("none up to {stable_to}");
    let first_extra = scan.iter().find(|s| s.1 >= 3).map_or(none.clone(), |s| format!("{}", s.0));
    let lasting = scan.iter().find(|s| s.2 >= 0.25).map_or(none, |s| format!("{}", s.0));
    let grid_note = format!("k_i/k {ki_from}..{ki_to} log-spaced, v0 {v0_from}..{v0_to}, {size} x {size}");
    // The paper's alternating window: outcomes along v0 at k_i/k = 0.75.
    let (window_ki, (window_from, window_to)) = s.window;
    let window_v0s =
        Axis::linspace(window_from, window_to, quality.pick(26, 6)).map_err(FigureError::on(LABEL))?;
    let column = Grid::new(Axis::from_values(vec![window_ki]).map_err(FigureError::on(LABEL))?, window_v0s)
        .map_err(FigureError::on(LABEL))?;
    let window = phase_diagram(params, Defect::Antikink, &column, s.cross_check).map_err(&fail)?.labels();
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
            format!("{grid_note}; {}", counts(&grids[0])),
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
            &counts(&grids[1]),
            format!(
                "{grid_note}; free ends; annihilated = by a wall from a free end before anything settled; \
                 unresolved (hatched grey) = {}",
                unresolved_note(s.cross_check)
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
            format!("antikink outcomes along v0 at k_i/k = {window_ki} (alternating regimes)"),
            "a small range of alternating transmitted / trapped regimes around k_i/k = 0.75, v0 = 3.6",
            &runs,
            format!(
                "v0 from {window_from} to {window_to} in {} steps; the {size} x {size} grid is too coarse to show it",
                column.ys().len()
            ),
        ),
        Row::words(
            format!("antikink stability against v0, perfect chain, θ̄ = {theta_bar}"),
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
    let isolated = if isolated.is_empty() {
        String::new()
    } else {
        format!(". Isolated cells, each run again: {}", isolated.join("; "))
    };
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Scattering phase diagrams of (a) the kink and (b) the antikink over k_i/k ({ki_from}..{ki_to}, \
             log-spaced) and v0 ({v0_from}..{v0_to}), {size} x {size}; (c, d) the antikink in a perfect chain \
             against v0 up to {stable_to}: θ̄ = {theta_bar}, n = {}, r/a = {}, k = {}, impurity on spring {}, free \
             ends; hatched grey: unresolved, {}{isolated}",
            params.n,
            params.r,
            params.k,
            middle_spring(params),
            unresolved_note(s.cross_check)
        ),
        panels,
        rows,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::outcomes::categories;
    use crate::palette;

    /// The chaotic corner's known point (antikink, k_i/k = 0.01, v0 = 1.1: Verlet and DOP853
    /// decide differently, docs/dynamics.md §6) is drawn unresolved, hatched, with its legend
    /// entry, beside the paper's reflected point (0.2, 4.8); the rows count it.
    #[test]
    fn the_diagram_draws_an_unresolved_point_hatched_and_counts_it() {
        let params = Params::default();
        assert!(params.scattering.cross_check);
        let grid = Grid::new(
            Axis::from_values(vec![0.01, 0.2]).unwrap(),
            Axis::from_values(vec![1.1, 4.8]).unwrap(),
        )
        .unwrap();
        let outcomes = phase_diagram(&params, Defect::Antikink, &grid, true).unwrap();
        assert!(matches!(outcomes.cells()[0][0], Cell::Unresolved { .. }), "{:?}", outcomes.cells()[0][0]);
        assert_eq!(outcomes.outcome(1, 1), Some(Outcome::Reflected));
        assert_eq!(outcomes.unresolved(), 1);
        let map = outcomes.heatmap("t");
        let name = &map.categories[map.values[0][0] as usize];
        assert_eq!(name, UNRESOLVED);
        assert!(palette::hatched(name) && !Outcome::ALL.iter().any(|o| palette::hatched(o.name())));
        assert_eq!(map.categories, categories());
        assert_eq!(map.categories[map.values[1][1] as usize], "reflected");
        assert!(counts(&outcomes).contains("1 unresolved"), "{}", counts(&outcomes));
        // Not cross-checked, the point keeps Verlet's outcome (no wall from an end came first).
        let plain = phase_diagram(&params, Defect::Antikink, &grid, false).unwrap();
        assert!(matches!(plain.cells()[0][0], Cell::Outcome(_)), "{:?}", plain.cells()[0][0]);
    }
}
