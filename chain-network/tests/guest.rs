//! Guest modes against the literature: the square lattice shears for free, the regular kagome
//! lattice has no soft strain (three families of straight lines), the twisted kagome lattice
//! dilates for free (zero bulk modulus, Sun et al. PNAS 2012), and a generic deformed kagome
//! lattice has one Guest mode (Rocklin et al., Nat. Commun. 8, 14201 (2017)).

use chain_network::cell::ready;
use chain_network::guest::guest_modes;

#[test]
fn guest_modes_of_the_standard_lattices() {
    let square = guest_modes(&ready::square()).unwrap();
    assert_eq!(square.count, 1);
    let e = square.strains[0];
    assert!(
        e[0][0].abs() < 1e-12 && e[1][1].abs() < 1e-12 && (e[0][1].abs() - 0.5f64.sqrt()).abs() < 1e-12,
        "{e:?}"
    );

    assert_eq!(guest_modes(&ready::kagome()).unwrap().count, 0);

    let twisted = guest_modes(&ready::twisted_kagome(0.3).unwrap()).unwrap();
    assert_eq!(twisted.count, 1);
    let e = twisted.strains[0];
    // Pure dilation: e = +-I / sqrt 2.
    assert!(
        (e[0][0] - e[1][1]).abs() < 1e-10
            && e[0][1].abs() < 1e-10
            && (e[0][0].abs() - 0.5f64.sqrt()).abs() < 1e-10,
        "{e:?}"
    );

    for (x1, x2, x3, z) in [(0.1, 0.1, -0.1, 0.0), (-0.05, 0.05, 0.05, 0.02), (0.07, -0.03, 0.09, -0.04)] {
        assert_eq!(
            guest_modes(&ready::deformed_kagome(x1, x2, x3, z).unwrap()).unwrap().count,
            1,
            "({x1}, {x2}, {x3}; {z})"
        );
    }
}
