//! Domain walls of a configuration without a heap (paper Appendix C).
//!
//! Angles are measured alternately from `+y` and `-y` (docs/theory.md), so a uniform state has one
//! sign throughout and a domain wall is a sign change of `theta`. Its position interpolates
//! linearly between the two rotors that lean opposite ways, `x = i + theta_i / (theta_i - theta_{i+1})`,
//! so a vertical rotor sits exactly on the wall. A wall from `+` to `-` (left to right) is a
//! **kink**, from `-` to `+` an **antikink**.
//!
//! This is `chain_core::statics::walls::domain_walls` as an iterator, with the same rule for
//! vertical rotors; that function collects into a `Vec`, which needs `alloc`. The embedded-host
//! tests check that both give the same walls.

use crate::Real;

/// Kink or antikink.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Charge {
    /// `+theta_bar` on the left, `-theta_bar` on the right: the zero-energy wall.
    Kink,
    /// `-theta_bar` on the left, `+theta_bar` on the right: stretches springs.
    Antikink,
}

impl Charge {
    /// `"kink"` or `"antikink"`, as printed in the firmware's output.
    pub const fn name(self) -> &'static str {
        match self {
            Charge::Kink => "kink",
            Charge::Antikink => "antikink",
        }
    }

    fn of_left<T: Real>(left: T) -> Self {
        if left > T::zero() { Charge::Kink } else { Charge::Antikink }
    }
}

/// A domain wall: where it is (in rotor indices, fractional) and which kind.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wall<T> {
    pub position: T,
    pub charge: Charge,
}

/// The domain walls of `theta`, left to right. A rotor exactly at zero belongs to the wall between
/// its neighbours and is not counted twice.
pub fn domain_walls<T: Real>(theta: &[T]) -> DomainWalls<'_, T> {
    DomainWalls { theta, next: 0 }
}

/// Iterator returned by [`domain_walls`].
#[derive(Clone, Debug)]
pub struct DomainWalls<'a, T> {
    theta: &'a [T],
    /// The left rotor of the next pair to look at.
    next: usize,
}

impl<T: Real> Iterator for DomainWalls<'_, T> {
    type Item = Wall<T>;

    fn next(&mut self) -> Option<Wall<T>> {
        let zero = T::zero();
        while self.next + 1 < self.theta.len() {
            let i = self.next;
            self.next += 1;
            let (t0, t1) = (self.theta[i], self.theta[i + 1]);
            if t0 == zero {
                continue;
            }
            if t1 == zero {
                // A vertical rotor: the wall sits on it if the signs on either side differ.
                match self.theta.get(i + 2) {
                    Some(&t2) if t2 != zero && t2.signum() != t0.signum() => {
                        return Some(Wall { position: T::of((i + 1) as f64), charge: Charge::of_left(t0) });
                    }
                    _ => continue,
                }
            }
            if t0.signum() != t1.signum() {
                return Some(Wall {
                    position: T::of(i as f64) + t0 / (t0 - t1),
                    charge: Charge::of_left(t0),
                });
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn walls_are_interpolated_sign_changes() {
        let theta = [0.5, 0.5, 0.25, -0.75, -0.5, -0.5, 0.0, 0.5];
        let mut walls = domain_walls(&theta);
        assert_eq!(walls.next(), Some(Wall { position: 2.25, charge: Charge::Kink }));
        assert_eq!(walls.next(), Some(Wall { position: 6.0, charge: Charge::Antikink }));
        assert_eq!(walls.next(), None);
    }

    #[test]
    fn a_uniform_state_has_no_wall_and_zeros_at_the_ends_none_either() {
        assert_eq!(domain_walls(&[0.3f32; 5]).count(), 0);
        assert_eq!(domain_walls(&[0.0, 0.3, 0.3, 0.0]).count(), 0);
        assert_eq!(domain_walls::<f64>(&[]).count(), 0);
    }
}
