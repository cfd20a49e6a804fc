//! Static linkage analysis (paper Sections II-V, VII and Appendices A, C, D), generic over
//! [`crate::ChainModel`], so it runs on macro-generated chains and runtime-sized chains alike.
//!
//! One analysis per file:
//! - [`cobweb`]: fixed points, slopes and decay lengths of the branch map, cobweb-plot data (Sec. II);
//! - [`kink`]: the zero-energy kink at any centre, built outward, and the mechanism path (Sec. II);
//! - [`walls`]: kink and antikink positions and charges (Appendix C);
//! - [`equilibrium`]: dissipative relaxation and Newton's method on the gradient;
//! - [`classify`]: minimum, saddle (index) or degenerate, from the tangent stiffness spectrum;
//! - [`antikink`]: the antikink, its minimum and saddle, the Peierls-Nabarro barrier (Secs. II, V);
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

pub mod antikink;
pub mod classify;
pub mod cobweb;
pub mod continuum;
pub mod counting;
pub mod equilibrium;
pub mod error;
pub mod impurity;
pub mod kink;
pub mod linkage;
pub mod modes;
mod validate;
pub mod walls;

pub use error::StaticsError;

/// The most numbers a dense result may hold (2^26 `f64`s, 512 MiB): the `n x (n - 1)` matrix of
/// [`counting::maxwell_calladine`]'s SVD, the `k` vectors of length `n` of [`modes::modes`]. A
/// larger request is [`StaticsError::TooLarge`], not an allocation failure.
pub const MAX_DENSE_VALUES: usize = 1 << 26;
