//! The results file: a CSV file whose first line identifies the sweep.
//!
//! ```text
//! # chain-sweep v1; grid x=0.01:1.0:40 y=0.5:12.0:40 fnv1a=3b5e...; run defect=kink n=60 ...
//! i,j,x,y,outcome,t_decided,kinks_final,antikinks_final,energy_error,error
//! 0,0,0.01,0.5,transmitted,31.5,1,0,2.1e-9,
//! 0,1,0.01,0.7948717948717949,,,,,,physics not wired yet
//! ```
//!
//! - Line 1, the *preamble*: [`FORMAT_TAG`], the grid's [`Grid::signature`], the caller's run
//!   label ([`crate::SweepOptions::run`]) and, in the file of one shard of a split sweep
//!   ([`crate::Shard`]), `; shard I/N`. A resumed sweep refuses a file whose grid, run or shard
//!   differs.
//! - Line 2, the header: `i,j,x,y`, the record's columns, `error`.
//! - One line per finished point, in the order points finished (not grid order). A point that
//!   failed has empty record fields and its message in `error`; a point that succeeded has an
//!   empty `error`. Floats are written so they read back bit for bit.
//! - Every line ends with `\n`; a last line without one is a write that was cut short and is not
//!   a point (the sweep cuts it off before appending).

use std::io::Read;
use std::path::Path;

use rotor_chain::allocation::try_vec;

use crate::error::SweepError;
use crate::grid::Grid;
use crate::record::{ParseError, Record, format_f64, parse_field, push_field, split_fields};
use crate::shard::Shard;

/// How line 1 of every results file starts (the `v1` is the version of this format).
pub const FORMAT_TAG: &str = "# chain-sweep v1";
const GRID_KEY: &str = "; grid ";
const RUN_KEY: &str = "; run ";
const SHARD_KEY: &str = "; shard ";
/// The leading columns of every results file, before the record's.
const INDEX_COLUMNS: [&str; 4] = ["i", "j", "x", "y"];
/// The trailing column: empty, or the point's error message.
const ERROR_COLUMN: &str = "error";

/// One line of a results file: a grid point and what computing it gave.
#[derive(Clone, Debug, PartialEq)]
pub struct Point<R> {
    /// `(i, j)`: the point is `(xs[i], ys[j])`.
    pub index: (usize, usize),
    /// The point's `(x, y)` values.
    pub coords: (f64, f64),
    /// The record, or the error message of a point that failed.
    pub outcome: Result<R, String>,
    /// The line of the file (1-based; 0 for a point computed in memory by
    /// [`crate::compute_grid`]).
    pub line: usize,
}

/// Line 1 of a results file, read back.
pub(crate) struct Preamble<'a> {
    pub grid: &'a str,
    pub run: &'a str,
    pub shard: Option<Shard>,
    /// The record's columns the file has: all of them, or those before the optional ones.
    pub columns: usize,
}

/// The two lines that start a results file, each ending in `\n`.
pub(crate) fn preamble<R: Record>(grid: &Grid, run: &str, shard: Option<Shard>) -> String {
    let shard = shard.map_or(String::new(), |s| format!("{SHARD_KEY}{s}"));
    format!(
        "{FORMAT_TAG}{GRID_KEY}{}{RUN_KEY}{}{shard}\n{}\n",
        grid.signature(),
        one_line(run),
        header_line::<R>()
    )
}

/// How a file's shard is named in messages.
pub(crate) fn shard_name(shard: Option<Shard>) -> String {
    shard.map_or("the whole grid".to_owned(), |s| format!("shard {s}"))
}

/// The run label as it is stored: one line, so control characters become spaces.
pub(crate) fn one_line(run: &str) -> String {
    run.chars().map(|c| if c.is_control() { ' ' } else { c }).collect()
}

pub(crate) fn header_line<R: Record>() -> String {
    header_line_of::<R>(R::header().len())
}

/// The header of a file with the record's first `columns` columns.
pub(crate) fn header_line_of<R: Record>(columns: usize) -> String {
    let columns: Vec<&str> =
        INDEX_COLUMNS.iter().chain(&R::header()[..columns]).chain([&ERROR_COLUMN]).copied().collect();
    columns.join(",")
}

/// The record's columns must be distinct, non-empty, CSV-safe and not the file's own columns.
pub(crate) fn check_record_header<R: Record>() -> Result<(), SweepError> {
    let reserved = INDEX_COLUMNS.iter().chain([&ERROR_COLUMN]);
    for (k, &name) in R::header().iter().enumerate() {
        let reason = if name.is_empty() {
            format!("column {k} has an empty name")
        } else if name.contains([',', '"', '\n', '\r']) {
            format!("column `{name}` contains `,`, `\"` or a line break")
        } else if reserved.clone().any(|&r| r == name) || R::header()[..k].contains(&name) {
            format!("column `{name}` appears twice (i, j, x, y and error are the file's own)")
        } else {
            continue;
        };
        return Err(SweepError::InvalidRecord { reason });
    }
    Ok(())
}

/// One complete line (with its `\n`) for point `(i, j)`.
pub(crate) fn format_point<R: Record>(
    index: (usize, usize),
    coords: (f64, f64),
    outcome: &Result<R, String>,
) -> String {
    let mut line = format!("{},{},{},{}", index.0, index.1, format_f64(coords.0), format_f64(coords.1));
    let columns = R::header().len();
    let (fields, error) = match outcome {
        Ok(record) => {
            let fields = record.to_fields();
            if fields.len() == columns {
                (fields, String::new())
            } else {
                let message = format!("the record gave {} fields for {columns} columns", fields.len());
                (vec![String::new(); columns], message)
            }
        }
        // An empty message would read back as a success.
        Err(message) if message.trim().is_empty() => (vec![String::new(); columns], "failed".to_owned()),
        Err(message) => (vec![String::new(); columns], message.clone()),
    };
    for field in fields.iter().chain([&error]) {
        line.push(',');
        push_field(&mut line, field);
    }
    line.push('\n');
    line
}

/// `line` (a point line of a file with the record's first `columns` columns) with the record's
/// missing optional columns added empty before `error`, as a file with every column has it.
pub(crate) fn with_every_column<R: Record>(line: &[u8], columns: usize) -> Vec<u8> {
    let missing = R::header().len().saturating_sub(columns);
    if missing == 0 {
        return line.to_vec();
    }
    // The error field is the last; it may be quoted, so split the line rather than search it.
    let Some(fields) = std::str::from_utf8(line).ok().and_then(|t| split_fields(t).ok()) else {
        return line.to_vec();
    };
    let (error, rest) = fields.split_last().expect("split_fields returns at least one field");
    let mut out = String::new();
    for (k, field) in rest.iter().map(|f| f.as_ref()).chain(std::iter::repeat_n("", missing)).enumerate() {
        if k > 0 {
            out.push(',');
        }
        push_field(&mut out, field);
    }
    out.push(',');
    push_field(&mut out, error);
    out.into_bytes()
}

/// The complete lines of `bytes` (each without its `\n`), numbered from 1, and the length of the
/// complete part: everything after the last `\n` is an unfinished write.
pub(crate) fn complete_lines(bytes: &[u8]) -> (impl Iterator<Item = (usize, &[u8])>, usize) {
    let complete = bytes.iter().rposition(|&b| b == b'\n').map_or(0, |p| p + 1);
    // `split` yields one empty piece after the final `\n`; `take` drops it.
    let count = bytes[..complete].iter().filter(|&&b| b == b'\n').count();
    let lines = bytes[..complete].split(|&b| b == b'\n').take(count);
    (lines.enumerate().map(|(k, line)| (k + 1, line)), complete)
}

fn text<'a>(path: &Path, line: usize, bytes: &'a [u8]) -> Result<&'a str, SweepError> {
    let text = std::str::from_utf8(bytes).map_err(|e| SweepError::Parse {
        path: path.to_owned(),
        line,
        reason: format!("not UTF-8: {e}"),
    })?;
    Ok(text.strip_suffix('\r').unwrap_or(text))
}

/// Read line 1 (the preamble) and check line 2 (the header) against `R`.
pub(crate) fn read_preamble<'a, R: Record>(
    path: &Path,
    line1: Option<&'a [u8]>,
    line2: Option<&'a [u8]>,
) -> Result<Preamble<'a>, SweepError> {
    let first = match line1 {
        Some(bytes) => text(path, 1, bytes)?,
        None => "",
    };
    let not_ours =
        || SweepError::NotAResultsFile { path: path.to_owned(), found: first.chars().take(120).collect() };
    let rest = first.strip_prefix(FORMAT_TAG).and_then(|r| r.strip_prefix(GRID_KEY)).ok_or_else(not_ours)?;
    let (grid, run) = rest.split_once(RUN_KEY).ok_or_else(not_ours)?;
    let (run, shard) = match run.rsplit_once(SHARD_KEY).map(|(run, s)| (run, s.parse::<Shard>())) {
        Some((run, Ok(shard))) => (run, Some(shard)),
        _ => (run, None),
    };
    let expected = header_line::<R>();
    let found = match line2 {
        Some(bytes) => text(path, 2, bytes)?,
        None => "",
    };
    let all = R::header().len();
    // Every column, or (a file written before the optional ones existed) those before them.
    let older = all.saturating_sub(R::optional_columns());
    let columns = if found == expected {
        all
    } else if older < all && found == header_line_of::<R>(older) {
        older
    } else {
        return Err(SweepError::HeaderMismatch { path: path.to_owned(), expected, found: found.to_owned() });
    };
    Ok(Preamble { grid, run, shard, columns })
}

/// Read one point line of a file with the record's first `columns` columns
/// ([`Preamble::columns`]). With a `grid`, the index must be inside it (and inside `shard`) and
/// the coordinates must be exactly the grid's.
pub(crate) fn parse_point<R: Record>(
    path: &Path,
    line: usize,
    bytes: &[u8],
    columns: usize,
    grid: Option<&Grid>,
    shard: Option<Shard>,
) -> Result<Point<R>, SweepError> {
    let fail = |reason: String| SweepError::Parse { path: path.to_owned(), line, reason };
    let fields = split_fields(text(path, line, bytes)?).map_err(|e| fail(e.to_string()))?;
    let fields: Vec<&str> = fields.iter().map(|f| f.as_ref()).collect();
    let expected = INDEX_COLUMNS.len() + columns + 1;
    if fields.len() != expected {
        return Err(fail(ParseError::FieldCount { expected, found: fields.len() }.to_string()));
    }
    let index = |k| parse_field::<usize>(&fields, k, INDEX_COLUMNS[k]).map_err(|e| fail(e.to_string()));
    let coord = |k| parse_field::<f64>(&fields, k, INDEX_COLUMNS[k]).map_err(|e| fail(e.to_string()));
    let (index, coords) = ((index(0)?, index(1)?), (coord(2)?, coord(3)?));
    if let Some(grid) = grid {
        let (i, j) = index;
        let (nx, ny) = (grid.xs().len(), grid.ys().len());
        let expected = grid
            .point(i, j)
            .ok_or_else(|| fail(format!("point ({i}, {j}) is outside the {nx} x {ny} grid")))?;
        if expected.0.to_bits() != coords.0.to_bits() || expected.1.to_bits() != coords.1.to_bits() {
            return Err(fail(format!(
                "point ({i}, {j}) is at ({:?}, {:?}) but the grid has it at ({:?}, {:?})",
                coords.0, coords.1, expected.0, expected.1
            )));
        }
        if let Some(shard) = shard.filter(|s| !s.contains(grid, index)) {
            return Err(fail(format!("point ({i}, {j}) does not belong to shard {shard}")));
        }
    }
    let error = fields[expected - 1];
    let outcome = if error.is_empty() {
        Ok(R::from_fields(&fields[INDEX_COLUMNS.len()..expected - 1]).map_err(|e| fail(e.to_string()))?)
    } else {
        Err(error.to_owned())
    };
    Ok(Point { index, coords, outcome, line })
}

/// Every point of a results file, in file order, failed ones included; an unfinished last line
/// (a sweep still writing, or killed) is left out. Duplicate points, which a sweep never writes,
/// are all returned.
pub fn read_points<R: Record>(path: impl AsRef<Path>) -> Result<Vec<Point<R>>, SweepError> {
    let path = path.as_ref();
    let bytes = read_file(path, &mut std::fs::File::open(path).map_err(SweepError::io("read", path))?)?;
    let (mut lines, _) = complete_lines(&bytes);
    let columns = read_preamble::<R>(path, lines.next().map(|l| l.1), lines.next().map(|l| l.1))?.columns;
    // At most one point per line, all of them held before any is parsed.
    let mut points = try_vec(bytes.iter().filter(|&&b| b == b'\n').count(), "the file's records")?;
    for (line, bytes) in lines.filter(|(_, bytes)| !bytes.is_empty()) {
        points.push(parse_point(path, line, bytes, columns, None, None)?);
    }
    Ok(points)
}

/// The bytes of `file` (at `path`), allocated fallibly for the length its metadata gives
/// (`read_to_end` fills that room first and grows it only for a file that grew meanwhile).
pub(crate) fn read_file(path: &Path, file: &mut std::fs::File) -> Result<Vec<u8>, SweepError> {
    let len = file.metadata().map_err(SweepError::io("read", path))?.len();
    let mut bytes = try_vec(usize::try_from(len).unwrap_or(usize::MAX), "a results file's bytes")?;
    file.read_to_end(&mut bytes).map_err(SweepError::io("read", path))?;
    Ok(bytes)
}

/// One row of [`read_results`]: `((i, j), (x, y), record)`.
pub type ResultRow<R> = ((usize, usize), (f64, f64), R);

/// The points that succeeded, for plotting, in file order. Failed points are left out (see
/// [`read_points`] for them).
pub fn read_results<R: Record>(path: impl AsRef<Path>) -> Result<Vec<ResultRow<R>>, SweepError> {
    let points = read_points::<R>(path)?;
    let mut rows = try_vec(points.iter().filter(|p| p.outcome.is_ok()).count(), "the file's records")?;
    rows.extend(points.into_iter().filter_map(|p| Some((p.index, p.coords, p.outcome.ok()?))));
    Ok(rows)
}
