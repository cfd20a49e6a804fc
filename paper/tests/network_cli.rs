//! The `network` command: the issue's subcommands, JSON keys and exit statuses.

use std::path::Path;
use std::process::{Command, Output};

fn network(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_network")).args(args).output().expect("the network binary runs")
}

fn json(out: &Output) -> serde_json::Value {
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("JSON on stdout")
}

fn ready(dir: &Path, name: &str, params: &[&str]) -> String {
    let mut args = vec!["cell", name];
    args.extend_from_slice(params);
    let out = network(&args);
    assert!(out.status.success());
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, &out.stdout).unwrap();
    path.to_string_lossy().into_owned()
}

#[test]
fn counts_winding_and_strip_print_the_issue_keys() {
    let dir = tempfile::tempdir().unwrap();
    let kagome = ready(dir.path(), "kagome", &[]);
    let v = json(&network(&["counts", &kagome, "--cells", "4x4", "--boundary", "periodic", "--json"]));
    assert_eq!((v["zero_modes"].as_u64(), v["self_stresses"].as_u64()), (Some(12), Some(12)));
    let v = json(&network(&["counts", &kagome, "--cells", "3x3", "--boundary", "free", "--json"]));
    assert_eq!(v["self_stresses"].as_u64(), Some(0));
    // No self-stress: the index theorem gives the zero modes.
    assert_eq!(v["zero_modes"].as_u64().unwrap(), v["dof"].as_u64().unwrap() - v["bonds"].as_u64().unwrap());
    assert_eq!(v["dof"].as_u64(), Some(54));

    let dk = ready(dir.path(), "deformed-kagome", &["0.1", "0.1", "-0.1", "0"]);
    let v = json(&network(&["winding", &dk, "--json"]));
    assert_eq!(v["winding"], serde_json::json!([-1, -1]));
    let p: Vec<f64> = v["polarization"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    assert!((p[0] - 1.0).abs() < 1e-9 && (p[1] - 1.0).abs() < 1e-9, "{p:?}");

    let v = json(&network(&["strip", &dk, "--along", "1", "--cells", "24", "--json"]));
    assert_eq!(v["edge_zero_modes"], serde_json::json!({"low": 1, "high": 3}));
    assert_eq!(v["q"].as_f64(), Some(2.0));

    let chain = ready(dir.path(), "rotor-chain", &["1", "0.8", "0.58"]);
    let v = json(&network(&["counts", &chain, "--cells", "10", "--boundary", "free", "--json"]));
    assert_eq!((v["zero_modes"].as_u64(), v["self_stresses"].as_u64()), (Some(1), Some(0)));
    let v = json(&network(&["winding", &chain, "--json"]));
    assert_eq!(v["winding"].as_array().unwrap().len(), 1);
}

#[test]
fn bad_input_exits_2_and_gapless_exits_3() {
    let dir = tempfile::tempdir().unwrap();
    let kagome = ready(dir.path(), "kagome", &[]);
    let out = network(&["counts", &kagome, "--cells", "2x4", "--boundary", "periodic", "--json"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("at least 3 cells"));
    let out = network(&["winding", &kagome, "--json"]);
    assert_eq!(out.status.code(), Some(3));
    assert!(String::from_utf8_lossy(&out.stderr).contains("winding undefined"));
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "dimension = 2\nlattice = [[1.0, 0.0], [0.0, 1.0]]\n[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [0, 0]\n[[bond]]\nfrom = \"a\"\nto = \"b\"\n").unwrap();
    let out = network(&["counts", bad.to_str().unwrap(), "--cells", "3x3", "--boundary", "free"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("line 9") && err.contains("bond[0].to"), "{err}");
    // A cell that is not square has no winding: exit 2.
    let open = dir.path().join("open.toml");
    std::fs::write(&open, "dimension = 2\nlattice = [[1.0, 0.0], [0.0, 1.0]]\n[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [0, 0]\n[[bond]]\nfrom = \"a\"\nto = \"a\"\ncell = [1, 0]\n").unwrap();
    let out = network(&["winding", open.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("square"));
    let out = network(&["counts", &kagome, "--cells", "4", "--boundary", "free"]);
    assert_eq!(out.status.code(), Some(2));
}

/// `network cell square | head -0`: the command ends quietly (SIGPIPE), never with a panic.
#[cfg(unix)]
#[test]
fn a_reader_that_goes_away_ends_network_quietly() {
    use std::os::unix::process::ExitStatusExt;
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = Command::new(env!("CARGO_BIN_EXE_network"))
        .args(["cell", "square"])
        .stdout(writer)
        .output()
        .expect("the network binary runs");
    assert_eq!(out.status.signal(), Some(libc::SIGPIPE), "{:?}", out.status);
    assert!(out.stderr.is_empty(), "{}", String::from_utf8_lossy(&out.stderr));
}

/// Starts `network args`, sends `signal` after `after`, and returns the exit status and stderr; a
/// process still running a minute after the signal fails the test (killed first).
#[cfg(unix)]
fn interrupted(args: &[&str], signal: libc::c_int, after: std::time::Duration) -> (Option<i32>, String) {
    use std::io::Read;
    use std::process::Stdio;
    use std::time::{Duration, Instant};
    let mut child = Command::new(env!("CARGO_BIN_EXE_network"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the network binary runs");
    std::thread::sleep(after);
    assert!(
        child.try_wait().unwrap().is_none(),
        "{args:?} ended before the signal: pick a longer computation"
    );
    // SAFETY: `kill` with the pid of our own child and a valid signal number.
    assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, signal) }, 0);
    let deadline = Instant::now() + Duration::from_secs(60);
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if Instant::now() > deadline {
            child.kill().unwrap();
            panic!("{args:?} still running a minute after signal {signal}");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let mut stderr = String::new();
    child.stderr.take().unwrap().read_to_string(&mut stderr).unwrap();
    (status.code(), stderr)
}

/// SIGTERM and SIGINT stop a long count (a free kagome patch of 50 x 50 cells, 15 000 degrees
/// of freedom: the sparse path) and a phase diagram, with 128 + the signal; the diagram's
/// results file keeps only whole records, which a rerun resumes from.
#[cfg(unix)]
#[test]
fn signals_stop_a_long_count_and_a_diagram() {
    let dir = tempfile::tempdir().unwrap();
    let kagome = ready(dir.path(), "kagome", &[]);
    let second = std::time::Duration::from_millis(1500);
    let (code, stderr) =
        interrupted(&["counts", &kagome, "--cells", "50x50", "--boundary", "free"], libc::SIGTERM, second);
    assert_eq!(code, Some(143), "{stderr}");
    assert!(stderr.contains("network: interrupted by SIGTERM"), "{stderr}");

    let out = dir.path().join("diagram");
    let args = ["diagram", "--x1=-0.2:0.2:300", "--x2=-0.2:0.2:300", "--out", out.to_str().unwrap()];
    let (code, stderr) = interrupted(&args, libc::SIGINT, second);
    assert_eq!(code, Some(130), "{stderr}");
    assert!(stderr.contains("network: interrupted by SIGINT"), "{stderr}");
    let text = std::fs::read_to_string(out.join("diagram.csv")).unwrap();
    assert!(text.ends_with('\n'), "a record cut short: {:?}", &text[text.len().saturating_sub(80)..]);
    let records = text.lines().filter(|l| !l.starts_with('#') && !l.starts_with("i,")).count();
    assert!(records > 0 && records < 300 * 300, "{records} records");
    for line in text.lines().filter(|l| !l.starts_with('#') && !l.starts_with("i,")) {
        assert_eq!(line.split(',').count(), 11, "{line}");
    }
}
