//! `network`: the linear topology of a periodic network read from a cell file (issue 33).
//!
//! ```text
//! network counts CELL.toml --cells N1xN2 --boundary periodic|free [--json]
//! network winding CELL.toml [--json]
//! network strip CELL.toml --along 1|2 --cells M [--q Q] [--json]
//! network guest CELL.toml [--json]
//! network bands CELL.toml [--path G-X-M-G] [--samples 60] [--out DIR]
//! network draw CELL.toml [--out DIR]
//! network diagram [--x1 -0.2:0.2:41] [--x2 -0.2:0.2:41] [--x3 0.1] [--z 0] [--out DIR] [--shard I/N|slurm | --merge]
//! network cell NAME [PARAMETERS...]     # a ready cell's TOML on stdout
//! network motion transition [--sites 200] [--damping 0.5] [--duration 70] [--out DIR]
//! network motion wall [--chains 6] [--cells 24] [--speed 0.05] [--duration 300] [--out DIR]
//! ```
//!
//! Exit status: 0 done; 2 bad input (a cell file's problem names its key and line; bad sizes and
//! arguments); 3 winding undefined (gapless lattice, or Weyl points); 1 any other failure;
//! 128 + N on signal N while writing figures.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use chain_paper::network::diagram::{DiagramParams, PolarizationPoint, compute_point, diagram_figure};
use chain_paper::network::{bands_figure, cell_figure, transition_figure, wall_figure, write_gif};
use chain_paper::{output, render};
use chain_sweep::{Axis, Grid, Shard, SweepOptions, find_shards, merge_shards, read_results, run_sweep};
use clap::{Parser, Subcommand, ValueEnum};
use rotor_chain::network::bloch::parse_path;
use rotor_chain::network::cell::ready;
use rotor_chain::network::counts::{Method, counts};
use rotor_chain::network::guest::guest_modes;
use rotor_chain::network::motion::MotionError;
use rotor_chain::network::motion::transition::BistableChain;
use rotor_chain::network::motion::wall::CoupledChains;
use rotor_chain::network::patch::{Boundary, Patch};
use rotor_chain::network::strip::{DEFAULT_Q, Strip, strip_modes};
use rotor_chain::network::winding::{WindingOptions, winding};
use rotor_chain::network::{Cell, CellError, NetworkError};
use serde_json::json;

/// Linear topology of periodic spring and rotor networks: counts, windings and polarization,
/// strips and edge modes, bands, figures. Exit status: 0 done; 2 bad input; 3 winding
/// undefined; 1 other failures.
#[derive(Parser)]
#[command(name = "network", version)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum)]
enum BoundaryArg {
    Periodic,
    Free,
}

#[derive(Subcommand)]
enum Command {
    /// Zero modes and states of self-stress of an N1 x N2 patch (N in one dimension); rank:
    /// singular values above 1e-9 times the largest.
    Counts {
        /// The cell file (TOML).
        cell: PathBuf,
        /// N1xN2 cells (N in one dimension); a periodic direction needs at least 3.
        #[arg(long)]
        cells: String,
        /// Periodic (through Bloch blocks) or free (one dense SVD) boundaries.
        #[arg(long, value_enum)]
        boundary: BoundaryArg,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// Winding numbers of det Q(k) along each reciprocal vector and the polarization R_T.
    Winding {
        /// The cell file (TOML).
        cell: PathBuf,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// Zero modes of a strip periodic along a_I, M cells wide, per edge.
    Strip {
        /// The cell file (TOML).
        cell: PathBuf,
        /// The periodic lattice vector, 1 or 2 (1 for a one-dimensional cell: its free chain).
        #[arg(long)]
        along: usize,
        /// Cells across the strip, M.
        #[arg(long)]
        cells: usize,
        /// Wave number Q = k.a_I (radians).
        #[arg(long, default_value_t = DEFAULT_Q, allow_negative_numbers = true)]
        q: f64,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// Guest modes: the strains the periodic lattice admits at no cost.
    Guest {
        /// The cell file (TOML).
        cell: PathBuf,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// The bands along a path, as a figure (PNG, SVG, CSV).
    Bands {
        /// The cell file (TOML).
        cell: PathBuf,
        /// Points joined by `-`: G X Y M K K' or reduced coordinates f1,f2.
        #[arg(long, default_value = "G-X-M-G")]
        path: String,
        /// Samples per segment.
        #[arg(long, default_value_t = 60)]
        samples: usize,
        /// Output folder.
        #[arg(long, default_value = "network-output")]
        out: PathBuf,
    },
    /// The cell's overview figure: a patch, arg det Q(k) over the zone, a strip's spectrum and
    /// edge zero modes, a zero mode's arrows.
    Draw {
        /// The cell file (TOML).
        cell: PathBuf,
        /// Output folder.
        #[arg(long, default_value = "network-output")]
        out: PathBuf,
    },
    /// The polarization phase diagram of Kane and Lubensky's deformed kagome over (x1, x2):
    /// a resumable results file and its figure.
    Diagram {
        /// x1 axis FROM:TO:COUNT.
        #[arg(long, default_value = "-0.2:0.2:41", allow_hyphen_values = true)]
        x1: String,
        /// x2 axis FROM:TO:COUNT.
        #[arg(long, default_value = "-0.2:0.2:41", allow_hyphen_values = true)]
        x2: String,
        /// Kane and Lubensky's x3.
        #[arg(long, default_value_t = 0.1, allow_negative_numbers = true)]
        x3: f64,
        /// Their z.
        #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
        z: f64,
        /// Output folder (results file `diagram.csv` and the figure).
        #[arg(long, default_value = "network-output")]
        out: PathBuf,
        /// Compute only shard I/N (or `slurm`: this task of a SLURM job array) into its own file
        /// (`diagram.shard-I-of-N.csv`); `--merge` joins them.
        #[arg(long, conflicts_with = "merge")]
        shard: Option<String>,
        /// Join the shard files beside `diagram.csv` into it (chain-sweep's checked merge), then
        /// draw the figure.
        #[arg(long)]
        merge: bool,
        /// Worker threads, at most 4 per core, never more than the points (default: every core).
        #[arg(long)]
        threads: Option<usize>,
    },
    /// Networks in motion (issue 36): nonlinear waves launched on a network, measured, drawn.
    Motion {
        #[command(subcommand)]
        demo: Motion,
    },
    /// Print a ready cell in the file format: square, kagome, deformed-kagome X1 X2 X3 Z,
    /// twisted-kagome ALPHA, rotor-chain A R THETA_BAR, paper-chain-right, paper-chain-left.
    Cell {
        /// The cell's name.
        name: String,
        /// Its parameters.
        #[arg(allow_negative_numbers = true)]
        parameters: Vec<f64>,
    },
}

#[derive(Subcommand)]
enum Motion {
    /// A transition wave in a chain of bistable elements (the polynomial double-well law): its
    /// fitted front speed against the continuum's closed form, and the x-t diagram.
    Transition {
        /// Sites of the chain.
        #[arg(long, default_value_t = BistableChain::default().sites)]
        sites: usize,
        /// The damping rate gamma (1 / time).
        #[arg(long, default_value_t = BistableChain::default().damping)]
        damping: f64,
        /// Length of the run (the fit starts at t = 15).
        #[arg(long, default_value_t = BistableChain::default().duration)]
        duration: f64,
        /// Output folder of the figure.
        #[arg(long, default_value = "network-output")]
        out: PathBuf,
    },
    /// A domain wall between two polarizations moving through coupled Kane-Lubensky chains: the
    /// counts and windings of each side before and after, four frames, and every frame as a GIF
    /// (network-wall.gif).
    Wall {
        /// Chains (rows).
        #[arg(long, default_value_t = CoupledChains::default().chains)]
        chains: usize,
        /// Cells per chain (two rotors each).
        #[arg(long, default_value_t = CoupledChains::default().cells)]
        cells: usize,
        /// The launch's speed amplitude v0.
        #[arg(long, default_value_t = CoupledChains::default().speed)]
        speed: f64,
        /// Length of the run.
        #[arg(long, default_value_t = CoupledChains::default().duration)]
        duration: f64,
        /// Output folder of the figure and the GIF.
        #[arg(long, default_value = "network-output")]
        out: PathBuf,
    },
}

/// A failure and its exit status.
struct Failure {
    status: u8,
    message: String,
}

impl From<CellError> for Failure {
    fn from(e: CellError) -> Self {
        Failure { status: 2, message: e.to_string() }
    }
}

impl From<NetworkError> for Failure {
    fn from(e: NetworkError) -> Self {
        let status = match e {
            NetworkError::WindingUndefined { .. } | NetworkError::WeylPoints { .. } => 3,
            NetworkError::PatchSize { .. }
            | NetworkError::PeriodicImage { .. }
            | NetworkError::NotSquare { .. }
            | NetworkError::Argument { .. }
            | NetworkError::InvalidOption(_)
            | NetworkError::TooLarge { .. } => 2,
            _ => 1,
        };
        Failure { status, message: e.to_string() }
    }
}

impl From<MotionError> for Failure {
    fn from(e: MotionError) -> Self {
        match e {
            MotionError::Network(e) => e.into(),
            MotionError::InvalidOption(_) | MotionError::Cell(_) => {
                Failure { status: 2, message: e.to_string() }
            }
            _ => Failure { status: 1, message: e.to_string() },
        }
    }
}

fn fail(status: u8, message: impl Into<String>) -> Failure {
    Failure { status, message: message.into() }
}

fn main() -> ExitCode {
    chain_sweep::pipe::exit_quietly_on_broken_pipe();
    let cli = Cli::parse();
    if let Err(e) = output::stop_on_signals("network", || {}) {
        eprintln!("network: error: cannot install the signal handlers: {e}");
        return ExitCode::from(1);
    }
    match run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!("network: error: {}", f.message);
            ExitCode::from(f.status)
        }
    }
}

fn read(path: &Path) -> Result<Cell, Failure> {
    Cell::from_toml_file(path).map_err(|e| fail(2, format!("{}: {e}", path.display())))
}

fn name_of(path: &Path) -> String {
    path.file_stem().map_or_else(|| "cell".to_owned(), |s| s.to_string_lossy().into_owned())
}

/// `N1xN2` (or `N` for a one-dimensional cell).
fn parse_cells(text: &str, dimension: usize) -> Result<[usize; 2], Failure> {
    let parts: Result<Vec<usize>, _> = text.split(['x', 'X']).map(|p| p.trim().parse::<usize>()).collect();
    let bad = || {
        fail(
            2,
            format!(
                "--cells `{text}`: expected {}",
                if dimension == 2 { "N1xN2, e.g. 10x10" } else { "N, e.g. 20" }
            ),
        )
    };
    let parts = parts.map_err(|_| bad())?;
    match (dimension, parts.as_slice()) {
        (1, [n]) => Ok([*n, 1]),
        (2, [n1, n2]) => Ok([*n1, *n2]),
        _ => Err(bad()),
    }
}

fn print(json: bool, value: serde_json::Value, text: String) {
    if json {
        println!("{value}");
    } else {
        println!("{text}");
    }
}

fn prepare(out: &Path) -> Result<(), Failure> {
    std::fs::create_dir_all(out).map_err(|e| fail(1, format!("cannot create {}: {e}", out.display())))?;
    output::clean_stale_temporaries(out)
        .map_err(|e| fail(1, format!("cannot clean {}: {e}", out.display())))?;
    Ok(())
}

fn write_figure(figure: &chain_paper::Figure, out: &Path) -> Result<(), Failure> {
    let files = render::render(figure, out).map_err(|e| fail(1, e.to_string()))?;
    let csv = chain_paper::data::write_csv(figure, out).map_err(|e| fail(1, e.to_string()))?;
    for f in files.iter().chain(&csv) {
        println!("{}", f.display());
    }
    Ok(())
}

fn run(command: Command) -> Result<(), Failure> {
    match command {
        Command::Counts { cell, cells, boundary, json } => {
            let c = read(&cell)?;
            let n = parse_cells(&cells, c.dimension())?;
            let boundary = match boundary {
                BoundaryArg::Periodic => Boundary::Periodic,
                BoundaryArg::Free => Boundary::Free,
            };
            let patch = Patch::new(&c, n, boundary)?;
            let k = counts(&patch)?;
            let method = match k.method {
                Method::BlochBlocks { .. } => "bloch-blocks",
                Method::DenseSvd => "dense-svd",
                Method::Sparse => "sparse",
            };
            let value = json!({
                "cells": if c.dimension() == 2 { json!(n) } else { json!([n[0]]) },
                "boundary": match boundary { Boundary::Periodic => "periodic", Boundary::Free => "free" },
                "dof": k.dof,
                "bonds": k.bonds,
                "rank": k.rank,
                "zero_modes": k.zero_modes,
                "self_stresses": k.self_stresses,
                "index_theorem": k.zero_modes as i64 - k.self_stresses as i64 == k.dof as i64 - k.bonds as i64,
                "largest_singular_value": k.largest_singular_value,
                "smallest_kept": k.smallest_kept,
                "largest_dropped": k.largest_dropped,
                "method": method,
            });
            let text = format!(
                "{} zero modes, {} states of self-stress ({} dof, {} bonds, rank {}; N0 - Nss = dof - bonds holds; {method})",
                k.zero_modes, k.self_stresses, k.dof, k.bonds, k.rank
            );
            print(json, value, text);
        }
        Command::Winding { cell, json } => {
            let c = read(&cell)?;
            let w = winding(&c, &WindingOptions::default())?;
            let value = json!({
                "winding": w.winding,
                "polarization": w.polarization,
                "dipole": w.dipole,
                "closest_approach": w.closest_approach,
            });
            let text = format!(
                "winding {:?}, polarization R_T = {:?} (lattice coordinates), cell dipole r0 = {:?}",
                w.winding, w.polarization, w.dipole
            );
            print(json, value, text);
        }
        Command::Strip { cell, along, cells, q, json } => {
            let c = read(&cell)?;
            if along == 0 || along > c.dimension() {
                return Err(fail(
                    2,
                    format!("--along {along}: the cell has {} lattice vector(s)", c.dimension()),
                ));
            }
            let strip = Strip { along: along - 1, cells, q };
            let m = strip_modes(&c, &strip)?;
            let value = json!({
                "along": along,
                "cells": cells,
                "q": q,
                "zero_modes": m.zero_modes,
                "self_stresses": m.self_stresses,
                "edge_zero_modes": {"low": m.low, "high": m.high},
                "bulk_zero_modes": m.bulk,
                "centres": m.centres,
                "predicted": m.predicted.map(|(l, h)| json!({"low": l, "high": h})),
            });
            let text = format!(
                "{} zero modes at q = {q}: low edge {}, high edge {}, bulk {}{}",
                m.zero_modes,
                m.low,
                m.high,
                m.bulk,
                m.predicted.map_or(String::new(), |(l, h)| format!(" (winding predicts low {l}, high {h})"))
            );
            print(json, value, text);
        }
        Command::Guest { cell, json } => {
            let c = read(&cell)?;
            let g = guest_modes(&c)?;
            let value = json!({"guest_modes": g.count, "strains": g.strains});
            print(json, value, format!("{} Guest mode(s); strains {:?}", g.count, g.strains));
        }
        Command::Bands { cell, path, samples, out } => {
            let c = read(&cell)?;
            let points = parse_path(&c, &path)?;
            let figure = bands_figure(&c, &name_of(&cell), &points, samples)?;
            prepare(&out)?;
            write_figure(&figure, &out)?;
        }
        Command::Draw { cell, out } => {
            let c = read(&cell)?;
            let figure = cell_figure(&c, &name_of(&cell))?;
            prepare(&out)?;
            write_figure(&figure, &out)?;
        }
        Command::Diagram { x1, x2, x3, z, out, shard, merge, threads } => {
            let axis = |flag: &str, text: &str| {
                text.parse::<Axis>().map_err(|e| fail(2, format!("--{flag} `{text}`: {e}")))
            };
            let grid = Grid::new(axis("x1", &x1)?, axis("x2", &x2)?).map_err(|e| fail(2, e.to_string()))?;
            if !(x3.is_finite() && z.is_finite()) {
                return Err(fail(2, "--x3 and --z must be finite"));
            }
            let params = DiagramParams { x3, z };
            chain_sweep::threads::worker_threads(threads, grid.len())
                .map_err(|e| fail(2, format!("invalid --threads: {e}")))?;
            prepare(&out)?;
            let path = out.join("diagram.csv");
            if merge {
                let shards = find_shards(&path).map_err(|e| fail(2, e.to_string()))?;
                let summary =
                    merge_shards::<PolarizationPoint>(&shards, &path).map_err(|e| fail(2, e.to_string()))?;
                eprintln!(
                    "network: merged {} shards into {}: {} points ({} failed)",
                    summary.shards,
                    path.display(),
                    summary.total,
                    summary.failed
                );
                let rows = read_results::<PolarizationPoint>(&path).map_err(|e| fail(1, e.to_string()))?;
                write_figure(&diagram_figure(&params, &grid, &rows), &out)?;
                return Ok(());
            }
            let mut options = SweepOptions::new("polarization", params.run_label());
            options.threads = threads;
            let shard = match shard.as_deref() {
                None => None,
                Some("slurm") => Some(Shard::from_slurm_env().map_err(|e| fail(2, e.to_string()))?),
                Some(text) => Some(text.parse::<Shard>().map_err(|e| fail(2, e.to_string()))?),
            };
            options.shard = shard;
            let summary = run_sweep(&grid, &path, |a, b| compute_point(&params, a, b), &options)
                .map_err(|e| fail(1, e.to_string()))?;
            eprintln!(
                "network: {} points computed, {} already in the file, {} failed",
                summary.computed, summary.skipped, summary.failed
            );
            if let Some(shard) = shard {
                println!("{}", shard.file_name(&path).display());
                return Ok(());
            }
            let rows = read_results::<PolarizationPoint>(&path).map_err(|e| fail(1, e.to_string()))?;
            write_figure(&diagram_figure(&params, &grid, &rows), &out)?;
            println!("{}", path.display());
        }
        Command::Motion { demo: Motion::Transition { sites, damping, duration, out } } => {
            let chain = BistableChain { sites, damping, duration, ..BistableChain::default() };
            let samples = (2.0 * duration).round() as usize + 1;
            let chain = BistableChain { samples: samples.max(2), ..chain };
            let (figure, wave) = transition_figure(&chain)?;
            println!(
                "front speed {:.5} (fit over {} samples, rms {:.3} sites), continuum {:.5}: {:+.3} %",
                wave.speed(),
                wave.fit.points,
                wave.fit.rms_residual,
                wave.predicted,
                100.0 * wave.relative_difference()
            );
            prepare(&out)?;
            write_figure(&figure, &out)?;
        }
        Command::Motion { demo: Motion::Wall { chains, cells, speed, duration, out } } => {
            let c = CoupledChains { chains, cells, speed, duration, ..CoupledChains::default() };
            let (figure, run) = wall_figure(&c)?;
            let (b, a) = (&run.crossed_before, &run.crossed_after);
            println!(
                "wall speed {:.5} rotors per unit time (rms {:.3}); largest spread between chains {:.3} rotors",
                run.fit.slope,
                run.fit.rms_residual,
                run.spread().into_iter().fold(0.0, f64::max)
            );
            for (when, r) in [("before", b), ("after", a)] {
                let u = &r.uniform;
                println!(
                    "rotors {}..{} {when}: mean tilt {:+.4} (deviation {:.2e}), N0 = {}, S = {}, floppy mode at {:.2}, winding {}",
                    r.from,
                    r.to,
                    r.mean_tilt,
                    r.largest_deviation,
                    u.counts.zero_modes,
                    u.counts.self_stresses,
                    u.floppy_mode_centre,
                    u.winding.winding[0]
                );
            }
            prepare(&out)?;
            write_figure(&figure, &out)?;
            let gif = out.join("network-wall.gif");
            let bytes = write_gif(&c, &run, &gif, 150).map_err(|e| fail(1, e.to_string()))?;
            println!("{} ({bytes} bytes)", gif.display());
        }
        Command::Cell { name, parameters } => {
            let cell = ready::by_name(&name, &parameters)?;
            print!("{}", cell.to_toml());
        }
    }
    Ok(())
}
