//! Bad input to `phase-diagram`: a clear message, a non-zero exit, and no file written.

use std::fs;
use std::process::{Command, Stdio};

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
    let output = Command::new(env!("CARGO_BIN_EXE_phase-diagram"))
        .args(args.iter().flat_map(|&(flag, value)| [flag, value]))
        .stdin(Stdio::null())
        .output()
        .unwrap();
    (output.status.code(), String::from_utf8_lossy(&output.stderr).into_owned())
}

#[test]
fn bad_arguments_are_refused_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.csv");
    let out = out.to_str().unwrap();
    let cases: &[(&[(&str, &str)], &str)] = &[
        (&[("--ki", "0.1:1:0")], "an axis needs at least 1 point, got count = 0"),
        (&[("--v0", "0.5:12:-4")], "COUNT `-4` is not a whole number >= 1"),
        (&[("--v0", "0.5-12-4")], "`0.5-12-4` is not a range FROM:TO:COUNT"),
        (&[("--ki", "0.1:x:3")], "TO `x` is not a number"),
        (&[("--ki", "0.1:inf:3")], "not a finite number"),
        (&[("--ki", "0:1:3")], "every k_i/k must be > 0"),
        (&[("--ki", "-1:1:3")], "every k_i/k must be > 0"),
        (&[("--defect", "soliton")], "invalid value 'soliton' for '--defect <DEFECT>'"),
        (&[("--theta-bar", "0.7")], "outside the flipper phase"),
        (&[("--n", "1")], "`n` must be at least 2"),
        (&[("--k", "-5")], "`k` must be a finite number > 0"),
        (&[("--threads", "0")], "invalid value '0' for '--threads"),
        (&[("--ki", "0.01:1:1000"), ("--v0", "0:1:100000")], "more than the limit"),
    ];
    for &(changes, expected) in cases {
        let (code, stderr) = phase_diagram(out, changes);
        assert!(matches!(code, Some(c) if c != 0), "{changes:?}: exit {code:?}");
        assert!(stderr.contains(expected), "{changes:?}: expected `{expected}` in:\n{stderr}");
        assert!(!dir.path().join("r.csv").exists(), "{changes:?} wrote the file");
    }
}

#[test]
fn an_unwritable_output_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no-such-dir").join("r.csv");
    let (code, stderr) = phase_diagram(missing.to_str().unwrap(), &[]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("cannot open") && stderr.contains("no-such-dir/r.csv"), "{stderr}");
    assert!(!dir.path().join("no-such-dir").exists());

    let (code, stderr) = phase_diagram(dir.path().to_str().unwrap(), &[]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("cannot open"), "{stderr}");
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn a_good_fake_sweep_writes_the_phase_diagram_columns() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r.csv");
    let (code, stderr) = phase_diagram(out.to_str().unwrap(), &[("--v0", "-1:1:3")]);
    assert_eq!(code, Some(0), "{stderr}");
    let text = fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    let first = lines.next().unwrap();
    assert!(first.starts_with("# chain-sweep v1; grid x=0.1:1.0:3 y=-1.0:1.0:3 fnv1a="), "{first}");
    assert!(first.ends_with("; run defect=kink n=60 r=0.8 k=10000.0 theta_bar=0.28 physics=fake"), "{first}");
    assert_eq!(
        lines.next(),
        Some("i,j,x,y,outcome,t_decided,kinks_final,antikinks_final,energy_error,error")
    );
    assert_eq!(lines.count(), 9);
}
