//! The compile-time tests of `#[rotor_chain]`, in `tests/ui.rs`: a compile-fail case with its
//! `.stderr` snapshot for every rule of the attribute (`tests/ui/compile_fail/`), and pass cases
//! that compile and run (`tests/ui/pass/`). The library itself is empty; the crate exists so that
//! trybuild's separate build of the cases needs nothing beyond the facade (see `Cargo.toml`).
#![deny(missing_docs)]
