//! Reproduction of the paper's numerical figures (issue "one command reproduces the paper").
//!
//! Every figure is a library function that takes the chain's parameters and returns a
//! [`Figure`]: the data of its panels, renderer-independent, plus the rows of the summary table it
//! contributes ([`Row`]). The `paper` binary only wires them together: it renders each figure to
//! PNG and SVG ([`render`]), writes its data as CSV ([`data`]), and the rows to `summary.md`.
//!
//! Figures are named by their LaTeX labels in the paper (`fig:kcobweb`, ...).

pub mod data;
pub mod figures;
pub mod model;
pub mod render;
pub mod summary;

pub use model::{Chart, Figure, Heatmap, Panel, Quality, Row, Series, Style};
