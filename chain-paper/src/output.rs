//! Every file of the `paper` binary is written through [`write_atomic`]: to a hidden temporary
//! file beside it, synced, then renamed over it, so a reader finds either the old file or the
//! complete new one. This module also keeps the promise that no temporary outlives its run:
//!
//! - [`stop_writes`], called on SIGINT, SIGTERM or SIGHUP, refuses new writes and waits for the
//!   writes in flight to finish (they are then complete files), so the process can exit leaving
//!   no temporary file;
//! - [`clean_stale_temporaries`], called at start, removes the temporaries that earlier runs left
//!   when they were killed outright (`kill -9`, a power cut). Only our own are touched: their
//!   names are `.<file>.paper-<pid>-<n>.tmp` (and `.paper-probe-<pid>`), and only those whose
//!   process is gone, so a run writing into the same folder at the same time keeps its files.

use std::fs::{self, File};
use std::io::{self, Write as _};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{RwLock, RwLockWriteGuard};
use std::time::{Duration, Instant};

/// A file that could not be written, and why.
#[derive(Debug, thiserror::Error)]
#[error("cannot write {}: {source}", path.display())]
pub struct WriteError {
    /// The file.
    pub path: PathBuf,
    #[source]
    /// The operating system's error.
    pub source: io::Error,
}

/// Writers hold it shared from creating their temporary file until it is renamed or removed;
/// [`stop_writes`] takes it exclusively.
static WRITES: RwLock<()> = RwLock::new(());
/// Set by [`stop_writes`]: no write starts after it.
static STOPPING: AtomicBool = AtomicBool::new(false);
/// Milliseconds each write waits between syncing its temporary file and renaming it (tests only).
static PAUSE_MS: AtomicU64 = AtomicU64::new(0);

/// The name of a temporary file of this process for `name`: `.<name>.paper-<pid>-<n>.tmp`.
fn temporary_name(name: &str, n: u64) -> String {
    format!(".{name}.paper-{}-{n}.tmp", std::process::id())
}

/// The process id in the name of one of our temporary files or probes, `None` for any other name.
/// Also recognises the temporaries of versions before the `paper-` tag (`.<name>.<pid>-<n>.tmp`).
pub fn temporary_owner(file_name: &str) -> Option<u32> {
    if let Some(pid) = file_name.strip_prefix(".paper-probe-") {
        return pid.parse().ok();
    }
    let inner = file_name.strip_prefix('.')?.strip_suffix(".tmp")?;
    let (_, tag) = inner.rsplit_once('.')?;
    let (pid, n) = tag.strip_prefix("paper-").unwrap_or(tag).split_once('-')?;
    n.parse::<u64>().ok()?;
    pid.parse().ok()
}

/// Write `bytes` to `path` atomically (see the module). On failure the temporary file is removed.
/// After [`stop_writes`] every write fails.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let error = |source| WriteError { path: path.to_owned(), source };
    let name = path.file_name().ok_or_else(|| error(io::Error::other("the path names no file")))?;
    let temp =
        path.with_file_name(temporary_name(&name.to_string_lossy(), COUNTER.fetch_add(1, Ordering::Relaxed)));
    let _writing = WRITES.read().unwrap_or_else(|e| e.into_inner());
    if STOPPING.load(Ordering::SeqCst) {
        return Err(error(io::Error::other("the run is stopping (interrupted)")));
    }
    let written = File::create(&temp)
        .and_then(|mut file| {
            file.write_all(bytes)?;
            file.sync_all()
        })
        .and_then(|()| {
            let pause = PAUSE_MS.load(Ordering::Relaxed);
            if pause > 0 {
                std::thread::sleep(Duration::from_millis(pause));
            }
            fs::rename(&temp, path)
        });
    written.map_err(|source| {
        let _ = fs::remove_file(&temp);
        error(source)
    })
}

/// For a signal handler: refuse every later write and wait, at most `patience`, for the writes
/// in flight to finish. Hold the returned guard until the process exits, so that no write starts.
/// `None` if the writes did not finish in time (their temporaries may then remain, for the next
/// run's [`clean_stale_temporaries`]).
pub fn stop_writes(patience: Duration) -> Option<RwLockWriteGuard<'static, ()>> {
    STOPPING.store(true, Ordering::SeqCst);
    let deadline = Instant::now() + patience;
    loop {
        match WRITES.try_write() {
            Ok(guard) => return Some(guard),
            Err(std::sync::TryLockError::Poisoned(e)) => return Some(e.into_inner()),
            Err(std::sync::TryLockError::WouldBlock) if Instant::now() < deadline => {
                std::thread::sleep(Duration::from_millis(5));
            }
            Err(std::sync::TryLockError::WouldBlock) => return None,
        }
    }
}

/// Whether [`stop_writes`] has been called: the process is about to exit on a signal.
pub fn stopping() -> bool {
    STOPPING.load(Ordering::SeqCst)
}

/// Make every write pause `pause` before its rename, so a test can interrupt a run while
/// temporaries exist. Not for anything else.
#[doc(hidden)]
pub fn pause_writes_for_tests(pause: Duration) {
    PAUSE_MS.store(pause.as_millis() as u64, Ordering::Relaxed);
}

/// Remove from `dir` (not its subfolders) the temporary files and probes of `paper` runs whose
/// process is gone (see the module). Returns the files removed. A missing `dir` has none.
pub fn clean_stale_temporaries(dir: &Path) -> io::Result<Vec<PathBuf>> {
    let entries = match fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(e),
    };
    let mut removed = Vec::new();
    for entry in entries {
        let entry = entry?;
        let Some(pid) = temporary_owner(&entry.file_name().to_string_lossy()) else { continue };
        if pid == std::process::id() || process_alive(pid) || !entry.file_type()?.is_file() {
            continue;
        }
        match fs::remove_file(entry.path()) {
            Ok(()) => removed.push(entry.path()),
            // Removed meanwhile by another run cleaning the same folder.
            Err(e) if e.kind() == io::ErrorKind::NotFound => {}
            Err(e) => return Err(e),
        }
    }
    Ok(removed)
}

/// Whether process `pid` exists (it may belong to another user).
#[cfg(unix)]
fn process_alive(pid: u32) -> bool {
    let Ok(pid) = libc::pid_t::try_from(pid) else { return false };
    if pid <= 0 {
        return false;
    }
    // SAFETY: signal 0 sends nothing; kill only checks that the process exists and may be
    // signalled. It reads no memory of ours.
    let status = unsafe { libc::kill(pid, 0) };
    status == 0 || io::Error::last_os_error().raw_os_error() == Some(libc::EPERM)
}

/// Without a way to ask, every owner counts as alive: nothing is removed.
#[cfg(not(unix))]
fn process_alive(_pid: u32) -> bool {
    true
}

/// On SIGINT, SIGTERM or SIGHUP: refuse new writes, let the writes in flight finish (at most
/// 5 s), call `tidy` (for example to leave a progress bar), say so on stderr as `program`, and
/// exit with 128 + the signal's number. Used by the `paper` and `network` commands.
#[cfg(unix)]
pub fn stop_on_signals(program: &'static str, tidy: impl Fn() + Send + 'static) -> io::Result<()> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])?;
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            let finished = stop_writes(Duration::from_secs(5));
            tidy();
            let name = signal_hook::low_level::signal_name(signal).unwrap_or("a signal");
            let state = if finished.is_some() {
                "the files written so far are complete and no temporary file is left"
            } else {
                "writes still in flight after 5 s may leave temporary files; the next run removes them"
            };
            eprintln!("{program}: interrupted by {name}: {state}");
            std::process::exit(128 + signal);
        }
    });
    Ok(())
}

/// Without Unix signals there is nothing to install.
#[cfg(not(unix))]
pub fn stop_on_signals(_program: &'static str, _tidy: impl Fn() + Send + 'static) -> io::Result<()> {
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_writes_replace_and_leave_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.csv");
        write_atomic(&path, b"old").unwrap();
        write_atomic(&path, b"new").unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "new");
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
        let missing = dir.path().join("no-such-dir").join("a.csv");
        let err = write_atomic(&missing, b"x").unwrap_err();
        assert!(err.to_string().starts_with(&format!("cannot write {}", missing.display())), "{err}");
    }

    #[test]
    fn our_temporaries_are_recognised_by_name() {
        let ours = temporary_name("kcobweb.png", 7);
        assert_eq!(temporary_owner(&ours), Some(std::process::id()));
        assert_eq!(temporary_owner(".summary.md.paper-123-4.tmp"), Some(123));
        assert_eq!(temporary_owner(".summary.md.123-4.tmp"), Some(123), "the earlier format");
        assert_eq!(temporary_owner(".paper-probe-55"), Some(55));
        for other in ["summary.md", ".notes.tmp", ".a.b.tmp", ".x.paper-12.tmp", ".x.12-y.tmp", "a.12-3.tmp"]
        {
            assert_eq!(temporary_owner(other), None, "{other}");
        }
    }

    #[test]
    fn only_stale_temporaries_of_ours_are_cleaned() {
        let dir = tempfile::tempdir().unwrap();
        // A process that has exited: its pid is free (and, within this test, not reused).
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let dead = child.id();
        child.wait().unwrap();
        let files = [
            (format!(".a.png.paper-{dead}-0.tmp"), false),
            (format!(".b.csv.{dead}-3.tmp"), false),
            (format!(".paper-probe-{dead}"), false),
            (temporary_name("live.png", 1), true),
            (format!(".c.svg.paper-{}-0.tmp", std::os::unix::process::parent_id()), true),
            (".notes.tmp".to_owned(), true),
            ("kcobweb.png".to_owned(), true),
        ];
        for (name, _) in &files {
            fs::write(dir.path().join(name), b"x").unwrap();
        }
        let removed = clean_stale_temporaries(dir.path()).unwrap();
        assert_eq!(removed.len(), 3, "{removed:?}");
        for (name, kept) in &files {
            assert_eq!(dir.path().join(name).exists(), *kept, "{name}");
        }
        assert!(clean_stale_temporaries(&dir.path().join("missing")).unwrap().is_empty());
    }
}
