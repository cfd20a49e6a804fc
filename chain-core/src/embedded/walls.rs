//! Domain walls of a configuration, without a heap (paper Appendix C).
//!
//! Angles are measured alternately from `+y` and `-y` (docs/theory.md), so a uniform state has one
//! sign throughout and a domain wall is a sign change of `theta`. Its position interpolates
//! linearly between the two rotors that lean opposite ways, `x = i + theta_i / (theta_i - theta_{i+1})`,
//! so a vertical rotor sits exactly on the wall. A wall from `+` to `-` (left to right) is a
//! **kink**, from `-` to `+` an **antikink**. `statics::walls::domain_walls` collects this
//! iterator into a `Vec`.

use super::Real;

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

/// The domain walls of `theta`, left to right: a sign change between two leaning rotors. A rotor
/// exactly at zero leans neither way; a wall across one vertical rotor sits on it, across a run
/// of them in its middle. A non-finite angle leans neither way either (read as zero), so no wall
/// gets a NaN position.
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
