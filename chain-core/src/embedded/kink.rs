//! The zero-energy kink at any centre (paper Sec. II), built by the branch solve into a caller's
//! array; and the paper's reflected kink, the first approximation of the antikink.
//!
//! Forward iteration of the branch map from the left end cannot centre a kink deep in a long
//! chain: near `+theta_bar` the map's slope is `F' = (a + 2 r sin theta_bar)/(a - 2 r sin theta_bar)`
//! (15.2 at `theta_bar = 0.58`), so a kink 30 sites in needs a starting offset of `F'^-30`, far
//! below double precision. Instead the kink is built **outward from its centre**: the forward map
//! to the right and the inverse map to the left. Each runs into the *attracting* fixed point of its
//! direction (`-theta_bar` to the right, `+theta_bar` to the left), so rounding errors shrink at
//! every step, whatever the length of the chain and the float type.
//!
//! The centre is the wall position of Appendix C: for an integer centre `c` rotor `c` stands
//! vertical; for `c = i + f` the angles of rotors `i` and `i + 1` are chosen on the spring-`i`
//! constraint, by bisection, so that the interpolated sign change sits at `i + f`.

use super::walls::{Charge, domain_walls};
use super::{EmbeddedError, FloatChain, Real};

/// The most bisection steps for a fractional centre: each halves the bracket, so 200 reach the
/// float's resolution from any bracket (64 suffice for `f64`); the loop stops earlier when the
/// midpoint no longer moves.
const BISECTION_STEPS: usize = 200;

/// Writes the zero-energy kink of `model` centred at `centre` (in rotor indices,
/// `0 <= centre <= n - 1`) into `theta`, which must hold one angle per rotor. At `centre = 0` or
/// `n - 1` the wall sits on the end rotor, which stands vertical: the wall has reached the end and
/// the chain is one domain (as for the statics' `kink`). A centre inside the chain whose profile
/// shows no wall (a `theta_bar` so small that the wall is far wider than the chain and its angles
/// round to zero) is [`EmbeddedError::NoWall`]. The wall's interpolated sign change sits at
/// `centre` to about `eps a / (r theta_bar^2)` sites (the statics' `kink` says why), below 1e-12
/// for `theta_bar >= 0.01`.
pub fn kink_into<T: Real, M: FloatChain<T> + ?Sized>(
    model: &M,
    centre: T,
    theta: &mut [T],
) -> Result<(), EmbeddedError> {
    wall_into(model, centre, theta, Wall::Kink)
}

/// Writes the paper's first approximation of the antikink (Sec. II, Fig. `fig:akcobweb`) into
/// `theta`: the kink's spring points reflected across the diagonal of the cobweb plot. Every spring
/// `p` is at rest, with its two angles swapped: `(theta_{p+1}, theta_p)` lies on spring `p`'s
/// flipper branch. It runs from `-theta_bar` to `+theta_bar`, centred at `centre`, and is not an
/// equilibrium.
pub fn reflected_kink_into<T: Real, M: FloatChain<T> + ?Sized>(
    model: &M,
    centre: T,
    theta: &mut [T],
) -> Result<(), EmbeddedError> {
    wall_into(model, centre, theta, Wall::Reflected)
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Wall {
    Kink,
    Reflected,
}

/// Builds a wall outward from its centre. For the kink, the forward map runs to the right and the
/// inverse map to the left; the reflected wall swaps the two maps.
fn wall_into<T: Real, M: FloatChain<T> + ?Sized>(
    model: &M,
    centre: T,
    theta: &mut [T],
    wall: Wall,
) -> Result<(), EmbeddedError> {
    let n = model.rotor_count();
    if theta.len() != n || n < 2 {
        return Err(EmbeddedError::WrongRotorCount { rotors: n, expected: theta.len() });
    }
    let max = T::of_index(n - 1);
    if !(centre.is_finite() && centre >= T::ZERO && centre <= max) {
        return Err(EmbeddedError::CentreOutOfRange { centre: centre.widen(), max: max.widen() });
    }
    // Spring p's map to the right (theta_p -> theta_{p+1}) and to the left.
    let right = |p: usize, t: T| -> Result<T, EmbeddedError> {
        Ok(match wall {
            Wall::Kink => model.next_angles(p, t)?[0],
            Wall::Reflected => model.previous_angles(p, t)?[0],
        })
    };
    let left = |p: usize, t: T| -> Result<T, EmbeddedError> {
        Ok(match wall {
            Wall::Kink => model.previous_angles(p, t)?[0],
            Wall::Reflected => model.next_angles(p, t)?[0],
        })
    };
    // `centre = i + f` with `0 <= f < 1` and `i + 1 < n`; a centre on the last rotor is read as
    // "rotor n - 1 vertical".
    let whole = centre.floor();
    let (i, f) = if whole >= max { (n - 1, T::ZERO) } else { (whole.floor_index(), centre - whole) };
    theta.iter_mut().for_each(|t| *t = T::ZERO);
    if f > T::ZERO {
        // theta_i between 0 and the angle whose right neighbour is 0, chosen so that the
        // interpolated sign change theta_i / (theta_i - theta_{i+1}) sits at i + f.
        let end = left(i, T::ZERO)?;
        let half = T::of(0.5);
        let (mut near, mut far) = (T::ZERO, end);
        for _ in 0..BISECTION_STEPS {
            let mid = half * (near + far);
            if mid == near || mid == far {
                break;
            }
            if mid / (mid - right(i, mid)?) < f {
                near = mid;
            } else {
                far = mid;
            }
        }
        theta[i] = half * (near + far);
    }
    for p in i..n - 1 {
        theta[p + 1] = right(p, theta[p])?;
    }
    for p in (0..i).rev() {
        theta[p] = left(p, theta[p + 1])?;
    }
    // A centre inside the chain leaves one wall of the asked charge there. At a `theta_bar` so
    // small that the wall is far wider than the chain (1e-8 at n = 60) the angles round to zero
    // with no sign change: that is no kink, and says so.
    if centre > T::ZERO && centre < max {
        let (expected, charge) = match wall {
            Wall::Kink => ("kink", Charge::Kink),
            Wall::Reflected => ("antikink", Charge::Antikink),
        };
        let (mut kinks, mut antikinks) = (0, 0);
        for w in domain_walls(theta) {
            match w.charge {
                Charge::Kink => kinks += 1,
                Charge::Antikink => antikinks += 1,
            }
        }
        let found = if charge == Charge::Kink { (kinks, antikinks) } else { (antikinks, kinks) };
        if found != (1, 0) {
            return Err(EmbeddedError::NoWall { expected, centre: centre.widen(), kinks, antikinks });
        }
    }
    Ok(())
}
