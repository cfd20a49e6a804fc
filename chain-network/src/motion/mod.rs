//! Networks in motion (issue 36, demonstrations 2 and 3): nonlinear waves launched on a patch
//! and measured from the run.
//!
//! - [`transition`]: a chain of bistable elements declared as a network with the run-time
//!   polynomial law (`chain_cell::Polynomial::double_well`), carrying a transition wave whose
//!   speed, fitted to the front's position against time, is compared with the continuum's closed
//!   form.
//! - [`wall`]: a 2D lattice of coupled Kane-Lubensky chains carrying the chain's zero-energy kink
//!   as a straight domain wall between the two polarizations; launched, run, and the counts and
//!   polarization of each side and of the region it crossed measured before and after.
//! - [`front`]: the position of a front between two states along a row of sites, and the
//!   least-squares speed of a front's positions against time (shared by both demonstrations).

pub mod front;
pub mod transition;
pub mod wall;

mod error;

pub use error::MotionError;
