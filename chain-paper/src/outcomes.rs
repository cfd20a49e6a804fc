//! Scattering outcomes on a grid (Sec. VI, Fig. `fig:phasediagram`), for any chain and any grid:
//! the points of a sweep, computed in memory (chain-sweep's `compute_grid`) or read back from a
//! results file (chain-sweep's `read_points`), become an [`OutcomeGrid`], and the grid a
//! phase-diagram panel ([`OutcomeGrid::heatmap`]) that [`crate::render`] draws.
//!
//! ```
//! use chain_paper::outcomes::OutcomeGrid;
//! use chain_paper::{Chart, Figure, render};
//! use chain_sweep::scattering::{Defect, Outcome, PhaseDiagram};
//! use chain_sweep::{Axis, Grid, compute_grid};
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! # let dir = tempfile::tempdir()?;
//! // A 40-rotor chain of shorter rotors at theta_bar = 0.3, its antikink on a 4 x 3 grid.
//! let diagram = PhaseDiagram::new(40, 0.7, 1.0e4, 0.3, Defect::Antikink)?;
//! let grid = Grid::new(Axis::geomspace(0.1, 3.0, 4)?, Axis::linspace(2.0, 6.0, 3)?)?;
//! let points = compute_grid(&grid, |ki, v0| diagram.compute_point(ki, v0), None)?;
//!
//! let outcomes = OutcomeGrid::new(&grid, &points)?;
//! assert_eq!(outcomes.cells().len(), 3);                  // one row per v0
//! let total: usize = Outcome::ALL.iter().map(|&o| outcomes.count(o)).sum();
//! assert_eq!(total + outcomes.unresolved() + outcomes.failed(), 12);   // every point shown
//!
//! let figure = Figure {
//!     label: "fig:my-antikink",
//!     caption: "Antikink outcomes, n = 40, r/a = 0.7, θ̄ = 0.3".to_owned(),
//!     panels: vec![Chart::Heat(outcomes.heatmap("antikink, θ̄ = 0.3"))],
//!     rows: Vec::new(),
//! };
//! let files = render::render(&figure, dir.path())?;        // my-antikink.png and .svg
//! assert_eq!(files.len(), 2);
//! # Ok(())
//! # }
//! ```

use chain_sweep::scattering::{PointRecord, Unresolved};
use chain_sweep::{Grid, Point};
use rotor_chain::dynamics::scatter::Outcome;

use crate::model::Heatmap;

/// The label of a point that failed (energy budget, unreadable walls): shown, never hidden.
pub const FAILED: &str = "failed";

/// The label of a point whose outcome is not the impurity's alone (chain-sweep's
/// `PointRecord::unresolved`): drawn hatched grey ([`crate::palette::hatched`]), never with an
/// outcome's colour.
pub const UNRESOLVED: &str = "unresolved";

/// One grid point of an [`OutcomeGrid`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Cell {
    /// The point's scattering outcome.
    Outcome(Outcome),
    /// The point's run decided `outcome`, but it is not the impurity's alone: why.
    Unresolved {
        /// What the kept run decided.
        outcome: Outcome,
        /// Why it is not robust.
        reason: Unresolved,
    },
    /// The point's computation failed; its error message.
    Failed(String),
    /// No point: the sweep has not computed it (yet).
    Missing,
}

/// A point of a sweep that does not belong to the grid it is placed on.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum OutcomeGridError {
    /// The point's index or values are not the grid's.
    #[error(
        "point ({}, {}) at k_i/k = {}, v0 = {} is not on the grid of {} k_i/k by {} v0 values (a results \
         file of another grid?)",
        index.0, index.1, coords.0, coords.1, columns, rows
    )]
    OffGrid {
        /// The point's `(i, j)`.
        index: (usize, usize),
        /// Its `(k_i/k, v0)`.
        coords: (f64, f64),
        /// The grid's `k_i/k` values.
        columns: usize,
        /// The grid's `v0` values.
        rows: usize,
    },
    /// Two points at one grid point.
    #[error("two points at ({}, {}): k_i/k = {}, v0 = {}", index.0, index.1, coords.0, coords.1)]
    Duplicate {
        /// The grid point's `(i, j)`.
        index: (usize, usize),
        /// Its `(k_i/k, v0)`.
        coords: (f64, f64),
    },
}

/// The outcome of every point of a phase diagram: `cells()[j][i]` at `k_i/k = ki()[i]`,
/// `v0 = v0()[j]`.
#[derive(Clone, Debug, PartialEq)]
pub struct OutcomeGrid {
    ki: Vec<f64>,
    v0: Vec<f64>,
    cells: Vec<Vec<Cell>>,
}

impl OutcomeGrid {
    /// The outcomes of `points` on `grid` (x: `k_i/k`, y: `v0`, as chain-sweep's phase diagrams
    /// lay them out); grid points without a point are [`Cell::Missing`]. A point whose index or
    /// values are not the grid's, or a second point at one place, is an error.
    pub fn new(grid: &Grid, points: &[Point<PointRecord>]) -> Result<Self, OutcomeGridError> {
        let (ki, v0) = (grid.xs().to_vec(), grid.ys().to_vec());
        let mut cells = vec![vec![Cell::Missing; ki.len()]; v0.len()];
        for point in points {
            let (i, j) = point.index;
            let on_grid = grid.point(i, j).is_some_and(|xy| xy == point.coords);
            if !on_grid {
                return Err(OutcomeGridError::OffGrid {
                    index: point.index,
                    coords: point.coords,
                    columns: ki.len(),
                    rows: v0.len(),
                });
            }
            if cells[j][i] != Cell::Missing {
                return Err(OutcomeGridError::Duplicate { index: point.index, coords: point.coords });
            }
            cells[j][i] = match &point.outcome {
                Ok(PointRecord { outcome, unresolved: Some(reason), .. }) => {
                    Cell::Unresolved { outcome: *outcome, reason: *reason }
                }
                Ok(record) => Cell::Outcome(record.outcome),
                Err(message) => Cell::Failed(message.clone()),
            };
        }
        Ok(Self { ki, v0, cells })
    }

    /// The `k_i/k` values, one per column.
    pub fn ki(&self) -> &[f64] {
        &self.ki
    }

    /// The `v0` values, one per row.
    pub fn v0(&self) -> &[f64] {
        &self.v0
    }

    /// The cells, `cells()[j][i]` at `(ki()[i], v0()[j])`.
    pub fn cells(&self) -> &[Vec<Cell>] {
        &self.cells
    }

    /// The outcome at column `i`, row `j` (`None` for an unresolved, failed or missing point, or
    /// off the grid).
    pub fn outcome(&self, i: usize, j: usize) -> Option<Outcome> {
        match self.cells.get(j)?.get(i)? {
            Cell::Outcome(o) => Some(*o),
            _ => None,
        }
    }

    /// How many points have `outcome`.
    pub fn count(&self, outcome: Outcome) -> usize {
        self.cells.iter().flatten().filter(|c| **c == Cell::Outcome(outcome)).count()
    }

    /// How many points are unresolved.
    pub fn unresolved(&self) -> usize {
        self.cells.iter().flatten().filter(|c| matches!(c, Cell::Unresolved { .. })).count()
    }

    /// How many points failed.
    pub fn failed(&self) -> usize {
        self.cells.iter().flatten().filter(|c| matches!(c, Cell::Failed(_))).count()
    }

    /// The cells unlike each of their (up to four) neighbours along the axes, `(i, j)` in row
    /// order: a label that holds at one grid point only, which a figure should explain (a window
    /// narrower than the grid's spacing, or an outcome that depends on rounding).
    pub fn isolated(&self) -> Vec<(usize, usize)> {
        let (columns, rows) = (self.ki.len(), self.v0.len());
        let mut found = Vec::new();
        for j in 0..rows {
            for i in 0..columns {
                let cell = &self.cells[j][i];
                let neighbours = [(i.wrapping_sub(1), j), (i + 1, j), (i, j.wrapping_sub(1)), (i, j + 1)];
                let mut present =
                    neighbours.iter().filter_map(|&(a, b)| self.cells.get(b)?.get(a)).peekable();
                if present.peek().is_some() && present.all(|other| other != cell) {
                    found.push((i, j));
                }
            }
        }
        found
    }

    /// The outcomes per row, `None` for an unresolved, failed or missing point.
    pub fn labels(&self) -> Vec<Vec<Option<Outcome>>> {
        (0..self.v0.len()).map(|j| (0..self.ki.len()).map(|i| self.outcome(i, j)).collect()).collect()
    }

    /// Whether the `k_i/k` axis is drawn logarithmic: every value positive and at least a decade
    /// between the least and the largest (the paper's 0.01 to 3, log-spaced, so that the kink's
    /// soft and the antikink's stiff regimes are both resolved).
    pub fn log_ki(&self) -> bool {
        let (lo, hi) = self.ki.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        lo > 0.0 && hi >= 10.0 * lo
    }

    /// The phase-diagram panel: one colour per outcome ([`crate::palette`]), unresolved points
    /// hatched grey, failed points black, missing points light grey; `k_i/k` on a logarithmic axis when [`OutcomeGrid::log_ki`]
    /// (the data's `x` are then `log10(k_i/k)`). The legend lists the outcomes present.
    pub fn heatmap(&self, title: impl Into<String>) -> Heatmap {
        let log = self.log_ki();
        Heatmap {
            title: title.into(),
            x_label: "k_i / k".to_owned(),
            y_label: "v0 (a/t)".to_owned(),
            x: self.ki.iter().map(|&x| if log { x.log10() } else { x }).collect(),
            y: self.v0.clone(),
            values: self.cells.iter().map(|row| row.iter().map(category).collect()).collect(),
            categories: categories(),
            value_label: "outcome".to_owned(),
            log_x: log,
            colour_limit: None,
        }
    }
}

/// The colour categories of a phase diagram: every outcome in the order of `Outcome::ALL`, then
/// [`UNRESOLVED`] and [`FAILED`]; each colour is [`crate::palette::Quantity::of_category`]'s.
pub fn categories() -> Vec<String> {
    Outcome::ALL.iter().map(|o| o.name()).chain([UNRESOLVED, FAILED]).map(str::to_owned).collect()
}

/// A cell's value in [`OutcomeGrid::heatmap`]: its place in [`categories`] (`NaN` when missing).
pub fn category(cell: &Cell) -> f64 {
    match cell {
        Cell::Outcome(o) => Outcome::ALL.iter().position(|x| x == o).unwrap_or(0) as f64,
        Cell::Unresolved { .. } => Outcome::ALL.len() as f64,
        Cell::Failed(_) => (Outcome::ALL.len() + 1) as f64,
        Cell::Missing => f64::NAN,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use chain_sweep::Axis;
    use chain_sweep::scattering::fake_point;

    fn point(grid: &Grid, (i, j): (usize, usize), outcome: Result<Outcome, &str>) -> Point<PointRecord> {
        let coords = grid.point(i, j).unwrap();
        let outcome = outcome
            .map(|o| PointRecord { outcome: o, ..fake_point(coords.0, coords.1) })
            .map_err(str::to_owned);
        Point { index: (i, j), coords, outcome, line: 0 }
    }

    #[test]
    fn points_land_in_their_cells_and_the_rest_are_missing() {
        let grid =
            Grid::new(Axis::geomspace(0.01, 1.0, 3).unwrap(), Axis::linspace(1.0, 2.0, 2).unwrap()).unwrap();
        let points = [
            point(&grid, (0, 0), Ok(Outcome::Reflected)),
            point(&grid, (2, 1), Ok(Outcome::Transmitted)),
            point(&grid, (1, 1), Err("energy budget")),
        ];
        let g = OutcomeGrid::new(&grid, &points).unwrap();
        assert_eq!(g.outcome(0, 0), Some(Outcome::Reflected));
        assert_eq!(g.outcome(2, 1), Some(Outcome::Transmitted));
        assert_eq!(g.cells()[1][1], Cell::Failed("energy budget".to_owned()));
        assert_eq!(g.cells()[0][2], Cell::Missing);
        assert_eq!((g.count(Outcome::Reflected), g.failed()), (1, 1));
        // Two decades, log-spaced: a logarithmic axis, its data log10(k_i/k).
        let map = g.heatmap("t");
        assert!(map.log_x);
        assert!(
            map.x.iter().zip([-2.0, -1.0, 0.0]).all(|(x, decade)| (x - decade).abs() < 1e-12),
            "{:?}",
            map.x
        );
        let failed = (Outcome::ALL.len() + 1) as f64;
        assert_eq!(map.values[1][1], failed);
        assert_eq!(map.categories[failed as usize], FAILED);
        assert!(map.values[0][2].is_nan());
        assert_eq!(map.values[0][0], 1.0); // reflected, second of Outcome::ALL
    }

    #[test]
    fn isolated_cells_differ_from_every_neighbour() {
        let grid =
            Grid::new(Axis::linspace(0.1, 0.4, 4).unwrap(), Axis::linspace(1.0, 3.0, 3).unwrap()).unwrap();
        // Transmitted everywhere but a trapped cell inside (2, 1), a reflected corner (0, 0) and
        // a split pair (3, 1), (3, 2), whose members each have one like neighbour.
        let odd = |i, j| match (i, j) {
            (2, 1) => Outcome::Trapped,
            (0, 0) => Outcome::Reflected,
            (3, 1) | (3, 2) => Outcome::Split,
            _ => Outcome::Transmitted,
        };
        let points: Vec<_> = grid.indices().map(|(i, j)| point(&grid, (i, j), Ok(odd(i, j)))).collect();
        let g = OutcomeGrid::new(&grid, &points).unwrap();
        assert_eq!(g.isolated(), vec![(0, 0), (2, 1)]);
    }

    #[test]
    fn points_of_another_grid_are_refused() {
        let grid =
            Grid::new(Axis::linspace(0.5, 1.0, 2).unwrap(), Axis::linspace(1.0, 2.0, 2).unwrap()).unwrap();
        let other =
            Grid::new(Axis::linspace(0.5, 0.9, 2).unwrap(), Axis::linspace(1.0, 2.0, 2).unwrap()).unwrap();
        let err = OutcomeGrid::new(&grid, &[point(&other, (1, 0), Ok(Outcome::Trapped))]).unwrap_err();
        assert!(matches!(err, OutcomeGridError::OffGrid { index: (1, 0), columns: 2, rows: 2, .. }), "{err}");
        let twice = [point(&grid, (1, 0), Ok(Outcome::Trapped)), point(&grid, (1, 0), Ok(Outcome::Trapped))];
        assert!(matches!(
            OutcomeGrid::new(&grid, &twice),
            Err(OutcomeGridError::Duplicate { index: (1, 0), .. })
        ));
        // Less than a decade: a linear axis, its data k_i/k.
        let g = OutcomeGrid::new(&grid, &[]).unwrap();
        assert!(!g.log_ki() && g.heatmap("t").x == vec![0.5, 1.0]);
    }
}
