//! Setting the kink in motion along its translation mode without a heap (paper Sec. V and
//! Appendix B): the launch of the firmware, for a kink only.
//!
//! The kink costs no energy wherever it sits: the kinks at all centres form a one-parameter
//! family of configurations with every spring at rest length, the mechanism of paper Sec. II. Its
//! tangent is the **zero mode of the compatibility matrix**: a velocity `u_i = r_i thetadot_i` (tip
//! speeds) with `C u = 0` changes no spring length to first order. With `n` rotors and `n - 1`
//! springs `C` is bidiagonal, `C[p][p] u_p + C[p][p+1] u_{p+1} = 0`, so the mode follows from one
//! entry by the two recurrences
//!
//! ```text
//! u_{p+1} = -C[p][p] / C[p][p+1] u_p     (to the right)
//! u_p     = -C[p][p+1] / C[p][p] u_{p+1} (to the left)
//! ```
//!
//! started at the rotor nearest the wall, where the mode is largest; outward the ratios are the
//! slopes of the branch map (`1 / 15.2` in both domains at `theta_bar = 0.58`), so the mode decays
//! away from the kink and no recurrence grows. `C` comes from the symbolic engine (the generated
//! `compatibility`), so no derivative is taken here.
//!
//! As in [`launch`](super::launch) (Appendix B), the mode is normalised in tip displacements,
//! `sum_i e_i^2 = 1`, signed so that the profile moves towards rotor `n - 1`, and the launch is
//! `r_i thetadot_i = v0 e_i`: the initial kinetic energy is exactly `M v0^2 / 2`. That function
//! finds the mode among the lowest eigenvectors of the tangent stiffness (it needs `alloc`, and
//! serves the antikink too, which is no zero mode of `C`); a test checks that both agree for a
//! kink.

use crate::dynamics::DynamicsError;
use crate::model::{ChainGeometry, CompatibilityLayout};
use crate::real::Real;
use crate::statics::StaticsError;

/// The kink's translation mode at `theta` in tip displacements: `C e = 0`, `sum e_i^2 = 1`,
/// pointing so that the kink moves towards rotor `n - 1`.
pub fn kink_translation_mode<T: Real, M: ChainGeometry<T> + ?Sized, const N: usize>(
    model: &M,
    theta: &[T; N],
) -> Result<[T; N], DynamicsError> {
    if model.rotor_count() != N || N < 2 {
        let wrong = StaticsError::WrongLength { what: "theta", len: N, expected: model.rotor_count() };
        return Err(wrong.into());
    }
    if model.compatibility_layout() != CompatibilityLayout::Bidiagonal {
        return Err(DynamicsError::NotAChain { what: "the compatibility matrix", expected: "bidiagonal" });
    }
    let zero = T::ZERO;
    // The two bands side by side in one buffer of 2N (the layout's 2(N - 1) values, then padding).
    let mut bands = [[zero; N]; 2];
    {
        let flat = bands.as_flattened_mut();
        model.compatibility_into(theta, &mut flat[..2 * (N - 1)]);
        // [left (N - 1) | right (N - 1) | 2 spare] -> rows of N: left, then right shifted by one.
        flat.copy_within(N - 1..2 * (N - 1), N);
    }
    let [left, right] = bands;
    let no_mode =
        |p: usize| DynamicsError::NoZeroMode { spring: p, left: left[p].widen(), right: right[p].widen() };
    // The rotor nearest the wall: the smallest |theta|.
    let start = (0..N).fold(0, |best, i| if theta[i].abs() < theta[best].abs() { i } else { best });
    let mut e = [zero; N];
    e[start] = T::ONE;
    for p in start..N - 1 {
        e[p + 1] = -left[p] / right[p] * e[p];
        if !e[p + 1].is_finite() {
            return Err(no_mode(p));
        }
    }
    for p in (0..start).rev() {
        e[p] = -right[p] / left[p] * e[p + 1];
        if !e[p].is_finite() {
            return Err(no_mode(p));
        }
    }
    let norm = e.iter().fold(zero, |s, &x| s + x * x).sqrt();
    e.iter_mut().for_each(|x| *x = *x / norm);
    // Moving right, the profile shifts as theta(x - v t), so thetadot = -v dtheta/dx: the mode
    // must have a positive overlap with -dtheta/dx (central differences, one-sided at the ends).
    let push = (0..N).fold(zero, |s, i| {
        let (l, r) = (theta[i.saturating_sub(1)], theta[(i + 1).min(N - 1)]);
        s - (r - l) * e[i] / model.rotor_length(i)
    });
    if push < zero {
        e.iter_mut().for_each(|x| *x = -*x);
    }
    Ok(e)
}

/// The kink at `theta` launched towards rotor `n - 1` with speed amplitude `v0` (tip speed, in
/// `a / t`): the angular velocities `thetadot_i = v0 e_i / r_i` (Appendix B). A negative `v0`
/// launches it towards rotor 0 at speed `|v0|` (the same velocities, negated): this module has no
/// separate direction, unlike `dynamics::launch`, which takes `v0 >= 0` and a `Direction`.
pub fn kink_launch_velocities<T: Real, M: ChainGeometry<T> + ?Sized, const N: usize>(
    model: &M,
    theta: &[T; N],
    v0: T,
) -> Result<[T; N], DynamicsError> {
    if !v0.is_finite() {
        return Err(DynamicsError::InvalidSetup {
            options: "kink_launch",
            name: "v0",
            value: v0.widen(),
            rule: "finite",
        });
    }
    let e = kink_translation_mode(model, theta)?;
    Ok(core::array::from_fn(|i| v0 * e[i] / model.rotor_length(i)))
}
