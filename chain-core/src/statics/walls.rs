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
    /// Position in rotor indices: `i + theta_i / (theta_i - theta_{i+1})` (Appendix C).
    pub position: f64,
    /// Kink or antikink.
    pub charge: Charge,
}

/// Every domain wall of `theta`, left to right: a sign change between two leaning rotors. A rotor
/// exactly at zero leans neither way; a wall across one vertical rotor sits on it, across a run
/// of them in its middle. A non-finite angle leans neither way either (read as zero), so no wall
/// gets a NaN position (the analyses reject non-finite angles before they get here).
pub fn domain_walls(theta: &[f64]) -> Vec<Wall> {
    let mut walls = Vec::new();
    // The last rotor that leans, and its angle.
    let mut last: Option<(usize, f64)> = None;
    for (j, &t) in theta.iter().enumerate() {
        if !t.is_finite() || t == 0.0 {
            continue;
        }
        if let Some((i, ti)) = last
            && (ti > 0.0) != (t > 0.0)
        {
            let position = if j == i + 1 { i as f64 + ti / (ti - t) } else { (i + j) as f64 / 2.0 };
            walls.push(Wall { position, charge: charge(ti) });
        }
        last = Some((j, t));
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
