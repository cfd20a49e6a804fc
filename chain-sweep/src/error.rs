//! The errors of a sweep and of reading a results file. Each names the file and carries what was
//! expected and what was found.

use std::io;
use std::path::PathBuf;

use crate::grid::GridError;

/// Why a sweep could not run, or a results file could not be read. Errors of a single point's
/// computation are not here: they are recorded in the file (the `error` column) and counted in
/// [`crate::Summary::failed`].
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SweepError {
    #[error("cannot {action} {}: {source}", path.display())]
    Io {
        action: &'static str,
        path: PathBuf,
        #[source]
        source: io::Error,
    },
    #[error(
        "{} is not a chain-sweep results file: its first line should start with `{}`, found `{found}`",
        path.display(), crate::file::FORMAT_TAG
    )]
    NotAResultsFile { path: PathBuf, found: String },
    #[error("{} has the columns `{found}`, this sweep writes `{expected}`", path.display())]
    HeaderMismatch { path: PathBuf, expected: String, found: String },
    #[error(
        "{} belongs to another grid: it was written for `{found}`, this sweep is over `{expected}`; \
         use another output file or the same ranges",
        path.display()
    )]
    GridMismatch { path: PathBuf, expected: String, found: String },
    #[error(
        "{} belongs to another run: it was written for `{found}`, this sweep computes `{expected}`; \
         use another output file or the same parameters",
        path.display()
    )]
    RunMismatch { path: PathBuf, expected: String, found: String },
    #[error(
        "{} belongs to another part of the sweep: it holds {found}, this sweep computes {expected}; \
         use another output file or the same --shard",
        path.display()
    )]
    ShardMismatch { path: PathBuf, expected: String, found: String },
    #[error("{} line {line}: {reason}", path.display())]
    Parse { path: PathBuf, line: usize, reason: String },
    /// A point appended to a [`crate::ResultsFile`] that is not one of its sweep's.
    #[error(
        "point {index:?} is not part of the sweep of {} ({sweep} of a {nx} x {ny} grid)",
        path.display()
    )]
    NotInSweep { path: PathBuf, index: (usize, usize), sweep: String, nx: usize, ny: usize },
    /// A point appended to a [`crate::ResultsFile`] that already holds it.
    #[error("point {index:?} is already in {}: a point is written once", path.display())]
    AlreadyDone { path: PathBuf, index: (usize, usize) },
    /// [`crate::merge_shards`] was given no shard files, or found none.
    #[error("no shard files to merge: {reason}")]
    NoShards { reason: String },
    /// A file given to [`crate::merge_shards`] is the results file of a whole sweep.
    #[error("{} is not the file of a shard (its first line has no `; shard I/N`)", path.display())]
    NotAShard { path: PathBuf },
    /// The shard files do not make up one split sweep.
    #[error("the shard files do not make up one sweep: {reason}")]
    ShardSet { reason: String },
    /// A grid point is in two shard files (or twice in one).
    #[error("point {index:?} appears twice: in {} and in {}", first.display(), second.display())]
    DuplicatePoint { index: (usize, usize), first: PathBuf, second: PathBuf },
    /// Grid points are in no shard file: those shards have not finished.
    #[error(
        "{missing} of the {total} grid points are in no shard file, first {first:?}; unfinished shards: {unfinished}. \
         Run those shards again (each resumes where it stopped), then merge"
    )]
    MissingPoints { missing: usize, total: usize, first: (usize, usize), unfinished: String },
    /// The merged file would replace a file that is not the results file of the same sweep.
    #[error("will not replace {}: {reason}", path.display())]
    WouldOverwrite { path: PathBuf, reason: String },
    #[error("{} is in use by another sweep (it holds the file's lock)", path.display())]
    Locked { path: PathBuf },
    /// The results path names something that is not a regular file (a directory, a FIFO, a
    /// device such as /dev/null): reading it back could block or lose every point.
    #[error("{} is {kind}, not a regular file: give a file path for the results", path.display())]
    NotAFile { path: PathBuf, kind: &'static str },
    #[error("the record type's columns are unusable: {reason}")]
    InvalidRecord { reason: String },
    #[error("cannot start {threads} worker threads: {source}")]
    ThreadPool {
        threads: usize,
        #[source]
        source: rayon::ThreadPoolBuildError,
    },
    #[error(transparent)]
    Grid(#[from] GridError),
}

impl SweepError {
    pub(crate) fn io(action: &'static str, path: impl Into<PathBuf>) -> impl FnOnce(io::Error) -> Self {
        let path = path.into();
        move |source| Self::Io { action, path, source }
    }
}
