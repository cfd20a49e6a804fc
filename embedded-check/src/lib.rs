//! The embedded kink run, `#![no_std]` without `alloc`: everything the Cortex-M firmware computes,
//! in one crate that the firmware (`embedded/firmware`) and the host harness (`embedded/host`)
//! both call, so that the two cannot drift apart.
//!
//! The pieces are the library's no-alloc ones (`rotor_chain::embedded`, re-exported here):
//! 1. [`kink_into`]: the zero-energy kink built by the branch solve (paper Sec. II, Appendix A);
//! 2. [`kink_launch_velocities`]: launched along its translation mode, the zero mode of the
//!    compatibility matrix, with `r_i thetadot_i = v0 e_i` (Appendix B);
//! 3. [`Verlet`]: stepped with velocity Verlet;
//! 4. [`DomainWalls`] and the energies: observed at fixed intervals (Appendix C).
//!
//! [`run()`] strings them together for a [`Scenario`]. Everything is generic over the float type
//! ([`Real`]) and the chain ([`ChainGeometry`]); [`Chain16`] is the `f64` chain the firmware runs and
//! [`Chain16F32`] the same chain in `f32`.
//!
//! CI also builds this crate on its own for the host (`cargo build -p embedded-check`), so
//! `rotor-chain` resolves without its default `std` feature, and checks that no `std` or `alloc`
//! feature reaches it.
#![deny(missing_docs)]
#![no_std]

pub mod report;
pub mod run;

pub use rotor_chain::embedded::{
    ChainGeometry, Charge, DomainWalls, DynamicsError, Phase, Potential, Real, Verlet, Wall, kink_into,
    kink_launch_velocities, kink_translation_mode,
};
pub use run::{MAX_WALLS, Sample, Scenario, Summary, launched_kink, run};

use rotor_chain::prelude::*;

/// The paper's chain geometry (`r/a = 0.8`, `theta_bar = 0.58`, `k = 1e4`, `M = 1`) on a
/// microcontroller-sized chain of 16 rotors: the chain of the firmware's kink run, in `f64`.
#[rotor_chain(n = 16, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 1.0)]
pub struct Chain16;

/// [`Chain16`] computing in `f32`: the same attribute with `float = f32`, so the same symbolic
/// derivation rendered in single precision, for the Cortex-M4F's FPU.
#[rotor_chain(n = 16, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 1.0, float = f32)]
pub struct Chain16F32;

/// The trace of the dense Hessian: the 16 x 16 `nalgebra` matrix lives on the stack, so even the
/// dense form needs no heap. Kept so that the host's no_std build covers `hessian()` too.
pub fn stiffness_trace(chain: &Chain16, theta: &[f64; 16]) -> f64 {
    chain.hessian(theta).trace()
}

/// The same in `f32`.
pub fn stiffness_trace_f32(chain: &Chain16F32, theta: &[f32; 16]) -> f32 {
    chain.hessian(theta).trace()
}
