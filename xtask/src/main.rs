//! `cargo xtask`: the repository's tasks that are more than one cargo command.
//!
//! ```text
//! cargo xtask test            the whole test suite: cargo test --workspace, then the Python tests
//! cargo xtask python [ARGS]   only the Python tests (ARGS go to pytest, e.g. -k dask -x)
//! ```
//!
//! The Python half: a virtual environment at `target/python/venv` (from `python3`, or `$PYTHON`),
//! the packages of `python/requirements-test.txt` installed into it with pip (only when that file
//! changed since the last install, so a second run skips it), the extension built in debug by
//! `maturin develop` (it reuses the workspace's build of every Rust crate), and pytest on
//! `python/tests/`, told where the Rust reference programs are (`ROTOR_CHAIN_REFERENCE`,
//! `PHASE_DIAGRAM`). The pip install runs while `cargo test` compiles and runs: one waits on the
//! network, the other on the CPU.
//!
//! Written by hand with `std::process` only: a task runner that needs nothing compiled beyond
//! itself is the point of the xtask pattern.

use std::env;
use std::ffi::OsString;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::thread;
use std::time::Instant;

const USAGE: &str = "usage: cargo xtask test | cargo xtask python [PYTEST ARGS...]";

/// A failed step, with what to say.
struct Failure(String);

type Step<T = ()> = Result<T, Failure>;

fn main() -> ExitCode {
    let args: Vec<OsString> = env::args_os().skip(1).collect();
    let result = match args.first().and_then(|a| a.to_str()) {
        Some("test") if args.len() == 1 => test(&[]),
        Some("python") => python_only(&args[1..]),
        Some("-h" | "--help") => {
            println!("{USAGE}");
            Ok(())
        }
        _ => Err(Failure(USAGE.to_owned())),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure(message)) => {
            eprintln!("xtask: {message}");
            ExitCode::FAILURE
        }
    }
}

/// The workspace root: the parent of this crate's folder.
fn root() -> PathBuf {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    manifest.parent().map(Path::to_owned).unwrap_or(manifest)
}

fn target_dir(root: &Path) -> PathBuf {
    env::var_os("CARGO_TARGET_DIR").map(PathBuf::from).unwrap_or_else(|| root.join("target"))
}

fn cargo() -> OsString {
    env::var_os("CARGO").unwrap_or_else(|| "cargo".into())
}

/// Runs `command`, inheriting stdout and stderr; an error unless it exits with status 0.
fn run(what: &str, command: &mut Command) -> Step {
    let start = Instant::now();
    let status = command
        .status()
        .map_err(|e| Failure(format!("{what}: cannot start {:?}: {e}", command.get_program())))?;
    if status.success() {
        eprintln!("xtask: {what}: done in {:.1} s", start.elapsed().as_secs_f64());
        Ok(())
    } else {
        Err(Failure(format!("{what} failed ({status})")))
    }
}

fn test(pytest_args: &[OsString]) -> Step {
    let root = root();
    // The Python environment is prepared (pip, network-bound) while cargo test runs (CPU-bound).
    let venv = {
        let root = root.clone();
        thread::spawn(move || prepare_venv(&root))
    };
    let rust =
        run("cargo test --workspace", Command::new(cargo()).current_dir(&root).args(["test", "--workspace"]));
    let venv = venv.join().map_err(|_| Failure("preparing the Python environment panicked".to_owned()))?;
    rust?;
    // `cargo test --workspace` has built both reference programs (their integration tests need
    // them), with the workspace's features; building them again with `cargo build -p` would
    // compile their dependencies anew with other features.
    python_tests(&root, &venv?, pytest_args)
}

fn python_only(pytest_args: &[OsString]) -> Step {
    let root = root();
    let venv = prepare_venv(&root)?;
    run(
        "cargo build (the Rust references of the Python tests)",
        Command::new(cargo()).current_dir(&root).args([
            "build",
            "--package",
            "rotor-chain-reference",
            "--package",
            "chain-sweep",
            "--bins",
        ]),
    )?;
    python_tests(&root, &venv, pytest_args)
}

/// The virtual environment with `python/requirements-test.txt` installed; its folder.
fn prepare_venv(root: &Path) -> Step<PathBuf> {
    let venv = target_dir(root).join("python").join("venv");
    let python = venv.join("bin").join("python");
    if !python.is_file() {
        let base = env::var_os("PYTHON").unwrap_or_else(|| "python3".into());
        fs::create_dir_all(venv.parent().unwrap_or(&venv))
            .map_err(|e| Failure(format!("cannot create {}: {e}", venv.display())))?;
        let made = Command::new(&base).arg("-m").arg("venv").arg(&venv).status();
        if !matches!(made, Ok(s) if s.success()) {
            return Err(Failure(format!(
                "`{} -m venv {}` failed: the Python tests need Python 3.9 or newer with the venv module \
                 (Debian: apt-get install python3-venv), or set PYTHON to such an interpreter",
                base.to_string_lossy(),
                venv.display()
            )));
        }
    }
    let requirements = root.join("python").join("requirements-test.txt");
    let wanted = fs::read_to_string(&requirements)
        .map_err(|e| Failure(format!("cannot read {}: {e}", requirements.display())))?;
    let stamp = venv.join("rotor-chain-requirements.txt");
    if fs::read_to_string(&stamp).ok().as_deref() == Some(wanted.as_str()) {
        return Ok(venv);
    }
    // Quiet unless it fails: its output would interleave with cargo test's.
    let start = Instant::now();
    let output = Command::new(&python)
        .args(["-m", "pip", "install", "--disable-pip-version-check", "-q", "-r"])
        .arg(&requirements)
        .stdin(Stdio::null())
        .output()
        .map_err(|e| Failure(format!("cannot run pip: {e}")))?;
    if !output.status.success() {
        return Err(Failure(format!(
            "pip install -r {} failed:\n{}{}",
            requirements.display(),
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        )));
    }
    fs::write(&stamp, wanted).map_err(|e| Failure(format!("cannot write {}: {e}", stamp.display())))?;
    eprintln!(
        "xtask: pip install -r python/requirements-test.txt: done in {:.1} s",
        start.elapsed().as_secs_f64()
    );
    Ok(venv)
}

/// Build the extension (debug), then run pytest with the reference programs of `target/debug`.
fn python_tests(root: &Path, venv: &Path, pytest_args: &[OsString]) -> Step {
    let debug = target_dir(root).join("debug");
    for program in ["rotor-chain-reference", "phase-diagram"] {
        if !debug.join(program).is_file() {
            return Err(Failure(format!(
                "{} is missing: the Rust build did not make it",
                debug.join(program).display()
            )));
        }
    }
    let bin = venv.join("bin");
    let mut path = OsString::from(&bin);
    if let Some(old) = env::var_os("PATH") {
        path.push(":");
        path.push(old);
    }
    run(
        "maturin develop (the extension, debug)",
        Command::new(bin.join("maturin"))
            .current_dir(root.join("python"))
            .args(["develop", "--quiet"])
            .env("VIRTUAL_ENV", venv)
            .env("PATH", &path)
            .env_remove("CONDA_PREFIX"),
    )?;
    let status = Command::new(bin.join("python"))
        .current_dir(root.join("python"))
        .args(["-m", "pytest", "tests", "-q", "-p", "no:cacheprovider"])
        .args(pytest_args)
        .env("VIRTUAL_ENV", venv)
        .env("PATH", &path)
        .env("ROTOR_CHAIN_REFERENCE", debug.join("rotor-chain-reference"))
        .env("PHASE_DIAGRAM", debug.join("phase-diagram"))
        .status()
        .map_err(|e| Failure(format!("cannot run pytest: {e}")))?;
    if status.success() { Ok(()) } else { Err(Failure(format!("pytest failed ({status})"))) }
}
