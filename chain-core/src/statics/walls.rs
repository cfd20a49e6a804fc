//! Domain walls of a configuration (paper Appendix C); the iterator needs no heap.
//!
//! Angles are measured alternately from `+y` and `-y` (docs/theory.md), so a uniform state has one
//! sign throughout and a domain wall is a sign change of `theta`. Its position interpolates
//! linearly between the two rotors that lean opposite ways, `x = i + theta_i / (theta_i - theta_{i+1})`,
//! so a vertical rotor sits exactly on the wall. A wall from `+` to `-` (left to right) is a
//! **kink**, from `-` to `+` an **antikink**. [`DomainWalls::of`] finds them without a heap;
//! [`domain_walls`] collects them into a `Vec`.

#[cfg(feature = "alloc")]
use alloc::vec::Vec;

use crate::model::ChainGeometry;
use crate::real::Real;

/// Kink or antikink.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Charge {
    /// `+theta_bar` on the left, `-theta_bar` on the right: the zero-energy wall.
    Kink,
    /// `-theta_bar` on the left, `+theta_bar` on the right: stretches springs.
    Antikink,
}

impl Charge {
    /// `"kink"` or `"antikink"`.
    pub const fn name(self) -> &'static str {
        match self {
            Charge::Kink => "kink",
            Charge::Antikink => "antikink",
        }
    }

    /// The charge of a wall whose left rotor leans at `left`.
    fn of_left<T: Real>(left: T) -> Self {
        if left > T::ZERO { Charge::Kink } else { Charge::Antikink }
    }
}

/// A domain wall: where it is (in rotor indices, fractional) and which kind.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wall<T = f64> {
    /// Position in rotor indices, fractional (paper Appendix C).
    pub position: T,
    /// Kink or antikink.
    pub charge: Charge,
}

/// The domain walls of a configuration, left to right, found as the iterator runs (no heap).
#[derive(Clone, Debug)]
pub struct DomainWalls<'a, T> {
    theta: &'a [T],
    /// The next rotor to look at.
    next: usize,
    /// The last rotor that leans, and its angle.
    last: Option<(usize, T)>,
}

impl<'a, T: Real> DomainWalls<'a, T> {
    /// The domain walls of `theta`, left to right: a sign change between two leaning rotors. A
    /// rotor exactly at zero leans neither way; a wall across one vertical rotor sits on it,
    /// across a run of them in its middle. A non-finite angle leans neither way either (read as
    /// zero), so no wall gets a NaN position.
    pub fn of(theta: &'a [T]) -> Self {
        Self { theta, next: 0, last: None }
    }
}

impl<T: Real> Iterator for DomainWalls<'_, T> {
    type Item = Wall<T>;

    fn next(&mut self) -> Option<Wall<T>> {
        while self.next < self.theta.len() {
            let j = self.next;
            let t = self.theta[j];
            self.next += 1;
            if !t.is_finite() || t == T::ZERO {
                continue;
            }
            let previous = self.last.replace((j, t));
            if let Some((i, ti)) = previous
                && (ti > T::ZERO) != (t > T::ZERO)
            {
                let position =
                    if j == i + 1 { T::of_index(i) + ti / (ti - t) } else { T::of_index(i + j) / T::of(2.0) };
                return Some(Wall { position, charge: Charge::of_left(ti) });
            }
        }
        None
    }
}

/// Every domain wall of `theta`, left to right: a sign change between two leaning rotors. A rotor
/// exactly at zero leans neither way; a wall across one vertical rotor sits on it, across a run
/// of them in its middle. A non-finite angle leans neither way either (read as zero), so no wall
/// gets a NaN position (the analyses reject non-finite angles before they get here). This is
/// [`DomainWalls::of`], the no-alloc iterator, collected.
#[cfg(feature = "alloc")]
pub fn domain_walls(theta: &[f64]) -> Vec<Wall> {
    DomainWalls::of(theta).collect()
}

/// `(kinks, antikinks)` in `theta`.
pub fn count_walls<T: Real>(theta: &[T]) -> (usize, usize) {
    DomainWalls::of(theta).fold((0, 0), |(k, a), w| match w.charge {
        Charge::Kink => (k + 1, a),
        Charge::Antikink => (k, a + 1),
    })
}

/// The continuum width of a wall in sites: `w / a` with `w = a^2 / (2 r sin theta_bar)` (paper
/// Sec. III, App. E), `r` the length of the middle rotor (for even `n` the mean of the two
/// middle ones, so that a chain and its mirror image have one width). Dimensionless: the
/// distances it is compared with (rotor indices, wall positions) are in sites, so lengths scaled
/// by any factor leave it unchanged. The reach of [`modes`](super::modes::modes)' kinds and the
/// launches' distances are in these widths.
pub fn wall_width<M: ChainGeometry + ?Sized>(model: &M) -> f64 {
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
    fn the_iterator_finds_interpolated_sign_changes() {
        let theta = [0.5, 0.5, 0.25, -0.75, -0.5, -0.5, 0.0, 0.5];
        let mut walls = DomainWalls::of(&theta);
        assert_eq!(walls.next(), Some(Wall { position: 2.25, charge: Charge::Kink }));
        assert_eq!(walls.next(), Some(Wall { position: 6.0, charge: Charge::Antikink }));
        assert_eq!(walls.next(), None);
    }

    #[test]
    fn a_uniform_state_has_no_wall_and_zeros_at_the_ends_none_either() {
        assert_eq!(DomainWalls::of(&[0.3f32; 5]).count(), 0);
        assert_eq!(DomainWalls::of(&[0.0, 0.3, 0.3, 0.0]).count(), 0);
        assert_eq!(DomainWalls::<f64>::of(&[]).count(), 0);
    }

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
