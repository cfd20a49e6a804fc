//! An address-space limit on the test process itself, for the tests that a result too large for
//! memory is a typed error with its bytes, never an abort (issue 37). The limit is set by
//! `prlimit --pid` (util-linux) on this process, so a test file that uses it holds one test: no
//! other test may run while the limit is in place.

use std::process::Command;

/// The bytes this process has mapped (`VmSize` of `/proc/self/status`).
fn mapped() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").expect("/proc/self/status");
    let line = status.lines().find(|l| l.starts_with("VmSize:")).expect("a VmSize line");
    let kib: u64 = line.split_whitespace().nth(1).and_then(|v| v.parse().ok()).expect("VmSize in kB");
    kib * 1024
}

/// Sets this process's soft address-space limit (`None`: unlimited).
fn limit(bytes: Option<u64>) {
    let value = bytes.map_or("unlimited".to_string(), |b| b.to_string());
    let pid = std::process::id().to_string();
    let done = Command::new("prlimit").args(["--pid", &pid, &format!("--as={value}:")]).status();
    assert!(done.is_ok_and(|s| s.success()), "prlimit failed");
}

/// Runs `f` with this process's address space limited to what it has mapped plus `headroom`
/// bytes, and lifts the limit before returning `f`'s result.
pub fn with_headroom<T>(headroom: u64, f: impl FnOnce() -> T) -> T {
    limit(Some(mapped() + headroom));
    let result = f();
    limit(None);
    result
}
