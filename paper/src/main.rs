//! `paper`: reproduce every numerical figure of the paper in one command.
//!
//! ```text
//! paper [--out DIR] [--quick | --resolution] [--only LABEL,...] [--list]
//! ```
//!
//! Computes the figures of `chain_paper::figures::all()` in parallel, and writes into `DIR`
//! (default `paper-output`): `<name>.png` and `<name>.svg` per figure (`name` is the label
//! without `fig:`), `data/<name>_<panel>.csv` per panel, and `summary.md`, the paper's numbers
//! beside ours. Every file is written atomically. Then prints one line on stdout:
//! `paper: F figures, R summary rows, X failed, T s -> DIR`.
//!
//! Exit status ([`EXIT_STATUS`], also in `--help` and docs/paper.md): 0 every figure written;
//! 1 the output folder could not be prepared or written (nothing computed, or no summary);
//! 2 bad arguments (nothing computed or written); 3 some figures failed (each reported with its
//! label on stderr and in `summary.md`, the others written); 128 + the signal's number when
//! interrupted by SIGHUP (129), SIGINT (130, Ctrl-C) or SIGTERM (143): the writes in flight are
//! finished, no temporary file is left, the files written so far are complete.

use std::io::IsTerminal as _;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

use chain_paper::figures::{self, Cause, FigureError, FigureFn, Params};
use chain_paper::output::{self, WriteError};
use chain_paper::render::RenderError;
use chain_paper::{Figure, Quality, Row, data, render, summary};
use clap::Parser;
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

/// The exit codes, as `--help` prints them.
const EXIT_STATUS: &str = "\
Exit status:
  0    every figure written
  1    the output folder could not be prepared or written (nothing computed, or no summary)
  2    bad arguments (nothing computed or written)
  3    some figures failed (each named on stderr and in summary.md; the others written)
  129  interrupted by SIGHUP   (writes in flight finished, no temporary file left)
  130  interrupted by SIGINT   (Ctrl-C; likewise)
  143  interrupted by SIGTERM  (likewise)";

/// Reproduce the paper's figures: PNG and SVG per figure, the data of every panel as CSV, and
/// summary.md with the paper's numbers beside ours.
#[derive(Debug, Parser)]
#[command(name = "paper", version, after_help = EXIT_STATUS)]
struct Cli {
    /// Output directory (created if missing)
    #[arg(long, value_name = "DIR", default_value = "paper-output")]
    out: PathBuf,
    /// Coarse grids and short runs: every figure in seconds, not at the paper's resolution
    #[arg(long)]
    quick: bool,
    /// Only these figures, comma-separated labels as `--list` prints them (`fig:` optional)
    #[arg(long, value_name = "LABEL,...", value_delimiter = ',')]
    only: Vec<String>,
    /// Print the label of every figure, one per line, and exit
    #[arg(long)]
    list: bool,
    /// Instead of the paper's figures: the antikink phase diagram at 400 x 400, the alternating
    /// window near k_i/k = 0.75, v0 = 3.6 and the whole plane (minutes; never in --quick)
    #[arg(long, conflicts_with = "quick")]
    resolution: bool,
    /// FOR TESTING ONLY: synthetic figures instead of the paper's (`fig:demo-fails` fails)
    #[arg(long, hide = true)]
    demo: bool,
    /// FOR TESTING ONLY: every file write pauses this many milliseconds before its rename
    #[arg(long, hide = true, value_name = "MS", requires = "demo")]
    demo_pause_writes: Option<u64>,
}

/// One figure written: what goes into the summary and the report.
struct Written {
    label: &'static str,
    rows: Vec<Row>,
    /// Time to compute the figure, and to draw and write its files.
    computed: Duration,
    written: Duration,
}

/// Why one figure is missing from the output.
#[derive(Debug, thiserror::Error)]
enum Failure {
    #[error("{0}")]
    Compute(#[from] FigureError),
    /// The payload of a panic inside a figure function (text, when it is text).
    #[error("{label}: panicked: {message}")]
    Panicked { label: &'static str, message: String },
    #[error("{0}")]
    Render(#[from] RenderError),
    #[error("{0}")]
    Data(#[from] WriteError),
}

/// One figure that could not be computed, rendered or written.
struct Failed {
    label: &'static str,
    failure: Box<Failure>,
}

impl Failed {
    /// What went wrong, without the figure's label in front.
    fn detail(&self) -> String {
        let text = self.failure.to_string();
        match text.strip_prefix(self.label) {
            Some(rest) => rest.trim_start_matches(':').trim_start().to_owned(),
            None => text,
        }
    }
}

/// The progress bar, for the signal handler to leave the terminal tidy.
static BAR: OnceLock<ProgressBar> = OnceLock::new();

fn main() -> ExitCode {
    let code = run();
    // Interrupted: the signal handler is finishing the writes in flight and exits with the
    // signal's status; the main thread must not end the process first with its own.
    while output::stopping() {
        std::thread::park();
    }
    code
}

fn run() -> ExitCode {
    let cli = Cli::parse();
    let all = if cli.demo {
        demo::figures()
    } else if cli.resolution {
        figures::resolution::figures()
    } else {
        figures::all()
    };
    if cli.list {
        for (label, _) in &all {
            println!("{label}");
        }
        return ExitCode::SUCCESS;
    }
    let selected = match select(&all, &cli.only) {
        Ok(selected) => selected,
        Err(message) => {
            eprintln!("paper: error: {message}");
            return ExitCode::from(2);
        }
    };
    if let Some(ms) = cli.demo_pause_writes {
        output::pause_writes_for_tests(Duration::from_millis(ms));
    }
    let tidy = || {
        if let Some(bar) = BAR.get() {
            bar.abandon();
        }
    };
    if let Err(e) = output::stop_on_signals("paper", tidy) {
        eprintln!("paper: error: cannot install the signal handlers: {e}");
        return ExitCode::FAILURE;
    }
    if let Err(message) = prepare_output(&cli.out) {
        eprintln!("paper: error: {message}");
        return ExitCode::FAILURE;
    }
    let quality = if cli.quick { Quality::Quick } else { Quality::Full };
    let start = Instant::now();
    let (written, failed) = produce_all(&selected, quality, &cli.out);
    let rows: Vec<(&'static str, Row)> =
        written.iter().flat_map(|w| w.rows.iter().map(|row| (w.label, row.clone()))).collect();
    let failures: Vec<(&str, String)> = failed.iter().map(|f| (f.label, f.detail())).collect();
    if let Err(e) = summary::write_summary(&cli.out, &rows, quality, &failures) {
        eprintln!("paper: error: {e}");
        return ExitCode::FAILURE;
    }
    println!(
        "paper: {} figures, {} summary rows, {} failed, {:.1} s -> {}",
        written.len(),
        rows.len(),
        failed.len(),
        start.elapsed().as_secs_f64(),
        cli.out.display()
    );
    if failed.is_empty() { ExitCode::SUCCESS } else { ExitCode::from(3) }
}

/// The figures named by `--only` (all of them without it), in the order of `all`. An unknown
/// label is refused with the nearest known one.
fn select(
    all: &[(&'static str, FigureFn)],
    only: &[String],
) -> Result<Vec<(&'static str, FigureFn)>, String> {
    if only.is_empty() {
        return Ok(all.to_vec());
    }
    let mut wanted = Vec::new();
    for name in only {
        let name = name.trim();
        if name.is_empty() {
            return Err("--only: empty figure label (labels are separated by single commas)".into());
        }
        let label = if name.starts_with("fig:") { name.to_owned() } else { format!("fig:{name}") };
        match all.iter().find(|(l, _)| *l == label) {
            Some(&(l, _)) => wanted.push(l),
            None => {
                return Err(match (all.is_empty(), close_match(all, &label)) {
                    (true, _) => format!("unknown figure `{name}`: no figures are defined"),
                    (false, Some(near)) => {
                        format!("unknown figure `{name}`; did you mean `{near}`? (`paper --list` lists them)")
                    }
                    (false, None) => format!("unknown figure `{name}` (`paper --list` lists them)"),
                });
            }
        }
    }
    Ok(all.iter().filter(|(l, _)| wanted.contains(l)).copied().collect())
}

/// The label nearest to `label` (both without `fig:`), if it is close: at most a third of the
/// longer name's letters differ (one for names up to five letters), as a typo's would. A name
/// that is no figure's gets no suggestion rather than an unrelated one.
fn close_match(all: &[(&'static str, FigureFn)], label: &str) -> Option<&'static str> {
    let bare = |l: &str| l.strip_prefix("fig:").unwrap_or(l).to_lowercase();
    let wanted = bare(label);
    let (distance, nearest) =
        all.iter().map(|&(l, _)| (edit_distance(&bare(l), &wanted), l)).min_by_key(|&(d, _)| d)?;
    let longer = wanted.chars().count().max(bare(nearest).chars().count());
    (distance <= longer.div_ceil(3).max(1) && distance < longer).then_some(nearest)
}

/// Levenshtein distance, for "did you mean".
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitute = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substitute.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}

/// Create the output directory and its `data/`, remove the temporary files earlier runs left
/// there when killed outright, and prove both folders writable with a probe file, before any
/// figure is computed.
fn prepare_output(dir: &Path) -> Result<(), String> {
    let data = dir.join("data");
    std::fs::create_dir_all(&data)
        .map_err(|e| format!("cannot create the output directory {}: {e}", data.display()))?;
    for dir in [dir, &data] {
        let removed = output::clean_stale_temporaries(dir).map_err(|e| {
            format!("cannot clean the temporary files of earlier runs in {}: {e}", dir.display())
        })?;
        if !removed.is_empty() {
            eprintln!(
                "paper: removed {} temporary file(s) left in {} by an interrupted earlier run",
                removed.len(),
                dir.display()
            );
        }
    }
    for dir in [dir, &data] {
        let probe = dir.join(format!(".paper-probe-{}", std::process::id()));
        std::fs::write(&probe, b"probe")
            .and_then(|()| std::fs::remove_file(&probe))
            .map_err(|e| format!("cannot write into the output directory {}: {e}", dir.display()))?;
    }
    Ok(())
}

/// Compute, render and write every selected figure, in parallel, with a progress bar on stderr
/// (hidden when stderr is not a terminal). Results are in the order of `selected`.
fn produce_all(
    selected: &[(&'static str, FigureFn)],
    quality: Quality,
    out: &Path,
) -> (Vec<Written>, Vec<Failed>) {
    let bar = BAR.get_or_init(|| {
        if std::io::stderr().is_terminal() {
            let bar = ProgressBar::new(selected.len() as u64);
            bar.set_style(
                ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} {wide_msg}")
                    .expect("a valid template"),
            );
            bar.enable_steady_tick(Duration::from_millis(120));
            bar
        } else {
            ProgressBar::hidden()
        }
    });
    bar.set_length(selected.len() as u64);
    let running = Mutex::new(Vec::<&str>::new());
    let show_running = |update: &dyn Fn(&mut Vec<&'static str>)| {
        let mut running = running.lock().unwrap_or_else(|e| e.into_inner());
        update(&mut running);
        bar.set_message(format!("computing {}", running.join(", ")));
    };
    let params = Params::default();
    let results: Vec<Result<Written, Failed>> = selected
        .par_iter()
        .map(|&(label, compute)| {
            show_running(&|r| r.push(label));
            let start = Instant::now();
            let result = produce(label, compute, &params, quality, out);
            show_running(&|r| r.retain(|l| *l != label));
            bar.inc(1);
            bar.suspend(|| match &result {
                Ok(w) => eprintln!(
                    "paper: {label}: {} summary rows, computed in {:.1} s, drawn and written in {:.1} s",
                    w.rows.len(),
                    w.computed.as_secs_f64(),
                    w.written.as_secs_f64()
                ),
                Err(f) => {
                    eprintln!(
                        "paper: {label}: FAILED after {:.1} s: {}",
                        start.elapsed().as_secs_f64(),
                        f.detail()
                    )
                }
            });
            result
        })
        .collect();
    bar.finish_and_clear();
    let (mut written, mut failed) = (Vec::new(), Vec::new());
    for result in results {
        match result {
            Ok(w) => written.push(w),
            Err(f) => failed.push(f),
        }
    }
    (written, failed)
}

/// One figure: compute it (a panic counts as a failure of this figure only), render it, write
/// its data.
fn produce(
    label: &'static str,
    compute: FigureFn,
    params: &Params,
    quality: Quality,
    out: &Path,
) -> Result<Written, Failed> {
    let fail = |failure: Failure| Failed { label, failure: Box::new(failure) };
    let start = Instant::now();
    let figure: Figure = match catch_unwind(AssertUnwindSafe(|| compute(params, quality))) {
        Ok(Ok(figure)) => figure,
        Ok(Err(e)) => return Err(fail(e.into())),
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned());
            let message = what.unwrap_or_else(|| "(no message)".into());
            return Err(fail(Failure::Panicked { label, message }));
        }
    };
    if figure.label != label {
        let wrong = FigureError::new(label, Cause::WrongLabel { returned: figure.label });
        return Err(fail(wrong.into()));
    }
    let computed = start.elapsed();
    render::render(&figure, out).map_err(|e| fail(e.into()))?;
    data::write_csv(&figure, &out.join("data")).map_err(|e| fail(e.into()))?;
    Ok(Written { label, rows: figure.rows, computed, written: start.elapsed() - computed })
}

/// Synthetic figures exercising every kind of panel, for the command-line tests (`--demo`).
mod demo {
    use chain_paper::figures::{Cause, FigureError, FigureFn, Params};
    use chain_paper::{ChainDrawing, Chart, Figure, Heatmap, Panel, Quality, Quantity, Row, Series, Style};

    pub fn figures() -> Vec<(&'static str, FigureFn)> {
        vec![("fig:demo-lines", lines), ("fig:demo-maps", maps), ("fig:demo-fails", fails)]
    }

    fn lines(p: &Params, q: Quality) -> Result<Figure, FigureError> {
        let n = q.pick(400, 60);
        let xs = (0..n).map(|i| 10.0 * i as f64 / (n - 1) as f64);
        let curve = |f: fn(f64) -> f64| xs.clone().map(|x| (x, f(x))).collect::<Vec<_>>();
        let wave = Panel {
            title: "Lines of every style".into(),
            x_label: "rotor index i".into(),
            y_label: "theta_i (rad)".into(),
            series: vec![
                Series::new(Quantity::Rotor, "sin x", curve(f64::sin), Style::Line),
                Series::new(Quantity::Spring, "cos x (dashed)", curve(f64::cos), Style::Dashed),
                Series::new(
                    Quantity::Mode,
                    "samples",
                    curve(|x| 0.5 * (x / 2.0).sin()).into_iter().step_by(4).collect(),
                    Style::Points,
                ),
                Series::new(
                    Quantity::Lattice,
                    "line with points",
                    curve(|x| 0.1 * x - 0.5).into_iter().step_by(6).collect(),
                    Style::LinePoints,
                ),
            ],
            log_y: false,
        };
        let decay = Panel {
            title: "A log axis (non-positive points skipped)".into(),
            x_label: "time t (sqrt(M/k))".into(),
            y_label: "energy error |dE/E|".into(),
            series: vec![
                Series::new(Quantity::Continuum, "exp(-x)", curve(|x| (-x).exp()), Style::Line),
                Series::new(Quantity::Fit, "x^2 sin x", curve(|x| x * x * x.sin()), Style::Dashed),
                Series::new(
                    Quantity::Mode,
                    "open points",
                    curve(|x| (-0.5 * x).exp()).into_iter().step_by(8).collect(),
                    Style::OpenPoints,
                ),
            ],
            log_y: true,
        };
        Ok(Figure {
            label: "fig:demo-lines",
            caption: format!(
                "Synthetic line panels, n = {}, r = {}, k = {}: every series style and a log axis.",
                p.n, p.r, p.k
            ),
            panels: vec![Chart::Lines(wave), Chart::Lines(decay)],
            rows: vec![
                Row::number("amplitude of sin", 1.05, 1.0, Some(1.0), "a pipe | in a note"),
                Row::words("shape", "wave", "wave", ""),
            ],
        })
    }

    fn maps(p: &Params, q: Quality) -> Result<Figure, FigureError> {
        let (nx, ny) = (q.pick(120, 30), q.pick(300, 40));
        let x: Vec<f64> = (0..nx).map(|i| i as f64).collect();
        let y: Vec<f64> = (0..ny).map(|j| 0.1 * j as f64).collect();
        let values = y
            .iter()
            .map(|&t| x.iter().map(|&i| ((i - nx as f64 / 2.0 - 5.0 * t) / 4.0).tanh()).collect())
            .collect();
        let space_time = Heatmap {
            title: "Space-time image".into(),
            x_label: "rotor index i".into(),
            y_label: "time t (sqrt(M/k))".into(),
            x: x.clone(),
            y: y.clone(),
            values,
            categories: Vec::new(),
            value_label: "θ (rad)".into(),
            log_x: false,
            colour_limit: None,
        };
        let outcomes = ["transmitted", "reflected", "trapped"];
        let model = rotor_chain::RuntimeChain::builder(12, p.r, p.k, 0.5)
            .spring_rest_length(5, 1.8)
            .build()
            .map_err(FigureError::on("fig:demo-maps"))?;
        let theta: Vec<f64> = (0..12).map(|i| 0.5 * (0.6 * (i as f64 - 5.5)).tanh()).collect();
        let shape: Vec<f64> = (0..12).map(|i| (-(i as f64 - 5.5).powi(2) / 8.0).exp()).collect();
        let drawing = ChainDrawing::new("A chain with a mode", &model, &theta, 0..12)
            .and_then(|d| d.with_mode(&shape))
            .map_err(FigureError::on("fig:demo-maps"))?;
        let phases = Heatmap {
            title: "Phase diagram".into(),
            x_label: "impurity stiffness k_i/k".into(),
            y_label: "launch speed v0 (a sqrt(k/M))".into(),
            x: (0..12).map(|i| 0.1 * (i + 1) as f64).collect(),
            y: (0..10).map(|j| 0.5 + j as f64).collect(),
            values: (0..10).map(|j| (0..12).map(|i| ((i + 2 * j) / 7 % 3) as f64).collect()).collect(),
            categories: outcomes.iter().map(|s| s.to_string()).collect(),
            value_label: String::new(),
            log_x: false,
            colour_limit: None,
        };
        Ok(Figure {
            label: "fig:demo-maps",
            caption: "Synthetic heat maps: a continuous space-time image and a categorical phase diagram; a \
                      drawing of a chain."
                .into(),
            panels: vec![Chart::Heat(space_time), Chart::Heat(phases), drawing.into()],
            rows: vec![Row::number("critical speed", 2.0, 2.5, None, "")],
        })
    }

    fn fails(_: &Params, _: Quality) -> Result<Figure, FigureError> {
        // On purpose: a synthetic computation that resolves too few points.
        Err(FigureError::new(
            "fig:demo-fails",
            Cause::TooFewPoints { what: "synthetic points", found: 0, needed: 2 },
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_are_matched_with_or_without_prefix_and_kept_in_order() {
        let all = demo::figures();
        let picked =
            select(&all, &["demo-maps".into(), "fig:demo-lines".into(), "demo-maps".into()]).unwrap();
        assert_eq!(picked.iter().map(|f| f.0).collect::<Vec<_>>(), ["fig:demo-lines", "fig:demo-maps"]);
        assert_eq!(edit_distance("fig:kcobwbe", "fig:kcobweb"), 2);
        // Typos are matched; a name of no figure gets no suggestion.
        let paper = chain_paper::figures::all();
        assert_eq!(close_match(&paper, "fig:kcobwbe"), Some("fig:kcobweb"));
        assert_eq!(close_match(&paper, "fig:phasediagrm"), Some("fig:phasediagram"));
        assert_eq!(close_match(&paper, "fig:AKENERGY"), Some("fig:akenergy"));
        assert_eq!(close_match(&paper, "fig:nonexistent"), None);
        assert_eq!(close_match(&paper, "fig:no-such-figure"), None);
        assert_eq!(close_match(&paper, "fig:x"), None);
        assert_eq!(edit_distance("", "abc"), 3);
    }
}
