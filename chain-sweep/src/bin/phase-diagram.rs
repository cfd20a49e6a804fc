//! `phase-diagram`: the scattering phase diagram of paper Fig. `fig:phasediagram`. One
//! simulation per point of a (k_i/k, v0) grid, each result appended to a CSV file as soon as it
//! is known. Run the same command again to resume a sweep that was stopped.
//!
//! ```text
//! phase-diagram --defect kink --ki 0.01:1:40 --v0 0.5:12:40 --out kink.csv
//! ```
//!
//! Exit status: 0 every point computed; 3 the sweep finished but some points failed (their
//! errors are in the file's `error` column; `--retry-failed` computes them again); 1 the sweep
//! could not run (the message says why); 2 bad arguments. On bad arguments nothing is written.

use std::num::NonZeroUsize;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use chain_sweep::scattering::{PointRecord, fake_point};
use chain_sweep::{Axis, Grid, Summary, SweepOptions, run_sweep};
use clap::{Parser, ValueEnum};
use rotor_chain::RuntimeChain;

/// Sweep a scattering phase diagram: a kink or antikink launched at speed v0 towards an impurity
/// spring of stiffness k_i, one simulation per grid point. Results are appended to --out as they
/// finish; rerun the same command to resume. Exit status 3 means some points failed.
#[derive(Debug, Parser)]
#[command(name = "phase-diagram", version, allow_negative_numbers = true)]
struct Cli {
    /// Impurity stiffness ratio k_i/k, evenly spaced (both ends included); every value > 0
    #[arg(long, value_name = "FROM:TO:COUNT", allow_hyphen_values = true)]
    ki: Axis,
    /// Launch speed of the defect, evenly spaced (both ends included)
    #[arg(long, value_name = "FROM:TO:COUNT", allow_hyphen_values = true)]
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
    defect: Defect,
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
enum Defect {
    /// The zero-energy domain wall (+theta_bar on the left, -theta_bar on the right)
    Kink,
    /// The domain wall that stretches springs (-theta_bar on the left, +theta_bar on the right)
    Antikink,
}

impl Defect {
    fn name(self) -> &'static str {
        match self {
            Defect::Kink => "kink",
            Defect::Antikink => "antikink",
        }
    }
}

/// The chain and defect of a sweep, checked. Everything a point's simulation needs besides its
/// `(k_i/k, v0)`.
#[derive(Clone, Debug)]
struct Config {
    /// Rotors, rotor length, stiffness, equilibrium angle (lattice spacing 1, mass 1).
    n: usize,
    r: f64,
    k: f64,
    theta_bar: f64,
    defect: Defect,
}

impl Config {
    /// Check the chain with the model's own rules (`chain-geometry`, through `RuntimeChain`) and
    /// that every impurity stiffness is a valid spring stiffness.
    fn new(cli: &Cli) -> Result<Self, String> {
        RuntimeChain::builder(cli.n, cli.r, cli.k, cli.theta_bar)
            .build()
            .map_err(|e| format!("invalid chain: {e}"))?;
        if let Some(&bad) =
            cli.ki.values().iter().find(|&&ki| !(ki * cli.k > 0.0 && (ki * cli.k).is_finite()))
        {
            return Err(format!(
                "invalid --ki: every k_i/k must be > 0 (k_i = {bad} * {} is a spring stiffness), got {bad}",
                cli.k
            ));
        }
        Ok(Self { n: cli.n, r: cli.r, k: cli.k, theta_bar: cli.theta_bar, defect: cli.defect })
    }

    /// The run label stored in the results file: a file of another chain or defect is refused.
    fn run_label(&self, physics: &str) -> String {
        let Self { n, r, k, theta_bar, defect } = self;
        format!("defect={} n={n} r={r:?} k={k:?} theta_bar={theta_bar:?} physics={physics}", defect.name())
    }
}

/// One point of the phase diagram (paper Sec. VI, Fig. `fig:phasediagram`): the chain with the
/// middle spring's stiffness set to `ki_ratio * k`, the defect launched from 15 sites to the right
/// of it with speed `v0`, run until the outcome is decided
/// (`rotor_chain::dynamics::scatter::scatter`). The sweep runs this on every core, records an
/// `Err` in the file and carries on, and turns a panic into an `Err`.
fn compute_point(cfg: &Config, ki_ratio: f64, v0: f64) -> Result<PointRecord, String> {
    use rotor_chain::dynamics::scatter::{ScatterSetup, scatter};
    use rotor_chain::statics::walls::Charge;
    let middle = (cfg.n - 1) / 2;
    let model = RuntimeChain::builder(cfg.n, cfg.r, cfg.k, cfg.theta_bar)
        .spring(middle, Some(ki_ratio * cfg.k), None)
        .build()
        .map_err(|e| e.to_string())?;
    let charge = match cfg.defect {
        Defect::Kink => Charge::Kink,
        Defect::Antikink => Charge::Antikink,
    };
    let result =
        scatter(&model, &ScatterSetup::from_the_right(charge, v0, middle)).map_err(|e| e.to_string())?;
    let last = result.run.tracker.snapshots.last().ok_or("the run recorded nothing")?;
    let (kinks_final, antikinks_final) = last.counts();
    let report = &result.run.report;
    Ok(PointRecord {
        outcome: result.outcome,
        t_decided: result.decided_at,
        kinks_final,
        antikinks_final,
        energy_error: report.max_energy_error / report.energy_initial.abs().max(f64::MIN_POSITIVE),
    })
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(&cli) {
        Ok(summary) => {
            report(&cli, &summary);
            if summary.failed + summary.failed_before > 0 { ExitCode::from(3) } else { ExitCode::SUCCESS }
        }
        Err(message) => {
            eprintln!("phase-diagram: error: {message}");
            ExitCode::FAILURE
        }
    }
}

/// Check everything, then sweep. Nothing is written before every argument has been checked.
fn run(cli: &Cli) -> Result<Summary, String> {
    let cfg = Config::new(cli)?;
    let grid = Grid::new(cli.ki.clone(), cli.v0.clone()).map_err(|e| e.to_string())?;
    let fake_delay = cli.fake_delay_ms.map(Duration::from_millis);
    let mut options = SweepOptions::new(
        format!("{} phase diagram", cfg.defect.name()),
        cfg.run_label(if fake_delay.is_some() { "fake" } else { "scatter" }),
    );
    options.threads = cli.threads.map(NonZeroUsize::get);
    options.retry_failed = cli.retry_failed;
    let compute = |ki_ratio: f64, v0: f64| match fake_delay {
        Some(delay) => {
            std::thread::sleep(delay);
            Ok(fake_point(ki_ratio, v0))
        }
        None => compute_point(&cfg, ki_ratio, v0),
    };
    run_sweep(&grid, &cli.out, compute, &options).map_err(|e| e.to_string())
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
