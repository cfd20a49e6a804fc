//! `phase-diagram`: the scattering phase diagram of paper Fig. `fig:phasediagram`. One
//! simulation per point of a (k_i/k, v0) grid ([`PhaseDiagram::compute_point`]), each result
//! appended to a CSV file as soon as it is known. Run the same command again to resume a sweep
//! that was stopped.
//!
//! ```text
//! phase-diagram --defect antikink --ki 0.01:3:40:log --v0 0.5:12:40 --out antikink.csv
//! ```
//!
//! Split over the tasks of a job array, each task computes one shard into its own file
//! (`--shard I/N`, or `--shard slurm` in a SLURM array), and `merge` joins them:
//!
//! ```text
//! phase-diagram --defect antikink --ki 0.01:3:40:log --v0 0.5:12:40 --out antikink.csv --shard 3/8
//!     # writes antikink.shard-3-of-8.csv
//! phase-diagram merge --out antikink.csv   # every antikink.shard-I-of-8.csv beside it
//! ```
//!
//! Exit status: 0 every point computed (merged); 1 the sweep (merge) could not run or stopped (a
//! file of another sweep, a locked file, an I/O error, shards that are missing points: the
//! message says why); 2 bad arguments or an invalid value, nothing written; 3 the sweep (merge)
//! finished but some points failed (their errors are in the file's `error` column;
//! `--retry-failed` computes them again); 128 + the signal's number (130 for Ctrl-C, 143 for
//! SIGTERM, as a SLURM time limit sends) stopped by a signal: the first SIGINT, SIGTERM or SIGHUP
//! lets the points being computed finish and be written, then says how many points the file
//! holds; a second one stops at once (a line cut short is repaired by the next run).

use std::num::NonZeroUsize;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicI32, Ordering};
use std::time::Duration;

use chain_sweep::scattering::{
    DEFAULT_ENERGY_TOLERANCE, Defect, Direction, Ends, Method, PhaseDiagram, PointRecord, fake_point,
};
use chain_sweep::threads::worker_threads;
use chain_sweep::{
    Axis, Grid, MergeSummary, Shard, Summary, SweepError, SweepOptions, find_shards, merge_shards, run_sweep,
};
use clap::{Parser, Subcommand, ValueEnum};

/// Sweep a scattering phase diagram: a kink or antikink launched at speed v0 towards an impurity
/// spring of stiffness k_i, one simulation per grid point. Results are appended to --out as they
/// finish; rerun the same command to resume. Exit status: 0 done, 1 the sweep could not run,
/// 2 bad arguments, 3 some points failed, 130 (143) stopped by Ctrl-C (SIGTERM) after writing the
/// points in progress. `phase-diagram merge --help`: join the files of a sweep split with --shard.
#[derive(Debug, Parser)]
#[command(
    name = "phase-diagram",
    version,
    allow_negative_numbers = true,
    args_conflicts_with_subcommands = true,
    subcommand_negates_reqs = true
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Impurity stiffness ratio k_i/k, evenly spaced (both ends included), or evenly spaced in
    /// the logarithm with a fourth part `log` (0.01:3:40:log); every value > 0
    #[arg(long, value_name = "FROM:TO:COUNT[:log]", allow_hyphen_values = true, required = true)]
    ki: Option<Axis>,
    /// Launch speed of the defect, evenly spaced (both ends included)
    #[arg(long, value_name = "FROM:TO:COUNT[:log]", allow_hyphen_values = true, required = true)]
    v0: Option<Axis>,
    /// Number of rotors (the paper's phase diagram: 60); at least 38 for the paper's experiment,
    /// for the defect's start 15.5 sites right of the middle spring to lie more than 3 sites from
    /// the end (the error names the least n for other --impurity, --start and --direction)
    #[arg(long, default_value_t = 60)]
    n: usize,
    /// The impurity spring P, between rotors P and P + 1 [default: the middle one, (n - 1) / 2]
    #[arg(long, value_name = "P")]
    impurity: Option<usize>,
    /// The impurity spring's rest length l0, in units of a (a rest-length impurity, with the
    /// stiffness impurity of --ki; --ki 1:1:1 for a pure one) [default: the chain's]
    #[arg(long, value_name = "L0")]
    impurity_rest_length: Option<f64>,
    /// Where the defect starts (rotor index, fractional allowed) [default: 15 sites from the
    /// impurity's centre on the side it comes from]
    #[arg(long, value_name = "SITE")]
    start: Option<f64>,
    /// Which way the defect is launched: left (towards rotor 0, from the right of the impurity:
    /// the paper's) or right
    #[arg(long, value_enum, default_value_t = DirectionArg::Left)]
    direction: DirectionArg,
    /// Damping rate of every rotor, in 1/t as given (the paper's runs: 0)
    #[arg(long, default_value_t = 0.0)]
    damping: f64,
    /// Run every point with DOP853 as well as Verlet and mark it unresolved where they decide
    /// differently (column `unresolved` = integrators-disagree); several times the cost of a
    /// point. Points where a wall from a free end reached the impurity before the decision are
    /// marked unresolved (end-wall-first) either way
    #[arg(long)]
    cross_check: bool,
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
    #[arg(long, value_enum, required = true)]
    defect: Option<DefectArg>,
    /// The chain's ends: free (the paper's) or absorbing (a damping sponge on the last 10 rotors)
    #[arg(long, value_enum, default_value_t = EndsArg::Free)]
    ends: EndsArg,
    /// The integrator each point starts with (the names of `rotor_chain::integrate::Method`)
    #[arg(long, default_value = "verlet", value_parser = integrator_parser())]
    integrator: Method,
    /// Verlet's time step, shortened to divide the output interval (0.01 sqrt(1e4 mass / k): the
    /// paper's 0.01 in the chain's time unit) [default: a tenth of its stability limit]
    #[arg(long)]
    dt: Option<f64>,
    /// Largest relative energy error of a point before it is recomputed with DOP853 (or, with
    /// --no-recompute, recorded as failed)
    #[arg(long, default_value_t = DEFAULT_ENERGY_TOLERANCE)]
    energy_tolerance: f64,
    /// Record a point over the energy tolerance as failed instead of recomputing it with DOP853
    #[arg(long)]
    no_recompute: bool,
    /// End time of each run, as given (the outcome rules' windows are the paper's in the chain's
    /// time unit sqrt(1e4 mass / k))
    #[arg(long, default_value_t = 20.0)]
    t_max: f64,
    /// The results file (CSV); created if missing, resumed if it holds part of this sweep. With
    /// --shard I/N the shard's own file, FILE with `.shard-I-of-N` before its extension
    #[arg(long, value_name = "FILE", required = true)]
    out: Option<PathBuf>,
    /// Compute only shard I of N (every N-th grid point from the I-th, I from 0) into its own
    /// file, for a job array; `slurm`: this task's shard of a SLURM job array
    /// (SLURM_ARRAY_TASK_ID of SLURM_ARRAY_TASK_COUNT). `phase-diagram merge` joins the shards
    #[arg(long, value_name = "I/N|slurm")]
    shard: Option<String>,
    /// Worker threads, at most 4 per core; never more are started than there are points to
    /// compute [default: every core]
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

#[derive(Debug, Subcommand)]
enum Command {
    /// Join the shard files of a sweep split with --shard into the whole diagram: every grid
    /// point must be in exactly one shard file, all of the same grid and run. Exit status: 0
    /// merged, 1 cannot merge (the message says why; nothing written), 3 merged but some points
    /// failed.
    Merge(MergeArgs),
}

#[derive(Debug, clap::Args)]
struct MergeArgs {
    /// The whole diagram's results file: the --out the shards were given
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
    /// The shard files [default: every FILE.shard-I-of-N beside --out, as --shard names them]
    #[arg(value_name = "SHARD_FILE")]
    shards: Vec<PathBuf>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum DefectArg {
    /// The zero-energy domain wall (+theta_bar on the left, -theta_bar on the right)
    Kink,
    /// The domain wall that stretches springs (-theta_bar on the left, +theta_bar on the right)
    Antikink,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum DirectionArg {
    /// Towards rotor 0
    Left,
    /// Towards rotor n - 1
    Right,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum EndsArg {
    Free,
    Absorbing,
}

/// The integrator's names, as `Method` spells them everywhere (runs, files, Python).
fn integrator_parser() -> impl clap::builder::TypedValueParser<Value = Method> {
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(Method::NAMES)
        .try_map(|name: String| chain_sweep::scattering::method_by_name(&name))
}

/// Why the tool stopped, and with which exit status.
enum Failure {
    /// Bad arguments or an invalid value: status 2, nothing written.
    Usage(String),
    /// The sweep could not run or stopped: status 1.
    Run(String),
    /// A signal stopped the sweep after the points in progress were written: status 128 + the
    /// signal.
    Signal(i32, String),
}

/// The phase diagram of the arguments, checked.
fn diagram(cli: &Cli, ki: &Axis, v0: &Axis) -> Result<PhaseDiagram, Failure> {
    let defect = match cli.defect {
        Some(DefectArg::Kink) | None => Defect::Kink,
        Some(DefectArg::Antikink) => Defect::Antikink,
    };
    let usage = |e: chain_sweep::scattering::ConfigError| Failure::Usage(e.to_string());
    let mut d = PhaseDiagram::new(cli.n, cli.r, cli.k, cli.theta_bar, defect).map_err(usage)?;
    d.ends = match cli.ends {
        EndsArg::Free => Ends::Free,
        EndsArg::Absorbing => Ends::Absorbing,
    };
    d.integrator = cli.integrator;
    d.dt = cli.dt;
    d.energy_tolerance = cli.energy_tolerance;
    d.recompute = !cli.no_recompute;
    d.t_max = cli.t_max;
    d.impurity_spring = cli.impurity;
    d.impurity_rest_length = cli.impurity_rest_length;
    d.start = cli.start;
    d.direction = match cli.direction {
        DirectionArg::Left => Direction::Left,
        DirectionArg::Right => Direction::Right,
    };
    d.damping = cli.damping;
    d.cross_check = cli.cross_check;
    d.check().map_err(usage)?;
    for &ki in ki.values() {
        d.check_ki(ki).map_err(|e| Failure::Usage(format!("invalid --ki: {e}")))?;
    }
    for &v0 in v0.values() {
        if !(v0 >= 0.0 && v0.is_finite()) {
            return Err(Failure::Usage(format!("invalid --v0: every launch speed must be >= 0, got {v0}")));
        }
    }
    Ok(d)
}

fn main() -> ExitCode {
    chain_sweep::pipe::exit_quietly_on_broken_pipe();
    // clap prints usage errors itself and exits with status 2.
    let cli = Cli::parse();
    let result = match &cli.command {
        Some(Command::Merge(args)) => merge(args).map(|summary| {
            eprintln!(
                "phase-diagram: merged {} shards into {}: {} points ({} failed); run {}",
                summary.shards,
                args.out.display(),
                summary.total,
                summary.failed,
                summary.run
            );
            report_unresolved(&args.out);
            summary.failed
        }),
        None => run(&cli).map(|(summary, out)| {
            report(&cli, &out, &summary);
            summary.failed + summary.failed_before
        }),
    };
    match result {
        Ok(failed) => {
            if failed > 0 {
                ExitCode::from(3)
            } else {
                ExitCode::SUCCESS
            }
        }
        Err(Failure::Usage(message)) => {
            eprintln!("phase-diagram: error: {message}");
            ExitCode::from(2)
        }
        Err(Failure::Run(message)) => {
            eprintln!("phase-diagram: error: {message}");
            ExitCode::from(1)
        }
        Err(Failure::Signal(signal, message)) => {
            eprintln!("phase-diagram: {message}");
            ExitCode::from(u8::try_from(128 + signal).unwrap_or(1))
        }
    }
}

/// The signal that asked the sweep to stop (0: none yet).
static SIGNAL: AtomicI32 = AtomicI32::new(0);

/// On the first SIGINT, SIGTERM or SIGHUP, set `stop` (the sweep starts no new point, writes the
/// points in progress, and returns [`SweepError::Stopped`]); on a second, exit at once with
/// 128 + the signal. The handler runs on a thread of its own (signal-hook), so it may print and
/// exit, which a bare signal handler may not.
#[cfg(unix)]
fn stop_on_signals(stop: Arc<AtomicBool>) -> std::io::Result<()> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])?;
    std::thread::spawn(move || {
        for signal in signals.forever() {
            if SIGNAL.swap(signal, Ordering::SeqCst) != 0 {
                eprintln!("phase-diagram: {}: stopping now", signal_name(signal));
                std::process::exit(128 + signal);
            }
            stop.store(true, Ordering::SeqCst);
            eprintln!(
                "phase-diagram: {}: finishing the points in progress, then stopping (send it again to stop at once)",
                signal_name(signal)
            );
        }
    });
    Ok(())
}

#[cfg(not(unix))]
fn stop_on_signals(_stop: Arc<AtomicBool>) -> std::io::Result<()> {
    Ok(())
}

/// The signal's name (`SIGINT`), from signal-hook's table.
fn signal_name(signal: i32) -> &'static str {
    #[cfg(unix)]
    let name = signal_hook::low_level::signal_name(signal);
    #[cfg(not(unix))]
    let name = None;
    name.unwrap_or("a signal")
}

/// The shard of `--shard`, if any.
fn shard(cli: &Cli) -> Result<Option<Shard>, Failure> {
    let usage = |e: chain_sweep::ShardError| Failure::Usage(format!("invalid --shard: {e}"));
    match cli.shard.as_deref() {
        None => Ok(None),
        Some("slurm") => Shard::from_slurm_env().map(Some).map_err(usage),
        Some(spec) => spec.parse().map(Some).map_err(usage),
    }
}

/// Check everything, then sweep. Nothing is written before every argument has been checked.
/// Returns the summary and the file written.
fn run(cli: &Cli) -> Result<(Summary, PathBuf), Failure> {
    let missing = |name: &str| Failure::Usage(format!("the argument {name} is required"));
    let (ki, v0) =
        (cli.ki.as_ref().ok_or_else(|| missing("--ki"))?, cli.v0.as_ref().ok_or_else(|| missing("--v0"))?);
    let out = cli.out.as_ref().ok_or_else(|| missing("--out"))?;
    let d = diagram(cli, ki, v0)?;
    let grid = Grid::new(ki.clone(), v0.clone()).map_err(|e| Failure::Usage(e.to_string()))?;
    let shard = shard(cli)?;
    let threads = cli.threads.map(NonZeroUsize::get);
    worker_threads(threads, grid.len()).map_err(|e| Failure::Usage(format!("invalid --threads: {e}")))?;
    let out = match shard {
        Some(s) => s.file_name(out),
        None => out.clone(),
    };
    let fake_delay = cli.fake_delay_ms.map(Duration::from_millis);
    let label = if fake_delay.is_some() {
        d.run_label().replace(&format!("physics={}", chain_sweep::scattering::PHYSICS), "physics=fake")
    } else {
        d.run_label()
    };
    let mut options = SweepOptions::new(format!("{} phase diagram", d.defect.name()), label);
    options.threads = threads;
    options.retry_failed = cli.retry_failed;
    options.shard = shard;
    let stop = Arc::new(AtomicBool::new(false));
    options.stop = Some(Arc::clone(&stop));
    stop_on_signals(stop)
        .map_err(|e| Failure::Run(format!("cannot install the handlers of SIGINT and SIGTERM: {e}")))?;
    if let Some(s) = shard {
        eprintln!("phase-diagram: shard {s}: its points go to {}", out.display());
    }
    let compute = |ki_ratio: f64, v0: f64| -> Result<PointRecord, String> {
        match fake_delay {
            Some(delay) => {
                std::thread::sleep(delay);
                Ok(fake_point(ki_ratio, v0))
            }
            None => d.compute_point(ki_ratio, v0).map_err(|e| e.to_string()),
        }
    };
    let summary = run_sweep(&grid, &out, compute, &options).map_err(|e| match e {
        e @ SweepError::NotAFile { .. } => Failure::Usage(e.to_string()),
        e @ SweepError::Stopped { .. } => {
            let signal = SIGNAL.load(Ordering::SeqCst);
            Failure::Signal(signal, format!("stopped by {}: {e}", signal_name(signal)))
        }
        e => Failure::Run(e.to_string()),
    })?;
    Ok((summary, out))
}

/// `phase-diagram merge`.
fn merge(args: &MergeArgs) -> Result<MergeSummary, Failure> {
    let run = |e: SweepError| Failure::Run(e.to_string());
    let shards =
        if args.shards.is_empty() { find_shards(&args.out).map_err(run)? } else { args.shards.clone() };
    merge_shards::<PointRecord>(&shards, &args.out).map_err(run)
}

fn report(cli: &Cli, path: &std::path::Path, s: &Summary) {
    let out = path.display();
    eprintln!(
        "phase-diagram: {out}: {} points: {} computed now ({} failed), {} already done ({} failed) in {:.1} s",
        s.total,
        s.computed,
        s.failed,
        s.skipped,
        s.failed_before,
        s.elapsed.as_secs_f64()
    );
    if let Some(asked) = cli.threads.map(NonZeroUsize::get).filter(|&t| s.threads > 0 && t > s.threads) {
        eprintln!(
            "phase-diagram: ran on {} worker thread(s), not the {asked} asked for: never more threads than points to compute",
            s.threads
        );
    }
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
    report_unresolved(path);
}

/// `phase-diagram: antikink.csv: 3 of 1600 points unresolved (2 end-wall-first, 1
/// integrators-disagree) ...`: the points of the file whose outcome is not the impurity's alone,
/// by reason (nothing when there are none).
fn report_unresolved(out: &std::path::Path) {
    let points = match chain_sweep::read_points::<PointRecord>(out) {
        Ok(points) => points,
        Err(e) => {
            eprintln!("phase-diagram: cannot count the unresolved points: {e}");
            return;
        }
    };
    let mut reasons: Vec<(&'static str, usize)> = Vec::new();
    for reason in points.iter().filter_map(|p| p.outcome.as_ref().ok()?.unresolved) {
        match reasons.iter_mut().find(|(name, _)| *name == reason.name()) {
            Some((_, count)) => *count += 1,
            None => reasons.push((reason.name(), 1)),
        }
    }
    let unresolved: usize = reasons.iter().map(|(_, count)| count).sum();
    if unresolved > 0 {
        reasons.sort();
        let by_reason: Vec<String> = reasons.iter().map(|(name, count)| format!("{count} {name}")).collect();
        eprintln!(
            "phase-diagram: {}: {unresolved} of {} points unresolved ({}): their outcome is not the impurity's alone (column `unresolved`)",
            out.display(),
            points.len(),
            by_reason.join(", ")
        );
    }
}
