//! The iterator of domain walls against chain-core's `domain_walls` on arbitrary configurations,
//! vertical and non-finite rotors included.

use embedded_check::domain_walls;
use proptest::prelude::*;
use rotor_chain::statics::walls;

fn angle() -> impl Strategy<Value = f64> {
    prop_oneof![3 => -1.0..1.0f64, 1 => Just(0.0), 1 => Just(0.58), 1 => Just(-0.58), 1 => Just(f64::NAN), 1 => Just(f64::INFINITY)]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, failure_persistence: None, rng_seed: proptest::test_runner::RngSeed::Fixed(0x13e5_b3d0), ..ProptestConfig::default() })]

    #[test]
    fn same_walls_as_chain_core(theta in proptest::collection::vec(angle(), 0..24)) {
        let ours: Vec<_> = domain_walls(&theta).collect();
        let reference = walls::domain_walls(&theta);
        prop_assert_eq!(ours.len(), reference.len());
        for (a, b) in ours.iter().zip(&reference) {
            prop_assert_eq!(a.position.to_bits(), b.position.to_bits());
            prop_assert_eq!(a.charge.name(), match b.charge { walls::Charge::Kink => "kink", walls::Charge::Antikink => "antikink" });
        }
    }
}
