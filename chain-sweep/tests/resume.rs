//! The `phase-diagram` binary killed mid-sweep and restarted: the file ends with every grid point
//! exactly once. Uses the hidden `--fake-delay-ms`, so it is fast and needs no physics.

use std::collections::HashSet;
use std::fs;
use std::io::Write;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::thread::sleep;
use std::time::{Duration, Instant};

use chain_sweep::scattering::{PointRecord, fake_point};
use chain_sweep::{Axis, read_points};

const KI: &str = "0.1:1:6";
const V0: &str = "0.5:12:6";

fn phase_diagram(out: &Path, ki: &str, extra: &[&str]) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_phase-diagram"));
    command
        .args(["--defect", "kink", "--ki", ki, "--v0", V0, "--threads", "2", "--out"])
        .arg(out)
        .args(extra);
    command.stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped());
    command
}

fn run(command: &mut Command) -> Output {
    command.output().expect("the phase-diagram binary runs")
}

/// Complete point lines in the file (the two preamble lines are not points).
fn finished_points(path: &Path) -> usize {
    let bytes = fs::read(path).unwrap_or_default();
    bytes.iter().filter(|&&b| b == b'\n').count().saturating_sub(2)
}

/// Every point of the 6 x 6 grid once, at the grid's coordinates, with the fake record.
fn assert_every_point_once(path: &Path) {
    let (xs, ys) = (KI.parse::<Axis>().unwrap(), V0.parse::<Axis>().unwrap());
    let points = read_points::<PointRecord>(path).unwrap();
    let mut seen = HashSet::new();
    for p in &points {
        assert!(seen.insert(p.index), "point {:?} is in the file twice (line {})", p.index, p.line);
        let (x, y) = (xs.values()[p.index.0], ys.values()[p.index.1]);
        assert_eq!(p.coords, (x, y), "line {}", p.line);
        assert_eq!(p.outcome, Ok(fake_point(x, y)), "line {}", p.line);
    }
    assert_eq!(seen.len(), 36);
}

#[test]
fn a_killed_sweep_resumes_to_every_point_exactly_once() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("kink.csv");
    let args = ["--fake-delay-ms", "20"];

    // 36 points x 20 ms on 2 threads take about 0.36 s: kill once a few are in the file.
    let mut child = phase_diagram(&out, KI, &args).spawn().unwrap();
    let start = Instant::now();
    while finished_points(&out) < 6 {
        assert!(start.elapsed() < Duration::from_secs(60), "no points written within 60 s");
        sleep(Duration::from_millis(2));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let after_kill = finished_points(&out);
    assert!(
        (6..36).contains(&after_kill),
        "the kill should leave some but not all points, found {after_kill}"
    );

    // What a kill in the middle of a write would leave: half a line.
    fs::OpenOptions::new().append(true).open(&out).unwrap().write_all(b"5,5,1.0,12.0,tran").unwrap();

    let resumed = run(&mut phase_diagram(&out, KI, &args));
    let stderr = String::from_utf8_lossy(&resumed.stderr);
    assert!(resumed.status.success(), "{stderr}");
    assert!(
        stderr.contains(&format!(
            "36 points: {} computed now (0 failed), {after_kill} already done",
            36 - after_kill
        )),
        "{stderr}"
    );
    assert!(stderr.contains("cut off an unfinished last line (17 bytes)"), "{stderr}");
    assert_every_point_once(&out);

    // A third run has nothing to do and leaves the file as it is.
    let before = fs::read(&out).unwrap();
    let again = run(&mut phase_diagram(&out, KI, &args));
    assert!(again.status.success());
    assert!(String::from_utf8_lossy(&again.stderr).contains("0 computed now (0 failed), 36 already done"));
    assert_eq!(fs::read(&out).unwrap(), before);
}

/// Sends `signal` (a name `kill` knows: INT, TERM) to the process `pid`.
fn send(signal: &str, pid: u32) {
    let status = Command::new("kill").arg(format!("-{signal}")).arg(pid.to_string()).status().unwrap();
    assert!(status.success(), "kill -{signal} {pid}");
}

#[test]
fn a_signal_lets_the_points_in_progress_finish_and_says_how_many_are_saved() {
    for (signal, status) in [("INT", 130), ("TERM", 143)] {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("kink.csv");
        // 36 points x 100 ms on 2 threads: the signal comes with two points in progress.
        let args = ["--fake-delay-ms", "100"];
        let child = phase_diagram(&out, KI, &args).spawn().unwrap();
        let start = Instant::now();
        while finished_points(&out) < 4 {
            assert!(start.elapsed() < Duration::from_secs(60), "no points written within 60 s");
            sleep(Duration::from_millis(2));
        }
        send(signal, child.id());
        let stopped = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&stopped.stderr);
        assert_eq!(stopped.status.code(), Some(status), "SIG{signal}: {stderr}");
        let saved = finished_points(&out);
        assert!((4..36).contains(&saved), "SIG{signal}: {saved} points saved");
        // Every point started was finished: the file ends with a whole line, and the message
        // gives the count the file holds.
        assert!(fs::read(&out).unwrap().ends_with(b"\n"));
        let message = format!(
            "phase-diagram: stopped by SIG{signal}: stopped before the end: {saved} of the 36 points are in {}, \
             {saved} of them computed by this run; run the same sweep again to compute the other {}",
            out.display(),
            36 - saved
        );
        assert!(stderr.contains(&message), "SIG{signal}: {stderr}");
        assert!(stderr.contains("finishing the points in progress"), "{stderr}");

        // Run again: only the rest is computed, and every point is there once.
        let resumed = run(&mut phase_diagram(&out, KI, &["--fake-delay-ms", "0"]));
        let stderr = String::from_utf8_lossy(&resumed.stderr);
        assert!(resumed.status.success(), "{stderr}");
        assert!(stderr.contains(&format!("{} computed now (0 failed), {saved} already done", 36 - saved)));
        assert_every_point_once(&out);
    }
}

#[test]
fn a_second_signal_stops_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("kink.csv");
    // Points of 5 s: the first signal would wait for the two in progress, the second does not.
    let child = phase_diagram(&out, KI, &["--fake-delay-ms", "5000"]).spawn().unwrap();
    let start = Instant::now();
    while !fs::read(&out).is_ok_and(|b| b.iter().filter(|&&c| c == b'\n').count() >= 2) {
        assert!(start.elapsed() < Duration::from_secs(60), "no preamble within 60 s");
        sleep(Duration::from_millis(2));
    }
    // The workers take their first points as soon as the file is ready; a second's wait makes
    // sure the first signal finds them in progress even on a loaded machine (a signal before any
    // point started would stop the sweep at once, with nothing to wait for).
    sleep(Duration::from_secs(1));
    send("INT", child.id());
    let first = Instant::now();
    sleep(Duration::from_millis(200));
    send("INT", child.id());
    let stopped = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&stopped.stderr);
    assert_eq!(stopped.status.code(), Some(130), "{stderr}");
    assert!(stderr.contains("SIGINT: stopping now"), "{stderr}");
    assert!(first.elapsed() < Duration::from_secs(3), "the second signal should not wait for the points");
    assert_eq!(finished_points(&out), 0);
}

#[test]
fn a_file_of_another_grid_or_chain_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("kink.csv");
    let args = ["--fake-delay-ms", "0"];
    assert!(run(&mut phase_diagram(&out, KI, &args)).status.success());
    let before = fs::read(&out).unwrap();

    let refused = [
        (phase_diagram(&out, "0.1:1:7", &args), "belongs to another grid"),
        // The header's `x=0.1:1.0:6` is the same for the log axis (it carries no `:log`); the
        // hash of the values tells them apart.
        (phase_diagram(&out, "0.1:1:6:log", &args), "belongs to another grid"),
        (phase_diagram(&out, KI, &["--fake-delay-ms", "0", "--theta-bar", "0.3"]), "belongs to another run"),
        (phase_diagram(&out, KI, &[]), "belongs to another run"),
    ];
    for (mut command, expected) in refused {
        let output = run(&mut command);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{stderr}");
        assert!(stderr.contains(expected) && stderr.contains("kink.csv"), "{stderr}");
        assert_eq!(fs::read(&out).unwrap(), before, "a refused run must not touch the file");
    }
}
