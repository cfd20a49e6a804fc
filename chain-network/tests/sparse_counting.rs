//! The Maxwell-Calladine count of a network beyond the dense SVD's bound
//! (`counting::MAX_DENSE_SVD_SIDE = 512`) through the sparse path (inertia counts of the Gram
//! matrices, null vectors by shift-invert subspace iteration): the literature's exact counts of
//! square and kagome patches, the dense path's counts and null spaces below the bound, a stop
//! question that stops it. The vectors are checked with the patch's own dense compatibility
//! matrix (chain-network's `Patch::compatibility_matrix`, built independently of the model's
//! sparse rows).

use chain_core::linalg::LinalgError;
use chain_core::statics::StaticsError;
use chain_core::statics::counting::{
    Counting, MAX_DENSE_SVD_SIDE, maxwell_calladine, maxwell_calladine_sparse, maxwell_calladine_with,
};
use chain_network::NetworkModel;
use chain_network::cell::ready;
use chain_network::patch::{Boundary, Patch};
use faer::Mat;

/// The count of the harmonic model of `patch` at its reference, which must take the sparse path.
fn count(patch: &Patch) -> Counting {
    assert!(patch.dof().max(patch.bonds().len()) > MAX_DENSE_SVD_SIDE);
    let model = NetworkModel::builder(patch).build().unwrap();
    maxwell_calladine(&model, &model.reference(), None).unwrap()
}

/// The null vectors are orthonormal and `C` (resp. `C^T`) maps them to zero, with `C` the patch's
/// dense compatibility matrix.
fn check_vectors(patch: &Patch, counting: &Counting) {
    let c = patch.compatibility_matrix().unwrap();
    let ct = c.transpose().to_owned();
    for (vectors, matrix, what) in
        [(&counting.zero_modes, &c, "C z"), (&counting.self_stresses, &ct, "C^T s")]
    {
        let len = matrix.ncols();
        let v = Mat::from_fn(len, vectors.len(), |i, j| vectors[j][i]);
        let image = matrix * &v;
        assert!(image.norm_max() < 1e-10, "|{what}| = {:e}", image.norm_max());
        let gram = v.transpose() * &v;
        let identity = Mat::<f64>::identity(vectors.len(), vectors.len());
        assert!((gram - identity).norm_max() < 1e-10, "{what}: not orthonormal");
    }
}

/// Periodic `N1 x N2` square: one zero mode and one self-stress per straight line (`N1 + N2`);
/// kagome: also the lines along `a3`, `gcd(N1, N2)` of them (Lubensky et al., Rep. Prog. Phys. 78
/// (2015), sections 5.1, 5.2; `tests/counts.rs` checks the same below the bound by Bloch blocks).
#[test]
fn periodic_square_and_kagome_above_the_bound_have_one_mode_and_stress_per_line() {
    let cases = [(ready::square(), [17, 18], 17 + 18), (ready::kagome(), [10, 12], 10 + 12 + 2)];
    for (cell, n, lines) in cases {
        let patch = Patch::new(&cell, n, Boundary::Periodic).unwrap();
        let counting = count(&patch);
        assert_eq!((counting.zero_modes.len(), counting.self_stresses.len()), (lines, lines), "{n:?}");
        assert_eq!(counting.rank, patch.dof() - lines);
        // The sparse path's singular values: its candidates', the zero modes' among them.
        assert_eq!(counting.singular_values.iter().filter(|&&s| s <= counting.tolerance).count(), lines);
        check_vectors(&patch, &counting);
    }
}

/// Free patches: the square's zero modes are a rigid `x` shift per row and a `y` shift per column
/// (`N1 + N2`, no self-stress: every line ends at the boundary); the kagome's have no self-stress
/// either, so `N0 = dof - bonds`.
#[test]
fn free_square_and_kagome_above_the_bound() {
    let square = ready::square();
    let patch = Patch::new(&square, [17, 19], Boundary::Free).unwrap();
    let counting = count(&patch);
    assert_eq!((counting.zero_modes.len(), counting.self_stresses.len()), (17 + 19, 0));
    check_vectors(&patch, &counting);
    let kagome = ready::kagome();
    let patch = Patch::new(&kagome, [10, 11], Boundary::Free).unwrap();
    let counting = count(&patch);
    let excess = patch.dof() - patch.bonds().len();
    assert_eq!((counting.zero_modes.len(), counting.self_stresses.len()), (excess, 0));
    check_vectors(&patch, &counting);
}

/// The twisted kagome lattice keeps only the two rigid translations and two self-stresses (Sun et
/// al., PNAS 109, 12369 (2012)).
#[test]
fn twisted_kagome_above_the_bound_keeps_only_translations() {
    let twisted = ready::twisted_kagome(0.2).unwrap();
    let patch = Patch::new(&twisted, [10, 10], Boundary::Periodic).unwrap();
    let counting = count(&patch);
    assert_eq!((counting.zero_modes.len(), counting.self_stresses.len()), (2, 2));
    check_vectors(&patch, &counting);
}

/// Below the bound the sparse path and the dense SVD give the same counts and span the same null
/// spaces (equal projectors), on a periodic and a free patch and at a disturbed configuration.
#[test]
fn the_sparse_path_agrees_with_the_dense_svd_below_the_bound() {
    let cells = [ready::kagome(), ready::deformed_kagome(0.1, -0.05, 0.02, 0.1).unwrap(), ready::square()];
    for cell in &cells {
        for boundary in [Boundary::Periodic, Boundary::Free] {
            let patch = Patch::new(cell, [6, 5], boundary).unwrap();
            let model = NetworkModel::builder(&patch).build().unwrap();
            let reference = model.reference();
            let disturbed: Vec<f64> =
                reference.iter().enumerate().map(|(i, x)| x + 0.01 * (0.37 * i as f64).sin()).collect();
            for x in [&reference, &disturbed] {
                let dense = maxwell_calladine(&model, x, None).unwrap();
                let sparse = maxwell_calladine_sparse(&model, x, None, &mut || false).unwrap();
                assert_eq!(
                    (sparse.rank, sparse.zero_modes.len(), sparse.self_stresses.len()),
                    (dense.rank, dense.zero_modes.len(), dense.self_stresses.len()),
                    "{boundary:?}"
                );
                for (a, b) in
                    [(&dense.zero_modes, &sparse.zero_modes), (&dense.self_stresses, &sparse.self_stresses)]
                {
                    let gap = projector_distance(a, b);
                    assert!(gap < 1e-8, "{boundary:?}: projectors differ by {gap:e}");
                }
            }
        }
    }
}

/// `max |P_a - P_b|` for the orthogonal projectors on the spans of two orthonormal bases.
fn projector_distance(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    let Some(len) = a.first().or(b.first()).map(Vec::len) else { return 0.0 };
    let projector = |basis: &[Vec<f64>]| {
        let v = Mat::from_fn(len, basis.len(), |i, j| basis[j][i]);
        &v * v.transpose()
    };
    (projector(a) - projector(b)).norm_max()
}

/// A stop question that answers yes ends the count with `Stopped`, wherever it is asked: at once
/// (the power iteration for `sigma_max`), and at every later asking tried (the factorizations,
/// the subspace iterations' Gram-Schmidt, Rayleigh-Ritz and rotations), never running on.
#[test]
fn a_stop_question_stops_the_sparse_count() {
    let kagome = ready::kagome();
    let patch = Patch::new(&kagome, [12, 12], Boundary::Periodic).unwrap();
    let model = NetworkModel::builder(&patch).build().unwrap();
    let x = model.reference();
    let mut total = 0;
    maxwell_calladine_with(&model, &x, None, &mut || {
        total += 1;
        false
    })
    .unwrap();
    let mut seen = Vec::new();
    for after in [0, total / 4, total / 2, total - 1] {
        let mut asked = 0;
        let stop = &mut || {
            asked += 1;
            asked > after
        };
        let err = maxwell_calladine_with(&model, &x, None, stop).unwrap_err();
        let StaticsError::Linalg(LinalgError::Stopped { what, .. }) = err else { panic!("{err}") };
        if after == 0 {
            assert_eq!(what, "power iterations");
        }
        seen.push(what);
        assert_eq!(asked, after + 1);
    }
    assert!(seen.contains(&"subspace iterations"), "{seen:?} of {total} askings");
}
