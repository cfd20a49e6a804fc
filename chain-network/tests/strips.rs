//! Strips: edge zero modes found by localizing the null space, against the polarization's
//! prediction.

use chain_network::cell::ready;
use chain_network::strip::{DEFAULT_Q, Strip, strip_modes};
use chain_network::winding::{WindingOptions, winding};

/// Kane and Lubensky's deformed kagome lattices. In the standard cell every direction has two
/// bonds cut per cell at each edge, so with R_T = c1 a1 + c2 a2 (their eq. 11) the edge counts
/// are low = 2 - c_J and high = 2 + c_J (the polarization points at the edge that gains modes).
#[test]
fn deformed_kagome_edge_modes_follow_the_polarization() {
    let cases = [
        ((0.1, 0.1, 0.1), [0, 0]),
        ((0.1, 0.1, -0.1), [1, 1]),
        ((-0.05, 0.05, 0.05), [-1, 0]),
        ((0.1, -0.08, 0.12), [0, -1]),
    ];
    for ((x1, x2, x3), c) in cases {
        let cell = ready::deformed_kagome(x1, x2, x3, 0.02).unwrap();
        let w = winding(&cell, &WindingOptions::default()).unwrap();
        assert_eq!([w.polarization[0].round() as i64, w.polarization[1].round() as i64], c);
        for along in 0..2 {
            let j = 1 - along;
            let strip = Strip { along, cells: 30, q: DEFAULT_Q };
            let modes = strip_modes(&cell, &strip).unwrap();
            let expected = (2 - c[j], 2 + c[j]);
            assert_eq!(
                (modes.low as i64, modes.high as i64),
                expected,
                "({x1}, {x2}, {x3}) along a{}: centres {:?}",
                along + 1,
                modes.centres
            );
            assert_eq!(modes.bulk, 0);
            assert_eq!(modes.predicted, Some(expected));
            assert_eq!(modes.zero_modes, 4);
        }
    }
}

/// The paper's chain: the single zero mode of a free chain sits at the end the winding says
/// (winding 1: the low end, cell 0; winding 0: the high end).
#[test]
fn the_chain_end_mode_is_where_the_winding_says() {
    for lean in [ready::Lean::Right, ready::Lean::Left] {
        let cell = ready::paper_chain(lean);
        let n = winding(&cell, &WindingOptions::default()).unwrap().winding[0];
        let modes = strip_modes(&cell, &Strip { along: 0, cells: 20, q: 0.0 }).unwrap();
        assert_eq!(modes.zero_modes, 1);
        let expected = if n == 1 { (1, 0) } else { (0, 1) };
        assert_eq!((modes.low, modes.high), expected, "{lean:?}: winding {n}, centre {:?}", modes.centres);
        assert_eq!(modes.predicted, Some((expected.0 as i64, expected.1 as i64)));
        // Exponentially localized: nearly all weight in the end cell's neighbourhood.
        let end = if n == 1 { 0 } else { 19 };
        assert!((modes.centres[0] - end as f64).abs() < 2.0, "{:?}", modes.centres);
    }
}
