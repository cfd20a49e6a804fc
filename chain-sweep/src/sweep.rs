//! [`run_sweep`]: compute every missing point of a grid in parallel, appending each to the
//! results file the moment it is done.
//!
//! Crash safety rests on three rules. (1) A point is written as one complete line by one
//! `write_all` under a lock, so the file only ever grows by whole points, except that a kill in
//! the middle of that call can leave one unfinished last line. (2) A restart cuts that line off
//! and computes exactly the points the file lacks, so no point is ever written twice. (3) The
//! file is locked while a sweep runs, so two sweeps cannot append to it at once.
//!
//! [`ResultsFile`] is that file, opened and resumed; [`run_sweep`] computes its missing points on
//! a thread pool, and callers that compute points elsewhere (other processes, a Dask cluster)
//! append them to it themselves.

use std::collections::HashMap;
use std::collections::hash_map::Entry;
use std::fmt::Display;
use std::fs::{File, OpenOptions, TryLockError};
use std::io::{IsTerminal, Write};
use std::marker::PhantomData;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};
use rayon::prelude::*;

use crate::error::SweepError;
use crate::file::{
    self, Point, check_record_header, complete_lines, format_point, parse_point, read_preamble,
};
use crate::grid::Grid;
use crate::record::Record;
use crate::shard::Shard;
use crate::threads::worker_threads;
use rotor_chain::allocation::try_vec;
use rotor_chain::validate::Validate;

/// How a sweep runs. Build with [`SweepOptions::new`] and change fields as needed.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct SweepOptions {
    /// Names the sweep in the progress bar.
    pub name: String,
    /// What is computed at each point, in one line (for example the chain's parameters). Stored
    /// in the file's first line; resuming refuses a file written with another label.
    pub run: String,
    /// Worker threads; `None` uses every core (rayon's default, which honours
    /// `RAYON_NUM_THREADS`). Between 1 and [`crate::threads::max_threads`] (4 per core: threads
    /// beyond a few per core only share the cores), else [`SweepError::Threads`] carrying the
    /// invalid option ([`crate::threads::worker_threads`]); never more threads start than there
    /// are points to compute.
    pub threads: Option<usize>,
    /// Compute again the points the file records as failed (their lines are removed first).
    /// Off by default: a failure is a result, and most failures repeat.
    pub retry_failed: bool,
    /// The longest time between `sync_data` calls. A kill loses nothing that was written (the
    /// kernel holds it); only a crash of the machine can lose the points of the last interval.
    /// 0.5 s keeps the cost of syncing negligible whatever the rate of points.
    pub sync_interval: Duration,
    /// Draw a progress bar on stderr if stderr is a terminal (it never is in CI).
    pub progress: bool,
    /// Compute only this shard's points (its file says so: `; shard I/N` on line 1); `None`:
    /// the whole grid.
    pub shard: Option<Shard>,
    /// Set it (from a signal handler, another thread) to stop the sweep early: no point is
    /// started after it is set, the points being computed are finished and written, and
    /// [`run_sweep`] returns [`SweepError::Stopped`] with how many points the file holds. Running
    /// the sweep again computes the rest. `None`: the sweep runs to the end.
    pub stop: Option<Arc<AtomicBool>>,
}

impl SweepOptions {
    /// A sweep named `name` with the run settings `run` (both written to the results file's first line).
    pub fn new(name: impl Into<String>, run: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            run: run.into(),
            threads: None,
            retry_failed: false,
            sync_interval: Duration::from_millis(500),
            progress: true,
            shard: None,
            stop: None,
        }
    }
}

impl Validate for SweepOptions {
    type Error = SweepError;

    /// `threads` between 1 and [`crate::threads::max_threads`] when given
    /// ([`SweepError::Threads`] with its `InvalidOption`, [`worker_threads`]'s rule). The other
    /// fields take any value:
    /// `name` is only shown, `run` is stored on one line (newlines escaped), any
    /// `sync_interval` is a valid rhythm (0: after every point), a [`Shard`] is checked when it
    /// is made, and the flags are choices.
    fn validate(&self) -> Result<(), SweepError> {
        // No `..`: a field added here does not compile until it is checked.
        let Self {
            name: _,
            run: _,
            threads,
            retry_failed: _,
            sync_interval: _,
            progress: _,
            shard: _,
            stop: _,
        } = self;
        worker_threads(*threads, 1).map(|_| ())
    }
}

/// What a sweep did.
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct Summary {
    /// Points in the grid (in the shard, for a shard's sweep).
    pub total: usize,
    /// Points the file already had, so not computed again.
    pub skipped: usize,
    /// Points computed by this run, failed ones included.
    pub computed: usize,
    /// Points of this run whose computation returned an error or panicked.
    pub failed: usize,
    /// Skipped points that the file records as failed (see [`SweepOptions::retry_failed`]).
    pub failed_before: usize,
    /// Failed lines removed so that their points were computed again.
    pub retried: usize,
    /// Points found on more than one line of the file. A sweep never writes these; they mean
    /// someone else wrote to the file. They are kept and not recomputed.
    pub duplicates: Vec<(usize, usize)>,
    /// Bytes of an unfinished last line (a write cut short by a kill) that were cut off.
    pub repaired_bytes: usize,
    /// Wall-clock time of the sweep.
    pub elapsed: Duration,
    /// Worker threads the sweep ran on: [`SweepOptions::threads`] clamped to the points to
    /// compute ([`crate::threads::worker_threads`]); 0 when no point was left.
    pub threads: usize,
}

/// Compute `compute(x, y)` at every point of `grid` that `path` does not have yet, in parallel,
/// appending each result to `path` as soon as it is known.
///
/// - A missing or empty file is created with its two-line preamble (see [`crate::file`]).
/// - An existing file must have been written for the same grid, the same `options.run` and the
///   same record columns, else [`SweepError::GridMismatch`], [`SweepError::RunMismatch`] or
///   [`SweepError::HeaderMismatch`], and the file is not touched.
/// - An error (or panic) of `compute` at one point is written to the file and counted in
///   [`Summary::failed`]; the sweep goes on. Errors writing the file stop it.
pub fn run_sweep<R, E, F>(
    grid: &Grid,
    path: impl AsRef<Path>,
    compute: F,
    options: &SweepOptions,
) -> Result<Summary, SweepError>
where
    R: Record + Send,
    E: Display,
    F: Fn(f64, f64) -> Result<R, E> + Sync,
{
    let start = Instant::now();
    // A bad count is refused before the file is touched; the pool is sized by the work left.
    options.validate()?;
    grid.validate()?;
    let file = ResultsFile::<R>::open(grid, path, options)?;
    let mut summary = file.summary.clone();
    let todo = file.missing();
    let pool = thread_pool(options.threads, todo.len())?;

    let bar = progress_bar(&options.name, summary.total, summary.skipped, todo.len(), options.progress);
    let path = file.path().to_owned();
    let file = Mutex::new(file);
    let failed = AtomicUsize::new(0);
    let written = AtomicUsize::new(0);
    let stopped = || options.stop.as_ref().is_some_and(|stop| stop.load(Ordering::Relaxed));
    let outcome = pool.install(|| {
        todo.par_iter().try_for_each(|&(i, j)| {
            if stopped() {
                // No point starts after a stop; those already started finish and are written.
                return Ok(());
            }
            let coords = (grid.xs()[i], grid.ys()[j]);
            let result = compute_one(&compute, coords);
            if result.is_err() {
                let failed = failed.fetch_add(1, Ordering::Relaxed) + 1;
                bar.set_message(format!("{} ({failed} failed)", options.name));
            }
            // A thread that panicked while holding the lock cannot have left a half line in the
            // file (`append` does not panic), so a poisoned lock is still usable.
            file.lock().unwrap_or_else(|e| e.into_inner()).append((i, j), coords, &result)?;
            written.fetch_add(1, Ordering::Relaxed);
            bar.inc(1);
            Ok::<_, SweepError>(())
        })
    });
    let synced = file.into_inner().unwrap_or_else(|e| e.into_inner()).finish();
    let computed = written.into_inner();
    if outcome.is_ok() && computed < todo.len() {
        // Only a stop skips points.
        bar.abandon();
        synced?;
        let done = summary.skipped + computed;
        return Err(SweepError::Stopped { path, done, total: summary.total, computed });
    }
    bar.finish();
    outcome?;
    synced?;
    summary.computed = todo.len();
    summary.failed = failed.into_inner();
    summary.elapsed = start.elapsed();
    summary.threads = if todo.is_empty() { 0 } else { pool.current_num_threads() };
    Ok(summary)
}

/// A results file opened by one sweep: locked, checked against the sweep's grid, run label and
/// shard, its unfinished last line cut off, with the points it already holds (see the module
/// doc for the rules). Append each computed point with [`ResultsFile::append`]; it reaches the
/// file as one whole line at once.
pub struct ResultsFile<R> {
    grid: Grid,
    shard: Option<Shard>,
    appender: Appender,
    /// Finished points, and whether each failed.
    done: HashMap<(usize, usize), bool>,
    summary: Summary,
    record: PhantomData<fn() -> R>,
}

impl<R: Record> ResultsFile<R> {
    /// Open (or create) the results file of the sweep of `grid` described by `options` (its
    /// `run`, `shard`, `retry_failed` and `sync_interval`): the same checks and repairs as
    /// [`run_sweep`], which is built on it.
    pub fn open(grid: &Grid, path: impl AsRef<Path>, options: &SweepOptions) -> Result<Self, SweepError> {
        let path = path.as_ref();
        check_record_header::<R>()?;
        let resumed = resume::<R>(grid, path, options)?;
        let total = match options.shard {
            Some(shard) => grid.indices().filter(|&ij| shard.contains(grid, ij)).count(),
            None => grid.len(),
        };
        let summary = Summary {
            total,
            skipped: resumed.done.len(),
            failed_before: resumed.done.values().filter(|&&failed| failed).count(),
            retried: resumed.retried,
            duplicates: resumed.duplicates,
            repaired_bytes: resumed.repaired_bytes,
            ..Summary::default()
        };
        Ok(Self {
            grid: grid.clone(),
            shard: options.shard,
            appender: Appender::new(resumed.file, path, options.sync_interval),
            done: resumed.done,
            summary,
            record: PhantomData,
        })
    }

    /// The results file.
    pub fn path(&self) -> &Path {
        &self.appender.path
    }

    /// The grid of the sweep.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// What the file held when it was opened ([`Summary::skipped`], [`Summary::failed_before`],
    /// repairs); the counts of this run are the caller's.
    pub fn summary(&self) -> &Summary {
        &self.summary
    }

    /// The points of the sweep (of its shard) that the file lacks, in grid order.
    pub fn missing(&self) -> Vec<(usize, usize)> {
        self.grid
            .indices()
            .filter(|ij| {
                self.shard.is_none_or(|s| s.contains(&self.grid, *ij)) && !self.done.contains_key(ij)
            })
            .collect()
    }

    /// Append point `index`, computed at `coords`, with its record or its error message. A point
    /// outside the sweep (the grid, or the shard), already in the file, or whose `coords` are not
    /// bit for bit the grid's coordinates of `index` ([`SweepError::WrongCoordinates`]: the
    /// reader would file its physics under the other point) is refused, and nothing is written.
    pub fn append(
        &mut self,
        index: (usize, usize),
        coords: (f64, f64),
        outcome: &Result<R, String>,
    ) -> Result<(), SweepError> {
        let (i, j) = index;
        let grid = self.grid.point(i, j).filter(|_| self.shard.is_none_or(|s| s.contains(&self.grid, index)));
        let Some(grid) = grid else {
            return Err(SweepError::NotInSweep {
                path: self.appender.path.clone(),
                index,
                sweep: crate::file::shard_name(self.shard),
                nx: self.grid.xs().len(),
                ny: self.grid.ys().len(),
            });
        };
        if grid.0.to_bits() != coords.0.to_bits() || grid.1.to_bits() != coords.1.to_bits() {
            return Err(SweepError::WrongCoordinates { index, given: coords, grid });
        }
        if self.done.contains_key(&index) {
            return Err(SweepError::AlreadyDone { path: self.appender.path.clone(), index });
        }
        self.appender.append(&format_point(index, grid, outcome))?;
        self.done.insert(index, outcome.is_err());
        Ok(())
    }

    /// Sync the file to disk and close it (dropping it closes it too, syncing at most what the
    /// kernel already holds).
    pub fn finish(mut self) -> Result<Summary, SweepError> {
        self.appender.sync()?;
        Ok(self.summary)
    }
}

/// Compute `compute(x, y)` at every point of `grid` in parallel, in memory (no file): the points
/// in grid order (`i` outer, `j` inner), each with its record or the error (or panic) of its
/// computation. The same per-point machinery as [`run_sweep`], for callers that plot the result
/// at once (the paper reproduction).
pub fn compute_grid<R, E, F>(
    grid: &Grid,
    compute: F,
    threads: Option<usize>,
) -> Result<Vec<Point<R>>, SweepError>
where
    R: Send,
    E: Display,
    F: Fn(f64, f64) -> Result<R, E> + Sync,
{
    grid.validate()?;
    // Every point's place before any is computed: a grid whose results cannot be held is an
    // error at once, not an abort after the work.
    let mut points = try_vec(grid.len(), "the grid's points")?;
    let pool = thread_pool(threads, grid.len())?;
    let ny = grid.ys().len();
    pool.install(|| {
        (0..grid.len())
            .into_par_iter()
            .map(|k| {
                let (i, j) = (k / ny, k % ny);
                let coords = (grid.xs()[i], grid.ys()[j]);
                Point { index: (i, j), coords, outcome: compute_one(&compute, coords), line: 0 }
            })
            .collect_into_vec(&mut points)
    });
    Ok(points)
}

/// A pool of [`worker_threads`] threads for `points` points.
fn thread_pool(requested: Option<usize>, points: usize) -> Result<rayon::ThreadPool, SweepError> {
    let threads = worker_threads(requested, points)?;
    rayon::ThreadPoolBuilder::new()
        .thread_name(|k| format!("sweep-{k}"))
        .num_threads(threads)
        .build()
        .map_err(|source| SweepError::ThreadPool { threads, source })
}

/// One point; a panic becomes the point's error instead of ending the sweep.
fn compute_one<R, E: Display>(
    compute: &impl Fn(f64, f64) -> Result<R, E>,
    (x, y): (f64, f64),
) -> Result<R, String> {
    match catch_unwind(AssertUnwindSafe(|| compute(x, y))) {
        Ok(result) => result.map_err(|e| e.to_string()),
        Err(payload) => {
            let message = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown payload".to_owned());
            Err(format!("panicked: {message}"))
        }
    }
}

/// The results file, locked and ready to append to, and what it already holds.
struct Resumed {
    file: File,
    /// Finished points, and whether each failed.
    done: HashMap<(usize, usize), bool>,
    duplicates: Vec<(usize, usize)>,
    repaired_bytes: usize,
    retried: usize,
}

/// Open (or create) and lock the file, check it belongs to this sweep, cut off an unfinished
/// last line, and collect the finished points.
fn resume<R: Record>(grid: &Grid, path: &Path, options: &SweepOptions) -> Result<Resumed, SweepError> {
    let mut file = open_locked(path)?;
    let bytes = crate::file::read_file(path, &mut file)?;
    let preamble = file::preamble::<R>(grid, &options.run, options.shard);
    let mut resumed =
        Resumed { file, done: HashMap::new(), duplicates: Vec::new(), repaired_bytes: 0, retried: 0 };

    // Empty, or killed while the preamble was being written: start afresh.
    if bytes.len() < preamble.len() && preamble.as_bytes().starts_with(&bytes) {
        resumed.file.set_len(0).map_err(SweepError::io("truncate", path))?;
        resumed.file.write_all(preamble.as_bytes()).map_err(SweepError::io("write to", path))?;
        resumed.file.sync_data().map_err(SweepError::io("sync", path))?;
        return Ok(resumed);
    }

    let (mut lines, complete) = complete_lines(&bytes);
    let found = read_preamble::<R>(path, lines.next().map(|l| l.1), lines.next().map(|l| l.1))?;
    let mismatch = |expected: String, found: &str| {
        (expected != found).then(|| (path.to_owned(), expected, found.to_owned()))
    };
    if let Some((path, expected, found)) = mismatch(grid.signature(), found.grid) {
        return Err(SweepError::GridMismatch { path, expected, found });
    }
    if let Some((path, expected, found)) = mismatch(file::one_line(&options.run), found.run) {
        return Err(SweepError::RunMismatch { path, expected, found });
    }
    if found.shard != options.shard {
        let (expected, found) = (file::shard_name(options.shard), file::shard_name(found.shard));
        return Err(SweepError::ShardMismatch { path: path.to_owned(), expected, found });
    }
    // A file of the same sweep without the record's optional columns reads, but new points would not fit it.
    if found.columns != R::header().len() {
        let found_header = file::header_line_of::<R>(found.columns);
        return Err(SweepError::HeaderMismatch {
            path: path.to_owned(),
            expected: file::header_line::<R>(),
            found: found_header,
        });
    }
    let mut failed_lines = Vec::new();
    for (line, text) in lines.filter(|(_, text)| !text.is_empty()) {
        let point = parse_point::<R>(path, line, text, found.columns, Some(grid), options.shard)?;
        let failed = point.outcome.is_err();
        if failed {
            failed_lines.push(point.line);
        }
        // A point counts as failed only if every line of it failed.
        match resumed.done.entry(point.index) {
            Entry::Occupied(mut seen) => {
                *seen.get_mut() &= failed;
                resumed.duplicates.push(point.index);
            }
            Entry::Vacant(new) => {
                new.insert(failed);
            }
        }
    }

    if options.retry_failed && !failed_lines.is_empty() {
        resumed.done.retain(|_, failed| !*failed);
        resumed.retried = failed_lines.len();
        resumed.file = rewrite_without(path, &bytes[..complete], &failed_lines, resumed.file)?;
    } else if complete < bytes.len() {
        resumed
            .file
            .set_len(complete as u64)
            .map_err(SweepError::io("cut the unfinished last line of", path))?;
        resumed.file.sync_data().map_err(SweepError::io("sync", path))?;
    }
    resumed.repaired_bytes = bytes.len() - complete;
    Ok(resumed)
}

/// What a path that is not a regular file is, for the error message.
fn kind_of(file_type: std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if file_type.is_fifo() {
            return "a FIFO";
        }
        if file_type.is_char_device() || file_type.is_block_device() {
            return "a device";
        }
        if file_type.is_socket() {
            return "a socket";
        }
    }
    if file_type.is_dir() { "a directory" } else { "not a regular file" }
}

/// `Err(NotAFile)` if `path` exists (following links) and is not a regular file.
pub(crate) fn check_regular(path: &Path) -> Result<(), SweepError> {
    match std::fs::metadata(path) {
        Ok(meta) if !meta.is_file() => {
            Err(SweepError::NotAFile { path: path.to_owned(), kind: kind_of(meta.file_type()) })
        }
        _ => Ok(()),
    }
}

/// Open for reading and appending, creating it if need be, and take the exclusive lock. A path
/// that is not a regular file is refused before it is opened (opening a FIFO for reading can
/// block forever, and reading /dev/null back would lose every point), and checked again once
/// open, in case it was replaced meanwhile.
fn open_locked(path: &Path) -> Result<File, SweepError> {
    check_regular(path)?;
    let file = OpenOptions::new()
        .read(true)
        .append(true)
        .create(true)
        .open(path)
        .map_err(SweepError::io("open", path))?;
    let meta = file.metadata().map_err(SweepError::io("inspect", path))?;
    if !meta.is_file() {
        return Err(SweepError::NotAFile { path: path.to_owned(), kind: kind_of(meta.file_type()) });
    }
    match file.try_lock() {
        Ok(()) => Ok(file),
        Err(TryLockError::WouldBlock) => Err(SweepError::Locked { path: path.to_owned() }),
        Err(TryLockError::Error(e)) => Err(SweepError::io("lock", path)(e)),
    }
}

/// Replace the file by its complete lines minus `drop` (1-based line numbers), atomically: a new
/// file beside it, synced, renamed over it. Returns the new file, locked. `old` keeps its lock
/// until the new file holds one.
fn rewrite_without(path: &Path, complete: &[u8], dropped: &[usize], old: File) -> Result<File, SweepError> {
    let mut kept = Vec::with_capacity(complete.len());
    let (lines, _) = complete_lines(complete);
    for (_, text) in lines.filter(|(line, _)| dropped.binary_search(line).is_err()) {
        kept.extend_from_slice(text);
        kept.push(b'\n');
    }
    let mut temp_name = path.file_name().unwrap_or_default().to_owned();
    temp_name.push(".rewrite");
    let temp = path.with_file_name(temp_name);
    let mut new = File::create(&temp).map_err(SweepError::io("create", &temp))?;
    new.write_all(&kept).map_err(SweepError::io("write to", &temp))?;
    new.sync_all().map_err(SweepError::io("sync", &temp))?;
    drop(new);
    std::fs::rename(&temp, path).map_err(SweepError::io("replace", path))?;
    let file = open_locked(path)?;
    drop(old);
    Ok(file)
}

/// Appends whole lines and syncs them to disk at most every `interval`.
struct Appender {
    file: File,
    path: PathBuf,
    interval: Duration,
    last_sync: Instant,
    unsynced: bool,
}

impl Appender {
    fn new(file: File, path: &Path, interval: Duration) -> Self {
        Self { file, path: path.to_owned(), interval, last_sync: Instant::now(), unsynced: false }
    }

    /// `line` must be one complete line: it reaches the file in one `write_all`.
    fn append(&mut self, line: &str) -> Result<(), SweepError> {
        self.file.write_all(line.as_bytes()).map_err(SweepError::io("append to", &self.path))?;
        // `File` has no buffer, so the line is already the kernel's and survives a kill; `flush`
        // states the intent and stays right if a buffer is ever put in between.
        self.file.flush().map_err(SweepError::io("append to", &self.path))?;
        self.unsynced = true;
        if self.last_sync.elapsed() >= self.interval { self.sync() } else { Ok(()) }
    }

    fn sync(&mut self) -> Result<(), SweepError> {
        if self.unsynced {
            self.file.sync_data().map_err(SweepError::io("sync", &self.path))?;
            self.unsynced = false;
        }
        self.last_sync = Instant::now();
        Ok(())
    }
}

/// The bar counts this run's points (so rate and ETA are this run's) and shows `done/total` over
/// the whole grid, the points already in the file included.
fn progress_bar(name: &str, total: usize, skipped: usize, todo: usize, enabled: bool) -> ProgressBar {
    if !enabled || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(todo as u64), ProgressDrawTarget::stderr());
    let template = "{msg} [{elapsed_precise}] {wide_bar} {done}/{total} points ({rate}, ETA {eta})";
    if let Ok(style) = ProgressStyle::with_template(template) {
        let style = style
            .with_key("done", move |s: &ProgressState, w: &mut dyn std::fmt::Write| {
                let _ = write!(w, "{}", skipped as u64 + s.pos());
            })
            .with_key("total", move |_: &ProgressState, w: &mut dyn std::fmt::Write| {
                let _ = write!(w, "{total}");
            })
            .with_key("rate", |s: &ProgressState, w: &mut dyn std::fmt::Write| {
                let _ = write!(w, "{:.1}/s", s.per_sec());
            });
        bar.set_style(style);
    }
    bar.set_message(name.to_owned());
    bar
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod validation {
    use super::*;
    use crate::threads::max_threads;
    use rotor_chain::validate::OptionError;

    /// Every field of [`SweepOptions`] (non-exhaustive, so destructured here in its crate, without
    /// `..`: a new field does not compile until it is listed): the thread count is refused at 0
    /// and above [`max_threads`], naming the count; the other fields take any value.
    #[test]
    fn every_field_of_the_sweep_options_is_validated() {
        let base = SweepOptions::new("name", "run");
        let SweepOptions { name, run, threads, retry_failed, sync_interval, progress, shard, stop } =
            base.clone();
        assert!(base.validate().is_ok() && threads.is_none());
        for bad in [0, max_threads() + 1, usize::MAX] {
            let e = SweepOptions { threads: Some(bad), ..base.clone() }.validate().unwrap_err();
            let o = e.invalid_option().unwrap_or_else(|| panic!("not an invalid option: {e}"));
            assert_eq!((o.options, o.field, o.value), ("SweepOptions", "threads", bad as f64), "{e}");
        }
        assert!(SweepOptions { threads: Some(max_threads()), ..base.clone() }.validate().is_ok());
        // Any text, rhythm, shard and flag.
        let anything = SweepOptions {
            name: format!("{name}\n\u{0}"),
            run: format!("{run}\nsecond line"),
            threads: Some(1),
            retry_failed: !retry_failed,
            sync_interval: if sync_interval.is_zero() { Duration::MAX } else { Duration::ZERO },
            progress: !progress,
            shard: shard.or(Shard::new(0, 3).ok()),
            stop: stop.or(Some(Arc::new(AtomicBool::new(true)))),
        };
        assert!(anything.validate().is_ok());
    }
}
