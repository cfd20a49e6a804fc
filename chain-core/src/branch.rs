//! The branch solve of paper Appendix A: given one rotor's angle, the angles of its neighbour for
//! which the spring between them sits at its rest length.
//!
//! In complex notation (pivot of rotor `p` at the origin, of rotor `p + 1` at `a`), the tips are
//! `z1 = i r1 e^{-i theta_p}` and `z2 = a - i r2 e^{i theta_{p+1}}` (the paper's Appendix A with
//! rotor lengths `r1`, `r2`). The two constraints `|z2 - z1|^2 = l0^2` and `|z2 - a|^2 = r2^2`
//! eliminate `conj(z2)` and leave the quadratic `A z2^2 + B z2 + C = 0` with
//!
//! ```text
//! A = (conj(z1) - a) / (a - z1)
//! B = (l0^2 + a^2 - 2 r^2) / (a - z1) - a (conj(z1) - z1) / (a - z1)
//! C = a^2 - r^2 - a (l0^2 + a^2 - 2 r^2) / (a - z1)
//! ```
//!
//! for equal rotor lengths `r` (a test checks that our roots satisfy it). We solve the same
//! quadratic, for rotor lengths `r1`, `r2`, shifted to the pivot of rotor `p + 1`, `w = z2 - a`,
//! where it reads `conj(c) w^2 + (r2^2 + |c|^2 - l0^2) w + c r2^2 = 0` with
//! `c = a - z1`: the form with the least cancellation. Its roots lie on the circle `|w| = r2` exactly
//! when the two circles meet, `|r2 - l0| <= |c| <= r2 + l0`; otherwise there is no real root and
//! the solve returns [`BranchError::NoRealRoot`], never NaN.
//!
//! **Root order.** Root `0` is the *flipper branch*: the intersection on the clockwise side of the
//! line from tip `p` to pivot `p + 1`. In the flipper phase both uniform states `+theta_bar` and
//! `-theta_bar` lie on it, so iterating root `0` traces the zero-energy kink (paper Sec. II, the
//! black curve of Fig. `fig:kcobweb`). Root `1` is the other intersection.
//!
//! The inverse map follows from the chain's mirror symmetry: reflecting `x -> -x` turns spring `p`
//! read from the right into a spring read from the left with `theta -> -theta` and the rotor
//! lengths swapped.

use crate::error::BranchError;
use crate::real::Real;

/// Both angles `theta_{p+1}` that put spring `p` at rest length `l0` for the given `theta_p`,
/// flipper branch first. `spring` only labels errors. Generic over the float type: an `f32` chain
/// solves in `f32` (its errors carry the numbers widened to `f64`, exactly).
///
/// The quadratic is solved in real arithmetic. With `c = a - z1`, `d^2 = |c|^2` and
/// `beta = r2^2 + d^2 - l0^2`, the product of its leading and constant coefficients is
/// `conj(c) c r2^2 = d^2 r2^2`, real, so its discriminant `beta^2 - 4 d^2 r2^2` is real too; where
/// the circles meet it is `<= 0`, `sqrt(disc) = i s` with
/// `s^2 = (2 d r2 - beta)(2 d r2 + beta)` (factored: no cancellation between two squares), and
/// the roots are `w0 = q / conj(c) = q c / d^2` and `w1 = c r2^2 / q` with `q = -(beta + i s) / 2`.
pub fn next_angles<T: Real>(
    spring: usize,
    a: T,
    r1: T,
    r2: T,
    l0: T,
    theta: T,
) -> Result<[T; 2], BranchError> {
    if !theta.is_finite() {
        return Err(BranchError::NotFinite { spring, theta: theta.widen() });
    }
    let (s, co) = theta.sin_cos();
    // c = a - z1, z1 = i r1 e^{-i theta} = (r1 sin theta, r1 cos theta).
    let (cx, cy) = (a - r1 * s, -(r1 * co));
    let d2 = cx * cx + cy * cy;
    let distance = d2.sqrt();
    let (min, max) = ((r2 - l0).abs(), r2 + l0);
    // Circles that touch within rounding still have one (double) root; allow a few ulps.
    let slack = T::of(8.0) * T::EPSILON * max;
    if !(distance >= min - slack && distance <= max + slack) {
        return Err(BranchError::NoRealRoot {
            spring,
            theta: theta.widen(),
            distance: distance.widen(),
            rotor_length: r2.widen(),
            rest_length: l0.widen(),
            min: min.widen(),
            max: max.widen(),
        });
    }
    if d2 == T::ZERO {
        // Tip p on pivot p + 1 (then r2 = l0 within the slack): every angle is a root.
        return Err(BranchError::Degenerate { spring, theta: theta.widen() });
    }
    let r22 = r2 * r2;
    let beta = r22 + d2 - l0 * l0;
    let reach = T::of(2.0) * distance * r2;
    // Rounding can leave s^2 slightly negative for touching circles: the double root.
    let s2 = (reach - beta) * (reach + beta);
    let root = if s2 > T::ZERO { s2.sqrt() } else { T::ZERO };
    let half = T::of(0.5);
    let (qx, qy) = (-(half * beta), -(half * root));
    // w0 = q c / d^2; w1 = c r2^2 conj(q) / |q|^2.
    let w0 = ((qx * cx - qy * cy) / d2, (qx * cy + qy * cx) / d2);
    let q2 = qx * qx + qy * qy;
    let w1 = (r22 * (cx * qx + cy * qy) / q2, r22 * (cy * qx - cx * qy) / q2);
    // theta_{p+1} from w = -i r2 e^{i theta}:  r2 sin theta = Re w, r2 cos theta = -Im w.
    let angle = |(wx, wy): (T, T)| wx.atan2(-wy);
    // Orientation of tip p+1 relative to the directed line tip p -> pivot p+1: the cross
    // product of c (tip p to pivot p + 1) with c + w (tip p to tip p + 1).
    let side = |(wx, wy): (T, T)| cx * wy - cy * wx;
    let (first, second) = if side(w0) <= side(w1) { (w0, w1) } else { (w1, w0) };
    Ok([angle(first), angle(second)])
}

/// Both angles `theta_p` that put spring `p` at rest length `l0` for the given `theta_{p+1}`,
/// flipper branch first: the inverse of [`next_angles`].
pub fn previous_angles<T: Real>(
    spring: usize,
    a: T,
    r1: T,
    r2: T,
    l0: T,
    theta_next: T,
) -> Result<[T; 2], BranchError> {
    next_angles(spring, a, r2, r1, l0, -theta_next).map(|[x, y]| [-x, -y]).map_err(|e| match e {
        BranchError::NoRealRoot { spring, distance, rotor_length, rest_length, min, max, .. } => {
            BranchError::NoRealRoot {
                spring,
                theta: theta_next.widen(),
                distance,
                rotor_length,
                rest_length,
                min,
                max,
            }
        }
        BranchError::Degenerate { spring, .. } => {
            BranchError::Degenerate { spring, theta: theta_next.widen() }
        }
        BranchError::NotFinite { spring, .. } => BranchError::NotFinite { spring, theta: theta_next.widen() },
        other => other,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use chain_geometry::{rest_length, spring_length};
    use nalgebra::Complex;

    const A: f64 = 1.0;
    const R: f64 = 0.8;

    /// Whether spring `p` can reach rest length `l0` for `theta_p = theta` at all: the range of
    /// its length over a fine grid of `theta_{p+1}` (Cartesian tips written out here, not the
    /// solve's circle criterion), and how far `l0` lies inside it.
    fn reachable(r1: f64, r2: f64, l0: f64, theta: f64) -> (bool, f64) {
        let length = |t2: f64| {
            let (x1, y1) = (r1 * theta.sin(), r1 * theta.cos());
            let (x2, y2) = (A + r2 * t2.sin(), -r2 * t2.cos());
            ((x2 - x1).powi(2) + (y2 - y1).powi(2)).sqrt()
        };
        let steps = 20_000;
        let (lo, hi) = (0..=steps)
            .map(|j| length(-core::f64::consts::PI + 2.0 * core::f64::consts::PI * j as f64 / steps as f64))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), l| (lo.min(l), hi.max(l)));
        (lo <= l0 && l0 <= hi, (l0 - lo).min(hi - l0).abs())
    }

    #[test]
    fn both_roots_put_the_spring_at_rest_length() {
        let (mut solved, mut refused) = (0, 0);
        for (r1, r2, l0) in [(R, R, 1.7), (0.8, 0.6, 1.5), (0.5, 0.9, 1.2), (0.8, 0.8, 2.55), (0.3, 0.4, 0.2)]
        {
            for theta in [-1.0, -0.3, 0.0, 0.4, 0.9, 2.0, 3.0] {
                let (exists, margin) = reachable(r1, r2, l0, theta);
                // Cases where l0 grazes the reachable range are decided by rounding: none here.
                assert!(margin > 1e-6, "a grazing case: {r1} {r2} {l0} {theta}");
                match next_angles(0, A, r1, r2, l0, theta) {
                    Ok(roots) => {
                        assert!(exists, "roots {roots:?} where l0 = {l0} is out of reach at {theta}");
                        for t2 in roots {
                            let l = spring_length(A, r1, r2, theta, t2);
                            assert!((l - l0).abs() < 1e-12, "theta {theta} -> {t2}: length {l} != {l0}");
                        }
                        solved += 1;
                    }
                    Err(e) => {
                        assert!(!exists, "no roots ({e}) where l0 = {l0} is within reach at {theta}");
                        assert!(matches!(e, BranchError::NoRealRoot { .. }), "{e}");
                        refused += 1;
                    }
                }
            }
        }
        // Both outcomes occur, so the test exercises both.
        assert!(solved >= 10 && refused >= 10, "{solved} solved, {refused} refused");
    }

    #[test]
    fn uniform_states_lie_on_the_flipper_branch() {
        let tb = 0.58;
        let l0 = rest_length(A, R, tb);
        for t in [tb, -tb] {
            let [z0, _] = next_angles(3, A, R, R, l0, t).unwrap();
            assert!((z0 - t).abs() < 1e-12, "{t} -> {z0}");
        }
    }

    #[test]
    fn slope_at_the_fixed_point_matches_the_closed_form() {
        // F'(theta_bar) = (a + 2 r sin theta_bar) / (a - 2 r sin theta_bar), from implicit
        // differentiation of Eq. (eq:instantlength) at theta_i = theta_{i+1} = theta_bar.
        let tb = 0.58;
        let l0 = rest_length(A, R, tb);
        let h = 1e-6;
        let f = |t: f64| next_angles(0, A, R, R, l0, t).unwrap()[0];
        let slope = (f(tb + h) - f(tb - h)) / (2.0 * h);
        let exact = (A + 2.0 * R * tb.sin()) / (A - 2.0 * R * tb.sin());
        assert!((slope - exact).abs() < 1e-5 * exact, "{slope} vs {exact}");
    }

    #[test]
    fn inverse_map_undoes_the_forward_map() {
        let l0 = 1.62;
        for theta in [-0.5, 0.1, 0.5] {
            let roots = next_angles(0, A, 0.8, 0.7, l0, theta).unwrap();
            for (b, t2) in roots.into_iter().enumerate() {
                let back = previous_angles(0, A, 0.8, 0.7, l0, t2).unwrap();
                assert!(back.iter().any(|&t| (t - theta).abs() < 1e-10), "branch {b}: {back:?} vs {theta}");
                for t1 in back {
                    assert!((spring_length(A, 0.8, 0.7, t1, t2) - l0).abs() < 1e-12);
                }
            }
        }
    }

    #[test]
    fn paper_coefficients_have_the_same_roots() {
        // The paper's A, B, C (Appendix A, r1 = r2 = r) evaluated literally.
        let (theta, l0) = (0.3f64, 1.7);
        let z1 = Complex::new(R * theta.sin(), R * theta.cos());
        let a = Complex::new(A, 0.0);
        let den = a - z1;
        let qa = (z1.conj() - a) / den;
        let k = Complex::new(l0 * l0 + A * A - 2.0 * R * R, 0.0);
        let qb = k / den - a * (z1.conj() - z1) / den;
        let qc = Complex::new(A * A - R * R, 0.0) - a * k / den;
        for t2 in next_angles(0, A, R, R, l0, theta).unwrap() {
            let z2 = Complex::new(A + R * t2.sin(), -R * t2.cos());
            let residual = qa * z2 * z2 + qb * z2 + qc;
            assert!(residual.norm_sqr().sqrt() < 1e-12, "{residual}");
        }
    }

    #[test]
    fn no_real_root_is_an_error_with_the_numbers() {
        // A rest length far too long for the rotors to reach.
        let err = next_angles(7, A, R, R, 5.0, 0.2).unwrap_err();
        match err {
            BranchError::NoRealRoot { spring, distance, min, .. } => {
                assert_eq!(spring, 7);
                assert!(distance < min);
            }
            other => panic!("unexpected {other:?}"),
        }
        assert!(matches!(next_angles(0, A, R, R, 1.7, f64::NAN), Err(BranchError::NotFinite { .. })));
    }

    #[test]
    fn the_f32_solve_agrees_with_the_f64_solve_to_f32_rounding() {
        // Both roots, forward and inverse, over angles on both sides of the kink: the f32 solve
        // is the same arithmetic in single precision, so its angles are within a few f32 ulps
        // (of the angle, rad) times the map's slope, at most 15.2 here.
        let l0 = rest_length(A, R, 0.58);
        let (a, r, l) = (A as f32, R as f32, l0 as f32);
        let mut worst = 0.0f64;
        for k in 0..=200 {
            let theta = -0.9 + 1.8 * f64::from(k) / 200.0;
            let t32 = theta as f32;
            for (f64_roots, f32_roots) in [
                (next_angles(1, A, R, R, f64::from(l), f64::from(t32)), next_angles(1, a, r, r, l, t32)),
                (
                    previous_angles(1, A, R, R, f64::from(l), f64::from(t32)),
                    previous_angles(1, a, r, r, l, t32),
                ),
            ] {
                match (f64_roots, f32_roots) {
                    (Ok(x), Ok(y)) => {
                        for (x, y) in x.iter().zip(y) {
                            worst = worst.max((x - f64::from(y)).abs());
                        }
                    }
                    (Err(_), Err(_)) => {}
                    (x, y) => panic!("theta {theta}: f64 {x:?}, f32 {y:?}"),
                }
            }
        }
        assert!(worst < 64.0 * f64::from(f32::EPSILON), "largest difference {worst:.3e} rad");
        // The uniform state is a fixed point in f32 too, to f32 rounding.
        let [z, _] = next_angles(0, a, r, r, l, 0.58f32).unwrap();
        assert!((z - 0.58).abs() < 8.0 * f32::EPSILON, "{z}");
    }

    #[test]
    fn f32_errors_carry_the_numbers_widened() {
        let err = next_angles(2, 1.0f32, 0.8, 0.8, 5.0, 0.25).unwrap_err();
        match err {
            BranchError::NoRealRoot { spring, theta, rest_length, .. } => {
                assert_eq!((spring, theta, rest_length), (2, 0.25, 5.0));
            }
            other => panic!("unexpected {other:?}"),
        }
        let err = previous_angles(4, 1.0f32, 0.8, 0.8, 1.7, f32::INFINITY).unwrap_err();
        // The angle given, not the mirrored one next_angles saw.
        assert_eq!(err, BranchError::NotFinite { spring: 4, theta: f64::INFINITY });
    }

    #[test]
    fn a_tip_on_the_next_pivot_is_degenerate_not_nan() {
        // a = 0 and r1 = 0: tip p sits on pivot p + 1, at distance r2 = l0 from every point of
        // rotor p + 1's circle.
        let err = next_angles(0, 0.0f64, 0.0, 0.8, 0.8, 0.3).unwrap_err();
        assert_eq!(err, BranchError::Degenerate { spring: 0, theta: 0.3 });
        let err = previous_angles(5, 0.0f32, 0.8, 0.0, 0.8, 0.25).unwrap_err();
        assert_eq!(err, BranchError::Degenerate { spring: 5, theta: 0.25 });
    }
}
