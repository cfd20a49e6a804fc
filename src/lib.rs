//! # rotor-chain
//!
//! A toolkit for topological mechanical rotor chains: rotors on a line, their tips joined by
//! springs, a unit cell that breaks inversion symmetry, so that a zero-energy **kink** and a costly
//! **antikink** exist. It implements Y. Zhou, B. G. Chen, N. Upadhyaya and V. Vitelli,
//! *Kink-antikink asymmetry and impurity interactions in topological mechanical chains*,
//! arXiv:1608.02127; equations and figures are cited by the paper's LaTeX labels.
//!
//! - **The model.** [`#[rotor_chain]`](macro@rotor_chain) on a struct writes the chain's energy,
//!   gradient, tangent stiffness (material part and stress matrix), spring lengths, tensions,
//!   compatibility matrix and branch solve, derived by a symbolic engine; an invalid model is a
//!   compile error at its key. [`RuntimeChain`] is the same chain with its size and parameters
//!   chosen at run time. Both climb the model ladder ([`model`]: [`Potential`], [`Stiffness`],
//!   [`SpringNetwork`], [`ChainGeometry`]; [`ChainModel`] is all four), which every analysis is
//!   generic over, each at the rung it needs; a model of your own implements the rungs it has
//!   ([`guide::models`]).
//! - **Statics** ([`statics`]): cobweb map, kink, antikink, Peierls–Nabarro barrier, vibrational
//!   modes, Maxwell–Calladine counting, spring-length impurity, linkage limit, continuum closed
//!   forms.
//! - **Dynamics** ([`dynamics`]): velocity Verlet and DOP853, launching a defect along its
//!   translation mode, wall tracking, scattering on a stiffness impurity.
//! - **Sweeps and figures** (features `sweep` and `figures`, see [Features](#features)):
//!   `rotor_chain::sweep`, resumable parallel phase diagrams (command `phase-diagram`);
//!   `rotor_chain::paper`, the paper's figures for any chain and pictures of your own sweeps
//!   (command `paper`).
//!
//! Units are the paper's (Appendix B): lattice spacing $a$, tip mass $M$, an arbitrary time unit
//! $t$; stiffness in $M/t^2$, energies in $M a^2/t^2$, angles in radians measured from the
//! vertical ([`guide::theory`]).
//!
//! ## Quick start
//!
//! ```
//! use rotor_chain::prelude::*;
//! use rotor_chain::statics::antikink::{AntikinkOptions, peierls_nabarro};
//! use rotor_chain::statics::kink::kink;
//!
//! // The paper's chain: 60 rotors of length r = 0.8 a, springs of stiffness k = 1e4 M/t^2,
//! // uniform states at theta_bar = +-0.58 rad.
//! #[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
//! pub struct Chain;
//!
//! fn main() -> Result<(), Box<dyn std::error::Error>> {
//!     let uniform = [0.58f64; Chain::N];
//!     assert!(Chain.energy(&uniform).abs() < 1e-9);         // every spring at rest
//!     let g = Chain.gradient(&uniform);                     // dV/dtheta_i; the forces are -g
//!     assert!(g.iter().all(|x| x.abs() < 1e-6));
//!
//!     let theta = kink(&Chain, 29.5)?;                      // the zero-energy kink (Sec. II)
//!     assert!(Potential::energy(&Chain, &theta) < 1e-16);
//!
//!     let pn = peierls_nabarro(&Chain, &AntikinkOptions::default())?; // Sec. V
//!     println!("antikink {:.4}, barrier {:.4}", pn.minimum()?.energy, pn.barrier);
//!     Ok(())
//! }
//! ```
//!
//! The same analysis on a chain built at run time:
//!
//! ```
//! use rotor_chain::RuntimeChain;
//! use rotor_chain::statics::antikink::{AntikinkOptions, peierls_nabarro};
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! for theta_bar in [0.4, 0.5, 0.58] {
//!     let chain = RuntimeChain::builder(60, 0.8, 1.0e4, theta_bar).build()?; // n, r, k, theta_bar
//!     let pn = peierls_nabarro(&chain, &AntikinkOptions::default())?;
//!     assert!(pn.resolved && pn.barrier > 0.0);
//! }
//! # Ok(())
//! # }
//! ```
//!
//! ## Map
//!
//! | where | what |
//! |---|---|
//! | [`prelude`] | the attribute, the model traits, [`RuntimeChain`], the banded matrix types, the errors |
//! | [`macro@rotor_chain`] | the attribute: every key, with an example |
//! | [`RuntimeChain`], [`ChainBuilder`], [`Law`] | a chain sized and parametrised at run time |
//! | [`model`]: [`Potential`], [`Stiffness`], [`SpringNetwork`], [`ChainGeometry`], [`ChainModel`] | the capability ladder the analyses take: slice methods, layouts, branch solve |
//! | [`integrate`] | velocity Verlet (any float type, `Vec` or array storage), DOP853, the step bound, [`integrate::Method`] |
//! | [`statics`] | static analyses, one module per analysis |
//! | [`dynamics`] | integrators, launching, tracking, scattering |
//! | [`linalg`] | the tridiagonal solvers and eigensolvers the analyses use |
//! | [`banded`], [`Tridiagonal`], [`Bidiagonal`] | stiffness and compatibility matrices of generated chains |
//! | [`geometry`] | the parameter rules and closed forms shared by the macro and the runtime |
//! | [`embedded`] | the pieces that need no heap, gathered for a firmware |
//! | `network` (feature `network`, default) | periodic spring and rotor networks: counts, bands, windings, polarization, edge modes |
//!
//! ## Guides
//!
//! | guide | for |
//! |---|---|
//! | [`guide::readme`] | set-up, the two commands, measured numbers |
//! | [`guide::first_hour`] | the first hour: a chain, its kink and antikink, a scattering run, a phase diagram and its picture, in Rust and Python |
//! | [`guide::theory`] | the model and its sign conventions, equation by equation |
//! | [`guide::macros`] | every key, generated item and compile error of the attribute |
//! | [`guide::statics`] | each static analysis: what it computes, the API, numbers against the paper |
//! | [`guide::dynamics`] | integrators, launches, tracking, scattering, phase diagrams |
//! | [`guide::paper`] | the reproduction of every figure of the paper |
//! | [`guide::guarantees`] | what each layer promises for hostile inputs |
//! | [`guide::benchmarks`], [`guide::embedded`], [`guide::scaling`] | speed, microcontrollers, Python and clusters |
//! | [`guide::publishing`] | the crates and the wheel as they would be published |
//! | `guide::network` | periodic networks, from a cell file to counts, polarization, strips and figures |
//!
//! Every Rust block of the guides is a doctest (`cargo test --doc`). Math renders with KaTeX on
//! docs.rs and with `cargo docs` locally.
//!
//! ## Features
//!
//! | feature | default | adds | brings |
//! |---|---|---|---|
//! | `std` | yes | the platform's maths, `alloc` | |
//! | `alloc` | with `std` | [`RuntimeChain`], the analyses, dense matrices | |
//! | `sweep` | no | `rotor_chain::sweep` (crate rotor-chain-sweep): resumable parallel phase diagrams, results files, shards | rayon, clap, indicatif, signal-hook |
//! | `figures` | no | `rotor_chain::paper` (crate rotor-chain-paper): every figure of the paper for any chain, outcome grids of your own sweeps, PNG/SVG/CSV; implies `sweep` | plotters, image, ab_glyph, an embedded font |
//!
//! With default features off the crate is `#![no_std]` without allocation (maths from `libm`),
//! and so is the code the attribute generates. `sweep` and `figures` are off by default because
//! of what they bring: the first debug build of a small program declaring a chain took 30 s
//! (41 s of CPU) on this 2-core machine, and 42 s (69 s of CPU) with `figures` (cargo's registry
//! cache warm, a new target folder, `/usr/bin/time cargo build`).
//!
//! ```toml
//! [dependencies]
//! rotor-chain = { version = "0.1", features = ["sweep", "figures"] }
//! # or, from a clone of the repository: { path = "../rotor-chain", features = [...] }
//! ```
//!
//! A phase diagram of your own chain and its picture, with both features:
//!
//! ```
//! # #[cfg(not(feature = "figures"))] fn main() {}
//! # #[cfg(feature = "figures")]
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! use rotor_chain::paper::outcomes::OutcomeGrid;
//! use rotor_chain::paper::{Chart, Figure, render};
//! use rotor_chain::sweep::scattering::{Defect, PhaseDiagram};
//! use rotor_chain::sweep::{Axis, Grid, compute_grid};
//!
//! # let dir = std::env::temp_dir().join(format!("rotor-chain-front-page-{}", std::process::id()));
//! // n = 40 rotors, r = 0.7 a, k = 1e4 M/t^2, theta_bar = 0.3; an antikink on the middle spring's
//! // impurity, k_i/k from 0.05 to 2 (log-spaced) by v0 from 1 to 8 a/t.
//! let diagram = PhaseDiagram::new(40, 0.7, 1.0e4, 0.3, Defect::Antikink)?;
//! let grid = Grid::new(Axis::geomspace(0.05, 2.0, 5)?, Axis::linspace(1.0, 8.0, 4)?)?;
//! let points = compute_grid(&grid, |ki, v0| diagram.compute_point(ki, v0), None)?;
//! let outcomes = OutcomeGrid::new(&grid, &points)?;
//!
//! let figure = Figure {
//!     label: "fig:my-chain",
//!     caption: "Antikink scattering, n = 40, r/a = 0.7, θ̄ = 0.3".to_owned(),
//!     panels: vec![Chart::Heat(outcomes.heatmap("antikink, θ̄ = 0.3"))],
//!     rows: Vec::new(),
//! };
//! # std::fs::create_dir_all(&dir)?;
//! render::render(&figure, &dir)?;                      // my-chain.png and my-chain.svg
//! # assert!(dir.join("my-chain.png").exists());
//! # std::fs::remove_dir_all(&dir)?;
//! # Ok(())
//! # }
//! ```
//!
//! Every figure of the paper is a function of `rotor_chain::paper::figures::Params`, whose
//! default is the paper's chain and choices; change a field to draw it for another chain.
#![deny(missing_docs)]
#![cfg_attr(not(feature = "std"), no_std)]

#[cfg(feature = "std")]
pub use chain_core::batch;
pub use chain_core::{
    Bidiagonal, BranchError, ChainGeometry, ChainModel, ParameterError, Potential, Real, SpringNetwork,
    Stiffness, Tridiagonal, Validate, banded, branch, dynamics, embedded, error, geometry, integrate, linalg,
    model, statics, validate,
};
#[cfg(feature = "alloc")]
pub use chain_core::{ChainBuilder, Law, RuntimeChain, allocation, runtime};
/// Implementation modules (run-time vector dispatch, the per-spring kernels, the float trait's
/// module, the elementary functions), public for the generated code and the benchmarks only.
#[doc(hidden)]
pub use chain_core::{kernel, math, real, simd};
/// Periodic spring and rotor networks in one and two dimensions: cells, Maxwell-Calladine
/// counts, Bloch bands, winding numbers and polarization, edge modes (crate `chain-network`;
/// guide [`guide::network`]).
#[cfg(feature = "network")]
pub use chain_network as network;
// The attribute's page: the keys and a runnable example of each. Written here, on the re-export,
// so that the examples are this crate's doctests (the proc-macro crate would need the facade as a
// dev-dependency, which compiles the facade and all its dependencies a second time for the host).
#[doc = include_str!("attribute.md")]
#[doc(inline)]
pub use chain_macros::rotor_chain;
// A patch of a periodic network as a struct; its page is written here for the same reason.
#[doc = include_str!("network_attribute.md")]
#[doc(inline)]
pub use chain_macros::rotor_network;
/// The paper's figures as functions of any chain's parameters, outcome grids of your own sweeps,
/// and their PNG, SVG and CSV output (feature `figures`; the crate rotor-chain-paper).
#[cfg(feature = "figures")]
#[doc(inline)]
pub use chain_paper as paper;
/// Resumable parallel sweeps and the scattering phase diagram (feature `sweep`; the crate
/// rotor-chain-sweep, whose command is `phase-diagram`).
#[cfg(feature = "sweep")]
#[doc(inline)]
pub use chain_sweep as sweep;
/// The linear-algebra crate of the matrices this crate returns, re-exported so versions match.
pub use nalgebra;

pub mod guide;

/// The macro and every trait and type a user needs: the four rungs of the model ladder
/// ([`model`]) and [`ChainModel`], so that their methods can be called on any chain.
pub mod prelude {
    pub use chain_core::{
        Bidiagonal, BranchError, ChainGeometry, ChainModel, ParameterError, Potential, SpringNetwork,
        Stiffness, Tridiagonal,
    };
    #[cfg(feature = "alloc")]
    pub use chain_core::{Law, RuntimeChain};
    pub use chain_macros::rotor_chain;
}

/// Support items for generated code. Not public API: the one path through which code emitted by
/// `#[rotor_chain]` reaches its dependencies, so users depend on this crate alone.
#[doc(hidden)]
pub mod __private {
    pub use chain_core::integrate::{IntegrateError, Phase, Verlet};
    pub use chain_core::model::layout::{split_bidiagonal, split_tridiagonal};
    pub use chain_core::model::{
        ChainGeometry, CompatibilityLayout, Potential, SpringNetwork, Stiffness, StiffnessLayout,
        chain_energy_floor, check_lengths,
    };
    pub use chain_core::{
        Bidiagonal, BranchError, ParameterError, Tridiagonal, branch, geometry, kernel, math,
    };
    pub use nalgebra::SMatrix;

    /// The body of every stub the macro emits beside its compile errors (so that calls on an
    /// invalid chain add no "no method named `energy`" errors). Those stubs exist only in a crate
    /// that fails to compile, so this is never called.
    pub fn invalid_chain<T>() -> T {
        panic!("#[rotor_chain] or #[rotor_network] stub called: the declaration has compile errors")
    }

    /// The network support of `#[rotor_network]` (feature `network`).
    #[cfg(feature = "network")]
    pub mod network {
        pub use chain_network::NetworkModel;
        pub use chain_network::kernel::{BondFn, BondKernels, Lane, LawKernels};
        pub use std::sync::OnceLock;

        use chain_network::cell::{Cell, ready};
        use chain_network::patch::{Boundary, Patch};

        /// Where a `#[rotor_network]` struct's cell comes from.
        pub enum CellSource {
            /// The text of a cell file (taken in with `include_str!`).
            Toml(&'static str),
            /// A ready cell without parameters, by name (`ready::by_name`).
            Ready(&'static str),
        }

        /// The model of a `#[rotor_network]` struct with the kernels `K` its attribute derived:
        /// the cell, the patch of `cells` and the overrides `(spring, k, l0)` and
        /// `(cell, node, mass)`. The attribute
        /// checked the cell, the size against the dimension, the boundary's minimum, the patch
        /// bound and the overrides at compile time; what it cannot check (periodic images of a
        /// bond that meet once wrapped) panics here, at the first use, with the library's error.
        pub fn model<K: LawKernels>(
            source: CellSource,
            cells: [usize; 2],
            periodic: bool,
            mass: f64,
            springs: &[(usize, Option<f64>, Option<f64>)],
            nodes: &[([usize; 2], usize, f64)],
        ) -> NetworkModel {
            let fail = |e: &dyn std::fmt::Display| -> ! { panic!("#[rotor_network]: {e}") };
            let cell: Cell = match source {
                CellSource::Toml(text) => Cell::from_toml_str(text).unwrap_or_else(|e| fail(&e)),
                CellSource::Ready(name) => ready::by_name(name, &[]).unwrap_or_else(|e| fail(&e)),
            };
            let boundary = if periodic { Boundary::Periodic } else { Boundary::Free };
            let patch = Patch::new(&cell, cells, boundary).unwrap_or_else(|e| fail(&e));
            let mut builder = NetworkModel::builder(&patch).kernels::<K>().mass(mass);
            for &(p, k, l0) in springs {
                if let Some(k) = k {
                    builder = builder.spring_constant(p, k);
                }
                if let Some(l0) = l0 {
                    builder = builder.rest_length(p, l0);
                }
            }
            for &(c, node, m) in nodes {
                builder = builder.node_mass(c, node, m);
            }
            builder.build().unwrap_or_else(|e| fail(&e))
        }
    }

    /// Nothing with the `network` feature; without it, the error that says a `#[rotor_network]`
    /// struct needs it.
    #[cfg(feature = "network")]
    #[doc(hidden)]
    #[macro_export]
    macro_rules! __rotor_chain_require_network {
        () => {};
    }
    #[cfg(not(feature = "network"))]
    #[doc(hidden)]
    #[macro_export]
    macro_rules! __rotor_chain_require_network {
        () => {
            ::core::compile_error!(
                "#[rotor_network] needs the `network` feature of rotor-chain (on by default)"
            );
        };
    }
    pub use crate::__rotor_chain_require_network as require_network;

    /// `theta` as a fixed-size array, for the slice-based model-trait methods.
    ///
    /// # Panics
    /// If `theta` does not have exactly `N` angles (a programming error: the chain has `N` rotors).
    #[inline(always)]
    #[track_caller]
    pub fn as_array<T, const N: usize>(theta: &[T]) -> &[T; N] {
        match theta.try_into() {
            Ok(a) => a,
            Err(_) => {
                panic!("expected one angle per rotor: {} angles for a chain of {} rotors", theta.len(), N)
            }
        }
    }
}
