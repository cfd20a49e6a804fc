//! The zero-energy kink at any centre (paper Sec. II), built by the branch solve into a
//! caller's array.
//!
//! The construction is the one of `chain_core::statics::kink` (which returns a `Vec` and so needs
//! `alloc`): the kink is built **outward from its centre**, with the forward branch map to the
//! right and the inverse map to the left. Each runs into the *attracting* fixed point of its
//! direction (`-theta_bar` to the right, `+theta_bar` to the left), so rounding errors shrink at
//! every step whatever the length of the chain; iterating from one end instead would need a
//! starting offset of `F'^-c` (`F' = 15.2` at `theta_bar = 0.58`) for a kink `c` sites in.
//!
//! The centre is the wall position of Appendix C: for an integer centre `c` rotor `c` stands
//! vertical; for `c = i + f` the angles of rotors `i` and `i + 1` are chosen on the spring-`i`
//! constraint, by bisection, so that the interpolated sign change sits at `i + f`.

use crate::{Model, Real, RunError};

/// The most bisection steps for a fractional centre: each halves the bracket, so 200 reach the
/// float's resolution from any bracket (64 suffice for `f64`); the loop stops earlier when the
/// midpoint no longer moves.
const BISECTION_STEPS: usize = 200;

/// Writes the zero-energy kink of `model` centred at `centre` (in rotor indices,
/// `0 <= centre <= n - 1`) into `theta`, which must hold one angle per rotor.
pub fn kink_into<T: Real, M: Model<T> + ?Sized>(
    model: &M,
    centre: T,
    theta: &mut [T],
) -> Result<(), RunError> {
    let n = model.rotor_count();
    if theta.len() != n {
        return Err(RunError::WrongRotorCount { rotors: n, expected: theta.len() });
    }
    let max = T::of((n - 1) as f64);
    if !(centre.is_finite() && centre >= T::zero() && centre <= max) {
        return Err(RunError::CentreOutOfRange { centre: centre.widen(), max: max.widen() });
    }
    // `centre = i + f` with `0 <= f < 1` and `i + 1 < n`; a centre on the last rotor is read as
    // "rotor n - 2 at the start of its spring, rotor n - 1 vertical".
    let whole = centre.floor();
    let (i, f) = if whole >= max { (n - 1, T::zero()) } else { (whole.widen() as usize, centre - whole) };
    theta.iter_mut().for_each(|t| *t = T::zero());
    if f > T::zero() {
        // theta_i between 0 and the angle whose right neighbour is 0, chosen so that the
        // interpolated sign change theta_i / (theta_i - theta_{i+1}) sits at i + f.
        let end = model.previous_angle(i, T::zero())?;
        let half = T::of(0.5);
        let (mut near, mut far) = (T::zero(), end);
        for _ in 0..BISECTION_STEPS {
            let mid = half * (near + far);
            if mid == near || mid == far {
                break;
            }
            let position = mid / (mid - model.next_angle(i, mid)?);
            if position < f {
                near = mid;
            } else {
                far = mid;
            }
        }
        theta[i] = half * (near + far);
    }
    for p in i..n - 1 {
        theta[p + 1] = model.next_angle(p, theta[p])?;
    }
    for p in (0..i).rev() {
        theta[p] = model.previous_angle(p, theta[p + 1])?;
    }
    Ok(())
}
