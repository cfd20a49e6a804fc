//! Static analysis (paper Sections II-V, VII and Appendices A, C, D), each analysis generic over
//! the rung of the model ladder ([`crate::model`]) it needs: equilibria, their classification and
//! the modes over [`Stiffness`](crate::model::Stiffness) (any model with a Hessian), counting over
//! [`SpringNetwork`](crate::model::SpringNetwork), and the chain's own analyses (kinks, walls,
//! cobweb, antikink) over [`ChainModel`](crate::ChainModel), so they run on macro-generated and
//! runtime-sized chains alike. The kink's construction and the domain walls need no heap; the
//! rest needs `alloc`.
//!
//! One analysis per file:
//! - [`cobweb`]: fixed points, slopes and decay lengths of the branch map, cobweb-plot data (Sec. II);
//! - [`kink`]: the zero-energy kink at any centre, built outward, and the mechanism path (Sec. II);
//! - [`walls`]: kink and antikink positions and charges (Appendix C);
//! - [`equilibrium`]: dissipative relaxation and Newton's method on the gradient;
//! - [`classify`]: minimum, saddle (index) or degenerate, from the tangent stiffness spectrum;
//! - [`antikink`]: the antikink, its minimum and saddle, the Peierls-Nabarro barrier (Secs. II, V);
//! - [`landscape`]: the antikink's equilibria near a place on a non-uniform chain, impurity
//!   pinning and repulsion energies, the default placement;
//! - [`path`]: the antikink's adiabatic path (its energy at any fixed centre) and the descent to a
//!   well between centrings;
//! - [`path_scan`]: the path across a window and its free equilibria (the landscape near impurities);
//! - [`step_off`]: leaving a saddle that a descent stopped at, along its unstable direction;
//! - [`modes`]: eigenmodes and frequencies, classified as translation, shape, edge, extended (Sec. IV);
//! - [`counting`]: Maxwell-Calladine counting, zero modes, states of self-stress, tensional modes;
//! - [`impurity`]: a spring-length impurity, its two-kink state, soft modes, `l_critical` (Sec. VII-A);
//! - [`linkage`]: the linkage limit, kink coordinates and the reduced two-kink model (Sec. VII-B, App. C);
//! - [`continuum`]: every closed form of the continuum theory (Secs. III-V, App. E).
//!
//! **Hostile inputs.** Every public analysis checks its inputs where it starts: angles (one finite
//! angle per rotor), spring indices, settings (finite, in range) and the model's `theta_bar`;
//! each failure is a [`StaticsError`] carrying the value. Every iteration has a bound fixed by its
//! inputs (iteration budgets in the options, bisections of at most 200 halvings, Newton steps of
//! at most 50), so no input makes an analysis hang, panic, or return a NaN as `Ok`.

#[cfg(feature = "alloc")]
pub mod antikink;
#[cfg(feature = "alloc")]
pub mod classify;
#[cfg(feature = "alloc")]
pub mod cobweb;
#[cfg(feature = "alloc")]
pub mod continuum;
#[cfg(feature = "alloc")]
pub mod counting;
#[cfg(feature = "alloc")]
pub mod equilibrium;
pub mod error;
#[cfg(feature = "alloc")]
pub mod impurity;
pub mod kink;
#[cfg(feature = "alloc")]
pub mod landscape;
#[cfg(feature = "alloc")]
pub mod linkage;
#[cfg(feature = "alloc")]
pub mod modes;
#[cfg(feature = "alloc")]
pub mod path;
#[cfg(feature = "alloc")]
pub mod path_scan;
#[cfg(feature = "alloc")]
pub mod step_off;
#[cfg(feature = "alloc")]
mod validate;
pub mod walls;

pub use error::StaticsError;

/// The most numbers a dense result may hold ([`crate::linalg::MAX_DENSE_VALUES`]).
#[cfg(feature = "alloc")]
pub use crate::linalg::MAX_DENSE_VALUES;
