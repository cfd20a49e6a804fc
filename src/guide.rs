//! The guides, as rustdoc: every guide of `docs/` and the README, one module each.
//!
//! Each module's page is the guide itself (`#[doc = include_str!(..)]`), so the Rust code blocks
//! in it are doctests: `cargo test --doc` compiles and runs every one of them, with the `use`
//! lines a program needs shown. A block that cannot run says why next to it. Shell commands,
//! TOML and Python are not Rust and are shown, not run.
//!
//! | module | guide | what it covers |
//! |---|---|---|
//! | [`readme`] | `README.md` | what it is, set-up, the two commands, five measured numbers, where to go next |
//! | [`first_hour`] | `docs/first-hour.md` | from the dependency line to a phase diagram and its picture, in Rust and Python |
//! | [`theory`] | `docs/theory.md` | the model, sign conventions, which wall is the kink, the branch solve |
//! | [`macros`] | `docs/macro.md` | every key of `#[rotor_chain]`, every generated item, every compile error |
//! | [`models`] | `docs/models.md` | the model ladder, and a model of your own (a Frenkel–Kontorova chain) through every analysis |
//! | [`statics`] | `docs/statics.md` | kink, antikink, Peierls–Nabarro barrier, modes, counting, impurity, linkage, continuum |
//! | [`dynamics`] | `docs/dynamics.md` | integrators, launching, wall tracking, scattering, phase diagrams |
//! | [`paper`] | `docs/paper.md` | the one-command reproduction of the paper's figures and numbers |
//! | [`guarantees`] | `docs/guarantees.md` | what each layer promises for hostile inputs, and which test holds it |
//! | [`benchmarks`] | `docs/benchmarks.md` | how the speed figures were measured |
//! | [`embedded`] | `docs/embedded.md` | a chain on a Cortex-M4F under QEMU, `no_std` without `alloc` |
//! | [`scaling`] | `docs/scaling.md` | the Python package, Dask and SLURM sweeps |
//! | [`publishing`] | `docs/publishing.md` | the crates and the wheel as they would be published, and CI's dry runs |
//! | [`network`] | `docs/network.md` | periodic networks: cells, counts, Bloch bands, windings and polarization, strips, Guest modes |
//!
//! Links between the guides point at the markdown files of the repository, where they also read
//! as plain markdown.

#[doc = include_str!("../README.md")]
pub mod readme {}

#[doc = include_str!("../docs/first-hour.md")]
pub mod first_hour {}

#[doc = include_str!("../docs/theory.md")]
pub mod theory {}

#[doc = include_str!("../docs/macro.md")]
pub mod macros {}

#[doc = include_str!("../docs/models.md")]
pub mod models {}

#[doc = include_str!("../docs/statics.md")]
pub mod statics {}

#[doc = include_str!("../docs/dynamics.md")]
pub mod dynamics {}

#[doc = include_str!("../docs/paper.md")]
pub mod paper {}

#[doc = include_str!("../docs/guarantees.md")]
pub mod guarantees {}

#[doc = include_str!("../docs/benchmarks.md")]
pub mod benchmarks {}

#[doc = include_str!("../docs/embedded.md")]
pub mod embedded {}

#[doc = include_str!("../docs/scaling.md")]
pub mod scaling {}

#[doc = include_str!("../docs/publishing.md")]
pub mod publishing {}
#[doc = include_str!("../docs/network.md")]
#[cfg(feature = "network")]
pub mod network {}
