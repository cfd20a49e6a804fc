//! What a microcontroller needs, in one place: the pieces of the library that run without a heap
//! (`default-features = false`, `#![no_std]` without `alloc`), generic over the float type
//! ([`Real`]: `f64`, or `f32` for a chain declared with `float = f32`). Each lives in its home
//! module; this module only gathers them for a firmware's `use` line (docs/embedded.md).
//!
//! | item | home | what | paper |
//! |---|---|---|---|
//! | [`kink_into`], [`reflected_kink_into`] | [`statics::kink`](crate::statics::kink) | the zero-energy kink at any centre, by the branch solve; the reflected kink | Sec. II, App. A |
//! | [`DomainWalls`], [`Wall`], [`Charge`] | [`statics::walls`](crate::statics::walls) | the domain walls of a configuration | App. C |
//! | [`kink_translation_mode`], [`kink_launch_velocities`] | [`dynamics::launch`](crate::dynamics::launch) | the kink's translation mode (null vector of the compatibility matrix) and the launch along it | Sec. II, App. B |
//! | [`Verlet`], [`Phase`] | [`integrate`](crate::integrate) | velocity Verlet on arrays, one gradient per step | Sec. V |
//! | [`DynamicsError`] | [`dynamics`](crate::dynamics) | every error of the above (it wraps the statics' and the integrator's) | |
//!
//! A chain declared with `#[rotor_chain]` implements the model traits ([`ChainGeometry`] and the
//! rungs below it) in its own float type, so all of these take it.

pub use crate::dynamics::DynamicsError;
pub use crate::dynamics::launch::{kink_launch_velocities, kink_translation_mode};
pub use crate::integrate::{Phase, Verlet};
pub use crate::model::{ChainGeometry, Potential, SpringNetwork, Stiffness};
pub use crate::real::Real;
pub use crate::statics::kink::{kink_into, reflected_kink_into};
pub use crate::statics::walls::{Charge, DomainWalls, Wall};
