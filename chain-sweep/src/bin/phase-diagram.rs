//! `phase-diagram`: the scattering phase diagram of paper Fig. `fig:phasediagram`. One
//! simulation per point of a (k_i/k, v0) grid ([`PhaseDiagram::compute_point`]), each result
//! appended to a CSV file as soon as it is known. Run the same command again to resume a sweep
//! that was stopped.
//!
//! ```text
//! phase-diagram --defect antikink --ki 0.01:3:40:log --v0 0.5:12:40 --out antikink.csv
//! ```
//!
//! Exit status: 0 every point computed; 1 the sweep could not run or stopped (a file of another
//! sweep, a locked file, an I/O error: the message says why); 2 bad arguments or an invalid
//! value, nothing written; 3 the sweep finished but some points failed (their errors are in the
//! file's `error` column; `--retry-failed` computes them again).

use std::num::NonZeroUsize;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use chain_sweep::scattering::{
    DEFAULT_ENERGY_TOLERANCE, Defect, Ends, Integrator, PhaseDiagram, PointRecord, fake_point,
};
use chain_sweep::{Axis, Grid, Summary, SweepError, SweepOptions, run_sweep};
use clap::{Parser, ValueEnum};

/// Sweep a scattering phase diagram: a kink or antikink launched at speed v0 towards an impurity
/// spring of stiffness k_i, one simulation per grid point. Results are appended to --out as they
/// finish; rerun the same command to resume. Exit status: 0 done, 1 the sweep could not run,
/// 2 bad arguments, 3 some points failed.
#[derive(Debug, Parser)]
#[command(name = "phase-diagram", version, allow_negative_numbers = true)]
struct Cli {
    /// Impurity stiffness ratio k_i/k, evenly spaced (both ends included), or evenly spaced in
    /// the logarithm with a fourth part `log` (0.01:3:40:log); every value > 0
    #[arg(long, value_name = "FROM:TO:COUNT[:log]", allow_hyphen_values = true)]
    ki: Axis,
    /// Launch speed of the defect, evenly spaced (both ends included)
    #[arg(long, value_name = "FROM:TO:COUNT[:log]", allow_hyphen_values = true)]
    v0: Axis,
    /// Number of rotors (the paper's phase diagram: 60)
    #[arg(long, default_value_t = 60)]
    n: usize,
    /// Rotor length r, in units of the lattice spacing a = 1 (paper: r/a = 0.8)
    #[arg(long, default_value_t = 0.8)]
    r: f64,
    /// Spring stiffness k (paper: 1e4)
    #[arg(long, default_value_t = 1.0e4)]
    k: f64,
    /// Equilibrium angle theta_bar from the vertical (paper's phase diagram: 0.28)
    #[arg(long, default_value_t = 0.28)]
    theta_bar: f64,
    /// The defect launched at the impurity
    #[arg(long, value_enum)]
    defect: DefectArg,
    /// The chain's ends: free (the paper's) or absorbing (a damping sponge on the last 10 rotors)
    #[arg(long, value_enum, default_value_t = EndsArg::Free)]
    ends: EndsArg,
    /// The integrator each point starts with
    #[arg(long, value_enum, default_value_t = IntegratorArg::Verlet)]
    integrator: IntegratorArg,
    /// Verlet's time step [default: a tenth of its stability limit]
    #[arg(long)]
    dt: Option<f64>,
    /// Largest relative energy error of a point before it is recomputed with DOP853 (or, with
    /// --no-recompute, recorded as failed)
    #[arg(long, default_value_t = DEFAULT_ENERGY_TOLERANCE)]
    energy_tolerance: f64,
    /// Record a point over the energy tolerance as failed instead of recomputing it with DOP853
    #[arg(long)]
    no_recompute: bool,
    /// End time of each run
    #[arg(long, default_value_t = 20.0)]
    t_max: f64,
    /// The results file (CSV); created if missing, resumed if it holds part of this sweep
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
    /// Worker threads [default: every core]
    #[arg(long)]
    threads: Option<NonZeroUsize>,
    /// Compute again the points the file records as failed
    #[arg(long)]
    retry_failed: bool,
    /// FOR TESTING ONLY: replace the physics by a deterministic fake record after sleeping this
    /// many milliseconds per point
    #[arg(long, hide = true, value_name = "MS")]
    fake_delay_ms: Option<u64>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum DefectArg {
    /// The zero-energy domain wall (+theta_bar on the left, -theta_bar on the right)
    Kink,
    /// The domain wall that stretches springs (-theta_bar on the left, +theta_bar on the right)
    Antikink,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum EndsArg {
    Free,
    Absorbing,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum IntegratorArg {
    Verlet,
    Dop853,
}

/// Why the tool stopped, and with which exit status.
enum Failure {
    /// Bad arguments or an invalid value: status 2, nothing written.
    Usage(String),
    /// The sweep could not run or stopped: status 1.
    Run(String),
}

/// The phase diagram of the arguments, checked.
fn diagram(cli: &Cli) -> Result<PhaseDiagram, Failure> {
    let defect = match cli.defect {
        DefectArg::Kink => Defect::Kink,
        DefectArg::Antikink => Defect::Antikink,
    };
    let usage = |e: chain_sweep::scattering::ConfigError| Failure::Usage(e.to_string());
    let mut d = PhaseDiagram::new(cli.n, cli.r, cli.k, cli.theta_bar, defect).map_err(usage)?;
    d.ends = match cli.ends {
        EndsArg::Free => Ends::Free,
        EndsArg::Absorbing => Ends::Absorbing,
    };
    d.integrator = match cli.integrator {
        IntegratorArg::Verlet => Integrator::Verlet,
        IntegratorArg::Dop853 => Integrator::Dop853,
    };
    d.dt = cli.dt;
    d.energy_tolerance = cli.energy_tolerance;
    d.recompute = !cli.no_recompute;
    d.t_max = cli.t_max;
    d.check().map_err(usage)?;
    for &ki in cli.ki.values() {
        d.check_ki(ki).map_err(|e| Failure::Usage(format!("invalid --ki: {e}")))?;
    }
    for &v0 in cli.v0.values() {
        if !(v0 >= 0.0 && v0.is_finite()) {
            return Err(Failure::Usage(format!("invalid --v0: every launch speed must be >= 0, got {v0}")));
        }
    }
    Ok(d)
}

fn main() -> ExitCode {
    // clap prints usage errors itself and exits with status 2.
    let cli = Cli::parse();
    match run(&cli) {
        Ok(summary) => {
            report(&cli, &summary);
            if summary.failed + summary.failed_before > 0 { ExitCode::from(3) } else { ExitCode::SUCCESS }
        }
        Err(Failure::Usage(message)) => {
            eprintln!("phase-diagram: error: {message}");
            ExitCode::from(2)
        }
        Err(Failure::Run(message)) => {
            eprintln!("phase-diagram: error: {message}");
            ExitCode::from(1)
        }
    }
}

/// Check everything, then sweep. Nothing is written before every argument has been checked.
fn run(cli: &Cli) -> Result<Summary, Failure> {
    let d = diagram(cli)?;
    let grid = Grid::new(cli.ki.clone(), cli.v0.clone()).map_err(|e| Failure::Usage(e.to_string()))?;
    let fake_delay = cli.fake_delay_ms.map(Duration::from_millis);
    let label = if fake_delay.is_some() {
        d.run_label().replace("physics=scatter-v2", "physics=fake")
    } else {
        d.run_label()
    };
    let mut options = SweepOptions::new(format!("{} phase diagram", d.defect.name()), label);
    options.threads = cli.threads.map(NonZeroUsize::get);
    options.retry_failed = cli.retry_failed;
    let compute = |ki_ratio: f64, v0: f64| -> Result<PointRecord, String> {
        match fake_delay {
            Some(delay) => {
                std::thread::sleep(delay);
                Ok(fake_point(ki_ratio, v0))
            }
            None => d.compute_point(ki_ratio, v0),
        }
    };
    run_sweep(&grid, &cli.out, compute, &options).map_err(|e| match e {
        e @ SweepError::NotAFile { .. } => Failure::Usage(e.to_string()),
        e => Failure::Run(e.to_string()),
    })
}

fn report(cli: &Cli, s: &Summary) {
    let out = cli.out.display();
    eprintln!(
        "phase-diagram: {out}: {} points: {} computed now ({} failed), {} already done ({} failed) in {:.1} s",
        s.total,
        s.computed,
        s.failed,
        s.skipped,
        s.failed_before,
        s.elapsed.as_secs_f64()
    );
    if s.repaired_bytes > 0 {
        eprintln!(
            "phase-diagram: cut off an unfinished last line ({} bytes) left by a stopped run",
            s.repaired_bytes
        );
    }
    if s.retried > 0 {
        eprintln!("phase-diagram: removed {} failed lines to compute them again", s.retried);
    }
    if !s.duplicates.is_empty() {
        eprintln!(
            "phase-diagram: warning: {} points appear on more than one line of {out} (kept, not recomputed): {:?}",
            s.duplicates.len(),
            s.duplicates
        );
    }
    if s.failed_before > 0 && !cli.retry_failed {
        eprintln!("phase-diagram: rerun with --retry-failed to compute the failed points again");
    }
}
