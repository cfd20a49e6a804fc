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
pub mod walls;

pub use error::StaticsError;
