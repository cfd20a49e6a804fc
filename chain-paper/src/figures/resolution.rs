//! Beyond the paper (issue 9): the antikink's scattering phase diagram at high resolution, of the
//! alternating transmitted / trapped window near `k_i/k = 0.75`, `v0 = 3.6` that the paper's
//! Sec. VI leaves "for future studies", and of the whole plane of Fig. `fig:phasediagram`.
//!
//! Run only with `paper --resolution` (never in the default or `--quick` runs): 2 x 400 x 400
//! scattering runs, each chain-sweep's `PhaseDiagram::compute_point` (the same point as the
//! `phase-diagram` tool and `fig:phasediagram`: the scattering issue's clean launch and lasting
//! outcomes, the energy budget with its DOP853 recomputation).

use chain_sweep::scattering::Defect;
use chain_sweep::{Axis, Grid};
use rotor_chain::dynamics::scatter::Outcome;

use super::dynamics::{label_counts, phase_diagram};
use super::{Cause, FigureError, FigureFn, Params};
use crate::model::{Chart, Figure, Quality, Row};
use crate::outcomes::OutcomeGrid;

/// This module's figures (`paper --resolution`).
pub fn figures() -> Vec<(&'static str, FigureFn)> {
    vec![(LABEL, phasediagram_resolution)]
}

const LABEL: &str = "fig:phasediagram-resolution";

/// The antikink's outcome at every point of `grid` (x: `k_i/k`, y: `v0`).
/// Not cross-checked with DOP853 (6 times the cost of 2 x 400 x 400 points); points where a
/// wall from a free end reached the impurity first are unresolved.
fn antikink_diagram(params: &Params, grid: &Grid) -> Result<OutcomeGrid, Cause> {
    phase_diagram(params, Defect::Antikink, grid, false)
}

/// `1023 reflected, 384 trapped, ...`: every label that occurs, with its count.
fn counts(outcomes: &OutcomeGrid) -> String {
    label_counts(outcomes).join(", ")
}

/// Along each `v0` column at the `k_i/k` nearest `ki`: how many times the outcome changes
/// between transmitted and trapped as `v0` rises (the alternation the paper reports).
fn alternations(labels: &[Vec<Option<Outcome>>], xs: &[f64], ki: f64) -> (f64, usize) {
    let i = (0..xs.len()).min_by(|&a, &b| (xs[a] - ki).abs().total_cmp(&(xs[b] - ki).abs())).unwrap_or(0);
    let column: Vec<Outcome> = labels
        .iter()
        .filter_map(|row| row[i])
        .filter(|o| matches!(o, Outcome::Transmitted | Outcome::Trapped))
        .collect();
    (xs.get(i).copied().unwrap_or(f64::NAN), column.windows(2).filter(|w| w[0] != w[1]).count())
}

/// The antikink's phase diagram, 400 x 400 (quick: 8 x 8), of the alternating window
/// (`k_i/k` 0.6 .. 0.9, `v0` 2.5 .. 5) and of the whole plane (`k_i/k` 0.01 .. 3 log-spaced,
/// `v0` 0.5 .. 12), `theta_bar = 0.28` (paper Sec. VI, Fig. `fig:phasediagram`); the ranges
/// are [`Scattering`](super::dynamics::Scattering)'s `resolution`, `ki_range` and `v0_range`.
pub fn phasediagram_resolution(params: &Params, quality: Quality) -> Result<Figure, FigureError> {
    let s = &params.scattering;
    let theta_bar = s.theta_bar;
    let ((wk_from, wk_to), (wv_from, wv_to), points) = s.resolution;
    let size = quality.pick(points, points.min(8));
    let on = FigureError::on(LABEL);
    let window = Grid::new(
        Axis::linspace(wk_from, wk_to, size).map_err(&on)?,
        Axis::linspace(wv_from, wv_to, size).map_err(&on)?,
    )
    .map_err(&on)?;
    let plane = Grid::new(
        Axis::geomspace(s.ki_range.0, s.ki_range.1, size).map_err(&on)?,
        Axis::linspace(s.v0_range.0, s.v0_range.1, size).map_err(&on)?,
    )
    .map_err(&on)?;
    let window_outcomes = antikink_diagram(params, &window).map_err(FigureError::on(LABEL))?;
    let plane_outcomes = antikink_diagram(params, &plane).map_err(FigureError::on(LABEL))?;
    let panels = vec![
        Chart::Heat(window_outcomes.heatmap(format!(
            "antikink, θ̄ = {theta_bar}: window k_i/k {wk_from}-{wk_to}, v0 {wv_from}-{wv_to} ({size} x {size})"
        ))),
        Chart::Heat(plane_outcomes.heatmap(format!("antikink, θ̄ = {theta_bar}: whole plane ({size} x {size})"))),
    ];
    let (ki, changes) = alternations(&window_outcomes.labels(), window.xs(), s.window.0);
    let rows = vec![
        Row::words(
            format!("antikink window near k_i/k = {}, v0 = 3.6 ({size} x {size})", s.window.0),
            "alternating transmitted / trapped regimes (left for future studies)",
            &counts(&window_outcomes),
            format!(
                "k_i/k {wk_from}..{wk_to}, v0 {wv_from}..{wv_to}; transmitted <-> trapped changes along v0 at k_i/k = \
                 {ki:.3}: {changes}"
            ),
        ),
        Row::words(
            format!("antikink phase diagram, whole plane ({size} x {size})"),
            "reflected (soft), trapped, transmitted, reflected (stiff)",
            &counts(&plane_outcomes),
            format!(
                "k_i/k {}..{} log-spaced, v0 {}..{}; free ends; unresolved: a wall from a free end reached the \
                 impurity before the decision (not cross-checked with DOP853)",
                s.ki_range.0, s.ki_range.1, s.v0_range.0, s.v0_range.1
            ),
        ),
    ];
    Ok(Figure {
        label: LABEL,
        caption: format!(
            "Antikink scattering phase diagram at {size} x {size}: the alternating window near k_i/k = 0.75, v0 = 3.6, \
             and the whole plane; θ̄ = {theta_bar}, n = {}, r/a = {}, k = {}, free ends",
            params.n, params.r, params.k
        ),
        panels,
        rows,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The quick figure: two 8 x 8 panels; at the window's soft edge (k_i/k = 0.6) every antikink
    /// is trapped and at its stiff edge (0.9) every one is transmitted, the two regimes the
    /// paper's alternation lies between (Sec. VI).
    #[test]
    fn the_window_lies_between_trapping_and_transmission() {
        let figure = phasediagram_resolution(&Params::default(), Quality::Quick).unwrap();
        assert_eq!((figure.label, figure.panels.len(), figure.rows.len()), (LABEL, 2, 2));
        let Chart::Heat(window) = &figure.panels[0] else { panic!("the window is a heat map") };
        assert_eq!((window.x.len(), window.y.len(), window.values.len()), (8, 8, 8));
        let category = |o| crate::outcomes::category(&crate::outcomes::Cell::Outcome(o));
        let (trapped, transmitted) = (category(Outcome::Trapped), category(Outcome::Transmitted));
        for row in &window.values {
            assert_eq!(row[0], trapped, "k_i/k = 0.6: {row:?}");
            assert_eq!(row[7], transmitted, "k_i/k = 0.9: {row:?}");
        }
    }
}
