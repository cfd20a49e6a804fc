//! The numbers behind each figure as CSV, one file per panel, and the atomic write every output
//! of the `paper` binary goes through.
//!
//! A line panel is written in long format, one row per point, so curves of different lengths
//! share one file:
//!
//! ```text
//! series,x,y
//! "kink, n = 60",0,0.58
//! ```
//!
//! A heat map is written one row per cell, `x,y,value`, with a fourth column `category` (the
//! name of the value) when the map is categorical. Numbers are Rust's shortest round-trip form,
//! so reading a file back gives the figure's `f64`s exactly; text is quoted as RFC 4180 says.

use std::fmt::Write as _;
use std::fs::{self, File};
use std::io::{self, Write as _};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::model::{Chart, Figure, Heatmap, Panel};

/// A file that could not be written, and why.
#[derive(Debug, thiserror::Error)]
#[error("cannot write {}: {source}", path.display())]
pub struct WriteError {
    pub path: PathBuf,
    #[source]
    pub source: io::Error,
}

/// The file stem of a figure's outputs: its label without the `fig:` prefix (`fig:kcobweb` →
/// `kcobweb`).
pub fn file_stem(label: &str) -> &str {
    label.strip_prefix("fig:").unwrap_or(label)
}

/// The CSV file of panel `index` (counted from 0) of the figure labelled `label`, in `dir`.
pub fn csv_path(dir: &Path, label: &str, index: usize) -> PathBuf {
    dir.join(format!("{}_{index}.csv", file_stem(label)))
}

/// Write one CSV per panel of `figure` into `dir` (created if missing): `<name>_<index>.csv`, see
/// [`csv_path`]. Returns the files written, in panel order. Each file is written atomically.
pub fn write_csv(figure: &Figure, dir: &Path) -> Result<Vec<PathBuf>, WriteError> {
    fs::create_dir_all(dir).map_err(|source| WriteError { path: dir.to_owned(), source })?;
    figure
        .panels
        .iter()
        .enumerate()
        .map(|(index, chart)| {
            let path = csv_path(dir, figure.label, index);
            write_atomic(&path, panel_csv(chart).as_bytes())?;
            Ok(path)
        })
        .collect()
}

/// The CSV text of one panel.
pub fn panel_csv(chart: &Chart) -> String {
    match chart {
        Chart::Lines(panel) => lines_csv(panel),
        Chart::Heat(map) => heatmap_csv(map),
    }
}

fn lines_csv(panel: &Panel) -> String {
    let mut csv = String::from("series,x,y\n");
    for series in &panel.series {
        let name = quote(&series.name);
        for (x, y) in &series.points {
            writeln!(csv, "{name},{x},{y}").expect("writing to a String");
        }
    }
    csv
}

fn heatmap_csv(map: &Heatmap) -> String {
    let categorical = !map.categories.is_empty();
    let mut csv = String::from(if categorical { "x,y,value,category\n" } else { "x,y,value\n" });
    for (row, y) in map.values.iter().zip(&map.y) {
        for (value, x) in row.iter().zip(&map.x) {
            write!(csv, "{x},{y},{value}").expect("writing to a String");
            if categorical {
                let name = category_index(*value, map.categories.len()).map_or("", |i| &map.categories[i]);
                write!(csv, ",{}", quote(name)).expect("writing to a String");
            }
            csv.push('\n');
        }
    }
    csv
}

/// The category a value of a categorical map stands for: a whole number in `0..count`.
pub(crate) fn category_index(value: f64, count: usize) -> Option<usize> {
    (value >= 0.0 && value.fract() == 0.0 && value < count as f64).then_some(value as usize)
}

/// A CSV field: quoted when it holds a comma, a quote or a line break.
fn quote(field: &str) -> String {
    if field.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", field.replace('"', "\"\""))
    } else {
        field.to_owned()
    }
}

/// Write `bytes` to `path` so that a reader finds either the old file or the complete new one,
/// never a part: the bytes go to a temporary file beside it, are synced, and the temporary file
/// is renamed over `path`. On failure the temporary file is removed.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    // Unique per process and call, so parallel writers never share a temporary file.
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let error = |source| WriteError { path: path.to_owned(), source };
    let name = path.file_name().ok_or_else(|| error(io::Error::other("the path names no file")))?;
    let temp = path.with_file_name(format!(
        ".{}.{}-{}.tmp",
        name.to_string_lossy(),
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    let written = File::create(&temp)
        .and_then(|mut file| {
            file.write_all(bytes)?;
            file.sync_all()
        })
        .and_then(|()| fs::rename(&temp, path));
    written.map_err(|source| {
        let _ = fs::remove_file(&temp);
        error(source)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Series, Style};

    #[test]
    fn line_panels_are_long_format_with_quoted_names() {
        let panel = Panel {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![
                Series::new("a, \"b\"", vec![(0.0, 0.1), (1.0, -2.5e-9)], Style::Line),
                Series::new("c", vec![(2.0, f64::NAN)], Style::Points),
            ],
            log_y: false,
        };
        assert_eq!(
            panel_csv(&Chart::Lines(panel)),
            "series,x,y\n\"a, \"\"b\"\"\",0,0.1\n\"a, \"\"b\"\"\",1,-0.0000000025\nc,2,NaN\n"
        );
    }

    #[test]
    fn categorical_maps_name_each_value() {
        let map = Heatmap {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            x: vec![0.5, 1.0],
            y: vec![3.0],
            values: vec![vec![1.0, 7.0]],
            categories: vec!["reflected".into(), "transmitted".into()],
            value_label: String::new(),
        };
        assert_eq!(panel_csv(&Chart::Heat(map)), "x,y,value,category\n0.5,3,1,transmitted\n1,3,7,\n");
    }

    #[test]
    fn atomic_writes_replace_and_leave_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.csv");
        write_atomic(&path, b"old").unwrap();
        write_atomic(&path, b"new").unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "new");
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
        let missing = dir.path().join("no-such-dir").join("a.csv");
        let err = write_atomic(&missing, b"x").unwrap_err();
        assert!(err.to_string().starts_with(&format!("cannot write {}", missing.display())), "{err}");
    }
}
