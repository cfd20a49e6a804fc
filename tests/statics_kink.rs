//! Statics, kink and cobweb (paper Sec. II): acceptance items of the statics issue.

mod common;

use rotor_chain::prelude::*;
use rotor_chain::statics::cobweb::{self, Stability};
use rotor_chain::statics::kink::{kink, mechanism_path};
use rotor_chain::statics::walls::{Charge, domain_walls};

#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Paper;

#[test]
fn kink_has_zero_energy_at_every_position_including_fractional_ones() {
    let k = 1.0e4;
    for centre in [0.0, 0.5, 3.25, 17.0, 29.5, 30.0, 41.75, 58.9, 59.0] {
        let theta = kink(&Paper, centre).unwrap();
        let e = Potential::energy(&Paper, &theta);
        assert!(e <= 1e-20 * k, "centre {centre}: energy {e:e}");
        let walls = domain_walls(&theta);
        if centre > 0.0 && centre < 59.0 {
            assert_eq!(walls.len(), 1, "centre {centre}: {walls:?}");
            assert_eq!(walls[0].charge, Charge::Kink);
            assert!(
                (walls[0].position - centre).abs() < 1e-9,
                "centre {centre}: wall at {}",
                walls[0].position
            );
        }
    }
}

#[test]
fn a_kink_deep_in_a_long_chain_is_exact() {
    let chain = RuntimeChain::builder(2000, 0.8, 1.0e4, 0.58).build().unwrap();
    let theta = kink(&chain, 1000.3).unwrap();
    assert!(chain.energy(&theta) <= 1e-20 * 1.0e4);
    assert!((theta[0] - 0.58).abs() < 1e-12 && (theta[1999] + 0.58).abs() < 1e-12);
    let path = mechanism_path(&chain, 990.0, 1010.0, 8).unwrap();
    assert!(path.iter().all(|(_, t)| chain.energy(t) <= 1e-20 * 1.0e4));
}

#[test]
fn cobweb_fixed_points_match_the_closed_form() {
    let [minus, plus] = cobweb::fixed_points(&Paper, 10).unwrap();
    assert!((plus.theta - 0.58).abs() < 1e-12 && (minus.theta + 0.58).abs() < 1e-12);
    let exact = cobweb::slope_closed_form(1.0, 0.8, 0.58);
    assert!((plus.slope - exact).abs() < 1e-9 * exact, "{} vs {exact}", plus.slope);
    assert!((minus.slope - 1.0 / exact).abs() < 1e-9, "{} vs {}", minus.slope, 1.0 / exact);
    assert_eq!(plus.stability, Stability::Repelling);
    assert_eq!(minus.stability, Stability::Attracting);
    assert!((plus.decay_length - 1.0 / exact.ln()).abs() < 1e-9);
    let theta = kink(&Paper, 30.0).unwrap();
    let web = cobweb::cobweb(&Paper, 10, &theta, 0.7, 101).unwrap();
    assert_eq!(web.springs.len(), 59);
    assert_eq!(web.staircase.len(), 2 * 59 + 1);
    assert!(!web.flipper_branch.is_empty());
}

#[test]
fn the_reflected_kink_is_an_unrelaxed_antikink_centred_where_asked() {
    use rotor_chain::statics::kink::reflected_kink;
    for centre in [29.5, 30.0, 12.25] {
        let theta = reflected_kink(&Paper, centre).unwrap();
        let walls = domain_walls(&theta);
        assert_eq!(walls.len(), 1);
        assert_eq!(walls[0].charge, Charge::Antikink);
        assert!((walls[0].position - centre).abs() < 1e-9, "{centre}: {}", walls[0].position);
        // Springs swapped onto the curve: (theta_{p+1}, theta_p) satisfies spring p's constraint.
        for p in 0..59 {
            let back = Paper.next_angles(p, theta[p + 1]).unwrap()[0];
            assert!((back - theta[p]).abs() < 1e-9, "spring {p}");
        }
        // The reflection costs what the independent model (tests/common) says.
        let reference = common::Reference::uniform(60, 0.58).energy(&theta);
        common::assert_close(Potential::energy(&Paper, &theta), reference, 1e-12, "reflected kink");
        assert!(reference > 0.0);
    }
}
