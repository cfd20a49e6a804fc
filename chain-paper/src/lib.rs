//! Reproduction of the paper's numerical figures (issue "one command reproduces the paper").
//!
//! Every figure is a library function that takes the parameters of the chain and of its family of
//! figures ([`figures::Params`], the paper's by default, any other chain's when changed) and
//! returns a [`Figure`]: the data of its panels (curves, heat maps, drawings of the chain),
//! renderer-independent, plus the rows of the summary table it contributes ([`Row`]). The `paper`
//! command (the repository's package `chain-paper`, `paper/`) only wires them together: it renders
//! each figure to PNG and SVG ([`render`]), writes its data as CSV ([`data`]), and the rows to
//! `summary.md` ([`summary`]), every file atomically ([`output`]). Colours come from one table,
//! quantity by quantity ([`palette`]). A phase diagram of your own sweep becomes a panel through
//! [`outcomes::OutcomeGrid`].
//!
//! Users reach this crate through the facade: `rotor-chain` with feature `figures`, as
//! `rotor_chain::paper`. Figures are named by their LaTeX labels in the paper (`fig:kcobweb`, ...).
#![deny(missing_docs)]

pub mod data;
pub mod drawing;
pub mod figures;
pub mod model;
pub mod network;
pub mod outcomes;
pub mod output;
pub mod palette;
pub mod render;
pub mod row;
pub mod summary;

pub use model::{
    ChainDrawing, Chart, Comparison, Figure, Heatmap, Panel, Printed, Quality, Quantity, Row, Series, Style,
};
