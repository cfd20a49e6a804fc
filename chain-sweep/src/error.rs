//! The errors of a sweep and of reading a results file. Each names the file and carries what was
//! expected and what was found.

use std::io;
use std::path::PathBuf;

use rotor_chain::geometry::Short;
use rotor_chain::validate::{InvalidOption, OptionError};

use crate::grid::GridError;

/// Why a sweep could not run, or a results file could not be read. Errors of a single point's
/// computation are not here: they are recorded in the file (the `error` column) and counted in
/// [`crate::Summary::failed`].
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SweepError {
    #[error("cannot {action} {}: {source}", path.display())]
    /// A file could not be opened, read, written or locked.
    Io {
        /// What was being done (`open`, `read`, `write`, ...).
        action: &'static str,
        /// The file.
        path: PathBuf,
        #[source]
        /// The operating system's error.
        source: io::Error,
    },
    #[error(
        "{} is not a chain-sweep results file: its first line should start with `{}`, found `{found}`",
        path.display(), crate::file::FORMAT_TAG
    )]
    /// The file exists but is not a results file of a sweep.
    NotAResultsFile {
        /// The file.
        path: PathBuf,
        /// Its first line.
        found: String,
    },
    #[error("{} has the columns `{found}`, this sweep writes `{expected}`", path.display())]
    /// The file has other columns than this sweep writes.
    HeaderMismatch {
        /// The file concerned.
        path: PathBuf,
        /// The columns this sweep writes.
        expected: String,
        /// The file's columns.
        found: String,
    },
    #[error(
        "{} belongs to another grid: it was written for `{found}`, this sweep is over `{expected}`; \
         use another output file or the same ranges",
        path.display()
    )]
    /// The file belongs to a sweep over another grid.
    GridMismatch {
        /// The file concerned.
        path: PathBuf,
        /// This sweep's grid.
        expected: String,
        /// The file's grid.
        found: String,
    },
    #[error(
        "{} belongs to another run: it was written for `{found}`, this sweep computes `{expected}`; \
         use another output file or the same parameters",
        path.display()
    )]
    /// The file belongs to a sweep with other run settings.
    RunMismatch {
        /// The file concerned.
        path: PathBuf,
        /// This sweep's run settings.
        expected: String,
        /// The file's run settings.
        found: String,
    },
    #[error(
        "{} belongs to another part of the sweep: it holds {found}, this sweep computes {expected}; \
         use another output file or the same --shard",
        path.display()
    )]
    /// The file belongs to another part (shard) of the sweep.
    ShardMismatch {
        /// The file concerned.
        path: PathBuf,
        /// The part this sweep computes.
        expected: String,
        /// The part the file holds.
        found: String,
    },
    #[error("{} line {line}: {reason}", path.display())]
    /// A line of the file cannot be read.
    Parse {
        /// The file.
        path: PathBuf,
        /// The line (from 1).
        line: usize,
        /// What is wrong with it.
        reason: String,
    },
    /// A point appended to a [`crate::ResultsFile`] that is not one of its sweep's.
    #[error(
        "point {index:?} is not part of the sweep of {} ({sweep} of a {nx} x {ny} grid)",
        path.display()
    )]
    NotInSweep {
        /// The results file.
        path: PathBuf,
        /// The point's grid index `(i, j)`.
        index: (usize, usize),
        /// The part of the sweep the file holds.
        sweep: String,
        /// Grid points along x.
        nx: usize,
        /// Grid points along y.
        ny: usize,
    },
    /// A point appended to a [`crate::ResultsFile`] (or merged) whose coordinates are not, bit
    /// for bit, those of the grid point its index names: it would be read back as the physics of
    /// another point. (The file is the caller's, or named by the merge's other errors: no path
    /// here keeps the error small.)
    #[error(
        "point {index:?} was computed at ({}, {}) but the grid has it at ({}, {}): \
         a point is filed only under its own coordinates",
        Short(given.0), Short(given.1), Short(grid.0), Short(grid.1)
    )]
    WrongCoordinates {
        /// The point's grid index `(i, j)`.
        index: (usize, usize),
        /// The coordinates the point was computed at.
        given: (f64, f64),
        /// The grid's coordinates of `index`.
        grid: (f64, f64),
    },
    /// A point appended to a [`crate::ResultsFile`] that already holds it.
    #[error("point {index:?} is already in {}: a point is written once", path.display())]
    AlreadyDone {
        /// The results file.
        path: PathBuf,
        /// The point's grid index `(i, j)`.
        index: (usize, usize),
    },
    /// [`crate::merge_shards`] was given no shard files, or found none.
    #[error("no shard files to merge: {reason}")]
    NoShards {
        /// Why none were found.
        reason: String,
    },
    /// A file given to [`crate::merge_shards`] is the results file of a whole sweep.
    #[error("{} is not the file of a shard (its first line has no `; shard I/N`)", path.display())]
    NotAShard {
        /// The file.
        path: PathBuf,
    },
    /// The shard files do not make up one split sweep.
    #[error("the shard files do not make up one sweep: {reason}")]
    ShardSet {
        /// What does not fit.
        reason: String,
    },
    /// A grid point is in two shard files (or twice in one).
    #[error("point {index:?} appears twice: in {} and in {}", first.display(), second.display())]
    DuplicatePoint {
        /// The point's grid index `(i, j)`.
        index: (usize, usize),
        /// The first file that holds it.
        first: PathBuf,
        /// The second.
        second: PathBuf,
    },
    /// Grid points are in no shard file: those shards have not finished.
    #[error(
        "{missing} of the {total} grid points are in no shard file, first {first:?}; unfinished shards: {unfinished}. \
         Run those shards again (each resumes where it stopped), then merge"
    )]
    MissingPoints {
        /// How many grid points are in no file.
        missing: usize,
        /// Grid points in all.
        total: usize,
        /// The first missing point `(i, j)`.
        first: (usize, usize),
        /// The shards that have not finished.
        unfinished: String,
    },
    /// The merged file would replace a file that is not the results file of the same sweep.
    #[error("will not replace {}: {reason}", path.display())]
    WouldOverwrite {
        /// The file that would be replaced.
        path: PathBuf,
        /// Why it is not the same sweep's.
        reason: String,
    },
    #[error("{} is in use by another sweep (it holds the file's lock)", path.display())]
    /// Another sweep holds the results file's lock.
    Locked {
        /// The results file.
        path: PathBuf,
    },
    /// The results path names something that is not a regular file (a directory, a FIFO, a
    /// device such as /dev/null): reading it back could block or lose every point.
    #[error("{} is {kind}, not a regular file: give a file path for the results", path.display())]
    NotAFile {
        /// The path given.
        path: PathBuf,
        /// What it is (a directory, a FIFO, ...).
        kind: &'static str,
    },
    #[error("the record type's columns are unusable: {reason}")]
    /// The record type's columns cannot be written (a programming error in a record type).
    InvalidRecord {
        /// What is wrong with the columns.
        reason: String,
    },
    #[error("{option}; at most {max} on this machine ({cores} cores)")]
    /// A thread count of 0 or above [`crate::threads::max_threads`]: `SweepOptions.threads`
    /// outside its range ([`crate::threads::worker_threads`]'s rule), with this machine's bound.
    Threads {
        /// The struct (`SweepOptions`), the field (`threads`), the count asked for and the rule.
        option: InvalidOption,
        /// The most a sweep starts on this machine.
        max: usize,
        /// The machine's cores.
        cores: usize,
    },
    #[error("cannot start {threads} worker threads: {source}")]
    /// The worker threads could not be started.
    ThreadPool {
        /// Worker threads asked for.
        threads: usize,
        #[source]
        /// rayon's error.
        source: rayon::ThreadPoolBuildError,
    },
    #[error(transparent)]
    /// An axis or grid that cannot be built.
    Grid(#[from] GridError),
    #[error(
        "stopped before the end: {done} of the {total} points are in {}, {computed} of them computed \
         by this run; run the same sweep again to compute the other {}",
        path.display(),
        total - done
    )]
    /// The sweep was asked to stop ([`crate::SweepOptions::stop`]) and did: the points being
    /// computed were finished and written, no other point was started.
    Stopped {
        /// The results file.
        path: PathBuf,
        /// Points in the file now (of the shard, for a shard's sweep).
        done: usize,
        /// Points of the sweep (of the shard).
        total: usize,
        /// Points this run computed and wrote before it stopped.
        computed: usize,
    },
    /// A result buffer sized by the grid or a results file (the grid's points, a file's records,
    /// the merge's tables) that the allocator could not give: the bytes and what they were for.
    #[error(transparent)]
    OutOfMemory(#[from] rotor_chain::allocation::AllocationError),
}

impl OptionError for SweepError {
    fn invalid_option(&self) -> Option<InvalidOption> {
        match self {
            Self::Threads { option, .. } => Some(*option),
            Self::Grid(e) => e.invalid_option(),
            _ => None,
        }
    }
}

impl SweepError {
    pub(crate) fn io(action: &'static str, path: impl Into<PathBuf>) -> impl FnOnce(io::Error) -> Self {
        let path = path.into();
        move |source| Self::Io { action, path, source }
    }
}
