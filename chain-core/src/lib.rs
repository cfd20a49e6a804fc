//! Model layer of `rotor-chain`: the [`ChainModel`] trait every analysis is generic over, the
//! runtime-sized [`RuntimeChain`], banded stiffness types, the branch solve of paper
//! Appendix A, and the no-alloc pieces of a dynamics run in `f64` or `f32` ([`embedded`]).
//!
//! `no_std` without allocation when default features are off (math from `libm`); the `alloc`
//! feature adds the runtime-sized chain and dense conversions, `std` the platform math.
#![deny(missing_docs)]
#![cfg_attr(not(feature = "std"), no_std)]

#[cfg(feature = "alloc")]
extern crate alloc;

pub mod banded;
#[cfg(feature = "std")]
pub mod batch;
pub mod branch;
#[cfg(feature = "alloc")]
pub mod dynamics;
pub mod embedded;
pub mod error;
pub mod kernel;
#[cfg(feature = "alloc")]
pub mod linalg;
pub mod math;
pub mod model;
pub mod real;
#[cfg(feature = "alloc")]
pub mod runtime;
pub mod simd;
#[cfg(feature = "alloc")]
pub mod statics;

pub use banded::{Bidiagonal, Tridiagonal};
pub use chain_geometry as geometry;
pub use error::{BranchError, ParameterError};
pub use model::ChainModel;
pub use real::Real;
#[cfg(feature = "alloc")]
pub use runtime::{ChainBuilder, Law, RuntimeChain};
