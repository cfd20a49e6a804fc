//! Free patches above `counts::MAX_DENSE_FREE_SIDE` are counted by chain-core's sparse, stoppable
//! path on the patch's model (a dense SVD of that size cannot be stopped): the counts and vectors
//! against faer's dense SVD of the patch's own compatibility matrix (`Patch::compatibility_matrix`,
//! built independently of the model's sparse rows), written here; the stop question stops it.

use chain_core::linalg::LinalgError;
use chain_core::statics::StaticsError;
use chain_network::NetworkError;
use chain_network::cell::ready;
use chain_network::counts::{
    MAX_DENSE_FREE_SIDE, Method, counts, counts_with, null_spaces, null_spaces_with,
};
use chain_network::patch::{Boundary, Patch};
use faer::Mat;

/// The reference rank of `c`: singular values above `max(n, m) eps sigma_max` (the sparse path's
/// rule), checked to be far from both thresholds (none between a thousandth of it and
/// `1e-6 sigma_max`, above this crate's dense rule `1e-9 sigma_max`), so either rule counts the same.
fn reference_rank(c: &Mat<f64>) -> usize {
    let sigma = c.singular_values().unwrap();
    let sigma_max = sigma.iter().copied().fold(0.0, f64::max);
    let tolerance = c.nrows().max(c.ncols()) as f64 * f64::EPSILON * sigma_max;
    for &s in &sigma {
        assert!(
            s < 1e-3 * tolerance || s > 1e-6 * sigma_max,
            "a singular value {s:e} near the thresholds ({tolerance:e}, {:e})",
            1e-9 * sigma_max
        );
    }
    sigma.iter().filter(|&&s| s > tolerance).count()
}

#[test]
fn a_large_free_patch_is_counted_by_the_sparse_path_as_the_dense_svd_counts_it() {
    for (name, cell, cells) in [
        ("kagome", ready::kagome(), [14, 14]),
        ("deformed kagome", ready::deformed_kagome(-0.05, 0.05, 0.05, 0.0).unwrap(), [14, 13]),
    ] {
        let patch = Patch::new(&cell, cells, Boundary::Free).unwrap();
        let (n, m) = (patch.dof(), patch.bonds().len());
        assert!(n.max(m) > MAX_DENSE_FREE_SIDE, "{name}: must take the sparse path");
        let c = patch.compatibility_matrix().unwrap();
        let rank = reference_rank(&c);

        let k = counts(&patch).unwrap();
        assert_eq!(k.method, Method::Sparse, "{name}");
        assert_eq!((k.rank, k.zero_modes, k.self_stresses), (rank, n - rank, m - rank), "{name}");
        // The free kagome is isostatic in the bulk: no self-stress (Kane and Lubensky 2014).
        assert_eq!(k.self_stresses, 0, "{name}");
        let sigma_max = c.singular_values().unwrap()[0];
        assert!((k.largest_singular_value - sigma_max).abs() < 0.05 * sigma_max, "{name}");

        // The vectors in the patch's coordinates: orthonormal, mapped to zero by its own C.
        let ns = null_spaces(&patch).unwrap();
        let z = &ns.zero_modes;
        assert_eq!((z.nrows(), z.ncols()), (n, n - rank), "{name}");
        let gram = z.transpose() * z;
        for i in 0..z.ncols() {
            for j in 0..z.ncols() {
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((gram[(i, j)] - expected).abs() < 1e-10, "{name}: Z^T Z at {i}, {j}");
            }
        }
        let cz = &c * z;
        let worst = (0..cz.ncols())
            .map(|j| (0..cz.nrows()).map(|i| cz[(i, j)] * cz[(i, j)]).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        assert!(worst < 1e-10 * sigma_max, "{name}: |C z| = {worst:e}");
        assert_eq!(ns.self_stresses.ncols(), 0, "{name}");
    }
}

#[test]
fn a_stop_question_stops_every_count() {
    let kagome = ready::kagome();
    let is_stopped = |e: &NetworkError| {
        matches!(e, NetworkError::Statics(StaticsError::Linalg(LinalgError::Stopped { .. })))
    };
    for (cells, boundary) in
        [([14, 14], Boundary::Free), ([6, 6], Boundary::Free), ([20, 20], Boundary::Periodic)]
    {
        let patch = Patch::new(&kagome, cells, boundary).unwrap();
        // Stopped at the first question and, where it is asked more than once (the sparse path,
        // the Bloch blocks), at a later one.
        let later = if cells == [6, 6] { vec![1] } else { vec![1, 3] };
        for stop_at in later {
            let mut asked = 0;
            let e = counts_with(&patch, &mut || {
                asked += 1;
                asked >= stop_at
            })
            .unwrap_err();
            assert!(is_stopped(&e), "{cells:?} {boundary:?}: {e}");
            assert_eq!(asked, stop_at, "{cells:?}: asked again after a yes");
            let e = null_spaces_with(&patch, &mut || true).unwrap_err();
            assert!(is_stopped(&e), "{cells:?} {boundary:?}: {e}");
        }
    }
}
