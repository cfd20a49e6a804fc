//! The renderer-independent description of a figure: panels of curves, heat maps and drawings of
//! the chain. Summary rows are in [`crate::row`], chain drawings in [`crate::drawing`].

pub use crate::drawing::ChainDrawing;
pub use crate::palette::Quantity;
pub use crate::row::{Comparison, Printed, Row, format_number};

/// How much work a figure does: `Full` reproduces the paper, `Quick` a coarse version (fewer
/// grid points, shorter runs) that exercises the same code in seconds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quality {
    /// Reproduce the paper: every grid and run at full size.
    Full,
    /// A coarse version in seconds.
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
    /// A solid line.
    Line,
    /// A dashed line.
    Dashed,
    /// Filled dots.
    Points,
    /// Open circles (the paper's translation-mode points, `fig:w-th`).
    OpenPoints,
    /// A line with dots at the points.
    LinePoints,
    /// Unfilled circles a little larger than [`Style::LinePoints`]'s dots: a series that lies on
    /// another (a starting guess under its converged result) stays visible around its dots.
    Rings,
}

/// One curve or set of points of a panel. Its colour is its quantity's
/// ([`Quantity::colour`]), the same in every figure.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// What it shows; sets its colour.
    pub quantity: Quantity,
    /// Legend entry (also the CSV column name); empty for no legend entry.
    pub name: String,
    /// The points `(x, y)`, in the axes' units.
    pub points: Vec<(f64, f64)>,
    /// How it is drawn.
    pub style: Style,
}

impl Series {
    /// A series of `points` `(x, y)` showing `quantity`, drawn in `style`, with legend entry `name`.
    pub fn new(quantity: Quantity, name: impl Into<String>, points: Vec<(f64, f64)>, style: Style) -> Self {
        Self { quantity, name: name.into(), points, style }
    }
}

/// A panel with axes and curves.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// Title above the panel.
    pub title: String,
    /// Axis labels with units, e.g. `"rotor index i"`, `"θ_i (rad)"`.
    pub x_label: String,
    /// Label of the y axis, with units.
    pub y_label: String,
    /// The curves.
    pub series: Vec<Series>,
    /// Logarithmic y axis.
    pub log_y: bool,
}

impl Panel {
    /// A panel on linear axes.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
        series: Vec<Series>,
    ) -> Self {
        Self { title: title.into(), x_label: x_label.into(), y_label: y_label.into(), series, log_y: false }
    }

    /// The same panel with a logarithmic y axis.
    pub fn log_y(self) -> Self {
        Self { log_y: true, ..self }
    }
}

/// A colour map over a regular grid (space-time images, phase diagrams). `values[row][col]` sits
/// at `(x[col], y[row])`. With `categories`, values are indices into it (discrete legend).
/// Continuous values of both signs are drawn with a diverging map centred on zero, others with
/// viridis (see [`crate::palette`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Heatmap {
    /// Title above the map.
    pub title: String,
    /// Label of the x axis, with units.
    pub x_label: String,
    /// Label of the y axis, with units.
    pub y_label: String,
    /// Column coordinates.
    pub x: Vec<f64>,
    /// Row coordinates.
    pub y: Vec<f64>,
    /// Values, `values[row][column]`.
    pub values: Vec<Vec<f64>>,
    /// Names of discrete values `0, 1, 2, ...` (e.g. outcomes); empty for a continuous map. A
    /// name of [`Quantity::of_category`] gets that quantity's colour.
    pub categories: Vec<String>,
    /// Label of the colour bar for a continuous map, with units.
    pub value_label: String,
    /// The `x` values are `log10` of the quantity `x_label` names; the axis is labelled with the
    /// quantity's own values (0.01, 0.1, 1, ...) at their logarithms. The data file keeps `x`.
    pub log_x: bool,
    /// The limit of a continuous map's diverging colour scale, `[-limit, limit]`, fixed by the
    /// figure (a physical scale, such as the two domains' `±θ̄`); values beyond it take its end
    /// colours and the colour bar's ends are pointed. `None`: the renderer's rule from the values.
    pub colour_limit: Option<f64>,
}

/// One panel of a figure.
#[derive(Clone, Debug, PartialEq)]
pub enum Chart {
    /// Curves on axes.
    Lines(Panel),
    /// A heat map.
    Heat(Heatmap),
    /// A drawing of the chain itself: pivots, rotors, springs coloured by their stretch.
    Chain(ChainDrawing),
    /// A drawing of a periodic network's patch: bonds, rotors, the unit cell, mode arrows.
    Network(crate::network::NetworkDrawing),
}

impl From<Panel> for Chart {
    fn from(panel: Panel) -> Self {
        Chart::Lines(panel)
    }
}

impl From<Heatmap> for Chart {
    fn from(map: Heatmap) -> Self {
        Chart::Heat(map)
    }
}

impl From<crate::network::NetworkDrawing> for Chart {
    fn from(drawing: crate::network::NetworkDrawing) -> Self {
        Chart::Network(drawing)
    }
}

impl From<ChainDrawing> for Chart {
    fn from(drawing: ChainDrawing) -> Self {
        Chart::Chain(drawing)
    }
}

/// A figure of the paper: its label, what it shows, and its panels.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// The paper's LaTeX label, e.g. `fig:kcobweb`.
    pub label: &'static str,
    /// One line: what the figure shows and with which parameters.
    pub caption: String,
    /// The panels, in reading order.
    pub panels: Vec<Chart>,
    /// Rows this figure contributes to the summary table.
    pub rows: Vec<Row>,
}
