//! `run_sweep` on small grids: fresh runs, resuming, repairing a cut-off line, refusing files of
//! other sweeps, recording failures.

use std::collections::HashMap;
use std::fs;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use super::*;
use crate::file::{read_points, read_results};
use crate::record::{ParseError, expect_fields, format_f64, parse_field};

/// A test record with a float and a text column (the text exercises quoting).
#[derive(Clone, Debug, PartialEq)]
struct Probe {
    value: f64,
    label: String,
}

impl Record for Probe {
    fn header() -> &'static [&'static str] {
        &["value", "label"]
    }

    fn to_fields(&self) -> Vec<String> {
        vec![format_f64(self.value), self.label.clone()]
    }

    fn from_fields(fields: &[&str]) -> Result<Self, ParseError> {
        expect_fields(fields, 2)?;
        Ok(Self { value: parse_field(fields, 0, "value")?, label: fields[1].to_owned() })
    }
}

fn probe(x: f64, y: f64) -> Result<Probe, String> {
    Ok(Probe { value: x * y + 1.0 / 3.0, label: format!("at \"{x}, {y}\"") })
}

fn grid(x: &str, y: &str) -> Grid {
    Grid::new(x.parse().unwrap(), y.parse().unwrap()).unwrap()
}

fn options() -> SweepOptions {
    let mut options = SweepOptions::new("test", "probe v1");
    options.progress = false;
    options.threads = Some(2);
    options
}

/// Every grid point must be in the file exactly once, with the value `probe` gives.
fn assert_complete(grid: &Grid, path: &Path) {
    let points = read_points::<Probe>(path).unwrap();
    let mut seen = HashMap::new();
    for p in &points {
        assert!(seen.insert(p.index, p.line).is_none(), "point {:?} twice", p.index);
        let (x, y) = grid.point(p.index.0, p.index.1).unwrap();
        assert_eq!(p.coords, (x, y));
        assert_eq!(p.outcome, probe(x, y));
    }
    assert_eq!(seen.len(), grid.len());
    assert!(fs::read(path).unwrap().ends_with(b"\n"));
}

#[test]
fn a_fresh_sweep_writes_every_point_and_reads_back() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("r.csv");
    let grid = grid("0:1:4", "-2:2:5");
    let summary = run_sweep(&grid, &path, probe, &options()).unwrap();
    assert_eq!((summary.total, summary.computed, summary.skipped, summary.failed), (20, 20, 0, 0));
    let text = fs::read_to_string(&path).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        format!("{}{}{}; run probe v1", file::FORMAT_TAG, "; grid ", grid.signature())
    );
    assert_eq!(lines.next().unwrap(), "i,j,x,y,value,label,error");
    assert_complete(&grid, &path);
    let results = read_results::<Probe>(&path).unwrap();
    assert_eq!(results.len(), 20);
    assert!(results.iter().all(|&((i, j), (x, y), ref r)| grid.point(i, j) == Some((x, y)) && Ok(r) == probe(x, y).as_ref()));

    let again =
        run_sweep(&grid, &path, |_, _| -> Result<Probe, String> { panic!("nothing to do") }, &options())
            .unwrap();
    assert_eq!((again.computed, again.skipped), (0, 20));
    assert_eq!(fs::read_to_string(&path).unwrap(), text);
}

#[test]
fn resuming_computes_only_the_missing_points_and_cuts_an_unfinished_line() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("r.csv");
    let grid = grid("0:1:3", "0:1:4");
    run_sweep(&grid, &path, probe, &options()).unwrap();
    // Keep all but the last three points, then half of the next line, as a kill mid-write leaves.
    let text = fs::read_to_string(&path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let keep = lines.len() - 3;
    let half = &lines[keep][..lines[keep].len() / 2];
    fs::write(&path, format!("{}\n{half}", lines[..keep].join("\n"))).unwrap();

    let calls = AtomicUsize::new(0);
    let counting = |x, y| {
        calls.fetch_add(1, Ordering::Relaxed);
        probe(x, y)
    };
    let summary = run_sweep(&grid, &path, counting, &options()).unwrap();
    assert_eq!((summary.computed, summary.skipped, summary.repaired_bytes), (3, 9, half.len()));
    assert_eq!(calls.into_inner(), 3);
    assert!(summary.duplicates.is_empty());
    assert_complete(&grid, &path);
}

#[test]
fn a_file_cut_inside_its_preamble_starts_afresh() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("r.csv");
    let grid = grid("0:1:2", "0:1:2");
    let preamble = file::preamble::<Probe>(&grid, "probe v1", None);
    for cut in [0, 10, preamble.find('\n').unwrap() + 1, preamble.len() - 1] {
        fs::write(&path, &preamble[..cut]).unwrap();
        let summary = run_sweep(&grid, &path, probe, &options()).unwrap();
        assert_eq!((summary.computed, summary.skipped), (4, 0), "cut at {cut}");
        assert_complete(&grid, &path);
    }
}

#[test]
fn files_of_other_sweeps_are_refused_untouched() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("r.csv");
    let grid_a = grid("0:1:3", "0:1:3");
    run_sweep(&grid_a, &path, probe, &options()).unwrap();
    let before = fs::read(&path).unwrap();

    let err = run_sweep(&grid("0:1:3", "0:2:3"), &path, probe, &options()).unwrap_err();
    assert!(
        matches!(&err, SweepError::GridMismatch { expected, found, .. } if found == &grid_a.signature() && expected != found)
    );
    assert!(err.to_string().contains("belongs to another grid"), "{err}");

    let mut other_run = options();
    other_run.run = "probe v2".to_owned();
    let err = run_sweep(&grid_a, &path, probe, &other_run).unwrap_err();
    assert!(
        matches!(&err, SweepError::RunMismatch { expected, found, .. } if expected == "probe v2" && found == "probe v1")
    );

    let err = run_sweep(&grid_a, &path, |x, y| probe(x, y).map(|p| (p.value,)), &options()).unwrap_err();
    assert!(
        matches!(&err, SweepError::HeaderMismatch { found, .. } if found == "i,j,x,y,value,label,error"),
        "{err}"
    );
    assert_eq!(fs::read(&path).unwrap(), before);

    let foreign = dir.path().join("notes.csv");
    fs::write(&foreign, "name,score\nada,3\n").unwrap();
    let err = run_sweep(&grid_a, &foreign, probe, &options()).unwrap_err();
    assert!(matches!(&err, SweepError::NotAResultsFile { found, .. } if found == "name,score"), "{err}");
    assert_eq!(fs::read_to_string(&foreign).unwrap(), "name,score\nada,3\n");
}

/// A one-column record, to have a second header.
impl Record for (f64,) {
    fn header() -> &'static [&'static str] {
        &["value"]
    }

    fn to_fields(&self) -> Vec<String> {
        vec![format_f64(self.0)]
    }

    fn from_fields(fields: &[&str]) -> Result<Self, ParseError> {
        Ok((parse_field(fields, 0, "value")?,))
    }
}

#[test]
fn failures_and_panics_are_recorded_and_can_be_retried() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("r.csv");
    let grid = grid("0:3:4", "0:1:2");
    let flaky = |x: f64, y: f64| match (x as i32, y as i32) {
        (1, 0) => Err("diverged, \"badly\"\nat t = 3".to_owned()),
        (2, 1) => panic!("boom at {x}"),
        _ => probe(x, y),
    };
    let summary = run_sweep(&grid, &path, flaky, &options()).unwrap();
    assert_eq!((summary.computed, summary.failed), (8, 2));
    let points = read_points::<Probe>(&path).unwrap();
    let failed: HashMap<_, _> =
        points.iter().filter_map(|p| Some((p.index, p.outcome.clone().err()?))).collect();
    assert_eq!(failed[&(1, 0)], "diverged, \"badly\" at t = 3");
    assert_eq!(failed[&(2, 1)].as_str(), "panicked: boom at 2");
    assert_eq!(read_results::<Probe>(&path).unwrap().len(), 6);

    let kept = run_sweep(&grid, &path, probe, &options()).unwrap();
    assert_eq!((kept.computed, kept.skipped, kept.failed_before), (0, 8, 2));

    let mut retry = options();
    retry.retry_failed = true;
    let retried = run_sweep(&grid, &path, probe, &retry).unwrap();
    assert_eq!((retried.computed, retried.skipped, retried.retried, retried.failed_before), (2, 6, 2, 0));
    assert_complete(&grid, &path);
    assert!(!dir.path().join("r.csv.rewrite").exists());
}

#[test]
fn duplicates_are_reported_and_edited_coordinates_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("r.csv");
    let grid = grid("0:1:2", "0:1:2");
    run_sweep(&grid, &path, probe, &options()).unwrap();
    let text = fs::read_to_string(&path).unwrap();
    let point_line = text.lines().nth(2).unwrap().to_owned();
    fs::write(&path, format!("{text}{point_line}\n")).unwrap();
    let summary = run_sweep(&grid, &path, probe, &options()).unwrap();
    let index = read_points::<Probe>(&path).unwrap()[0].index;
    assert_eq!((summary.computed, summary.duplicates), (0, vec![index]));

    let mut fields: Vec<&str> = point_line.split(',').collect();
    fields[2] = "0.75";
    let moved = fields.join(",");
    fs::write(&path, format!("{text}{moved}\n")).unwrap();
    let err = run_sweep(&grid, &path, probe, &options()).unwrap_err();
    assert!(
        matches!(&err, SweepError::Parse { line: 7, reason, .. } if reason.contains("but the grid has it at")),
        "{err}"
    );
    fs::write(&path, format!("{text}9,0,0.0,0.0,1.0,x,\n")).unwrap();
    let err = run_sweep(&grid, &path, probe, &options()).unwrap_err();
    assert!(
        matches!(&err, SweepError::Parse { reason, .. } if reason.contains("outside the 2 x 2 grid")),
        "{err}"
    );
}

#[test]
fn a_locked_file_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("r.csv");
    let holder = open_locked(&path).unwrap();
    let err = run_sweep(&grid("0:1:2", "0:1:2"), &path, probe, &options()).unwrap_err();
    assert!(matches!(err, SweepError::Locked { .. }), "{err}");
    drop(holder);
    run_sweep(&grid("0:1:2", "0:1:2"), &path, probe, &options()).unwrap();
}

#[test]
fn unusable_record_columns_are_refused() {
    struct Clash;
    impl Record for Clash {
        fn header() -> &'static [&'static str] {
            &["energy", "error"]
        }
        fn to_fields(&self) -> Vec<String> {
            Vec::new()
        }
        fn from_fields(_: &[&str]) -> Result<Self, ParseError> {
            Ok(Clash)
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("r.csv");
    let err =
        run_sweep(&grid("0:1:2", "0:1:2"), &path, |_, _| Ok::<_, String>(Clash), &options()).unwrap_err();
    assert!(matches!(&err, SweepError::InvalidRecord { reason } if reason.contains("`error`")), "{err}");
    assert!(!path.exists());
}

#[test]
fn an_unwritable_path_is_an_io_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("missing").join("r.csv");
    let err = run_sweep(&grid("0:1:2", "0:1:2"), &path, probe, &options()).unwrap_err();
    assert!(matches!(&err, SweepError::Io { action: "open", .. }), "{err}");
    assert!(err.to_string().contains("missing/r.csv"), "{err}");
}

#[test]
fn a_stop_finishes_the_points_started_and_says_how_many_the_file_holds() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("stopped.csv");
    let g = grid("0:1:8", "0:1:8");
    let stop = Arc::new(AtomicBool::new(false));
    let mut stopping = options();
    stopping.stop = Some(Arc::clone(&stop));
    // The 5th point asks for the stop: it and the points already started are written, no later
    // one starts.
    let calls = AtomicUsize::new(0);
    let compute = |x, y| {
        if calls.fetch_add(1, Ordering::SeqCst) + 1 == 5 {
            stop.store(true, Ordering::SeqCst);
        }
        probe(x, y)
    };
    match run_sweep(&g, &path, compute, &stopping) {
        Err(SweepError::Stopped { path: p, done, total, computed }) => {
            assert_eq!((p, total, done), (path.clone(), 64, computed));
            // At most the other thread's point in progress after the 5th.
            assert!((5..=6).contains(&computed), "{computed} points computed");
            assert_eq!(computed, calls.load(Ordering::SeqCst));
            assert_eq!(read_points::<Probe>(&path).unwrap().len(), computed);
        }
        other => panic!("{other:?}"),
    }
    // A stop set before the run starts no point and leaves the file as it is.
    let before = fs::read(&path).unwrap();
    let held = read_points::<Probe>(&path).unwrap().len();
    match run_sweep(&g, &path, probe, &stopping) {
        Err(SweepError::Stopped { computed: 0, done, .. }) => assert_eq!(done, held),
        other => panic!("{other:?}"),
    }
    assert_eq!(fs::read(&path).unwrap(), before);
    // Without the stop the same sweep computes the rest.
    let summary = run_sweep(&g, &path, probe, &options()).unwrap();
    assert_eq!(summary.computed + summary.skipped, 64);
    assert_complete(&g, &path);
}

#[test]
fn a_point_is_appended_only_under_its_own_coordinates() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("r.csv");
    let grid = grid("0:1:3", "1:2:2");
    let mut file = ResultsFile::<Probe>::open(&grid, &path, &options()).unwrap();
    let (x1, y0) = grid.point(1, 0).unwrap();
    assert_eq!((x1, y0), (0.5, 1.0));
    // Computed at x = 0.0 (the coordinates of point (0, 0)) but filed as point (1, 0); then at
    // NaN, then one ulp off, then the sign of a zero: each refused with both coordinates.
    let next_up = f64::from_bits(x1.to_bits() + 1);
    for given in [(0.0, y0), (f64::NAN, y0), (next_up, y0), (x1, 2.0)] {
        let err = file.append((1, 0), given, &probe(given.0, given.1)).unwrap_err();
        match err {
            SweepError::WrongCoordinates { index, given: g, grid: at, .. } => {
                assert_eq!(index, (1, 0));
                assert_eq!((g.0.to_bits(), g.1.to_bits()), (given.0.to_bits(), given.1.to_bits()));
                assert_eq!(at, (0.5, 1.0));
            }
            other => panic!("expected WrongCoordinates, got {other}"),
        }
    }
    let err = file.append((0, 0), (-0.0, 1.0), &probe(0.0, 1.0)).unwrap_err();
    assert!(err.to_string().contains("computed at (-0, 1) but the grid"), "{err}");
    // Nothing was written, and the right coordinates are accepted.
    file.append((1, 0), (x1, y0), &probe(x1, y0)).unwrap();
    file.finish().unwrap();
    let points = read_points::<Probe>(&path).unwrap();
    assert_eq!(points.len(), 1);
    assert_eq!((points[0].index, points[0].coords), ((1, 0), (0.5, 1.0)));
}
