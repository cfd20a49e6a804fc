//! The iterator of domain walls against the rule of its documentation (paper Appendix C), written
//! here as a second, independent program on arbitrary configurations, vertical and non-finite
//! rotors included: keep the rotors that lean (finite, non-zero), and between two neighbours of
//! that list that lean opposite ways put a wall, interpolated when they are adjacent rotors and
//! in the middle of the vertical run between them otherwise; a kink when the left one leans `+`.

use embedded_check::DomainWalls;
use proptest::prelude::*;

fn angle() -> impl Strategy<Value = f64> {
    prop_oneof![3 => -1.0..1.0f64, 1 => Just(0.0), 1 => Just(0.58), 1 => Just(-0.58), 1 => Just(f64::NAN), 1 => Just(f64::INFINITY)]
}

fn reference(theta: &[f64]) -> Vec<(f64, &'static str)> {
    let leaning: Vec<(usize, f64)> =
        theta.iter().copied().enumerate().filter(|&(_, t)| t.is_finite() && t != 0.0).collect();
    leaning
        .windows(2)
        .filter(|w| (w[0].1 > 0.0) != (w[1].1 > 0.0))
        .map(|w| {
            let ((i, a), (j, b)) = (w[0], w[1]);
            let x = if j == i + 1 { i as f64 + a / (a - b) } else { (i + j) as f64 / 2.0 };
            (x, if a > 0.0 { "kink" } else { "antikink" })
        })
        .collect()
}

#[test]
fn the_reference_rule_on_known_cases() {
    assert_eq!(reference(&[0.5, 0.25, -0.75]), vec![(1.25, "kink")]);
    assert_eq!(reference(&[-0.5, 0.0, 0.0, f64::NAN, 0.5]), vec![(2.0, "antikink")]);
    assert_eq!(reference(&[0.0, 0.3, 0.0]), vec![]);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, failure_persistence: None, rng_seed: proptest::test_runner::RngSeed::Fixed(0x13e5_b3d0), ..ProptestConfig::default() })]

    #[test]
    fn walls_follow_the_documented_rule(theta in proptest::collection::vec(angle(), 0..24)) {
        let ours: Vec<_> = DomainWalls::of(&theta).collect();
        let expected = reference(&theta);
        prop_assert_eq!(ours.len(), expected.len());
        for (wall, (x, charge)) in ours.iter().zip(&expected) {
            prop_assert_eq!(wall.position.to_bits(), x.to_bits());
            prop_assert_eq!(wall.charge.name(), *charge);
        }
    }
}
