//! `phase-diagram` as a user runs it: exit statuses as documented (0 done, 1 the sweep could not
//! run, 2 bad arguments or an invalid value, 3 some points failed), a clear message, no file
//! written on bad input, and no hang on an output that is not a regular file.

use std::fs;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Run with the arguments of a valid fake sweep, `changes` replacing or adding options.
fn phase_diagram(out: &str, changes: &[(&str, &str)]) -> (Option<i32>, String) {
    let mut args = vec![
        ("--defect", "kink"),
        ("--ki", "0.1:1:3"),
        ("--v0", "0.5:12:3"),
        ("--out", out),
        ("--fake-delay-ms", "0"),
    ];
    for &(flag, value) in changes {
        match args.iter_mut().find(|(f, _)| *f == flag) {
            Some(arg) => arg.1 = value,
            None => args.push((flag, value)),
        }
    }
    let mut flat: Vec<&str> = Vec::new();
    for &(flag, value) in &args {
        flat.push(flag);
        if !value.is_empty() {
            flat.push(value);
        }
    }
    let mut child = Command::new(env!("CARGO_BIN_EXE_phase-diagram"))
        .args(flat)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // A hang is a failure of the test, not of the suite: kill it after 60 s.
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            child.kill().unwrap();
            panic!("phase-diagram {changes:?} hung");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let output = child.wait_with_output().unwrap();
    (output.status.code(), String::from_utf8_lossy(&output.stderr).into_owned())
}

#[test]
fn bad_arguments_exit_2_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.csv");
    let out = out.to_str().unwrap();
    let cases: &[(&[(&str, &str)], &str)] = &[
        // Malformed (clap and the range parser).
        (&[("--ki", "0.1:1:0")], "an axis needs at least 1 point, got count = 0"),
        (&[("--v0", "0.5:12:-4")], "COUNT `-4` is not a whole number >= 1"),
        (&[("--v0", "0.5-12-4")], "`0.5-12-4` is not a range FROM:TO:COUNT"),
        (&[("--ki", "0.1:x:3")], "TO `x` is not a number"),
        (&[("--ki", "0.1:inf:3")], "not a finite number"),
        (&[("--ki", "0:1:3:log")], "a logarithmic axis needs FROM and TO > 0"),
        (&[("--ki", "0.1:1:3:lin")], "the fourth part must be `log`"),
        (&[("--defect", "soliton")], "invalid value 'soliton' for '--defect <DEFECT>'"),
        (&[("--ends", "sticky")], "invalid value 'sticky' for '--ends <ENDS>'"),
        (&[("--threads", "0")], "invalid value '0' for '--threads"),
        (&[("--n", "many")], "invalid value 'many' for '--n <N>'"),
        // Well formed, invalid values (our checks): the same status.
        (&[("--ki", "0:1:3")], "must be > 0"),
        (&[("--ki", "-1:1:3")], "must be > 0"),
        (&[("--ki", "1e-3:1e305:3")], "k_i = k_i/k * k finite"),
        (&[("--v0", "-1:1:3")], "every launch speed must be >= 0"),
        (&[("--theta-bar", "0.7")], "outside the flipper phase"),
        (&[("--n", "1")], "`n` must be at least 2"),
        (&[("--n", "12")], "a chain of 12 rotors cannot hold the experiment"),
        (&[("--n", "20")], "start = 24.5 is invalid"),
        (&[("--n", "37")], "a chain of 37 rotors cannot hold the experiment (this experiment needs n >= 38)"),
        (&[("--impurity", "50")], "cannot hold the experiment (this experiment needs n >= 70)"),
        (&[("--damping", "-1")], "PhaseDiagram.damping = -1 is invalid: it must be non-negative and finite"),
        (&[("--direction", "up")], "invalid value 'up' for '--direction <DIRECTION>'"),
        (
            &[("--impurity-rest-length", "0")],
            "PhaseDiagram.impurity_rest_length = 0 is invalid: it must be positive and finite",
        ),
        (&[("--k", "-5")], "`k` must be a finite number > 0"),
        (&[("--r", "nan")], "`r` must be a finite number > 0"),
        (&[("--dt", "0")], "PhaseDiagram.dt = 0 is invalid: it must be positive and finite"),
        (&[("--dt=-1e-3", "")], "PhaseDiagram.dt = -0.001 is invalid: it must be positive and finite"),
        (
            &[("--energy-tolerance", "0")],
            "PhaseDiagram.energy_tolerance = 0 is invalid: it must be positive and finite",
        ),
        (&[("--t-max", "inf")], "PhaseDiagram.t_max = inf is invalid: it must be positive and finite"),
        // A step no run could take to t_max within its budget: refused before any point, as
        // t_max past the output budget is (1e-300 and 1e-7: 2e301 and 2e8 steps against 1e8).
        (
            &[("--dt", "1e-300")],
            "dt = 1e-300 needs 1.9999999999999999e301 Verlet steps to reach t_max = 20, more than a run's budget of 100000000",
        ),
        (&[("--dt", "1e-7")], "dt = 1e-7 needs 2e8 Verlet steps"),
        (&[("--t-max", "1e300")], "t_max = 1e300 needs"),
        (&[("--ki", "0.01:1:1000"), ("--v0", "0:1:100000")], "more than the limit"),
    ];
    for &(changes, expected) in cases {
        let (code, stderr) = phase_diagram(out, changes);
        assert_eq!(code, Some(2), "{changes:?}: {stderr}");
        assert!(stderr.contains(expected), "{changes:?}: expected `{expected}` in:\n{stderr}");
        assert!(!dir.path().join("r.csv").exists(), "{changes:?} wrote the file");
    }
}

#[test]
fn a_t_max_past_the_runs_output_budget_exits_2_with_its_numbers() {
    // ConfigError::OutputBudget: 1e9 / 0.01 = 1e11 outputs per run, against 1 000 000; refused
    // by the settings' check before the file is touched, not at every point.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.csv");
    let (code, stderr) = phase_diagram(out.to_str().unwrap(), &[("--t-max", "1e9")]);
    assert_eq!(code, Some(2), "{stderr}");
    for expected in [
        "t_max = 1000000000 needs 1",
        "e11 outputs of the run every 0.01, more than its budget of 1000000: shorten t_max",
    ] {
        assert!(stderr.contains(expected), "expected `{expected}` in:\n{stderr}");
    }
    assert!(!out.exists(), "a refused sweep wrote the file");
    // A t_max within the budget (1e4: 1e6 outputs every 0.01) is accepted.
    let (code, stderr) = phase_diagram(out.to_str().unwrap(), &[("--t-max", "1e4")]);
    assert_eq!(code, Some(0), "{stderr}");
}

#[test]
fn an_output_that_is_not_a_regular_file_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    // A directory.
    let (code, stderr) = phase_diagram(dir.path().to_str().unwrap(), &[]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("is a directory, not a regular file"), "{stderr}");
    // A FIFO: opening it for reading would block until a writer came.
    let fifo = dir.path().join("pipe");
    let made = Command::new("mkfifo").arg(&fifo).status().map(|s| s.success()).unwrap_or(false);
    if made {
        let (code, stderr) = phase_diagram(fifo.to_str().unwrap(), &[]);
        assert_eq!(code, Some(2), "{stderr}");
        assert!(stderr.contains("is a FIFO, not a regular file"), "{stderr}");
    }
    // A device: reading /dev/null back would lose every point.
    let (code, stderr) = phase_diagram("/dev/null", &[]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("/dev/null is a device"), "{stderr}");
    // A symbolic link to a directory.
    let link = dir.path().join("link");
    std::os::unix::fs::symlink(dir.path(), &link).unwrap();
    let (code, stderr) = phase_diagram(link.to_str().unwrap(), &[]);
    assert_eq!(code, Some(2), "{stderr}");
}

#[test]
fn a_sweep_that_cannot_run_exits_1() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no-such-dir").join("r.csv");
    let (code, stderr) = phase_diagram(missing.to_str().unwrap(), &[]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("cannot open") && stderr.contains("no-such-dir/r.csv"), "{stderr}");
    assert!(!dir.path().join("no-such-dir").exists());
    // A results file of another sweep.
    let out = dir.path().join("r.csv");
    let (code, _) = phase_diagram(out.to_str().unwrap(), &[]);
    assert_eq!(code, Some(0));
    let before = fs::read(&out).unwrap();
    let (code, stderr) = phase_diagram(out.to_str().unwrap(), &[("--theta-bar", "0.3")]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("belongs to another run"), "{stderr}");
    assert_eq!(fs::read(&out).unwrap(), before, "the file is untouched");
}

#[test]
fn a_good_fake_sweep_writes_the_phase_diagram_columns() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.csv");
    let (code, stderr) = phase_diagram(out.to_str().unwrap(), &[("--v0", "0:1:3"), ("--ki", "0.01:3:3:log")]);
    assert_eq!(code, Some(0), "{stderr}");
    let text = fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    let first = lines.next().unwrap();
    assert!(first.starts_with("# chain-sweep v1; grid x=0.01:3.0:3 y=0.0:1.0:3 fnv1a="), "{first}");
    assert!(
        first.contains("; run defect=kink n=60 r=0.8 k=10000.0 theta_bar=0.28 ends=free integrator=verlet"),
        "{first}"
    );
    assert!(first.ends_with("physics=fake"), "{first}");
    assert_eq!(
        lines.next(),
        Some(
            "i,j,x,y,outcome,t_decided,confirmed,later,t_later,kinks_final,antikinks_final,energy_error,integrator,unresolved,unresolved_outcome,t_unresolved,error"
        )
    );
    assert_eq!(lines.count(), 9);

    // The experiment off the paper's: every setting in the file's first line, so a file of
    // another experiment is refused on resume; the paper's experiment's line is unchanged.
    let other = dir.path().join("other.csv");
    let settings = [
        ("--impurity", "20"),
        ("--impurity-rest-length", "1.75"),
        ("--direction", "right"),
        ("--start", "5"),
        ("--damping", "0.5"),
    ];
    let (code, stderr) = phase_diagram(other.to_str().unwrap(), &settings);
    assert_eq!(code, Some(0), "{stderr}");
    let text = fs::read_to_string(&other).unwrap();
    let first = text.lines().next().unwrap();
    let expected = "physics=fake impurity=20 impurity_rest_length=1.75 direction=right start=5.0 damping=0.5";
    assert!(first.ends_with(expected), "{first}");
    let (code, stderr) = phase_diagram(other.to_str().unwrap(), &settings[..4]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("belongs to another run"), "{stderr}");
}

#[test]
fn real_points_come_with_their_energy_budget() {
    // Two real points (the paper's trapped and transmitted antikinks) through the binary: each
    // records its outcome, its energy error below the tolerance, and the integrator.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.csv");
    let args = [("--defect", "antikink"), ("--ki", "0.7:0.8:2"), ("--v0", "4:4:1"), ("--fake-delay-ms", "")];
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_phase-diagram"));
    for (flag, value) in args.iter().filter(|(f, _)| *f != "--fake-delay-ms") {
        cmd.args([*flag, *value]);
    }
    let output = cmd.args(["--out", out.to_str().unwrap()]).output().unwrap();
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
    let points = chain_sweep::read_results::<chain_sweep::scattering::PointRecord>(&out).unwrap();
    let mut outcomes: Vec<(f64, &str, f64)> =
        points.iter().map(|(_, (ki, _), r)| (*ki, r.outcome.name(), r.energy_error)).collect();
    outcomes.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert_eq!(outcomes.iter().map(|o| o.1).collect::<Vec<_>>(), ["trapped", "transmitted"]);
    assert!(outcomes.iter().all(|o| o.2 > 0.0 && o.2 < 1e-3), "{outcomes:?}");
}

#[test]
fn threads_are_bounded_by_the_cores_and_clamped_to_the_points() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.csv");
    let out = out.to_str().unwrap();
    let max = chain_sweep::threads::max_threads();
    // 20 000 threads on any machine this runs on: refused at once, nothing written.
    let start = Instant::now();
    let (code, stderr) = phase_diagram(out, &[("--threads", "20000")]);
    assert_eq!(code, Some(2), "{stderr}");
    let expected = format!(
        "invalid --threads: SweepOptions.threads = 20000 is invalid: it must be {}; at most {max} on this machine",
        chain_sweep::threads::THREADS_RULE
    );
    assert!(stderr.contains(&expected), "{stderr}");
    assert!(start.elapsed() < Duration::from_secs(10) && !dir.path().join("r.csv").exists());
    // The most allowed, on one point: one thread, and the clamp is reported.
    let max = max.to_string();
    let (code, stderr) = phase_diagram(out, &[("--threads", &max), ("--ki", "0.5:0.5:1"), ("--v0", "1:1:1")]);
    assert_eq!(code, Some(0), "{stderr}");
    let expected = format!("ran on 1 worker thread(s), not the {max} asked for");
    assert!(stderr.contains(&expected), "{stderr}");
}

/// The reader of stderr gone (`phase-diagram ... 2>&1 | head -0`): the sweep ends quietly by
/// SIGPIPE when it first reports, never with a panic, and the results file holds whole points.
#[cfg(unix)]
#[test]
fn a_reader_that_goes_away_ends_phase_diagram_quietly() {
    use std::os::unix::process::ExitStatusExt;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.csv");
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let status = Command::new(env!("CARGO_BIN_EXE_phase-diagram"))
        .args(["--defect", "kink", "--ki", "0.1:1:3", "--v0", "0.5:12:3", "--fake-delay-ms", "0", "--out"])
        .arg(&out)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(writer)
        .status()
        .unwrap();
    assert_eq!(status.signal(), Some(libc::SIGPIPE), "{status:?}");
    let points = chain_sweep::read_points::<chain_sweep::scattering::PointRecord>(&out).unwrap();
    assert_eq!(points.len(), 9);
}
