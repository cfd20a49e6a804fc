//! Setting a kink or an antikink in motion (paper Sec. V and Appendix B).
//!
//! The static defect (the zero-energy kink, or the antikink at its Peierls-Nabarro minimum) is
//! given velocities along its **translation mode** `e`, normalised in tip displacements
//! (`sum_i e_i^2 = 1`): `r_i thetadot_i = v0 e_i`, so the initial kinetic energy is
//! `sum_i M (v0 e_i)^2 / 2 = M v0^2 / 2` (Appendix B).
//!
//! **Separating the translation from the edge modes.** Each uniform domain has a zero-energy
//! mechanism living at one of its ends (docs/theory.md §6). For a kink both sit at the wall and
//! combine into its translation; the chain has one zero mode and its free ends are rigid. For an
//! antikink they sit at the two free ends: the lowest three modes of `I^{-1/2} K I^{-1/2}` are two
//! edge modes and the translation, all far below the phonon band, and in a finite chain the
//! eigenvectors are mixtures of the three whenever their eigenvalues differ by less than the
//! (exponentially small) coupling between the wall and an end. Launched along such a mixture, an
//! end moves from the first step: at `theta_bar = 0.28` with the antikink at rotor 44 of 60, 24 %
//! of `sum e_i^2` sat on rotors 54-59 and a kink walked in from the right end in every run.
//!
//! The launch therefore uses the **most localised vector of the near-null subspace**: among the
//! unit vectors `u` (in the `I^{1/2}`-scaled coordinates, where `u_i` is proportional to `e_i`)
//! spanned by the lowest [`near_null_count`] modes, the one that minimises the spread about the
//! wall, `sum_i (i - x_wall)^2 u_i^2`: the lowest eigenvector of that quadratic form restricted to
//! the subspace (a 1x1 or 3x3 symmetric eigenproblem). Of the options measured at `n = 60`,
//! `theta_bar = 0.1 ... 0.65`, every start from rotor 8 to 51 (docs/dynamics.md §2), it and the
//! vector maximising the weight within two or three widths of the wall all leave at most `6e-5` of
//! the kinetic energy farther than three widths from the wall; the previous choice (the eigenvector
//! classified as the translation) left up to 33 %. The spread has no window width to choose, so
//! it is the one used. Within the subspace the edge modes have eigenvalues within rounding of zero
//! and the translation's is small, so the launch vector is still a translation to within the
//! subspace's spectral width (`omega_t` of the infinite chain).

//!
//! Without a heap, [`kink_translation_mode`] and [`kink_launch_velocities`] launch a kink (the
//! zero-energy defect, whose translation is the zero mode of the compatibility matrix) by a
//! recurrence along the chain, in `f64` or `f32`: the firmware's launch.

#[cfg(feature = "alloc")]
mod defect;
mod zero_mode;

#[cfg(feature = "alloc")]
pub use defect::*;
pub use zero_mode::{kink_launch_velocities, kink_translation_mode};
