//! Model layer of `rotor-chain`: the capability traits every analysis is generic over
//! ([`model`]: [`Potential`], [`Stiffness`], [`SpringNetwork`], [`ChainGeometry`], and
//! [`ChainModel`], all four in `f64`), the runtime-sized [`RuntimeChain`], the integrators
//! ([`integrate`]), the statics and the dynamics.
//!
//! The import graph is a chain: `model` (traits, layouts, the branch solve) -> `linalg` ->
//! `integrate` -> `statics` -> `dynamics`; `embedded` only gathers the pieces that need no heap.
//!
//! `no_std` without allocation when default features are off (math from `libm`): the model
//! traits, the kink's construction, the domain walls, the kink's launch and velocity Verlet on
//! arrays. The `alloc` feature adds the runtime-sized chain, the linear algebra, the analyses and
//! the runs; `std` the platform math and the batch evaluations on threads.
#![deny(missing_docs)]
#![cfg_attr(not(feature = "std"), no_std)]

#[cfg(feature = "alloc")]
extern crate alloc;

#[cfg(feature = "alloc")]
pub mod allocation;
pub mod banded;
#[cfg(feature = "std")]
pub mod batch;
pub mod branch;
pub mod dynamics;
pub mod embedded;
pub mod error;
pub mod integrate;
#[doc(hidden)]
pub mod kernel;
pub mod linalg;
#[doc(hidden)]
pub mod math;
pub mod model;
#[doc(hidden)]
pub mod real;
#[cfg(feature = "alloc")]
pub mod runtime;
#[doc(hidden)]
pub mod simd;
pub mod statics;
pub mod validate;

pub use banded::{Bidiagonal, Tridiagonal};
pub use chain_geometry as geometry;
pub use error::{BranchError, ParameterError};
pub use model::{ChainGeometry, ChainModel, Potential, SpringNetwork, Stiffness};
pub use real::Real;
#[cfg(feature = "alloc")]
pub use runtime::{ChainBuilder, Law, RuntimeChain};
pub use validate::Validate;
