//! [`merge_shards`]: the files of a split sweep ([`crate::Shard`]), joined into the results file
//! of the whole sweep.
//!
//! Nothing is written unless the shard files make up exactly one sweep: the same grid, the same
//! run label, the same number of shards `N`, every shard `0..N` once, every point in the shard it
//! belongs to, and every grid point exactly once across the files. The merged file is the one a
//! single process would have written (the same first two lines, so `phase-diagram` resumes it
//! with nothing left to do), with the points in grid order, written through a temporary file and
//! renamed into place.

use std::collections::HashMap;
use std::collections::hash_map::Entry;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

use rotor_chain::allocation::{AllocationError, bytes_of, try_filled, try_grow, try_vec};

use crate::error::SweepError;
use crate::file::{self, complete_lines, parse_point, read_preamble};
use crate::grid::{Axis, Grid, signature_dims};
use crate::record::Record;
use crate::shard::Shard;
use crate::sweep::check_regular;

/// What [`merge_shards`] wrote.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct MergeSummary {
    /// Grid points in the merged file (all of them).
    pub total: usize,
    /// Of those, points whose computation failed (their message is in the `error` column).
    pub failed: usize,
    /// The number of shards `N`.
    pub shards: usize,
    /// The run label of the sweep.
    pub run: String,
}

/// One shard file, read and checked on its own.
struct ShardFile {
    path: PathBuf,
    shard: Shard,
    grid: String,
    run: String,
    points: Vec<ShardPoint>,
}

/// One point line of a shard file.
struct ShardPoint {
    index: (usize, usize),
    coords: (f64, f64),
    failed: bool,
    /// Its line number in the file (from 1).
    line_number: usize,
    /// The line as written, without its `\n`.
    line: Vec<u8>,
}

/// Every point of the merge: its file and its line.
type Seen<'a> = HashMap<(usize, usize), (&'a Path, &'a ShardPoint)>;

fn read_shard<R: Record>(path: &Path) -> Result<ShardFile, SweepError> {
    check_regular(path)?;
    let bytes = file::read_file(path, &mut std::fs::File::open(path).map_err(SweepError::io("read", path))?)?;
    // An unfinished last line (a shard killed while writing) is not a point.
    let (mut lines, _) = complete_lines(&bytes);
    let preamble = read_preamble::<R>(path, lines.next().map(|l| l.1), lines.next().map(|l| l.1))?;
    let shard = preamble.shard.ok_or_else(|| SweepError::NotAShard { path: path.to_owned() })?;
    let (grid, run) = (preamble.grid.to_owned(), preamble.run.to_owned());
    let (nx, ny) = signature_dims(&grid).ok_or_else(|| SweepError::Parse {
        path: path.to_owned(),
        line: 1,
        reason: format!("cannot read the grid's point counts from `{grid}`"),
    })?;
    // At most one point per line.
    let mut points = try_vec(bytes.iter().filter(|&&b| b == b'\n').count(), "a shard's points")?;
    for (line, text) in lines.filter(|(_, text)| !text.is_empty()) {
        let point = parse_point::<R>(path, line, text, preamble.columns, None, None)?;
        let (i, j) = point.index;
        let fail = |reason: String| SweepError::Parse { path: path.to_owned(), line, reason };
        if i >= nx || j >= ny {
            return Err(fail(format!("point ({i}, {j}) is outside the {nx} x {ny} grid")));
        }
        if !shard.contains_position(i * ny + j) {
            return Err(fail(format!("point ({i}, {j}) does not belong to shard {shard}")));
        }
        let failed = point.outcome.is_err();
        let (index, coords, line_number) = (point.index, point.coords, line);
        // A shard written before the record's optional columns existed joins with them empty.
        let line = file::with_every_column::<R>(text, preamble.columns);
        points.push(ShardPoint { index, coords, failed, line_number, line });
    }
    Ok(ShardFile { path: path.to_owned(), shard, grid, run, points })
}

/// Join the shard files `shards` of one split sweep into `out`, the results file of the whole
/// sweep (module doc). `out` may exist only as the results file of the same sweep (a previous
/// merge), which is replaced.
pub fn merge_shards<R: Record>(shards: &[PathBuf], out: &Path) -> Result<MergeSummary, SweepError> {
    if shards.is_empty() {
        return Err(SweepError::NoShards { reason: "no files were given".to_owned() });
    }
    let files = shards.iter().map(|p| read_shard::<R>(p)).collect::<Result<Vec<_>, _>>()?;
    let first = &files[0];
    let count = first.shard.count();
    let mut by_index: Vec<Option<&Path>> = try_filled(count, None, "the merge's shard table")?;
    for f in &files {
        if f.grid != first.grid {
            let (expected, found) = (first.grid.clone(), f.grid.clone());
            return Err(SweepError::GridMismatch { path: f.path.clone(), expected, found });
        }
        if f.run != first.run {
            let (expected, found) = (first.run.clone(), f.run.clone());
            return Err(SweepError::RunMismatch { path: f.path.clone(), expected, found });
        }
        if f.shard.count() != count {
            return Err(SweepError::ShardSet {
                reason: format!(
                    "{} is shard {} but {} is shard {}: every file must be a shard of the same N",
                    f.path.display(),
                    f.shard,
                    first.path.display(),
                    first.shard
                ),
            });
        }
        if let Some(other) = by_index[f.shard.index()].replace(&f.path) {
            return Err(SweepError::ShardSet {
                reason: format!("{} and {} are both shard {}", other.display(), f.path.display(), f.shard),
            });
        }
    }
    let absent: Vec<String> =
        (0..count).filter(|&k| by_index[k].is_none()).map(|k| format!("{k}/{count}")).collect();
    if !absent.is_empty() {
        return Err(SweepError::ShardSet {
            reason: format!("{} of {count} shard files are missing: {}", absent.len(), absent.join(", ")),
        });
    }

    let (nx, ny) = signature_dims(&first.grid).unwrap_or_default();
    let total = nx * ny;
    let mut seen: Seen<'_> = HashMap::new();
    seen.try_reserve(total).map_err(|_| AllocationError {
        bytes: bytes_of::<((usize, usize), (&Path, &ShardPoint))>(total),
        what: "the merge's table of points",
    })?;
    for f in &files {
        for point in &f.points {
            match seen.entry(point.index) {
                Entry::Occupied(e) => {
                    return Err(SweepError::DuplicatePoint {
                        index: point.index,
                        first: e.get().0.to_owned(),
                        second: f.path.clone(),
                    });
                }
                Entry::Vacant(e) => {
                    e.insert((&f.path, point));
                }
            }
        }
    }
    if seen.len() != total {
        let missing: Vec<(usize, usize)> =
            (0..nx).flat_map(|i| (0..ny).map(move |j| (i, j))).filter(|ij| !seen.contains_key(ij)).collect();
        let unfinished: Vec<String> = files
            .iter()
            .filter_map(|f| {
                let lacks = missing.iter().filter(|&&(i, j)| f.shard.contains_position(i * ny + j)).count();
                (lacks > 0).then(|| format!("{} ({} lacks {lacks} points)", f.shard, f.path.display()))
            })
            .collect();
        return Err(SweepError::MissingPoints {
            missing: missing.len(),
            total,
            first: missing[0],
            unfinished: unfinished.join(", "),
        });
    }

    // The axes from the points' coordinates; their signature must be the files' (which hashes
    // every value), so every point sits exactly where the grid has it.
    let grid = rebuild_grid(&seen, (nx, ny), (&first.path, &first.grid))?;

    check_replaceable::<R>(out, &first.grid, &first.run, shards)?;
    let mut text = file::preamble::<R>(&grid, &first.run, None).into_bytes();
    let lines: usize = seen.values().map(|(_, p)| p.line.len() + 1).sum();
    try_grow(&mut text, lines, "the merged file's text")?;
    for index in grid.indices() {
        text.extend_from_slice(&seen[&index].1.line);
        text.push(b'\n');
    }
    write_atomically(out, &text)?;
    let failed = seen.values().filter(|(_, p)| p.failed).count();
    Ok(MergeSummary { total, failed, shards: count, run: first.run.clone() })
}

/// The grid of the points' coordinates. A row's x (a column's y) is the value most of its points
/// have; a point that differs is refused at its file and line ([`SweepError::Parse`]) with the
/// text of [`SweepError::WrongCoordinates`]: the point, its coordinates and those of its row and
/// column, a point filed under another point's index.
fn rebuild_grid(
    seen: &Seen<'_>,
    (nx, ny): (usize, usize),
    (first, signature): (&Path, &str),
) -> Result<Grid, SweepError> {
    let (mut x_votes, mut y_votes) = (vec![HashMap::new(); nx], vec![HashMap::new(); ny]);
    for (&(i, j), (_, point)) in seen {
        *x_votes[i].entry(point.coords.0.to_bits()).or_insert(0_usize) += 1;
        *y_votes[j].entry(point.coords.1.to_bits()).or_insert(0_usize) += 1;
    }
    // Ties go to the smaller bit pattern, so the choice does not depend on the hash order.
    let most = |votes: &HashMap<u64, usize>| {
        votes
            .iter()
            .max_by_key(|&(bits, count)| (*count, std::cmp::Reverse(*bits)))
            .map(|(b, _)| f64::from_bits(*b))
    };
    let xs: Vec<f64> = x_votes.iter().map(|v| most(v).unwrap_or(f64::NAN)).collect();
    let ys: Vec<f64> = y_votes.iter().map(|v| most(v).unwrap_or(f64::NAN)).collect();
    let mut indices: Vec<&(usize, usize)> = try_vec(seen.len(), "the merge's table of points")?;
    indices.extend(seen.keys());
    indices.sort_unstable();
    for &(i, j) in indices {
        let (path, point) = seen[&(i, j)];
        let (x, y) = point.coords;
        if xs[i].to_bits() != x.to_bits() || ys[j].to_bits() != y.to_bits() {
            let wrong = SweepError::WrongCoordinates { index: (i, j), given: (x, y), grid: (xs[i], ys[j]) };
            return Err(SweepError::Parse {
                path: path.to_owned(),
                line: point.line_number,
                reason: wrong.to_string(),
            });
        }
    }
    let unparsed = |reason: String| SweepError::Parse { path: first.to_owned(), line: 0, reason };
    let axis = |values: Vec<f64>| Axis::from_values(values).map_err(|e| unparsed(e.to_string()));
    let grid = Grid::new(axis(xs)?, axis(ys)?).map_err(|e| unparsed(e.to_string()))?;
    if grid.signature() != signature {
        return Err(unparsed(format!(
            "the points' coordinates make the grid `{}`, but the files were written for `{signature}`",
            grid.signature()
        )));
    }
    Ok(grid)
}

/// `out` must not be a shard file being merged, and may exist only as the results file of this
/// sweep (the result of an earlier merge) or be empty.
fn check_replaceable<R: Record>(
    out: &Path,
    grid: &str,
    run: &str,
    shards: &[PathBuf],
) -> Result<(), SweepError> {
    let refuse = |reason: String| SweepError::WouldOverwrite { path: out.to_owned(), reason };
    let same = |p: &PathBuf| match (p.canonicalize(), out.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => p == out,
    };
    if shards.iter().any(same) {
        return Err(refuse("it is one of the shard files being merged".to_owned()));
    }
    check_regular(out)?;
    let bytes = match std::fs::read(out) {
        Ok(bytes) => bytes,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(SweepError::io("read", out)(e)),
    };
    if bytes.is_empty() {
        return Ok(());
    }
    let (mut lines, _) = complete_lines(&bytes);
    let preamble = read_preamble::<R>(out, lines.next().map(|l| l.1), lines.next().map(|l| l.1))
        .map_err(|e| refuse(format!("it is not the results file of this sweep ({e})")))?;
    if preamble.grid != grid || preamble.run != run || preamble.shard.is_some() {
        return Err(refuse(format!(
            "it is the results file of another sweep ({}; run {}): merge into a new file",
            file::shard_name(preamble.shard),
            preamble.run
        )));
    }
    Ok(())
}

/// Write `bytes` to a temporary file beside `path`, sync it, and rename it over `path`.
fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), SweepError> {
    let mut name = path.file_name().unwrap_or_default().to_owned();
    name.push(".merging");
    let temp = path.with_file_name(name);
    let mut file = File::create(&temp).map_err(SweepError::io("create", &temp))?;
    file.write_all(bytes).map_err(SweepError::io("write to", &temp))?;
    file.sync_all().map_err(SweepError::io("sync", &temp))?;
    drop(file);
    std::fs::rename(&temp, path).map_err(SweepError::io("replace", path))
}

/// The shard files of the whole sweep's `out` (`pd.csv`: every `pd.shard-I-of-N.csv` beside it,
/// [`Shard::file_name`]), sorted by name.
pub fn find_shards(out: &Path) -> Result<Vec<PathBuf>, SweepError> {
    let dir = match out.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_owned(),
        _ => PathBuf::from("."),
    };
    let probe = Shard::new(0, 1).map_err(|e| SweepError::NoShards { reason: e.to_string() })?;
    let pattern = probe.file_name(out).file_name().unwrap_or_default().to_string_lossy().into_owned();
    let (before, after) = pattern.split_once("shard-0-of-1").unwrap_or((&pattern, ""));
    let mut found = Vec::new();
    let entries = std::fs::read_dir(&dir).map_err(SweepError::io("list", &dir))?;
    for entry in entries {
        let entry = entry.map_err(SweepError::io("list", &dir))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(middle) = name.strip_prefix(before).and_then(|r| r.strip_suffix(after)) else { continue };
        let is_shard = middle
            .strip_prefix("shard-")
            .and_then(|r| r.split_once("-of-"))
            .is_some_and(|(i, n)| i.parse::<usize>().is_ok() && n.parse::<usize>().is_ok());
        if is_shard {
            found.push(entry.path());
        }
    }
    found.sort();
    if found.is_empty() {
        return Err(SweepError::NoShards {
            reason: format!("no file named {before}shard-I-of-N{after} in {}", dir.display()),
        });
    }
    Ok(found)
}
