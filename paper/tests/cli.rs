//! The `paper` command: bad input refused before anything is written, `--list`, a full run on
//! synthetic figures (`--demo`), and the render → CSV → summary round trip through the library.

use std::fs;
use std::path::Path;
use std::process::{Command, Stdio};

use chain_paper::{Chart, Figure, Heatmap, Panel, Quantity, Row, Series, Style, data, render, summary};

/// Run `paper` with `args`: exit code, stdout, stderr.
fn paper(args: &[&str]) -> (Option<i32>, String, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_paper")).args(args).stdin(Stdio::null()).output().unwrap();
    let text = |bytes: Vec<u8>| String::from_utf8_lossy(&bytes).into_owned();
    (output.status.code(), text(output.stdout), text(output.stderr))
}

#[test]
fn an_unknown_label_is_refused_with_the_nearest_one() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    let (code, _, stderr) = paper(&["--demo", "--out", out, "--only", "fig:demo-lines,demo-mpas"]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("unknown figure `demo-mpas`; did you mean `fig:demo-maps`?"), "{stderr}");
    assert!(!Path::new(out).exists(), "a refused run created its output directory");

    let (code, _, stderr) = paper(&["--out", out, "--only", "fig:no-such-figure"]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("unknown figure `fig:no-such-figure`"), "{stderr}");
    // Nothing close: no suggestion (it named an unrelated figure).
    let (code, _, stderr) = paper(&["--out", out, "--only", "fig:nonexistent"]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("unknown figure `fig:nonexistent` (`paper --list` lists them)"), "{stderr}");
    assert!(!stderr.contains("did you mean"), "{stderr}");
    let (code, _, stderr) = paper(&["--demo", "--out", out, "--only", "fig:demo-lines,,fig:demo-maps"]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("empty figure label"), "{stderr}");
    assert!(!Path::new(out).exists());
}

#[test]
fn an_unwritable_output_directory_is_refused_before_computing() {
    let (code, stdout, stderr) = paper(&["--demo", "--out", "/proc/forbidden"]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("cannot create the output directory /proc/forbidden"), "{stderr}");
    assert!(stdout.is_empty() && !stderr.contains("fig:demo-lines:"), "it computed figures:\n{stderr}");

    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("a-file");
    fs::write(&file, "").unwrap();
    let (code, _, stderr) = paper(&["--demo", "--out", file.to_str().unwrap()]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("cannot create the output directory"), "{stderr}");
}

#[test]
fn list_prints_one_label_per_line() {
    let (code, stdout, _) = paper(&["--demo", "--list"]);
    assert_eq!(code, Some(0));
    assert_eq!(stdout, "fig:demo-lines\nfig:demo-maps\nfig:demo-fails\n");
    let (code, stdout, _) = paper(&["--list"]);
    assert_eq!(code, Some(0));
    assert!(stdout.lines().all(|l| l.starts_with("fig:")), "{stdout}");
}

#[test]
fn a_run_writes_every_figure_and_reports_the_failed_one() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let (code, stdout, stderr) = paper(&["--demo", "--quick", "--out", out.to_str().unwrap()]);
    assert_eq!(code, Some(3), "{stderr}");
    assert!(stderr.contains("fig:demo-fails: FAILED"), "{stderr}");
    assert!(stdout.starts_with("paper: 2 figures, 3 summary rows, 1 failed, "), "{stdout}");
    for name in ["demo-lines", "demo-maps"] {
        assert!(fs::read(out.join(format!("{name}.png"))).unwrap().starts_with(b"\x89PNG\r\n\x1a\n"));
        assert!(fs::read_to_string(out.join(format!("{name}.svg"))).unwrap().contains("<svg"));
        let panels = if name == "demo-maps" { 3 } else { 2 };
        for panel in 0..panels {
            assert!(out.join("data").join(format!("{name}_{panel}.csv")).is_file());
        }
    }
    assert!(!out.join("demo-fails.png").exists());
    let summary = fs::read_to_string(out.join("summary.md")).unwrap();
    assert_eq!(summary.lines().filter(|l| l.starts_with("| fig:")).count(), 3, "{summary}");
    assert!(
        summary.contains("- `fig:demo-fails`: synthetic points: 0 resolved, at least 2 needed"),
        "{summary}"
    );
    let hidden: Vec<_> = fs::read_dir(&out)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().starts_with('.'))
        .collect();
    assert!(hidden.is_empty(), "temporary or probe files left: {hidden:?}");

    let (code, stdout, stderr) =
        paper(&["--demo", "--quick", "--out", out.to_str().unwrap(), "--only", "demo-maps"]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stdout.starts_with("paper: 1 figures, 1 summary rows, 0 failed, "), "{stdout}");
}

/// A figure with both kinds of panel and awkward data: a name with a comma, a non-finite point,
/// a log axis with non-positive values.
fn synthetic() -> Figure {
    let points: Vec<(f64, f64)> = (0..50).map(|i| (i as f64 * 0.1, (i as f64 * 0.3).sin())).collect();
    Figure {
        label: "fig:roundtrip",
        caption: "A synthetic figure for the round trip.".into(),
        panels: vec![
            Chart::Lines(Panel {
                title: "lines".into(),
                x_label: "rotor index i".into(),
                y_label: "theta (rad)".into(),
                series: vec![
                    Series::new(Quantity::Rotor, "sin, sampled", points.clone(), Style::LinePoints),
                    Series::new(
                        Quantity::Spring,
                        "gap",
                        vec![(0.0, 1.0), (1.0, f64::NAN), (2.0, -3.0)],
                        Style::Dashed,
                    ),
                ],
                log_y: true,
            }),
            Chart::Heat(Heatmap {
                title: "map".into(),
                x_label: "x (a)".into(),
                y_label: "t (s)".into(),
                x: vec![0.0, 1.0, 2.0],
                y: vec![0.0, 0.5],
                values: vec![vec![0.0, 1.0, 2.0], vec![f64::NAN, 4.0, 5.0]],
                categories: Vec::new(),
                value_label: "energy (J)".into(),
                log_x: false,
                colour_limit: None,
            }),
        ],
        rows: vec![Row::number("a number", "2.0", 2.2, Some(2.1), "")],
    }
}

#[test]
fn a_figure_round_trips_through_render_csv_and_summary() {
    let dir = tempfile::tempdir().unwrap();
    let figure = synthetic();
    let files = render::render(&figure, dir.path()).unwrap();
    assert_eq!(files, vec![dir.path().join("roundtrip.png"), dir.path().join("roundtrip.svg")]);
    let png = fs::read(&files[0]).unwrap();
    let size = |at: usize| u32::from_be_bytes(png[at..at + 4].try_into().unwrap());
    assert_eq!(size(16), 2 * render::CELL.0, "two panels side by side");
    assert!(size(20) > render::CELL.1, "one row of panels below the caption");

    let csvs = data::write_csv(&figure, &dir.path().join("data")).unwrap();
    assert_eq!(csvs.len(), 2);
    let lines = fs::read_to_string(&csvs[0]).unwrap();
    let mut read: Vec<(String, f64, f64)> = Vec::new();
    for line in lines.lines().skip(1) {
        // The only quoted field here is the first.
        let (name, rest) = match line.strip_prefix('"') {
            Some(quoted) => quoted.split_once("\",").unwrap(),
            None => line.split_once(',').unwrap(),
        };
        let (x, y) = rest.split_once(',').unwrap();
        read.push((name.to_owned(), x.parse().unwrap(), y.parse().unwrap()));
    }
    let Chart::Lines(panel) = &figure.panels[0] else { unreachable!() };
    let expected: Vec<(String, f64, f64)> =
        panel.series.iter().flat_map(|s| s.points.iter().map(|&(x, y)| (s.name.clone(), x, y))).collect();
    assert_eq!(read.len(), expected.len());
    for (r, e) in read.iter().zip(&expected) {
        assert!(r.0 == e.0 && r.1 == e.1 && (r.2 == e.2 || (r.2.is_nan() && e.2.is_nan())), "{r:?} != {e:?}");
    }
    let map = fs::read_to_string(&csvs[1]).unwrap();
    assert_eq!(map.lines().next(), Some("x,y,value"));
    assert_eq!(map.lines().count(), 1 + 6);
    assert!(map.contains("\n0,0.5,NaN\n"), "{map}");

    let rows: Vec<_> = figure.rows.iter().map(|r| (figure.label, r.clone())).collect();
    let path = summary::write_summary(dir.path(), &rows, chain_paper::Quality::Quick, &[]).unwrap();
    let text = fs::read_to_string(path).unwrap();
    assert!(text.contains("| fig:roundtrip | a number | 2.0 | 2.2 | 2.1 | 10.00 |  |"), "{text}");
}

/// Our temporary files in `dir` and `dir/data`.
fn temporaries(dir: &Path) -> Vec<String> {
    [dir.to_owned(), dir.join("data")]
        .iter()
        .filter_map(|d| fs::read_dir(d).ok())
        .flatten()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|name| name.starts_with('.') && name.ends_with(".tmp"))
        .collect()
}

/// Wait (at most a minute) until `ready`.
fn wait_until(mut ready: impl FnMut() -> bool) {
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    while !ready() {
        assert!(std::time::Instant::now() < deadline, "timed out");
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
}

/// Every PNG in `dir` is whole: it starts with the signature and ends with the IEND chunk.
fn every_png_is_complete(dir: &Path) {
    for entry in fs::read_dir(dir).unwrap().filter_map(|e| e.ok()) {
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.ends_with(".png") {
            let bytes = fs::read(entry.path()).unwrap();
            assert!(
                bytes.starts_with(b"\x89PNG\r\n\x1a\n") && bytes.ends_with(b"IEND\xae\x42\x60\x82"),
                "{name}"
            );
        }
    }
}

/// A run interrupted by SIGTERM, SIGINT or SIGHUP while its writes are in flight exits with
/// 128 + the signal, having finished those writes: no temporary file, every file complete.
#[cfg(unix)]
#[test]
fn a_signal_stops_the_run_leaving_no_temporary_file() {
    for (signal, code) in [("TERM", 143), ("INT", 130), ("HUP", 129)] {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let child = Command::new(env!("CARGO_BIN_EXE_paper"))
            .args(["--demo", "--quick", "--demo-pause-writes", "1500", "--out", out.to_str().unwrap()])
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Interrupt while a temporary file exists: a write is in flight.
        wait_until(|| !temporaries(&out).is_empty());
        let sent =
            Command::new("kill").arg(format!("-{signal}")).arg(child.id().to_string()).status().unwrap();
        assert!(sent.success());
        let output = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(code), "SIG{signal}: {stderr}");
        assert!(stderr.contains(&format!("paper: interrupted by SIG{signal}")), "{stderr}");
        assert!(output.stdout.is_empty(), "an interrupted run printed its report");
        assert_eq!(temporaries(&out), Vec::<String>::new(), "SIG{signal} left temporaries");
        every_png_is_complete(&out);
    }
}

/// kill -9 cannot be handled: the run leaves its temporaries, and the next run into the folder
/// removes them, and only them (not a live run's, not a file of someone else's).
#[cfg(unix)]
#[test]
fn the_next_run_removes_what_a_killed_run_left() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let mut child = Command::new(env!("CARGO_BIN_EXE_paper"))
        .args(["--demo", "--quick", "--demo-pause-writes", "60000", "--out", out.to_str().unwrap()])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    wait_until(|| !temporaries(&out).is_empty());
    child.kill().unwrap();
    child.wait().unwrap();
    let left = temporaries(&out);
    assert!(!left.is_empty(), "kill -9 left nothing to clean");
    let live = format!(".x.png.paper-{}-0.tmp", std::process::id());
    for name in [live.as_str(), ".notes.tmp"] {
        fs::write(out.join(name), "not paper's to remove").unwrap();
    }
    let (code, _, stderr) =
        paper(&["--demo", "--quick", "--only", "demo-lines", "--out", out.to_str().unwrap()]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stderr.contains(&format!("removed {} temporary file(s)", left.len())), "{stderr}");
    let mut remaining = temporaries(&out);
    remaining.sort();
    assert_eq!(remaining, vec![".notes.tmp".to_owned(), live]);
}

/// Every exit status the binary documents in `--help` is the one docs/paper.md lists, and the
/// binary exits with each where it says (the signals' in the test above).
#[test]
fn exit_codes_are_documented_and_kept() {
    let (code, help, _) = paper(&["--help"]);
    assert_eq!(code, Some(0));
    let listed = |text: &str, pattern: fn(&str) -> Option<u8>| -> Vec<u8> {
        text.lines().filter_map(pattern).collect()
    };
    let in_help = listed(&help, |line| {
        let mut words = line.split_whitespace();
        let code = words.next()?.parse().ok()?;
        words.next().map(|_| code)
    });
    let docs = fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/paper.md")).unwrap();
    let section = docs.split("### Exit status").nth(1).expect("docs/paper.md has an exit-status section");
    let in_docs = listed(section.split("\n#").next().unwrap(), |line| {
        line.strip_prefix("| ")?.split(" |").next()?.trim().parse().ok()
    });
    assert_eq!(in_help, vec![0, 1, 2, 3, 129, 130, 143]);
    assert_eq!(in_docs, in_help, "docs/paper.md and --help list different exit codes");

    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    assert_eq!(paper(&["--demo", "--quick", "--only", "demo-lines", "--out", out]).0, Some(0));
    assert_eq!(paper(&["--demo", "--out", "/proc/forbidden"]).0, Some(1));
    assert_eq!(paper(&["--demo", "--no-such-flag"]).0, Some(2));
    assert_eq!(paper(&["--demo", "--only", "nothing", "--out", out]).0, Some(2));
    assert_eq!(paper(&["--demo-pause-writes", "5"]).0, Some(2), "a test flag without --demo");
    assert_eq!(paper(&["--demo", "--quick", "--out", out]).0, Some(3));
}
