//! The `paper` command: bad input refused before anything is written, `--list`, a full run on
//! synthetic figures (`--demo`), and the render → CSV → summary round trip through the library.

use std::fs;
use std::path::Path;
use std::process::{Command, Stdio};

use chain_paper::{Chart, Figure, Heatmap, Panel, Row, Series, Style, data, render, summary};

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
        for panel in 0..2 {
            assert!(out.join("data").join(format!("{name}_{panel}.csv")).is_file());
        }
    }
    assert!(!out.join("demo-fails.png").exists());
    let summary = fs::read_to_string(out.join("summary.md")).unwrap();
    assert_eq!(summary.lines().filter(|l| l.starts_with("| fig:")).count(), 3, "{summary}");
    assert!(summary.contains("- `fig:demo-fails`: the synthetic solver diverged"), "{summary}");
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
                    Series::new("sin, sampled", points.clone(), Style::LinePoints),
                    Series::new("gap", vec![(0.0, 1.0), (1.0, f64::NAN), (2.0, -3.0)], Style::Dashed),
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
            }),
        ],
        rows: vec![Row::number("a number", 2.0, 2.2, Some(2.1), "")],
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
    assert!(text.contains("| fig:roundtrip | a number | 2 | 2.2 | 2.1 | 10.00 |  |"), "{text}");
}
