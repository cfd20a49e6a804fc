//! # rotor-chain
//!
//! Declare a topological mechanical rotor chain on a struct and get fast, exact,
//! compile-time-checked code for it: energy, gradient, tangent stiffness (and its split into
//! material part and stress matrix), spring lengths and tensions, compatibility matrix, and the
//! branch solve of the paper "Kink-antikink asymmetry and impurity interactions in topological
//! mechanical chains" (Zhou, Chen, Upadhyaya, Vitelli).
//!
//! ```
//! use rotor_chain::prelude::*;
//!
//! #[rotor_chain(n = 60, a = 1.0, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 1.0,
//!               spring(29, k = k_imp),      // an identifier: read from the struct field at run time
//!               spring(7, l0 = 2.30))]      // a literal: folded into the generated code
//! pub struct Chain { pub k_imp: f64 }
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let c = Chain { k_imp: 100.0 };
//! let theta = [0.58f64; 60];
//! let e: f64 = c.energy(&theta);                 // potential energy
//! let g = c.gradient(&theta);                    // dV/dtheta_i, indexable g[i] (forces are -g)
//! let h = c.hessian(&theta);                     // nalgebra matrix, h[(i, j)] = d2V/dtheta_i dtheta_j
//! let [z0, z1] = c.next_angles(10, 0.3)?;        // both roots of the spring-10 branch solve
//! # let _ = (e, g[0], h[(0, 0)], z0, z1);
//! # Ok(())
//! # }
//! ```
//!
//! The model, its sign conventions and the keys of the attribute are documented in
//! `docs/theory.md` and `docs/macro.md`. With default features off the crate is `#![no_std]`
//! without allocation (math from `libm`), and so is the code the macro generates.
#![deny(missing_docs)]
#![cfg_attr(not(feature = "std"), no_std)]

pub use chain_core::{
    Bidiagonal, BranchError, ChainModel, ParameterError, Tridiagonal, banded, branch, error, geometry,
    kernel, math, model, simd,
};
#[cfg(feature = "alloc")]
pub use chain_core::{ChainBuilder, Law, RuntimeChain, dynamics, linalg, runtime, statics};
pub use chain_macros::rotor_chain;
/// The linear-algebra crate of the matrices this crate returns, re-exported so versions match.
pub use nalgebra;

pub mod guide;

/// The macro and every trait and type a user needs.
pub mod prelude {
    pub use chain_core::{Bidiagonal, BranchError, ChainModel, ParameterError, Tridiagonal};
    #[cfg(feature = "alloc")]
    pub use chain_core::{Law, RuntimeChain};
    pub use chain_macros::rotor_chain;
}

/// Support items for generated code. Not public API: the one path through which code emitted by
/// `#[rotor_chain]` reaches its dependencies, so users depend on this crate alone.
#[doc(hidden)]
pub mod __private {
    pub use chain_core::{Bidiagonal, ChainModel, ParameterError, Tridiagonal, geometry, kernel, math};
    pub use nalgebra::SMatrix;

    /// The body of every stub the macro emits beside its compile errors (so that calls on an
    /// invalid chain add no "no method named `energy`" errors). Those stubs exist only in a crate
    /// that fails to compile, so this is never called.
    pub fn invalid_chain<T>() -> T {
        panic!("#[rotor_chain] stub called: the chain's declaration has compile errors")
    }

    /// `theta` as a fixed-size array, for the slice-based [`ChainModel`] methods.
    ///
    /// # Panics
    /// If `theta` does not have exactly `N` angles (a programming error: the chain has `N` rotors).
    #[inline(always)]
    #[track_caller]
    pub fn as_array<const N: usize>(theta: &[f64]) -> &[f64; N] {
        match theta.try_into() {
            Ok(a) => a,
            Err(_) => {
                panic!("expected one angle per rotor: {} angles for a chain of {} rotors", theta.len(), N)
            }
        }
    }
}
