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

use nalgebra::{Complex, ComplexField};

use crate::error::BranchError;
use crate::math;

/// Both angles `theta_{p+1}` that put spring `p` at rest length `l0` for the given `theta_p`,
/// flipper branch first. `spring` only labels errors.
pub fn next_angles(
    spring: usize,
    a: f64,
    r1: f64,
    r2: f64,
    l0: f64,
    theta: f64,
) -> Result<[f64; 2], BranchError> {
    if !theta.is_finite() {
        return Err(BranchError::NotFinite { spring, theta });
    }
    let (s, co) = math::sin_cos(theta);
    let z1 = Complex::new(r1 * s, r1 * co);
    let c = Complex::new(a, 0.0) - z1;
    let distance = c.norm_sqr().sqrt();
    let (min, max) = ((r2 - l0).abs(), r2 + l0);
    // Circles that touch within rounding still have one (double) root; allow a few ulps.
    let slack = 8.0 * f64::EPSILON * max;
    if !(distance >= min - slack && distance <= max + slack) {
        return Err(BranchError::NoRealRoot {
            spring,
            theta,
            distance,
            rotor_length: r2,
            rest_length: l0,
            min,
            max,
        });
    }
    // conj(c) w^2 + beta w + c r2^2 = 0, solved without cancellation: q = -(beta + sign sqrt(disc)) / 2.
    let qa = c.conj();
    let beta = Complex::new(r2 * r2 + c.norm_sqr() - l0 * l0, 0.0);
    let qc = c * (r2 * r2);
    let disc = beta * beta - qa * qc * 4.0;
    let root = ComplexField::sqrt(disc);
    let root = if (beta.conj() * root).re >= 0.0 { root } else { -root };
    let q = (beta + root) * -0.5;
    let w = [q / qa, qc / q];
    // theta_{p+1} from w = -i r2 e^{i theta}:  r2 sin theta = Re w, r2 cos theta = -Im w.
    let angle = |w: Complex<f64>| math::atan2(w.re, -w.im);
    // Orientation of tip p+1 relative to the directed line tip p -> pivot p+1.
    let side = |w: Complex<f64>| {
        let v = c; // from tip p to pivot p+1
        let u = c + w; // from tip p to tip p+1
        v.re * u.im - v.im * u.re
    };
    let (first, second) = if side(w[0]) <= side(w[1]) { (w[0], w[1]) } else { (w[1], w[0]) };
    Ok([angle(first), angle(second)])
}

/// Both angles `theta_p` that put spring `p` at rest length `l0` for the given `theta_{p+1}`,
/// flipper branch first: the inverse of [`next_angles`].
pub fn previous_angles(
    spring: usize,
    a: f64,
    r1: f64,
    r2: f64,
    l0: f64,
    theta_next: f64,
) -> Result<[f64; 2], BranchError> {
    next_angles(spring, a, r2, r1, l0, -theta_next).map(|[x, y]| [-x, -y]).map_err(|e| match e {
        BranchError::NoRealRoot { spring, distance, rotor_length, rest_length, min, max, .. } => {
            BranchError::NoRealRoot {
                spring,
                theta: theta_next,
                distance,
                rotor_length,
                rest_length,
                min,
                max,
            }
        }
        other => other,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use chain_geometry::{rest_length, spring_length};

    const A: f64 = 1.0;
    const R: f64 = 0.8;

    #[test]
    fn both_roots_put_the_spring_at_rest_length() {
        for (r1, r2, l0) in [(R, R, 1.7), (0.8, 0.6, 1.5), (0.5, 0.9, 1.2)] {
            for theta in [-1.0, -0.3, 0.0, 0.4, 0.9] {
                let Ok(roots) = next_angles(0, A, r1, r2, l0, theta) else {
                    continue;
                };
                for t2 in roots {
                    let l = spring_length(A, r1, r2, theta, t2);
                    assert!((l - l0).abs() < 1e-12, "theta {theta} -> {t2}: length {l} != {l0}");
                }
            }
        }
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
        let (theta, l0) = (0.3, 1.7);
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
}
