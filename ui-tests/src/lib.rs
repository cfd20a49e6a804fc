//! The compile-time tests of `#[rotor_chain]` and `#[rotor_network]`: in `tests/ui.rs`, a
//! compile-fail case with its `.stderr` snapshot for every rule of the attributes
//! (`tests/ui/compile_fail/`); in `tests/pass.rs`, the pass cases of `tests/pass/`, which compile
//! and run. The library itself is empty; the crate exists so that trybuild's separate build of the
//! cases needs nothing beyond the facade (see `Cargo.toml`).
#![deny(missing_docs)]
