//! The numbers behind each figure as CSV, one file per panel.
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
//! name of the value) when the map is categorical; `x` as the map holds it (`log10(k_i/k)` on a
//! phase diagram's logarithmic axis, [`Heatmap::log_x`]). A drawing of the chain is written one row per
//! drawn part, `part,index,x0,y0,x1,y1,value`: each rotor from pivot to tip (value `θ_i`), each
//! spring from tip to tip (value its stretch `(l − l0)/a`; `impurity` for an impurity spring), each
//! mode arrow (value its length) and tension bar (value its amplitude). Numbers are Rust's shortest round-trip form,
//! so reading a file back gives the figure's `f64`s exactly; text is quoted as RFC 4180 says.

use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

use crate::model::{ChainDrawing, Chart, Figure, Heatmap, Panel};
pub use crate::output::{WriteError, write_atomic};

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
        Chart::Chain(drawing) => chain_csv(drawing),
        Chart::Network(drawing) => drawing.csv(),
    }
}

fn chain_csv(d: &ChainDrawing) -> String {
    let mut csv = String::from("part,index,x0,y0,x1,y1,value\n");
    let mut row = |part: &str, index: usize, from: (f64, f64), to: (f64, f64), value: f64| {
        writeln!(csv, "{part},{index},{},{},{},{},{value}", from.0, from.1, to.0, to.1)
            .expect("writing to a String");
    };
    let first = d.rotors.start;
    for (j, ((&pivot, &tip), &angle)) in d.pivots.iter().zip(&d.tips).zip(&d.angles).enumerate() {
        row("rotor", first + j, pivot, tip, angle);
    }
    for (j, (&stretch, pair)) in d.stretch.iter().zip(d.tips.windows(2)).enumerate() {
        let part = if d.impurities.contains(&j) { "impurity" } else { "spring" };
        row(part, first + j, pair[0], pair[1], stretch);
    }
    for (j, (&tip, &(dx, dy))) in d.tips.iter().zip(&d.arrows).enumerate() {
        row("arrow", first + j, tip, (tip.0 + dx, tip.1 + dy), dx.hypot(dy));
    }
    for (j, (&amplitude, pair)) in d.tensions.iter().zip(d.tips.windows(2)).enumerate() {
        row("tension", first + j, pair[0], pair[1], amplitude);
    }
    csv
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Quantity, Series, Style};

    #[test]
    fn line_panels_are_long_format_with_quoted_names() {
        let panel = Panel {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![
                Series::new(Quantity::Rotor, "a, \"b\"", vec![(0.0, 0.1), (1.0, -2.5e-9)], Style::Line),
                Series::new(Quantity::Spring, "c", vec![(2.0, f64::NAN)], Style::Points),
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
            log_x: false,
            colour_limit: None,
        };
        assert_eq!(panel_csv(&Chart::Heat(map)), "x,y,value,category\n0.5,3,1,transmitted\n1,3,7,\n");
    }
}
