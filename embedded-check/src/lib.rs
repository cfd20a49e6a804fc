//! The embedded kink run, `#![no_std]` without `alloc`: everything the Cortex-M firmware computes,
//! in one crate that the firmware (`embedded/firmware`) and the host harness (`embedded/host`)
//! both call, so that the two cannot drift apart.
//!
//! 1. [`kink_into`]: the zero-energy kink built by the branch solve (paper Sec. II, Appendix A);
//! 2. [`launch_velocities`]: launched along its translation mode, the zero mode of the
//!    compatibility matrix, with `r_i thetadot_i = v0 e_i` (Appendix B);
//! 3. [`Verlet`]: stepped with velocity Verlet;
//! 4. [`domain_walls`] and the energies: observed at fixed intervals (Appendix C);
//! 5. [`report`]: the text the firmware prints and the host reads back.
//!
//! [`run()`] strings them together for a [`Scenario`]. Everything is generic over the float type
//! ([`Real`]) and the chain ([`Model`]); [`Chain16`] is the `f64` chain the firmware runs.
//!
//! CI also builds this crate on its own for the host (`cargo build -p embedded-check`), so
//! `rotor-chain` resolves without its default `std` feature, and checks that no `std` or `alloc`
//! feature reaches it.
#![deny(missing_docs)]
#![no_std]

pub mod error;
pub mod kink;
pub mod launch;
pub mod model;
pub mod real;
pub mod report;
pub mod run;
pub mod verlet;
pub mod walls;

pub use error::RunError;
pub use kink::kink_into;
pub use launch::{launch_velocities, translation_mode};
pub use model::Model;
pub use real::Real;
pub use run::{MAX_WALLS, Sample, Scenario, Summary, launched_kink, run};
pub use verlet::Verlet;
pub use walls::{Charge, Wall, domain_walls};

use rotor_chain::prelude::*;

/// The paper's chain geometry (`r/a = 0.8`, `theta_bar = 0.58`, `k = 1e4`, `M = 1`) on a
/// microcontroller-sized chain of 16 rotors: the chain of the firmware's kink run.
#[rotor_chain(n = 16, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 1.0)]
pub struct Chain16;

/// The trace of the dense Hessian: the 16 x 16 `nalgebra` matrix lives on the stack, so even the
/// dense form needs no heap. Kept so that the host's no_std build covers `hessian()` too.
pub fn stiffness_trace(chain: &Chain16, theta: &[f64; 16]) -> f64 {
    chain.hessian(theta).trace()
}
