//! Positions and charges of the domain walls in a configuration (paper Appendix C).
//!
//! Angles are measured alternately from `+y` and `-y` (docs/theory.md), so a uniform state has
//! one sign throughout and a domain wall is a sign change of `theta`. Its position interpolates
//! linearly between the two rotors that lean opposite ways: `x = i + theta_i / (theta_i - theta_{i+1})`,
//! so a vertical rotor (`theta_i = 0`) sits exactly on the wall. A wall from `+` to `-` (left to
//! right) is a **kink**, from `-` to `+` an **antikink**.

use alloc::vec::Vec;

use crate::model::ChainModel;

/// Kink or antikink, and a wall's position and charge: the no-alloc module's types (`f64` here).
pub use crate::embedded::walls::{Charge, Wall};

/// Every domain wall of `theta`, left to right: a sign change between two leaning rotors. A rotor
/// exactly at zero leans neither way; a wall across one vertical rotor sits on it, across a run
/// of them in its middle. A non-finite angle leans neither way either (read as zero), so no wall
/// gets a NaN position (the analyses reject non-finite angles before they get here). This is
/// [`crate::embedded::domain_walls`], the no-alloc iterator, collected.
pub fn domain_walls(theta: &[f64]) -> Vec<Wall> {
    crate::embedded::domain_walls(theta).collect()
}

/// `(kinks, antikinks)` in `theta`.
pub fn count_walls(theta: &[f64]) -> (usize, usize) {
    let walls = domain_walls(theta);
    let kinks = walls.iter().filter(|w| w.charge == Charge::Kink).count();
    (kinks, walls.len() - kinks)
}

/// The continuum width of a wall in sites: `w / a` with `w = a^2 / (2 r sin theta_bar)` (paper
/// Sec. III, App. E), `r` the length of the middle rotor (for even `n` the mean of the two
/// middle ones, so that a chain and its mirror image have one width). Dimensionless: the
/// distances it is compared with (rotor indices, wall positions) are in sites, so lengths scaled
/// by any factor leave it unchanged. The reach of [`modes`](super::modes::modes)' kinds and the
/// launches' distances are in these widths.
pub fn wall_width<M: ChainModel + ?Sized>(model: &M) -> f64 {
    let a = model.lattice_spacing();
    let n = model.rotor_count();
    // Equal lengths give `r` exactly: r + r and the halving are exact.
    let r = 0.5 * (model.rotor_length((n - 1) / 2) + model.rotor_length(n / 2));
    a / (2.0 * r * libm::sin(model.theta_bar()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn walls_are_interpolated_sign_changes() {
        let theta = [0.5, 0.5, 0.25, -0.75, -0.5, -0.5, 0.0, 0.5];
        let walls = domain_walls(&theta);
        assert_eq!(walls.len(), 2);
        assert_eq!(walls[0].charge, Charge::Kink);
        assert!((walls[0].position - 2.25).abs() < 1e-15);
        assert_eq!(walls[1], Wall { position: 6.0, charge: Charge::Antikink });
        assert_eq!(count_walls(&theta), (1, 1));
    }

    #[test]
    fn non_finite_angles_lean_neither_way() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 0.0] {
            let walls = domain_walls(&[0.5, bad, -0.5, -0.5, bad, bad, 0.5]);
            assert_eq!(
                walls,
                [
                    Wall { position: 1.0, charge: Charge::Kink },
                    Wall { position: 4.5, charge: Charge::Antikink }
                ],
                "{bad}"
            );
        }
    }
}
