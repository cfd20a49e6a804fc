//! Reproduction of the paper's numerical figures (issue "one command reproduces the paper").
//!
//! Every figure is a library function that takes the chain's parameters and returns a
//! [`Figure`]: the data of its panels (curves, heat maps, drawings of the chain),
//! renderer-independent, plus the rows of the summary table it contributes ([`Row`]). The `paper`
//! binary only wires them together: it renders each figure to PNG and SVG ([`render`]), writes its
//! data as CSV ([`data`]), and the rows to `summary.md` ([`summary`]), every file atomically
//! ([`output`]). Colours come from one table, quantity by quantity ([`palette`]).
//!
//! Figures are named by their LaTeX labels in the paper (`fig:kcobweb`, ...).
#![deny(missing_docs)]

pub mod data;
pub mod drawing;
pub mod figures;
pub mod model;
pub mod outcomes;
pub mod output;
pub mod palette;
pub mod render;
pub mod row;
pub mod summary;

pub use model::{
    ChainDrawing, Chart, Comparison, Figure, Heatmap, Panel, Printed, Quality, Quantity, Row, Series, Style,
};
