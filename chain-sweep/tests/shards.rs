//! A sweep split over separate `phase-diagram` processes with `--shard I/N` (one of them killed and
//! resumed), joined by `phase-diagram merge`: the merged file holds every grid point once, equal
//! to the single-process sweep's, and `phase-diagram` resumes it with nothing left to do. Bad
//! shard sets are refused with the reason and nothing written; `--shard slurm` reads the job
//! array's variables or says which is missing.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::thread::sleep;
use std::time::{Duration, Instant};

use chain_sweep::read_points;
use chain_sweep::scattering::PointRecord;

const KI: &str = "0.1:1:6";
const V0: &str = "0.5:12:6";

fn phase_diagram(args: &[&str]) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_phase-diagram"));
    command.args(args).stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped());
    // A test run inside a SLURM job must not pick up its variables.
    for var in
        ["SLURM_ARRAY_TASK_ID", "SLURM_ARRAY_TASK_COUNT", "SLURM_ARRAY_TASK_MIN", "SLURM_ARRAY_TASK_MAX"]
    {
        command.env_remove(var);
    }
    command
}

/// A fake sweep of the 6 x 6 grid into `out`, with `extra` arguments.
fn fake_sweep(out: &Path, extra: &[&str]) -> Command {
    let out = out.to_str().unwrap();
    let mut args = vec!["--defect", "kink", "--ki", KI, "--v0", V0, "--threads", "1", "--out", out];
    args.extend_from_slice(extra);
    phase_diagram(&args)
}

fn run(mut command: Command) -> (Option<i32>, String) {
    let output: Output = command.output().expect("phase-diagram runs");
    (output.status.code(), String::from_utf8_lossy(&output.stderr).into_owned())
}

/// The points of a results file by index: `(coords, record or error)`.
type Points = BTreeMap<(usize, usize), ((f64, f64), Result<PointRecord, String>)>;

fn points(path: &Path) -> Points {
    let mut map = Points::new();
    for p in read_points::<PointRecord>(path).unwrap() {
        assert!(
            map.insert(p.index, (p.coords, p.outcome)).is_none(),
            "{:?} twice in {}",
            p.index,
            path.display()
        );
    }
    map
}

fn lines(path: &Path) -> usize {
    fs::read(path).unwrap_or_default().iter().filter(|&&b| b == b'\n').count()
}

fn shard_file(dir: &Path, i: usize, n: usize) -> PathBuf {
    dir.join(format!("pd.shard-{i}-of-{n}.csv"))
}

#[test]
fn shards_in_separate_processes_one_killed_and_resumed_merge_into_the_whole_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("pd.csv");
    let delay = ["--fake-delay-ms", "40"];

    // Three shards at once, each its own process; shard 1 is killed once it has written 3 of its
    // 12 points.
    let mut children: Vec<_> = (0..3)
        .map(|i| {
            let spec = format!("{i}/3");
            fake_sweep(&out, &[&delay[..], &["--shard", &spec]].concat()).spawn().unwrap()
        })
        .collect();
    let start = Instant::now();
    while lines(&shard_file(dir.path(), 1, 3)) < 2 + 3 {
        assert!(start.elapsed() < Duration::from_secs(60), "shard 1 wrote nothing within 60 s");
        sleep(Duration::from_millis(2));
    }
    children[1].kill().unwrap();
    children[1].wait().unwrap();
    for (i, child) in children.into_iter().enumerate().filter(|(i, _)| *i != 1) {
        let output = child.wait_with_output().unwrap();
        assert!(output.status.success(), "shard {i}: {}", String::from_utf8_lossy(&output.stderr));
    }
    let killed_at = lines(&shard_file(dir.path(), 1, 3)) - 2;
    assert!((3..12).contains(&killed_at), "shard 1 had {killed_at} points when killed");

    // Merging now fails: shard 1 lacks points. Nothing is written.
    let (code, stderr) = run(phase_diagram(&["merge", "--out", out.to_str().unwrap()]));
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains(&format!("{} of the 36 grid points are in no shard file", 12 - killed_at)),
        "{stderr}"
    );
    assert!(stderr.contains("unfinished shards: 1/3"), "{stderr}");
    assert!(!out.exists());

    // The killed shard resumes: only its missing points are computed.
    let (code, stderr) = run(fake_sweep(&out, &[&delay[..], &["--shard", "1/3"]].concat()));
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        stderr.contains(&format!(
            "12 points: {} computed now (0 failed), {killed_at} already done",
            12 - killed_at
        )),
        "{stderr}"
    );

    let (code, stderr) = run(phase_diagram(&["merge", "--out", out.to_str().unwrap()]));
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stderr.contains("merged 3 shards") && stderr.contains("36 points (0 failed)"), "{stderr}");

    // The same sweep in one process gives the same points.
    let whole = dir.path().join("whole.csv");
    assert_eq!(run(fake_sweep(&whole, &["--fake-delay-ms", "0"])).0, Some(0));
    let merged = points(&out);
    assert_eq!(merged.len(), 36);
    assert_eq!(merged, points(&whole));
    // The merged file has the single-process file's first two lines, and phase-diagram resumes
    // it with nothing to do.
    let head =
        |p: &Path| fs::read_to_string(p).unwrap().lines().take(2).map(str::to_owned).collect::<Vec<_>>();
    assert_eq!(head(&out), head(&whole));
    let (code, stderr) = run(fake_sweep(&out, &["--fake-delay-ms", "0"]));
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stderr.contains("0 computed now (0 failed), 36 already done"), "{stderr}");

    // Merging again replaces the merged file with the same content.
    let before = fs::read(&out).unwrap();
    assert_eq!(run(phase_diagram(&["merge", "--out", out.to_str().unwrap()])).0, Some(0));
    assert_eq!(fs::read(&out).unwrap(), before);
}

#[test]
fn real_points_merged_from_shards_equal_the_single_process_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("pd.csv");
    let sweep = |out: &Path, extra: &[&str]| {
        let out = out.to_str().unwrap();
        let mut args = vec!["--defect", "antikink", "--ki", "0.2:0.8:2", "--v0", "4:4.8:2", "--out", out];
        args.extend_from_slice(extra);
        phase_diagram(&args)
    };
    for i in 0..2 {
        let (code, stderr) = run(sweep(&out, &["--shard", &format!("{i}/2")]));
        assert_eq!(code, Some(0), "{stderr}");
    }
    let (code, stderr) = run(phase_diagram(&["merge", "--out", out.to_str().unwrap()]));
    assert_eq!(code, Some(0), "{stderr}");
    let whole = dir.path().join("whole.csv");
    assert_eq!(run(sweep(&whole, &[])).0, Some(0));
    let merged = points(&out);
    assert_eq!(merged.len(), 4);
    assert_eq!(merged, points(&whole), "records bit for bit");
}

#[test]
fn bad_shard_sets_are_refused_with_the_reason_and_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = d.join("pd.csv");
    let fast = ["--fake-delay-ms", "0"];
    for spec in ["0/2", "1/2", "0/3"] {
        assert_eq!(run(fake_sweep(&out, &[&fast[..], &["--shard", spec]].concat())).0, Some(0));
    }
    let other = d.join("other.csv");
    assert_eq!(
        run(fake_sweep(&other, &["--fake-delay-ms", "0", "--shard", "1/2", "--theta-bar", "0.3"])).0,
        Some(0)
    );
    let merge = |files: &[PathBuf], into: &Path| {
        let mut args = vec!["merge".to_owned(), "--out".to_owned(), into.to_str().unwrap().to_owned()];
        args.extend(files.iter().map(|f| f.to_str().unwrap().to_owned()));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        run(phase_diagram(&args))
    };
    let s = |i, n| shard_file(d, i, n);
    let cases: Vec<(Vec<PathBuf>, &str)> = vec![
        (vec![s(0, 2)], "1 of 2 shard files are missing: 1/2"),
        (vec![s(0, 2), s(0, 2)], "are both shard 0/2"),
        (vec![s(0, 2), s(1, 2), s(0, 3)], "every file must be a shard of the same N"),
        (vec![s(0, 2), d.join("other.shard-1-of-2.csv")], "belongs to another run"),
        (vec![d.join("missing.csv")], "cannot read"),
    ];
    for (files, expected) in cases {
        let (code, stderr) = merge(&files, &out);
        assert_eq!(code, Some(1), "{files:?}: {stderr}");
        assert!(stderr.contains(expected), "{files:?}: expected `{expected}` in {stderr}");
        assert!(!out.exists(), "{files:?}");
    }
    // Auto-discovery finds shards of 2 and of 3 beside pd.csv: not one sweep.
    let (code, stderr) = run(phase_diagram(&["merge", "--out", out.to_str().unwrap()]));
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("shard of the same N"), "{stderr}");
    // A whole sweep's file is not a shard.
    let whole = d.join("whole.csv");
    assert_eq!(run(fake_sweep(&whole, &fast)).0, Some(0));
    let (code, stderr) = merge(std::slice::from_ref(&whole), &out);
    assert_eq!(code, Some(1));
    assert!(stderr.contains("is not the file of a shard"), "{stderr}");
    // A point put into the wrong shard's file.
    let bad = d.join("bad.shard-0-of-2.csv");
    let text = fs::read_to_string(s(0, 2)).unwrap();
    let stolen = fs::read_to_string(s(1, 2)).unwrap().lines().nth(2).unwrap().to_owned();
    fs::write(&bad, format!("{text}{stolen}\n")).unwrap();
    let (code, stderr) = merge(&[bad, s(1, 2)], &out);
    assert_eq!(code, Some(1));
    assert!(stderr.contains("does not belong to shard 0/2"), "{stderr}");
    // A point filed under its index with other coordinates (k_i/k edited to 0.55): refused with
    // both coordinates, whichever shard's row it disagrees with.
    let edited = d.join("edited.shard-0-of-2.csv");
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let mut fields: Vec<String> = lines[2].split(',').map(str::to_owned).collect();
    let grid_x = fields[2].clone();
    fields[2] = "0.55".to_owned();
    lines[2] = fields.join(",");
    fs::write(&edited, lines.join("\n") + "\n").unwrap();
    let (code, stderr) = merge(&[edited, s(1, 2)], &out);
    assert_eq!(code, Some(1), "{stderr}");
    let expected = format!("was computed at (0.55, {}) but the grid", fields[3]);
    assert!(stderr.contains(&expected), "{stderr}");
    assert!(stderr.contains(&format!("has it at ({grid_x}, {})", fields[3])), "{stderr}");
    assert!(!out.exists());
    // The output must not clobber a file of another kind.
    let notes = d.join("notes.csv");
    fs::write(&notes, "name,score\n").unwrap();
    let (code, stderr) = merge(&[s(0, 2), s(1, 2)], &notes);
    assert_eq!(code, Some(1));
    assert!(stderr.contains("will not replace"), "{stderr}");
    assert_eq!(fs::read_to_string(&notes).unwrap(), "name,score\n");
    // And finally the good pair merges.
    let (code, stderr) = merge(&[s(0, 2), s(1, 2)], &out);
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(points(&out), points(&whole));
}

#[test]
fn a_shard_file_is_resumed_only_as_the_same_shard() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("pd.csv");
    assert_eq!(run(fake_sweep(&out, &["--fake-delay-ms", "0", "--shard", "0/2"])).0, Some(0));
    // Renamed to what shard 1/2 would write, it is refused as another part of the sweep.
    fs::rename(shard_file(dir.path(), 0, 2), shard_file(dir.path(), 1, 2)).unwrap();
    let (code, stderr) = run(fake_sweep(&out, &["--fake-delay-ms", "0", "--shard", "1/2"]));
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("it holds shard 0/2, this sweep computes shard 1/2"), "{stderr}");
}

#[test]
fn shard_slurm_reads_the_job_array_or_says_what_is_missing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("pd.csv");
    let with = |vars: &[(&str, &str)]| {
        let mut command = fake_sweep(&out, &["--fake-delay-ms", "0", "--shard", "slurm"]);
        command.envs(vars.iter().copied());
        run(command)
    };
    let (code, stderr) = with(&[]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("needs the environment variable SLURM_ARRAY_TASK_ID"), "{stderr}");
    let (code, stderr) = with(&[("SLURM_ARRAY_TASK_ID", "2")]);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("SLURM_ARRAY_TASK_COUNT"), "{stderr}");
    let (code, stderr) = with(&[("SLURM_ARRAY_TASK_ID", "4"), ("SLURM_ARRAY_TASK_COUNT", "4")]);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("use a contiguous range such as --array=0-3"), "{stderr}");
    let (code, stderr) = with(&[("SLURM_ARRAY_TASK_ID", "two"), ("SLURM_ARRAY_TASK_COUNT", "4")]);
    assert_eq!(code, Some(2));
    assert!(stderr.contains("SLURM_ARRAY_TASK_ID = `two` is not a whole number"), "{stderr}");
    assert!(fs::read_dir(dir.path()).unwrap().next().is_none(), "nothing written");
    let (code, stderr) = with(&[("SLURM_ARRAY_TASK_ID", "2"), ("SLURM_ARRAY_TASK_COUNT", "4")]);
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(lines(&shard_file(dir.path(), 2, 4)), 2 + 9);
}
