//! `cargo xtask`: the repository's tasks that are more than one cargo command.
//!
//! ```text
//! cargo xtask test            the whole test suite: every Rust test (cargo test --workspace),
//!                             then the Python tests
//! cargo xtask python [ARGS]   only the Python tests (ARGS go to pytest, e.g. -k dask -x)
//! ```
//!
//! **`test`** runs exactly what `cargo test --workspace` runs, plus the Python tests, arranged so
//! that the two cores stay busy:
//! 1. `cargo test --workspace --no-run` compiles every test target once (its diagnostics on
//!    stderr; the list of test executables read from its JSON messages);
//! 2. then two lanes run side by side:
//!    - this process: `cargo test --workspace -- --exact --skip rotor_chain_compile_time_checks`
//!      (every unit, integration and doc test except the one trybuild test, nothing left to
//!      compile), streamed;
//!    - a second thread: the trybuild test `ui-tests/tests/ui.rs` (compile-fail cases, which
//!      trybuild checks in its own target folder), run as cargo would run it, then the
//!      Python half below; their output is kept and printed when the lane ends.
//!
//! The Python half: a virtual environment at `target/python/venv` (from `python3`, or `$PYTHON`),
//! the packages of `python/requirements-test.txt` installed into it with pip (only when that file
//! changed since the last install, so a second run skips it; it runs while the Rust tests
//! compile: one waits on the network, the other on the CPU), the extension built in debug by
//! `maturin develop` (it reuses the workspace's build of every Rust crate), and pytest on
//! `python/tests/`, told where the Rust reference programs are (`ROTOR_CHAIN_REFERENCE`,
//! `PHASE_DIAGRAM`).
//!
//! Written by hand with `std::process` only: a task runner that needs nothing compiled beyond
//! itself is the point of the xtask pattern (so the JSON of step 1 is searched, not parsed).

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

/// Where a step's output goes: inherited (streamed to the terminal), or appended to a log that
/// is printed later (a lane running beside a streamed one).
type Log<'a> = Option<&'a mut Vec<u8>>;

/// Runs `command`, its output streamed or logged; an error unless it exits with status 0. A logged
/// step still prints its one-line result at once, so its progress shows among streamed output.
fn run(what: &str, command: &mut Command, log: Log) -> Step {
    let start = Instant::now();
    let program = command.get_program().to_owned();
    let cannot_start = |e| Failure(format!("{what}: cannot start {program:?}: {e}"));
    let status = match log {
        None => command.status().map_err(cannot_start)?,
        Some(log) => {
            let output = command.stdin(Stdio::null()).output().map_err(cannot_start)?;
            log.extend_from_slice(&output.stdout);
            log.extend_from_slice(&output.stderr);
            let line = format!("xtask: {what}: {}\n", outcome(output.status, start));
            log.extend_from_slice(line.as_bytes());
            output.status
        }
    };
    eprintln!("xtask: {what}: {}", outcome(status, start));
    if status.success() { Ok(()) } else { Err(Failure(format!("{what} failed ({status})"))) }
}

/// "done in X s" or "failed (status)".
fn outcome(status: std::process::ExitStatus, start: Instant) -> String {
    if status.success() {
        format!("done in {:.1} s", start.elapsed().as_secs_f64())
    } else {
        format!("failed ({status})")
    }
}

/// The trybuild test target, `ui-tests/tests/ui.rs`.
const UI_TARGET: &str = "ui";
/// Its one test function: a name no other test in the workspace may take, since lane one skips
/// it by name (`--exact --skip`); see `ui-tests/tests/ui.rs`.
const UI_TEST: &str = "rotor_chain_compile_time_checks";

fn test(pytest_args: &[OsString]) -> Step {
    let root = root();
    // The Python environment is prepared (pip, network-bound) while cargo compiles (CPU-bound).
    let venv = {
        let root = root.clone();
        thread::spawn(move || prepare_venv(&root))
    };
    let ui = build_tests(&root)?;
    // Lane two: the trybuild test, then the Python tests, output kept for the end.
    let lane = {
        let (root, pytest_args) = (root.clone(), pytest_args.to_vec());
        thread::spawn(move || {
            let mut log = Vec::new();
            let ui = run_ui_test(&root, &ui, &mut log);
            let python = venv
                .join()
                .map_err(|_| Failure("preparing the Python environment panicked".to_owned()))
                .and_then(|venv| venv)
                .and_then(|venv| python_tests(&root, &venv, &pytest_args, Some(&mut log)));
            (ui, python, log)
        })
    };
    // Lane one: every other Rust test, streamed. `--exact` makes `--skip` match the whole name.
    let rust = run(
        "cargo test --workspace (all but the trybuild test, which runs beside it)",
        Command::new(cargo()).current_dir(&root).args([
            "test",
            "--workspace",
            "--",
            "--exact",
            "--skip",
            UI_TEST,
        ]),
        None,
    );
    let (ui, python, log) =
        lane.join().map_err(|_| Failure("the trybuild and Python lane panicked".to_owned()))?;
    eprintln!("\nxtask: the trybuild test and the Python tests, run beside the other tests:");
    let mut stderr = std::io::stderr().lock();
    let _ = std::io::Write::write_all(&mut stderr, &log);
    drop(stderr);
    rust?;
    ui?;
    python
}

/// Step 1: `cargo test --workspace --no-run`; the trybuild test's executable.
fn build_tests(root: &Path) -> Step<PathBuf> {
    let start = Instant::now();
    let output = Command::new(cargo())
        .current_dir(root)
        .args(["test", "--workspace", "--no-run", "--message-format=json-render-diagnostics"])
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| Failure(format!("cannot start cargo: {e}")))?;
    if !output.status.success() {
        return Err(Failure(format!("cargo test --workspace --no-run failed ({})", output.status)));
    }
    eprintln!("xtask: cargo test --workspace --no-run: done in {:.1} s", start.elapsed().as_secs_f64());
    let messages = String::from_utf8_lossy(&output.stdout);
    let wanted = format!(r#""name":"{UI_TARGET}","src_path":"#);
    messages
        .lines()
        .filter(|m| m.contains(r#""reason":"compiler-artifact""#) && m.contains(&wanted))
        .filter(|m| m.contains(r#""kind":["test"]"#) && m.contains("ui-tests"))
        .find_map(|m| json_string_after(m, r#""executable":""#))
        .map(PathBuf::from)
        .ok_or_else(|| {
            Failure(format!("cargo built no test executable named `{UI_TARGET}` (ui-tests/tests/ui.rs)"))
        })
}

/// The JSON string value that follows `key` in `message`, with the escapes `\\`, `\"` and `\/`
/// undone; `None` for any other escape (a control character in a path), which is not decoded.
fn json_string_after(message: &str, key: &str) -> Option<String> {
    let rest = &message[message.find(key)? + key.len()..];
    let mut value = String::new();
    let mut chars = rest.chars();
    while let Some(c) = chars.next() {
        match c {
            '"' => return Some(value),
            '\\' => match chars.next()? {
                c @ ('\\' | '"' | '/') => value.push(c),
                _ => return None,
            },
            c => value.push(c),
        }
    }
    None
}

/// The trybuild test, run the way `cargo test` runs it: from its package's folder, with the
/// variables cargo sets for a test (trybuild reads the manifest folder and the package name).
fn run_ui_test(root: &Path, executable: &Path, log: &mut Vec<u8>) -> Step {
    let package = root.join("ui-tests");
    let mut command = Command::new(executable);
    command
        .current_dir(&package)
        .args(["--exact", UI_TEST])
        .env("CARGO", cargo())
        .env("CARGO_MANIFEST_DIR", &package)
        .env("CARGO_MANIFEST_PATH", package.join("Cargo.toml"))
        .env("CARGO_PKG_NAME", "ui-tests")
        .env("CARGO_CRATE_NAME", UI_TARGET)
        .env("CARGO_TARGET_TMPDIR", target_dir(root).join("tmp"));
    run("trybuild test (ui-tests/tests/ui.rs)", &mut command, Some(log))
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
            "rotor-chain-sweep",
            "--bins",
        ]),
        None,
    )?;
    python_tests(&root, &venv, pytest_args, None)
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
fn python_tests(root: &Path, venv: &Path, pytest_args: &[OsString], mut log: Log) -> Step {
    let [mut maturin, mut pytest] = python_commands(root, venv, pytest_args)?;
    run("maturin develop (the extension, debug)", &mut maturin, log.as_deref_mut())?;
    run("pytest", &mut pytest, log)
}

/// `maturin develop` and pytest, set up to use the venv and the reference programs.
fn python_commands(root: &Path, venv: &Path, pytest_args: &[OsString]) -> Step<[Command; 2]> {
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
    let mut maturin = Command::new(bin.join("maturin"));
    maturin
        .current_dir(root.join("python"))
        .args(["develop", "--quiet"])
        .env("VIRTUAL_ENV", venv)
        .env("PATH", &path)
        .env_remove("CONDA_PREFIX");
    let mut pytest = Command::new(bin.join("python"));
    pytest
        .current_dir(root.join("python"))
        .args(["-m", "pytest", "tests", "-q", "-p", "no:cacheprovider"])
        .args(pytest_args)
        .env("VIRTUAL_ENV", venv)
        .env("PATH", &path)
        .env("ROTOR_CHAIN_REFERENCE", debug.join("rotor-chain-reference"))
        .env("PHASE_DIAGRAM", debug.join("phase-diagram"));
    Ok([maturin, pytest])
}

#[cfg(test)]
mod tests {
    use super::json_string_after;

    #[test]
    fn the_executable_is_read_from_a_cargo_message() {
        let message = r#"{"reason":"compiler-artifact","target":{"kind":["test"],"name":"ui","src_path":"/r/ui-tests/tests/ui.rs"},"executable":"/r/a \"b\"\\c\/target/debug/deps/ui-0f","fresh":true}"#;
        let key = r#""executable":""#;
        assert_eq!(json_string_after(message, key).as_deref(), Some(r#"/r/a "b"\c/target/debug/deps/ui-0f"#));
        assert_eq!(json_string_after(r#"{"executable":"a\nb"}"#, key), None, "an escape not decoded");
        assert_eq!(json_string_after(r#"{"executable":"unterminated"#, key), None);
        assert_eq!(json_string_after(r#"{"executable":null}"#, key), None);
    }
}
