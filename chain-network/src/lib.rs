//! # chain-network
//!
//! The linear topology of periodic spring and rotor networks in one and two dimensions (issue
//! 33): a unit cell described once ([`Cell`], from the TOML cell format, a builder or a ready
//! lattice), its compatibility matrix, Maxwell-Calladine counts of finite patches (periodic or
//! free), the Bloch compatibility matrix `Q(k)` and its bands, the winding numbers of `det Q(k)`
//! and the topological polarization `R_T` (Kane and Lubensky, Nature Physics 10, 39 (2014),
//! arXiv:1308.0554, eq. 7), strips with edge zero modes, and Guest modes.
//!
//! Every convention (degrees of freedom as displacements, the bond direction, the Bloch phase,
//! the rank tolerance, the gauge of the polarization) is stated once, in the guide
//! `rotor_chain::guide::network` (`docs/network.md`), with a test each.
//!
//! | module | what |
//! | --- | --- |
//! | [`cell`] | the typed cell, its file format, builder, validation and ready cells |
//! | [`compatibility`] | the compatibility row of a bond, the dense real matrix of a patch |
//! | [`patch`] | finite `N1 x N2` patches, periodic or free |
//! | [`counts`] | zero modes and states of self-stress: ranks, vectors, the index theorem |
//! | [`bloch`] | `Q(k)`, the dynamical matrix, bands along a path |
//! | [`winding`] | winding numbers of `det Q(k)`, the cell dipole `r0`, the polarization `R_T` |
//! | [`strip`] | strips periodic along one lattice vector: zero modes per edge |
//! | [`guest`] | Guest modes: macroscopic strains at no cost |
//! | [`kernel`] | the generated per-bond kernels (energy, gradient, Hessian block, ...) |
//! | [`model`] | the nonlinear mechanics of a patch: the capability ladder on a network |
//! | [`linalg`] | the decompositions used (faer), with the rank rule |
#![deny(missing_docs)]

pub mod bloch;
pub mod cell;
pub mod compatibility;
pub mod counts;
pub mod error;
pub mod guest;
pub mod kernel;
pub mod linalg;
pub mod model;
pub mod motion;
pub mod patch;
pub mod strip;
pub mod winding;

pub use cell::{Bond, BondLaw, Cell, CellBuilder, CellDescription, Node, NodeKind, Polynomial};
pub use error::{CellError, Location, NetworkError};
/// The linear-algebra crate whose matrices the API returns.
pub use faer;
pub use faer::c64;
pub use model::{ChainView, IntoBondLaw, NetworkModel, NetworkModelBuilder};
