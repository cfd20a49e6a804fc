//! The host side of the embedded kink run (`docs/embedded.md`).
//!
//! The firmware in `embedded/firmware` runs [`embedded_check::run()`] under QEMU and prints its
//! samples; [`compare()`] runs the same function on the host, in the same float type, reads the
//! firmware's text back and checks every number against the host's within the float type's
//! [`Tolerance`]. The `compare-firmware` binary does this for a file of QEMU's output.
#![deny(missing_docs)]

pub mod compare;

pub use compare::{
    Agreement, CompareError, Tolerance, Tolerated, compare, compare_accuracy, compare_final_energy, host_run,
};
