//! The renderer-independent description of a figure and of a summary row.

/// How much work a figure does: `Full` reproduces the paper, `Quick` a coarse version (fewer
/// grid points, shorter runs) that exercises the same code in seconds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quality {
    Full,
    Quick,
}

impl Quality {
    /// `full` when full, `quick` otherwise: grid sizes and counts.
    pub fn pick(self, full: usize, quick: usize) -> usize {
        match self {
            Quality::Full => full,
            Quality::Quick => quick,
        }
    }
}

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    Line,
    Dashed,
    Points,
    LinePoints,
}

/// One curve or set of points of a panel.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend entry (also the CSV column name).
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
}

impl Series {
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>, style: Style) -> Self {
        Self { name: name.into(), points, style }
    }
}

/// A panel with axes and curves.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    pub title: String,
    /// Axis labels with units, e.g. `"rotor index i"`, `"theta (rad)"`.
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    /// Logarithmic y axis.
    pub log_y: bool,
}

/// A colour map over a regular grid (space-time images, phase diagrams). `values[row][col]` sits
/// at `(x[col], y[row])`. With `categories`, values are indices into it (discrete legend).
#[derive(Clone, Debug, PartialEq)]
pub struct Heatmap {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub values: Vec<Vec<f64>>,
    /// Names of discrete values `0, 1, 2, ...` (e.g. outcomes); empty for a continuous map.
    pub categories: Vec<String>,
    /// Label of the colour bar for a continuous map, with units.
    pub value_label: String,
}

/// One panel of a figure.
#[derive(Clone, Debug, PartialEq)]
pub enum Chart {
    Lines(Panel),
    Heat(Heatmap),
}

/// A figure of the paper: its label, what it shows, and its panels.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// The paper's LaTeX label, e.g. `fig:kcobweb`.
    pub label: &'static str,
    /// One line: what the figure shows and with which parameters.
    pub caption: String,
    pub panels: Vec<Chart>,
    /// Rows this figure contributes to the summary table.
    pub rows: Vec<Row>,
}

/// One row of the summary table: a number the paper states, beside ours.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// What the number is, with its parameters.
    pub quantity: String,
    /// The paper's statement (a number or a word such as "transmitted").
    pub paper: String,
    pub ours: String,
    /// The continuum theory's value where one exists.
    pub continuum: Option<String>,
    /// `|ours - paper| / |paper|` when both are numbers.
    pub relative_difference: Option<f64>,
    /// One line on why they differ, where they do.
    pub note: String,
}

impl Row {
    /// A numeric row; the relative difference is computed here.
    pub fn number(
        quantity: impl Into<String>,
        paper: f64,
        ours: f64,
        continuum: Option<f64>,
        note: impl Into<String>,
    ) -> Self {
        Self {
            quantity: quantity.into(),
            paper: format_number(paper),
            ours: format_number(ours),
            continuum: continuum.map(format_number),
            relative_difference: (paper != 0.0).then(|| ((ours - paper) / paper).abs()),
            note: note.into(),
        }
    }

    /// A row whose values are words (outcomes).
    pub fn words(quantity: impl Into<String>, paper: &str, ours: &str, note: impl Into<String>) -> Self {
        Self {
            quantity: quantity.into(),
            paper: paper.to_owned(),
            ours: ours.to_owned(),
            continuum: None,
            relative_difference: None,
            note: note.into(),
        }
    }
}

/// Six significant digits with trailing zeros dropped (the paper's 1359.15 and 1359.75, whose
/// difference is its barrier, must stay apart), scientific notation outside `[1e-3, 1e5)`.
pub fn format_number(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 {
        return "0".to_owned();
    }
    if !(1e-3..1e5).contains(&a) {
        let text = format!("{x:.5e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        return format!("{}e{exponent}", trim_zeros(mantissa));
    }
    let digits = (5 - a.log10().floor() as i32).max(0) as usize;
    trim_zeros(&format!("{x:.digits$}")).to_owned()
}

/// `1.500` -> `1.5`, `2.000` -> `2`; integers untouched.
fn trim_zeros(text: &str) -> &str {
    if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.') } else { text }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_compute_their_relative_difference() {
        let r = Row::number("barrier", 0.60, 0.668, None, "");
        assert!((r.relative_difference.unwrap() - 0.1133).abs() < 1e-3);
        assert_eq!(r.paper, "0.6");
        assert_eq!(format_number(1359.15), "1359.15");
        assert_eq!(format_number(1392.029215), "1392.03");
        assert_eq!(format_number(7.7e-9), "7.7e-9");
        assert_eq!(format_number(-10.6), "-10.6");
    }
}
