//! Maxwell-Calladine counts against the literature's exact values and independent references.

use chain_network::cell::ready;
use chain_network::counts::{Method, counts, null_spaces};
use chain_network::patch::{Boundary, Patch};
use chain_network::{Cell, NetworkError};

fn count(cell: &Cell, n: [usize; 2], boundary: Boundary) -> (usize, usize) {
    let c = counts(&Patch::new(cell, n, boundary).unwrap()).unwrap();
    (c.zero_modes, c.self_stresses)
}

/// Square N x N periodic: 2N zero modes and 2N states of self-stress (one per straight line);
/// kagome N x N periodic: 3N and 3N (Lubensky et al., Rep. Prog. Phys. 78 (2015), sections 5.1, 5.2).
#[test]
fn periodic_square_and_kagome_have_one_mode_and_stress_per_line() {
    for n in 3..=8 {
        assert_eq!(count(&ready::square(), [n, n], Boundary::Periodic), (2 * n, 2 * n), "square {n}");
        assert_eq!(count(&ready::kagome(), [n, n], Boundary::Periodic), (3 * n, 3 * n), "kagome {n}");
    }
    // Rectangular patches: the square has N1 + N2 lines; the kagome also has lines along
    // a3 = -a1 - a2, whose number on an N1 x N2 torus is the number of orbits of the shift
    // (1, 1): gcd(N1, N2).
    assert_eq!(count(&ready::square(), [3, 5], Boundary::Periodic), (8, 8));
    assert_eq!(count(&ready::kagome(), [4, 6], Boundary::Periodic), (4 + 6 + 2, 4 + 6 + 2));
    assert_eq!(count(&ready::kagome(), [3, 5], Boundary::Periodic), (3 + 5 + 1, 3 + 5 + 1));
}

/// The twisted kagome lattice: only the two rigid translations, and (index theorem) two states
/// of self-stress (Sun et al., PNAS 109, 12369 (2012)); the same for a polarized deformed kagome.
#[test]
fn twisted_kagome_keeps_only_translations() {
    for cell in [ready::twisted_kagome(0.2).unwrap(), ready::deformed_kagome(0.1, 0.1, -0.1, 0.0).unwrap()] {
        for n in [3, 4, 7] {
            assert_eq!(count(&cell, [n, n], Boundary::Periodic), (2, 2), "{n}");
        }
    }
}

/// Free patches: the square's zero modes are a rigid x shift per row and a y shift per column
/// (2N, no self-stress: every straight line ends at the boundary); kagome and twisted kagome
/// have no self-stress either, so N0 = dof - bonds by the index theorem.
#[test]
fn free_patches_by_the_index_theorem() {
    for n in [2, 3, 5, 8] {
        assert_eq!(count(&ready::square(), [n, n], Boundary::Free), (2 * n, 0), "square {n}");
        for cell in [
            ready::kagome(),
            ready::twisted_kagome(0.25).unwrap(),
            ready::deformed_kagome(-0.05, 0.05, 0.05, 0.0).unwrap(),
        ] {
            let p = Patch::new(&cell, [n, n], Boundary::Free).unwrap();
            let c = counts(&p).unwrap();
            assert_eq!(c.self_stresses, 0, "{n}");
            assert_eq!(c.zero_modes, p.dof() - p.bonds().len(), "{n}");
            assert_eq!(c.method, Method::DenseSvd);
        }
    }
}

/// The Bloch-block count equals a dense count of the same periodic patch's matrix, and the
/// vectors are null vectors.
#[test]
fn bloch_blocks_agree_with_the_whole_matrix() {
    for cell in [ready::kagome(), ready::deformed_kagome(0.1, -0.07, 0.03, 0.05).unwrap(), ready::square()] {
        for n in [[3, 4], [5, 3]] {
            let p = Patch::new(&cell, n, Boundary::Periodic).unwrap();
            let c = counts(&p).unwrap();
            let dense = p.compatibility_matrix().unwrap();
            let s = dense.singular_values().unwrap();
            let rank = s.iter().filter(|&&x| x > 1e-9 * s[0]).count();
            assert_eq!((c.zero_modes, c.self_stresses), (p.dof() - rank, p.bonds().len() - rank));
            let null = null_spaces(&p).unwrap();
            assert_eq!(null.zero_modes.ncols(), c.zero_modes);
            assert_eq!(null.self_stresses.ncols(), c.self_stresses);
            assert!((&dense * &null.zero_modes).norm_max() < 1e-12);
            assert!((dense.transpose() * &null.self_stresses).norm_max() < 1e-12);
            // Orthonormal.
            let g = null.zero_modes.transpose() * &null.zero_modes;
            for i in 0..g.nrows() {
                for j in 0..g.ncols() {
                    assert!((g[(i, j)] - if i == j { 1.0 } else { 0.0 }).abs() < 1e-12);
                }
            }
        }
    }
}

/// A periodic direction needs three cells; bonds that wrap onto themselves are refused.
#[test]
fn small_periodic_patches_are_refused() {
    let e = Patch::new(&ready::kagome(), [2, 5], Boundary::Periodic).unwrap_err();
    assert!(matches!(e, NetworkError::PatchSize { direction: 1, found: 2, .. }), "{e}");
    assert!(e.to_string().contains("at least 3"));
    let long = Cell::builder(1, &[[1.0, 0.0]])
        .joint("a", [0.0, 0.0])
        .bond("a", "a", &[1])
        .bond("a", "a", &[4])
        .build()
        .unwrap();
    let e = Patch::new(&long, [4, 1], Boundary::Periodic).unwrap_err();
    assert!(matches!(e, NetworkError::PeriodicImage { bond: 1, .. }), "{e}");
    let e = Patch::new(&long, [5, 1], Boundary::Periodic).unwrap_err();
    assert!(matches!(e, NetworkError::PeriodicImage { bond: 1, .. }), "{e}");
    assert!(Patch::new(&long, [9, 1], Boundary::Periodic).is_ok());
    assert!(Patch::new(&ready::kagome(), [2, 2], Boundary::Free).is_ok());
}

/// A patch larger than `MAX_PATCH_BONDS` is a typed error before anything is allocated (a
/// 100 000 x 100 000 kagome patch asked for 6e10 bonds, 2.4 TB, and aborted the process); the
/// bound sits between 2 364 and 2 365 kagome cells a side (6 bonds each).
#[test]
fn patches_beyond_the_size_bound_are_refused_before_allocating() {
    use chain_network::patch::MAX_PATCH_BONDS;
    let kagome = ready::kagome();
    for boundary in [Boundary::Free, Boundary::Periodic] {
        let e = Patch::new(&kagome, [100_000, 100_000], boundary).unwrap_err();
        assert!(matches!(e, NetworkError::PatchSize { direction: 1, found: 100_000, .. }), "{e}");
        assert!(e.to_string().contains(&MAX_PATCH_BONDS.to_string()), "{e}");
        // Overflowing usize is the same error, not a wrapped small size.
        let e = Patch::new(&kagome, [usize::MAX / 2, 3], boundary).unwrap_err();
        assert!(matches!(e, NetworkError::PatchSize { .. }), "{e}");
    }
    // Just above the bound along one direction (6 bonds per cell: 2 365 x 2 365 x 6 > 2^25).
    const { assert!(2365 * 2365 * 6 > MAX_PATCH_BONDS && 2364 * 2364 * 6 <= MAX_PATCH_BONDS) };
    assert!(Patch::new(&kagome, [2365, 2365], Boundary::Free).is_err());
}

/// The paper's chain as a rotor network: its compatibility matrix equals the chain code's
/// (`SpringNetwork::compatibility_into`, per `r_i theta_i`) up to the column signs
/// `dphi = -dtheta` (up rotors, even i) and `+dtheta` (down rotors, odd i), to 1e-12.
#[test]
fn the_paper_chain_matches_the_chain_code() {
    use chain_core::SpringNetwork;
    for (theta_bar, r) in [(0.58, 0.8), (-0.58, 0.8), (0.3, 0.55), (-0.1, 1.2)] {
        let cell = ready::rotor_chain(1.0, r, theta_bar).unwrap();
        let cells = 7;
        let n = 2 * cells;
        let patch = Patch::new(&cell, [cells, 1], Boundary::Free).unwrap();
        let c = patch.compatibility_matrix().unwrap();
        assert_eq!((c.nrows(), c.ncols()), (n - 1, n));
        let chain = chain_core::RuntimeChain::builder(n, r, 1.0, theta_bar.abs()).build().unwrap();
        let theta = vec![theta_bar; n];
        // The chain's bidiagonal layout: the n - 1 entries C[p][p], then the n - 1 entries C[p][p + 1].
        let mut values = vec![0.0; 2 * (n - 1)];
        chain.compatibility_into(&theta, &mut values);
        let (left, right) = values.split_at(n - 1);
        for p in 0..n - 1 {
            for i in 0..n {
                let chain_entry = if i == p {
                    left[p]
                } else if i == p + 1 {
                    right[p]
                } else {
                    0.0
                };
                let sign = if i % 2 == 0 { -1.0 } else { 1.0 };
                assert!(
                    (c[(p, i)] - sign * chain_entry).abs() < 1e-12,
                    "theta_bar {theta_bar}: C[{p}][{i}] = {} vs {}",
                    c[(p, i)],
                    sign * chain_entry
                );
            }
        }
        // One zero mode (n rotors, n - 1 springs, no self-stress).
        let k = counts(&patch).unwrap();
        assert_eq!((k.zero_modes, k.self_stresses), (1, 0));
    }
}

/// An independent check of the free count: cutting the `s` seam bonds of the periodic patch
/// gives the free patch, so N0(free) = N0(periodic) + s - rank(S), with S the periodic states of
/// self-stress restricted to the seam bonds (the free patch keeps exactly the periodic stresses
/// that vanish on the seams). The periodic side comes from the Bloch blocks, the free side from
/// one dense SVD; strongly polarized deformed kagome lattices included (their free patches hold
/// edge modes decaying across the whole patch).
#[test]
fn free_counts_agree_with_the_seam_identity() {
    let cells = [
        ready::kagome(),
        ready::twisted_kagome(0.3).unwrap(),
        ready::deformed_kagome(0.1, 0.1, -0.1, 0.0).unwrap(),
        ready::deformed_kagome(-0.05, 0.05, 0.05, 0.0).unwrap(),
        ready::deformed_kagome(0.2, 0.2, -0.2, 0.1).unwrap(),
        ready::square(),
    ];
    for cell in &cells {
        for n in [[3, 3], [5, 4], [7, 7]] {
            let free = counts(&Patch::new(cell, n, Boundary::Free).unwrap()).unwrap();
            let periodic = Patch::new(cell, n, Boundary::Periodic).unwrap();
            let null = null_spaces(&periodic).unwrap();
            let seams: Vec<usize> = periodic
                .bonds()
                .iter()
                .enumerate()
                .filter(|(_, pb)| {
                    let r = cell.bonds()[pb.bond].cell;
                    let t = [pb.from_cell[0] as i64 + r[0], pb.from_cell[1] as i64 + r[1]];
                    t[0] < 0 || t[1] < 0 || t[0] >= n[0] as i64 || t[1] >= n[1] as i64
                })
                .map(|(i, _)| i)
                .collect();
            let s = seams.len();
            let stresses = &null.self_stresses;
            let restricted = faer::Mat::<f64>::from_fn(s, stresses.ncols(), |i, j| stresses[(seams[i], j)]);
            let sv = if s == 0 || stresses.ncols() == 0 {
                Vec::new()
            } else {
                restricted.singular_values().unwrap()
            };
            let rank = sv.iter().filter(|&&x| x > 1e-9 * sv[0]).count();
            assert_eq!(free.zero_modes, null.counts.zero_modes + s - rank, "{n:?}");
        }
    }
}
