//! Positions and charges of the domain walls in a configuration (paper Appendix C).
//!
//! Angles are measured alternately from `+y` and `-y` (docs/theory.md), so a uniform state has
//! one sign throughout and a domain wall is a sign change of `theta`. Its position interpolates
//! linearly between the two rotors that lean opposite ways: `x = i + theta_i / (theta_i - theta_{i+1})`,
//! so a vertical rotor (`theta_i = 0`) sits exactly on the wall. A wall from `+` to `-` (left to
//! right) is a **kink**, from `-` to `+` an **antikink**.

use alloc::vec::Vec;

/// Kink or antikink.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Charge {
    /// `+theta_bar` on the left, `-theta_bar` on the right: the zero-energy wall.
    Kink,
    /// `-theta_bar` on the left, `+theta_bar` on the right: stretches springs.
    Antikink,
}

/// A domain wall: where it is (in rotor indices, fractional) and which kind.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wall {
    pub position: f64,
    pub charge: Charge,
}

/// Every domain wall of `theta`, left to right. A rotor exactly at zero belongs to the wall
/// between its neighbours (it is not counted twice).
pub fn domain_walls(theta: &[f64]) -> Vec<Wall> {
    let mut walls = Vec::new();
    let mut i = 0;
    while i + 1 < theta.len() {
        let (t0, t1) = (theta[i], theta[i + 1]);
        if t0 == 0.0 {
            i += 1;
            continue;
        }
        if t1 == 0.0 {
            // A vertical rotor: the wall sits on it if the signs on either side differ.
            if let Some(&t2) = theta.get(i + 2)
                && t2 != 0.0
                && t2.signum() != t0.signum()
            {
                walls.push(Wall { position: (i + 1) as f64, charge: charge(t0) });
            }
            i += 1;
            continue;
        }
        if t0.signum() != t1.signum() {
            walls.push(Wall { position: i as f64 + t0 / (t0 - t1), charge: charge(t0) });
        }
        i += 1;
    }
    walls
}

fn charge(left: f64) -> Charge {
    if left > 0.0 { Charge::Kink } else { Charge::Antikink }
}

/// `(kinks, antikinks)` in `theta`.
pub fn count_walls(theta: &[f64]) -> (usize, usize) {
    let walls = domain_walls(theta);
    let kinks = walls.iter().filter(|w| w.charge == Charge::Kink).count();
    (kinks, walls.len() - kinks)
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
}
