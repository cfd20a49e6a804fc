//! # chain-sweep
//!
//! Resumable, parallel sweeps over a 2-D parameter grid, for the scattering phase diagrams of the
//! paper (Fig. `fig:phasediagram`: impurity stiffness `k_i/k` against launch speed `v0`), and the
//! `phase-diagram` tool that runs them.
//!
//! Each grid point runs one computation that yields a [`Record`] (or an error). [`run_sweep`]
//! computes the points in parallel and appends each to a CSV results file the moment it is done,
//! so a sweep that is killed loses only the points in flight; run again with the same arguments,
//! it computes only the points the file lacks. [`read_results`] reads the file back for plotting.
//!
//! ```
//! use chain_sweep::{Axis, Grid, SweepOptions, read_results, run_sweep};
//! use chain_sweep::scattering::{Outcome, PointRecord, fake_point};
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! # let dir = tempfile::tempdir()?;
//! let grid = Grid::new(Axis::linspace(0.1, 1.0, 4)?, "0.5:12:5".parse()?)?;
//! let path = dir.path().join("kink.csv");
//! let options = SweepOptions::new("kink", "toy model");
//! let compute = |ki: f64, v0: f64| -> Result<PointRecord, String> {
//!     let outcome = if v0 > 5.0 * ki { Outcome::Split } else { Outcome::Transmitted };
//!     Ok(PointRecord { outcome, ..fake_point(ki, v0) })
//! };
//! let summary = run_sweep(&grid, &path, compute, &options)?;
//! assert_eq!((summary.computed, summary.skipped, summary.failed), (20, 0, 0));
//!
//! // A second run finds every point done.
//! let again = run_sweep(&grid, &path, compute, &options)?;
//! assert_eq!((again.computed, again.skipped), (0, 20));
//!
//! let points = read_results::<PointRecord>(&path)?;
//! assert_eq!(points.len(), 20);
//! # Ok(())
//! # }
//! ```
//!
//! The paper's phase diagram (Sec. VI, Fig. `fig:phasediagram`): every point is one scattering
//! run of [`scattering::PhaseDiagram::compute_point`], here on a small grid of the antikink
//! diagram (the paper's chain at $\bar\theta = 0.28$, the impurity on the middle spring):
//!
//! ```
//! use chain_sweep::{Axis, Grid, SweepOptions, read_results, run_sweep};
//! use chain_sweep::scattering::{Defect, Outcome, PhaseDiagram, PointRecord};
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! # let dir = tempfile::tempdir()?;
//! // n = 60, r = 0.8 a, k = 1e4 M/t^2, theta_bar = 0.28 rad; free ends, Verlet, t_max = 20 t.
//! let diagram = PhaseDiagram::new(60, 0.8, 1.0e4, 0.28, Defect::Antikink)?;
//! let grid = Grid::new("0.2:0.8:2".parse()?, "4:4.8:2".parse()?)?;   // k_i/k by v0 (a/t)
//! let path = dir.path().join("antikink.csv");
//! let options = SweepOptions::new("antikink", diagram.run_label());
//! run_sweep(&grid, &path, |ki, v0| diagram.compute_point(ki, v0), &options)?;
//!
//! let points = read_results::<PointRecord>(&path)?;
//! assert_eq!(points.len(), 4);                             // (index, (k_i/k, v0), record)
//! let at = |ki: f64, v0: f64| points.iter().find(|(_, xy, _)| *xy == (ki, v0)).map(|p| p.2.outcome);
//! assert_eq!(at(0.2, 4.8), Some(Outcome::Reflected));       // the paper's named points
//! assert_eq!(at(0.8, 4.0), Some(Outcome::Transmitted));
//! # Ok(())
//! # }
//! ```
//!
//! | module | what |
//! | --- | --- |
//! | [`grid`] | [`Axis`] (`FROM:TO:COUNT`), [`Grid`] and its signature |
//! | [`record`] | the [`Record`] trait and field helpers |
//! | [`file`](mod@file) | the results file format, [`read_points`], [`read_results`] |
//! | [`sweep`] | [`run_sweep`], [`SweepOptions`], [`Summary`], [`ResultsFile`]; the crash-safety rules |
//! | [`shard`] | [`Shard`]: one of `N` interleaved parts of a grid, for job arrays; `--shard slurm` |
//! | [`threads`] | [`threads::worker_threads`]: never more threads than points, at most four per core |
//! | [`pipe`] | [`pipe::exit_quietly_on_broken_pipe`]: the commands end quietly when their reader goes away |
//! | [`merge`] | [`merge_shards`]: the shard files of a split sweep joined into the whole diagram |
//! | [`scattering`] | [`scattering::PhaseDiagram`]: one point of the scattering phase diagram, its energy budget, and [`scattering::PointRecord`], its record |
#![deny(missing_docs)]

pub mod error;
pub mod file;
pub mod grid;
pub mod merge;
pub mod pipe;
pub mod record;
pub mod scattering;
pub mod shard;
pub mod sweep;
pub mod threads;

pub use error::SweepError;
pub use file::{Point, ResultRow, read_points, read_results};
pub use grid::{Axis, Grid, GridError};
pub use merge::{MergeSummary, find_shards, merge_shards};
pub use record::{ParseError, Record};
pub use shard::{Shard, ShardError};
pub use sweep::{ResultsFile, Summary, SweepOptions, compute_grid, run_sweep};
