//! How many worker threads a sweep starts: [`worker_threads`], the one rule for every place that
//! takes a thread count (`phase-diagram --threads`, `network diagram --threads`, Python's
//! `PhaseDiagram.compute_points`, [`crate::run_sweep`], [`crate::compute_grid`]).
//!
//! A thread beyond the number of points has nothing to do, and threads beyond a few per core only
//! share the cores: 20 000 threads took a 2-core machine to a load of 700 while they started,
//! and the sweep answered no signal meanwhile. So a count is refused above
//! [`THREADS_PER_CORE`] per core, and clamped (the [`crate::Summary`] says to how many) to the
//! number of points.

use crate::error::SweepError;
use rotor_chain::validate::Fields;

/// The rule of every thread count, in words (`SweepOptions.threads`'s).
pub const THREADS_RULE: &str = "between 1 and max_threads() = THREADS_PER_CORE = 4 per core";

/// The most threads per core a sweep starts. Four keeps a core busy while a thread waits on the
/// results file's lock or a write, and bounds the threads by the machine, not by the input.
pub const THREADS_PER_CORE: usize = 4;

/// The cores of this machine (as the operating system gives them to this process; 1 if unknown).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
}

/// The most threads a sweep starts on this machine: [`THREADS_PER_CORE`] times [`cores`].
pub fn max_threads() -> usize {
    THREADS_PER_CORE * cores()
}

/// The threads to start for `points` points when `requested` were asked for (`None`: rayon's
/// default, `RAYON_NUM_THREADS` or every core): never more than the points (and at least one),
/// never more than [`max_threads`]. A request of 0 or above [`max_threads`] is
/// [`SweepError::Threads`] (`SweepOptions.threads` invalid, [`THREADS_RULE`]), before anything
/// starts.
pub fn worker_threads(requested: Option<usize>, points: usize) -> Result<usize, SweepError> {
    let max = max_threads();
    let wanted = match requested {
        Some(t) if t == 0 || t > max => {
            let option = Fields("SweepOptions").rule("threads", t as f64, false, THREADS_RULE).unwrap_err();
            return Err(SweepError::Threads { option, max, cores: cores() });
        }
        Some(t) => t,
        None => default_threads().min(max),
    };
    Ok(wanted.min(points).max(1))
}

/// rayon's default count: `RAYON_NUM_THREADS` if it is a positive number, else every core.
fn default_threads() -> usize {
    std::env::var("RAYON_NUM_THREADS")
        .ok()
        .and_then(|v| v.trim().parse::<usize>().ok())
        .filter(|&t| t > 0)
        .unwrap_or_else(cores)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn threads_are_bounded_by_the_points_and_the_cores() {
        let max = max_threads();
        assert_eq!(max, THREADS_PER_CORE * cores());
        // Never more threads than points, never fewer than one.
        assert_eq!(worker_threads(Some(max), 1).unwrap(), 1);
        assert_eq!(worker_threads(Some(1), 0).unwrap(), 1);
        assert_eq!(worker_threads(Some(2), 1000).unwrap(), 2);
        assert!(worker_threads(None, 3).unwrap() <= 3);
        assert_eq!(worker_threads(Some(max), usize::MAX).unwrap(), max);
        for bad in [0, max + 1, 20_000, usize::MAX] {
            match worker_threads(Some(bad), 10) {
                Err(SweepError::Threads { option, max: m, cores: c }) => {
                    assert_eq!(
                        (option.options, option.field, option.value),
                        ("SweepOptions", "threads", bad as f64)
                    );
                    assert_eq!((option.rule, m, c), (THREADS_RULE, max, cores()));
                }
                other => panic!("{bad} threads: expected Threads, got {other:?}"),
            }
        }
        let message = worker_threads(Some(20_000), 10).unwrap_err().to_string();
        let expected =
            format!("SweepOptions.threads = 20000 is invalid: it must be {THREADS_RULE}; at most {max}");
        assert!(message.contains(&expected), "{message}");
    }
}
