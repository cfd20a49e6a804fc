//! The zero-energy kink at any centre (paper Sec. II), built by the branch solve (into a caller's
//! array without a heap, or into a new `Vec`); the paper's reflected kink, the first
//! approximation of the antikink; and the mechanism, the kink moved along the chain.
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

#[cfg(feature = "alloc")]
use alloc::vec;
#[cfg(feature = "alloc")]
use alloc::vec::Vec;

use super::error::StaticsError;
use super::walls::{Charge, count_walls};
use crate::model::ChainGeometry;
#[cfg(feature = "alloc")]
use crate::model::ChainModel;
use crate::real::Real;

/// The most bisection steps for a fractional centre: each halves the bracket, so 200 reach the
/// float's resolution from any bracket (64 suffice for `f64`); the loop stops earlier when the
/// midpoint no longer moves.
const BISECTION_STEPS: usize = 200;

/// Writes the zero-energy kink of `model` centred at `centre` (in rotor indices,
/// `0 <= centre <= n - 1`) into `theta`, which must hold one angle per rotor. At `centre = 0` or
/// `n - 1` the wall sits on the end rotor, which stands vertical: the wall has reached the end and
/// the chain is one domain (as for the statics' `kink`). A centre inside the chain whose profile
/// shows no wall (a `theta_bar` so small that the wall is far wider than the chain and its angles
/// round to zero) is [`StaticsError::NoWall`]. The wall's interpolated sign change sits at
/// `centre` to about `eps a / (r theta_bar^2)` sites (the statics' `kink` says why), below 1e-12
/// for `theta_bar >= 0.01`.
pub fn kink_into<T: Real, M: ChainGeometry<T> + ?Sized>(
    model: &M,
    centre: T,
    theta: &mut [T],
) -> Result<(), StaticsError> {
    wall_into(model, centre, theta, Wall::Kink)
}

/// Writes the paper's first approximation of the antikink (Sec. II, Fig. `fig:akcobweb`) into
/// `theta`: the kink's spring points reflected across the diagonal of the cobweb plot. Every spring
/// `p` is at rest, with its two angles swapped: `(theta_{p+1}, theta_p)` lies on spring `p`'s
/// flipper branch. It runs from `-theta_bar` to `+theta_bar`, centred at `centre`, and is not an
/// equilibrium.
pub fn reflected_kink_into<T: Real, M: ChainGeometry<T> + ?Sized>(
    model: &M,
    centre: T,
    theta: &mut [T],
) -> Result<(), StaticsError> {
    wall_into(model, centre, theta, Wall::Reflected)
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Wall {
    Kink,
    Reflected,
}

/// Builds a wall outward from its centre. For the kink, the forward map runs to the right and the
/// inverse map to the left; the reflected wall swaps the two maps.
fn wall_into<T: Real, M: ChainGeometry<T> + ?Sized>(
    model: &M,
    centre: T,
    theta: &mut [T],
    wall: Wall,
) -> Result<(), StaticsError> {
    let n = model.rotor_count();
    if theta.len() != n {
        return Err(StaticsError::WrongLength { what: "theta", len: theta.len(), expected: n });
    }
    let max = T::of_index(n.saturating_sub(1));
    if n < 2 || !(centre.is_finite() && centre >= T::ZERO && centre <= max) {
        return Err(StaticsError::CentreOutOfRange { centre: centre.widen(), n, max: max.widen() });
    }
    // Spring p's map to the right (theta_p -> theta_{p+1}) and to the left.
    let right = |p: usize, t: T| -> Result<T, StaticsError> {
        Ok(match wall {
            Wall::Kink => model.next_angles(p, t)?[0],
            Wall::Reflected => model.previous_angles(p, t)?[0],
        })
    };
    let left = |p: usize, t: T| -> Result<T, StaticsError> {
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
        let (kinks, antikinks) = count_walls(theta);
        let found = if charge == Charge::Kink { (kinks, antikinks) } else { (antikinks, kinks) };
        if found != (1, 0) {
            let (centre, theta_bar) = (centre.widen(), model.theta_bar().widen());
            return Err(StaticsError::NoWall { expected, centre, theta_bar, kinks, antikinks });
        }
    }
    Ok(())
}

/// The zero-energy kink of `model` centred at `centre` (in rotor indices, `0 <= centre <= n - 1`).
/// At `centre = 0` or `n - 1` the wall sits on the end rotor, which stands vertical: the wall has
/// reached the end, the chain is one domain, and [`domain_walls`](super::walls::domain_walls)
/// finds no wall (it reports sign changes between two leaning rotors). A centre inside the chain
/// whose profile shows no wall (a `theta_bar` so small that the wall is far wider than the chain
/// and its angles round to zero) is [`StaticsError::NoWall`].
///
/// **How exactly the wall sits at `centre`.** The branch solve gives each angle to a rounding of
/// the O(1) geometry, an absolute `eps` (2.2e-16), not `eps` relative to the angle; near the core
/// of a wide wall neighbouring angles differ by about `2 r theta_bar^2 / a`, so the interpolated
/// sign change is placed to about `eps a / (r theta_bar^2)` sites: below 1e-12 from
/// `theta_bar = 0.01` up, 3e-8 at 1e-4 and 2e-4 at 1e-6 (`r = 0.8 a`). The kink still has zero
/// energy to rounding; only its label `centre` is that uncertain (a test checks the bound for
/// `r / a` from 0.3 to 1.5).
///
/// # Example
///
/// ```
/// use rotor_chain::RuntimeChain;
/// use rotor_chain::statics::kink::kink;
/// use rotor_chain::statics::walls::domain_walls;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let chain = RuntimeChain::builder(60, 0.8, 1.0e4, 0.58).build()?; // n, r, k, theta_bar
/// let theta = kink(&chain, 41.25)?;                               // any centre, fractional too
/// assert!((domain_walls(&theta)[0].position - 41.25).abs() < 1e-9);
/// assert!(rotor_chain::Potential::energy(&chain, &theta) < 1e-16); // zero energy, in M a^2/t^2
/// # Ok(())
/// # }
/// ```
#[cfg(feature = "alloc")]
pub fn kink<M: ChainModel + ?Sized>(model: &M, centre: f64) -> Result<Vec<f64>, StaticsError> {
    wall_profile(model, centre, Wall::Kink)
}

/// The paper's first approximation of the antikink (Sec. II, Fig. `fig:akcobweb`): the kink's
/// spring points reflected across the diagonal of the cobweb plot. Every spring `p` is at rest,
/// but with its two angles swapped: `(theta_{p+1}, theta_p)` lies on spring `p`'s flipper branch.
/// It runs from `-theta_bar` to `+theta_bar`, centred at `centre`, and is not an equilibrium: the
/// antikink analysis relaxes it.
#[cfg(feature = "alloc")]
pub fn reflected_kink<M: ChainModel + ?Sized>(model: &M, centre: f64) -> Result<Vec<f64>, StaticsError> {
    wall_profile(model, centre, Wall::Reflected)
}

/// Builds a wall outward from its centre into a new `Vec` ([`kink_into`] and
/// [`reflected_kink_into`]).
#[cfg(feature = "alloc")]
fn wall_profile<M: ChainModel + ?Sized>(
    model: &M,
    centre: f64,
    wall: Wall,
) -> Result<Vec<f64>, StaticsError> {
    let mut theta = vec![0.0; model.rotor_count()];
    wall_into(model, centre, &mut theta, wall)?;
    Ok(theta)
}

/// The most steps [`mechanism_path`] takes.
#[cfg(feature = "alloc")]
pub const MAX_PATH_STEPS: usize = 1_000_000;

/// The mechanism: kinks at `steps + 1` evenly spaced centres from `from` to `to`, each a
/// zero-energy configuration (paper Sec. II: the kink can sit anywhere along the chain).
///
/// # Errors
/// A centre outside the chain or not finite, more than [`MAX_PATH_STEPS`] steps, or a failed
/// branch solve.
#[cfg(feature = "alloc")]
pub fn mechanism_path<M: ChainModel + ?Sized>(
    model: &M,
    from: f64,
    to: f64,
    steps: usize,
) -> Result<Vec<(f64, Vec<f64>)>, StaticsError> {
    super::validate::at_most("steps", steps, MAX_PATH_STEPS)?;
    (0..=steps)
        .map(|s| {
            let c = if steps == 0 { from } else { from + (to - from) * s as f64 / steps as f64 };
            kink(model, c).map(|theta| (c, theta))
        })
        .collect()
}
