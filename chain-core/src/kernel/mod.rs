//! Per-spring kernels rendered by the symbolic engine (`chain-symbolic`), checked in so that
//! `chain-core` needs no build script. They are the same source the `#[rotor_chain]` macro emits
//! for large chains; `tests/kernels_are_current.rs` regenerates them and fails if they differ
//! (run it with `UPDATE_KERNELS=1` to rewrite them after changing the engine).
//!
//! Every function takes `(s1, c1, s2, c2, a, r1, r2, k, l0)`: sine and cosine of the two rotor
//! angles, lattice spacing, the two rotor lengths, and the spring's stiffness and rest length.

/// The harmonic law `k (l - l0)^2 / 2` (paper Eq. `eq:discretelagrangian`).
#[rustfmt::skip]
pub mod harmonic;

/// The paper's quartic approximation `k (l^2 - l0^2)^2 / (8 l0^2)` (Eq. `eq:discretepotential`).
#[rustfmt::skip]
pub mod quartic;
