//! Winding numbers and the polarization against Kane and Lubensky (arXiv:1308.0554).

use chain_network::NetworkError;
use chain_network::cell::ready;
use chain_network::winding::{WindingOptions, dipole, winding};

/// Kane and Lubensky eq. 11, R_T = sum_p a_p sign(x_p) / 2 with a3 = -a1 - a2, at their three
/// points, in the lattice coordinates of (a1, a2): 0; -a3 = a1 + a2; -a1. Independent of z.
#[test]
fn kane_lubensky_polarizations() {
    let cases =
        [((0.1, 0.1, 0.1), [0.0, 0.0]), ((0.1, 0.1, -0.1), [1.0, 1.0]), ((-0.05, 0.05, 0.05), [-1.0, 0.0])];
    for ((x1, x2, x3), expected) in cases {
        for z in [0.0, 0.03, -0.02] {
            let cell = ready::deformed_kagome(x1, x2, x3, z).unwrap();
            let w = winding(&cell, &WindingOptions::default()).unwrap();
            // The standard cell: r0 = 0.
            assert!(w.dipole.iter().all(|r| r.abs() < 1e-12), "{:?}", w.dipole);
            for i in 0..2 {
                assert!(
                    (w.polarization[i] - expected[i]).abs() < 1e-12,
                    "({x1}, {x2}, {x3}; {z}): {:?} vs {expected:?}",
                    w.polarization
                );
            }
            assert_eq!(w.winding, vec![-expected[0] as i64, -expected[1] as i64]);
        }
    }
    // Eq. 11 over all eight octants (C6-related phases).
    for s1 in [-1.0, 1.0] {
        for s2 in [-1.0, 1.0] {
            for s3 in [-1.0, 1.0] {
                let cell = ready::deformed_kagome(0.08 * s1, 0.06 * s2, 0.07 * s3, 0.0).unwrap();
                let w = winding(&cell, &WindingOptions::default()).unwrap();
                // sum_p s_p a_p / 2 with a3 = -a1 - a2: coefficients ((s1 - s3)/2, (s2 - s3)/2).
                let expected = [(s1 - s3) / 2.0, (s2 - s3) / 2.0];
                assert!(
                    (w.polarization[0] - expected[0]).abs() < 1e-12
                        && (w.polarization[1] - expected[1]).abs() < 1e-12,
                    "{s1} {s2} {s3}: {:?}",
                    w.polarization
                );
            }
        }
    }
}

/// R_T does not depend on how the cell is written: moving a node to another cell, or a bond to
/// its other end, changes the windings and the dipole together.
#[test]
fn polarization_is_gauge_invariant() {
    let cell = ready::deformed_kagome(0.1, 0.1, -0.1, 0.0).unwrap();
    let w0 = winding(&cell, &WindingOptions::default()).unwrap();
    // Node d2 moved by +a1 (its position shifts, bonds to it shift their offsets by -1 along a1,
    // bonds from it by +1), and bond 0 written from its other end.
    let mut text = String::new();
    let a = ready::kane_lubensky_vectors();
    let mut b = chain_network::Cell::builder(2, &[a[0], a[1]]);
    for (n, node) in cell.nodes().iter().enumerate() {
        let mut p = node.point();
        if n == 1 {
            p = [p[0] + a[0][0], p[1] + a[0][1]];
        }
        b = b.joint(&node.name, p);
    }
    for (i, bond) in cell.bonds().iter().enumerate() {
        let mut c = bond.cell;
        if bond.to == 1 {
            c[0] -= 1;
        }
        if bond.from == 1 {
            c[0] += 1;
        }
        if i == 0 {
            // Written from its other end: its row now belongs to the cell of d3.
            b = b.bond(&cell.nodes()[bond.to].name, &cell.nodes()[bond.from].name, &[-c[0], -c[1]]);
        } else {
            b = b.bond(&cell.nodes()[bond.from].name, &cell.nodes()[bond.to].name, &c);
        }
    }
    let moved = b.build().unwrap();
    let w1 = winding(&moved, &WindingOptions::default()).unwrap();
    assert_ne!(w1.winding, w0.winding);
    assert!(w1.dipole.iter().any(|r| r.abs() > 0.5));
    for i in 0..2 {
        assert!((w1.polarization[i] - w0.polarization[i]).abs() < 1e-12, "{:?} vs {:?}", w1, w0);
    }
    text.push_str(&moved.to_toml());
    let reread = chain_network::Cell::from_toml_str(&text).unwrap();
    assert_eq!(winding(&reread, &WindingOptions::default()).unwrap().winding, w1.winding);
    let _ = dipole(&cell);
}

/// Gapless lattices have no winding: square and regular kagome (lines of zeros).
#[test]
fn gapless_lattices_are_refused() {
    for cell in [ready::square(), ready::kagome(), ready::deformed_kagome(0.0, 0.1, 0.1, 0.0).unwrap()] {
        let e = winding(&cell, &WindingOptions::default()).unwrap_err();
        assert!(matches!(e, NetworkError::WindingUndefined { .. }), "{e}");
        assert!(e.to_string().contains("winding undefined"), "{e}");
    }
}

/// A non-square cell is refused with its counts.
#[test]
fn non_square_cells_are_refused() {
    let cell = chain_network::Cell::builder(2, &[[1.0, 0.0], [0.0, 1.0]])
        .joint("a", [0.0, 0.0])
        .bond("a", "a", &[1, 0])
        .build()
        .unwrap();
    assert!(matches!(
        winding(&cell, &WindingOptions::default()),
        Err(NetworkError::NotSquare { bonds: 1, dof: 2 })
    ));
}

/// The paper's chain: winding 1 or 0 by the lean (Kane and Lubensky's 1D model, |q1| < |q2|).
#[test]
fn paper_chain_winds_by_its_lean() {
    let right = winding(&ready::paper_chain(ready::Lean::Right), &WindingOptions::default()).unwrap();
    let left = winding(&ready::paper_chain(ready::Lean::Left), &WindingOptions::default()).unwrap();
    let mut both = [right.winding[0], left.winding[0]];
    both.sort();
    assert_eq!(both, [0, 1], "{right:?} {left:?}");
    // R_T = -n - r0 with r0 = -1/2 (tips each in two bonds): +-1/2, opposite for the two leans.
    assert!((right.polarization[0] + left.polarization[0]).abs() < 1e-12);
    assert!((right.polarization[0].abs() - 0.5).abs() < 1e-12);
    // The straight chain (theta_bar = 0) is gapless at k = 0.
    let straight = ready::rotor_chain(1.0, 0.8, 0.0).unwrap();
    assert!(matches!(
        winding(&straight, &WindingOptions::default()),
        Err(NetworkError::WindingUndefined { .. })
    ));
}

/// A lattice whose det Q vanishes identically (Kane and Lubensky's parametrisation at
/// (-0.3, 0, 0.1; 0.3), where Q(k) is singular at every k) has no winding: the rounding-level
/// determinant is not followed as if it were a signal.
#[test]
fn an_identically_singular_q_has_no_winding() {
    let cell = ready::deformed_kagome(-0.3, 0.0, 0.1, 0.3).unwrap();
    for theta in [[0.3, 1.7], [2.0, -0.4], [5.0, 4.0]] {
        let q = chain_network::bloch::compatibility(&cell, theta);
        let s = chain_network::linalg::singular_values("test", q.as_ref()).unwrap();
        assert!(s[s.len() - 1] < 1e-12 * s[0], "{s:?}");
    }
    let e = winding(&cell, &WindingOptions::default()).unwrap_err();
    assert!(matches!(e, NetworkError::WindingUndefined { .. }), "{e}");
}
