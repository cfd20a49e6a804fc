//! Domain walls of a configuration without a heap (paper Appendix C).
//!
//! Angles are measured alternately from `+y` and `-y` (docs/theory.md), so a uniform state has one
//! sign throughout and a domain wall is a sign change of `theta`. Its position interpolates
//! linearly between the two rotors that lean opposite ways, `x = i + theta_i / (theta_i - theta_{i+1})`,
//! so a vertical rotor sits exactly on the wall. A wall from `+` to `-` (left to right) is a
//! **kink**, from `-` to `+` an **antikink**.
//!
//! This is `chain_core::statics::walls::domain_walls` as an iterator, with the same rule for
//! vertical and non-finite rotors; that function collects into a `Vec`, which needs `alloc`. The embedded-host
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
    /// Position in rotor indices: `i + theta_i / (theta_i - theta_{i+1})` (Appendix C).
    pub position: T,
    /// Kink or antikink.
    pub charge: Charge,
}

/// The domain walls of `theta`, left to right. Rotors exactly at zero (vertical) and non-finite
/// angles lean neither way: a wall across them sits in the middle between the two leaning rotors
/// around them, and is counted once.
pub fn domain_walls<T: Real>(theta: &[T]) -> DomainWalls<'_, T> {
    DomainWalls { theta, next: 0, last: None }
}

/// Iterator returned by [`domain_walls`].
#[derive(Clone, Debug)]
pub struct DomainWalls<'a, T> {
    theta: &'a [T],
    /// The next rotor to look at.
    next: usize,
    /// The last rotor that leans, and its angle.
    last: Option<(usize, T)>,
}

impl<T: Real> Iterator for DomainWalls<'_, T> {
    type Item = Wall<T>;

    fn next(&mut self) -> Option<Wall<T>> {
        let zero = T::zero();
        while self.next < self.theta.len() {
            let j = self.next;
            let t = self.theta[j];
            self.next += 1;
            if !t.is_finite() || t == zero {
                continue;
            }
            let previous = self.last.replace((j, t));
            if let Some((i, ti)) = previous
                && (ti > zero) != (t > zero)
            {
                let position =
                    if j == i + 1 { T::of(i as f64) + ti / (ti - t) } else { T::of((i + j) as f64 / 2.0) };
                return Some(Wall { position, charge: Charge::of_left(ti) });
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
