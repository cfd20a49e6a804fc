//! `math::sin_cos_into` at every dispatch level this machine supports: within 2 ulp of the
//! correctly rounded sine and cosine (dashu-float) on 1e5 points over the ranges the dynamics
//! sees and beyond, and exactly the scalar `math::sin_cos` where the vector reduction stops.
//! The 1.02e7-point measurement is `examples/sin_cos_ulp.rs`.

use chain_core::math;
use chain_core::simd::{self, Level, VECTOR_SIN_COS_LIMIT};
use test_support::ulp;

fn levels() -> impl Iterator<Item = Level> {
    Level::ALL.into_iter().filter(|l| l.is_supported())
}

fn at_level(level: Level, theta: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let (mut sin, mut cos) = (vec![0.0; theta.len()], vec![0.0; theta.len()]);
    simd::with_level(level, || math::sin_cos_into(theta, &mut sin, &mut cos)).expect("a supported level");
    (sin, cos)
}

#[test]
fn within_two_ulp_of_the_correctly_rounded_values_at_every_level() {
    let per_range = 100_000 / ulp::RANGES.len() + 1;
    for (seed, (name, range)) in ulp::RANGES.iter().enumerate() {
        let theta = ulp::angles(*range, per_range, 0x7E57_0000 + seed as u64);
        let reference: Vec<_> = theta.iter().map(|&x| ulp::reference(x)).collect();
        for level in levels() {
            let (sin, cos) = at_level(level, &theta);
            let w = ulp::worst(&theta, &sin, &cos, &reference);
            assert!(w.ulps <= 2, "{}: {} ulp at {:e} on {name}", level.name(), w.ulps, w.angle);
        }
    }
}

/// Angles next to multiples of pi/2, where the remainder is tiny, and either side of
/// `|hi| = 2^-28`, below which the reduction's last term `k P3` starts to matter.
#[test]
fn within_two_ulp_next_to_multiples_of_half_pi() {
    let mut theta = Vec::new();
    let ks = (1..=400u32).map(f64::from).chain([1e3, 12345.0, 1e5, 7.77e6, 1.0e7, 1.06e7]);
    for k in ks {
        let x = k * core::f64::consts::FRAC_PI_2;
        for ulps in -3i64..=3 {
            theta.push(f64::from_bits((x.to_bits() as i64 + ulps) as u64));
            theta.push(-f64::from_bits((x.to_bits() as i64 + ulps) as u64));
        }
        for d in [2.0f64.powi(-28), 2.0f64.powi(-27), 2.0f64.powi(-29)] {
            theta.extend([x + d, x - d, x + 1.5 * d, x - 0.75 * d]);
        }
    }
    theta.extend([2.0f64.powi(-28), -2.0f64.powi(-28), 3e-9, 4e-9, 1e-300, 1e-12, -1e-12, 0.0, -0.0]);
    let reference: Vec<_> = theta.iter().map(|&x| ulp::reference(x)).collect();
    for level in levels() {
        let (sin, cos) = at_level(level, &theta);
        let w = ulp::worst(&theta, &sin, &cos, &reference);
        assert!(w.ulps <= 2, "{}: {} ulp at {:e}", level.name(), w.ulps, w.angle);
    }
}

/// `pi/2` in fixed point, `floor(pi 2^123) = floor(pi/2 2^124)`, from dashu-float's pi (not
/// the library's constants).
fn half_pi_fixed() -> u128 {
    use test_support::dashu_float::ConstCache;
    use test_support::dashu_float::round::mode::HalfEven;
    let pi = ConstCache::default().pi::<2, HalfEven>(160).value();
    let (significand, exponent) = (pi.repr().significand(), pi.repr().exponent());
    let shift = usize::try_from(-(exponent + 123)).expect("160 bits reach below 2^-123");
    u128::try_from(significand >> shift).expect("pi 2^123 < 2^125")
}

/// The doubles below the vector reduction's limit nearest to a nonzero multiple `k pi/2`, over
/// every `k` up to `2^24 2/pi` (the three doubles around each `k pi/2`, their distance to it in
/// 124-bit fixed point, exact modulo `2^128`): the `n` nearest, with their distances.
fn nearest_to_multiples_of_half_pi(n: usize) -> Vec<(f64, f64)> {
    let half_pi = half_pi_fixed();
    let mut nearest: Vec<(u128, f64)> = Vec::with_capacity(n + 1);
    let k_max = (VECTOR_SIN_COS_LIMIT * core::f64::consts::FRAC_2_PI) as u128;
    for k in 1..=k_max {
        let y = k as f64 * core::f64::consts::FRAC_PI_2;
        let target = k.wrapping_mul(half_pi);
        for x in [y.next_down(), y, y.next_up()] {
            let bits = x.to_bits();
            let mantissa = u128::from(bits & ((1 << 52) - 1) | 1 << 52);
            // x = mantissa 2^(e - 1075) >= 1, so x 2^124 is an integer; its top bits wrap away,
            // and the difference, below 2^100, is exact as a signed number.
            let shift = (bits >> 52) as u32 + 124 - 1075;
            let distance = ((mantissa << shift).wrapping_sub(target) as i128).unsigned_abs();
            if nearest.len() < n || distance < nearest[n - 1].0 {
                let at = nearest.partition_point(|&(d, _)| d <= distance);
                nearest.insert(at, (distance, x));
                nearest.truncate(n);
            }
        }
    }
    nearest.into_iter().map(|(d, x)| (x, d as f64 * 2f64.powi(-124))).collect()
}

/// The hardest angles for the reduction: the 32 doubles below the limit nearest to a nonzero
/// multiple of pi/2. Their remainders are at least 2^-61 (`simd::trig` relies on that to keep
/// the sign of `sin(-0)` and to leave out a separate path near multiples of pi/2), and their
/// sines and cosines are within 1 ulp at every level.
#[test]
fn the_doubles_nearest_to_multiples_of_half_pi_are_within_one_ulp() {
    let nearest = nearest_to_multiples_of_half_pi(32);
    let (x0, r0) = nearest[0];
    assert!(r0 > 2f64.powi(-61), "remainder {r0:e} at {x0:e}");
    let theta: Vec<f64> = nearest.iter().flat_map(|&(x, _)| [x, -x]).collect();
    let reference: Vec<_> = theta.iter().map(|&x| ulp::reference(x)).collect();
    for level in levels() {
        let (sin, cos) = at_level(level, &theta);
        let w = ulp::worst(&theta, &sin, &cos, &reference);
        assert!(w.ulps <= 1, "{}: {} ulp at {:e}", level.name(), w.ulps, w.angle);
    }
}

#[test]
fn the_reference_is_right_where_the_answer_is_known() {
    assert_eq!(ulp::reference(0.0), (0.0, 1.0));
    // The two doubles around pi/6 = 0.523598775598298873...: the one below is 5.74e-17 short, so
    // its sine is 1/2 - 4.97e-17, nearer to the double 1/2 - 2^-54 than to 1/2; the one above
    // (`FRAC_PI_6`) is 5.36e-17 long, so its sine 1/2 + 4.64e-17 rounds to 1/2.
    assert_eq!(ulp::reference(f64::from_bits(0x3FE0_C152_382D_7365)).0, 0.5 - f64::EPSILON / 4.0);
    assert_eq!(ulp::reference(core::f64::consts::FRAC_PI_6).0, 0.5);
    assert_eq!(ulp::ulps(1.0, 1.0 + f64::EPSILON), 1);
    assert_eq!(ulp::ulps(-0.0, 0.0), 0);
    assert_eq!(ulp::ulps(-5e-324, 5e-324), 2);
}

/// 24 ordinary angles in [-3, 5.5] with `values` (at most 12) put at every other position from
/// `shift`: so across shifts 0..8 each value sits in every lane of a vector.
fn among_ordinary_angles(values: &[f64], shift: usize) -> Vec<f64> {
    let mut theta: Vec<f64> = (0..24).map(|i| 0.37 * i as f64 - 3.0).collect();
    for (j, &x) in values.iter().enumerate() {
        theta[(shift + 2 * j) % 24] = x;
    }
    theta
}

#[test]
fn special_and_large_angles_give_exactly_the_scalar_result() {
    let l = VECTOR_SIN_COS_LIMIT;
    let special = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        -0.0,
        0.0,
        f64::MIN_POSITIVE,
        -5e-324,
        l * (1.0 + f64::EPSILON),
        -l * 1.5,
        1e22,
        -1e300,
        f64::MAX,
    ];
    for shift in 0..8 {
        let theta = among_ordinary_angles(&special, shift);
        for level in levels() {
            let (sin, cos) = at_level(level, &theta);
            for (i, &x) in theta.iter().enumerate() {
                if !special.iter().any(|s| s.to_bits() == x.to_bits()) || (x.abs() < 1.0 && x != 0.0) {
                    continue;
                }
                let (s, c) = math::sin_cos(x);
                assert_eq!(sin[i].to_bits(), s.to_bits(), "{}: sin({x:e})", level.name());
                assert_eq!(cos[i].to_bits(), c.to_bits(), "{}: cos({x:e})", level.name());
            }
        }
    }
}

/// Signed zeros and tiny angles among ordinary ones (so their vector takes the polynomials, not
/// the scalar lanes that NaN or huge lanes send it to): `sin(-0)` is `-0`, `sin(+0)` is `+0`, and
/// a tiny angle's sine is the angle itself, with its sign, as the scalar path gives.
#[test]
fn signed_zeros_and_tiny_angles_keep_their_sign_among_ordinary_angles() {
    let tiny = [-0.0, 0.0, -5e-324, 5e-324, -1e-300, 1e-300, -f64::MIN_POSITIVE, 1e-20, -1e-20];
    for shift in 0..8 {
        let theta = among_ordinary_angles(&tiny, shift);
        for level in levels() {
            let (sin, cos) = at_level(level, &theta);
            for (i, &x) in theta.iter().enumerate() {
                if !tiny.iter().any(|t| t.to_bits() == x.to_bits()) {
                    continue;
                }
                assert_eq!(sin[i].to_bits(), x.to_bits(), "{}: sin({x:e}) = {:e}", level.name(), sin[i]);
                assert_eq!(cos[i], 1.0, "{}: cos({x:e})", level.name());
            }
        }
    }
}

#[test]
fn an_angle_gets_the_same_result_in_every_position() {
    let theta: Vec<f64> = (0..37).map(|i| 0.58 * (0.3 * i as f64).cos() + 0.01 * i as f64).collect();
    for level in levels() {
        let (sin, cos) = at_level(level, &theta);
        for start in 0..theta.len() {
            let (s, c) = at_level(level, &theta[start..]);
            assert_eq!(s, sin[start..], "{} from {start}", level.name());
            assert_eq!(c, cos[start..], "{} from {start}", level.name());
        }
    }
}

/// AVX2 takes its angles two vectors at a time (interleaved polynomials), AVX-512 one vector at
/// a time: the same operations in each lane, so the same bits, on ordinary angles of every size.
#[test]
fn the_vector_levels_give_the_same_bits() {
    let vector: Vec<Level> = levels().filter(|l| *l != Level::Scalar).collect();
    let theta: Vec<f64> = (0..20_000)
        .map(|i| {
            let x = i as f64;
            (0.37 * x).sin() * 10f64.powf(-3.0 + 9.0 * ((0.61 * x).cos() * 0.5 + 0.5))
        })
        .collect();
    let results: Vec<_> = vector.iter().map(|&l| at_level(l, &theta)).collect();
    for (level, (sin, cos)) in vector.iter().zip(&results).skip(1) {
        let (s0, c0) = &results[0];
        for i in 0..theta.len() {
            assert_eq!(sin[i].to_bits(), s0[i].to_bits(), "{} sin({:e})", level.name(), theta[i]);
            assert_eq!(cos[i].to_bits(), c0[i].to_bits(), "{} cos({:e})", level.name(), theta[i]);
        }
    }
}

/// A vector with one unusual lane (NaN, infinite or huge, which takes the scalar `sin_cos`; or
/// next to a nonzero multiple of pi/2) leaves the other lanes as the polynomials have them: an
/// ordinary angle's result does not depend on its neighbours (batches laid back to back rely on
/// it).
#[test]
fn an_unusual_angle_leaves_its_neighbours_as_they_are_alone() {
    let near_half_pi = f64::from_bits(core::f64::consts::FRAC_PI_2.to_bits() + 1);
    for unusual in [f64::NAN, f64::INFINITY, -1.0e300, 3.0e7, near_half_pi, -3.0 * near_half_pi] {
        for shift in 0..8 {
            let theta = among_ordinary_angles(&[unusual], shift);
            for level in levels() {
                let (sin, cos) = at_level(level, &theta);
                for (i, &x) in theta.iter().enumerate() {
                    let (s, c) = at_level(level, &[x]);
                    assert!(
                        sin[i].to_bits() == s[0].to_bits() || (sin[i].is_nan() && s[0].is_nan()),
                        "{}: sin({x:e}) beside {unusual:e}",
                        level.name()
                    );
                    assert!(
                        cos[i].to_bits() == c[0].to_bits() || (cos[i].is_nan() && c[0].is_nan()),
                        "{}: cos({x:e}) beside {unusual:e}",
                        level.name()
                    );
                }
            }
        }
    }
}

#[test]
fn forcing_an_unsupported_level_is_refused_and_the_scalar_level_is_the_math_function() {
    for level in Level::ALL {
        assert_eq!(simd::with_level(level, simd::level).is_some(), level.is_supported());
        if level.is_supported() {
            assert_eq!(simd::with_level(level, simd::level), Some(level));
        }
    }
    let theta = [0.1, -2.0, 3.0, 100.5];
    let (sin, cos) = at_level(Level::Scalar, &theta);
    for (i, &x) in theta.iter().enumerate() {
        assert_eq!((sin[i], cos[i]), math::sin_cos(x));
    }
}
