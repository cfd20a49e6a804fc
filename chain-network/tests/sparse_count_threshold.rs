//! The sparse Maxwell-Calladine count's zero threshold is the dense SVD's rule: a singular value
//! of `C` between the dense rule's tolerance `max(n, m) eps sigma_max` and the Gram matrix's
//! resolution `sqrt(128 max(n, m) eps ||C^T C||_inf)` counts as nonzero, as the dense SVD counts
//! it. The reference is faer's dense SVD of the patch's own dense compatibility matrix
//! (`Patch::compatibility_matrix`, built independently of the model's sparse rows), written here.

use chain_core::statics::counting::{MAX_DENSE_SVD_SIDE, maxwell_calladine};
use chain_network::NetworkModel;
use chain_network::cell::ready;
use chain_network::patch::{Boundary, Patch};
use faer::Mat;

/// The twisted kagome lattice at a twist of 1e-7 rad: the kagome's line modes (one per straight
/// line, `N1 + N2 + gcd(N1, N2)` = 30 on a periodic 10 x 10 patch, Lubensky et al. 2015 sec. 5.2)
/// but the two translations are lifted by the twist to singular values of order the twist (Sun et al., PNAS 109, 12369 (2012)), far above the dense
/// rule's tolerance and far below the Gram matrix's resolution; only the two translations stay
/// zero, with two self-stresses.
#[test]
fn a_slightly_twisted_kagome_counts_its_lifted_line_modes_as_the_dense_svd_does() {
    let twisted = ready::twisted_kagome(1e-7).unwrap();
    let patch = Patch::new(&twisted, [10, 10], Boundary::Periodic).unwrap();
    let (n, m) = (patch.dof(), patch.bonds().len());
    assert!(n.max(m) > MAX_DENSE_SVD_SIDE, "the count must take the sparse path");

    // The reference: the dense SVD's singular values and rule.
    let c = patch.compatibility_matrix().unwrap();
    let sigma = c.singular_values().unwrap();
    let sigma_max = sigma.iter().copied().fold(0.0, f64::max);
    let dense_tolerance = n.max(m) as f64 * f64::EPSILON * sigma_max;
    let rank = sigma.iter().filter(|&&s| s > dense_tolerance).count();
    // The Gram matrix's resolution: ||C^T C||_inf from the dense product.
    let ctc = c.transpose() * &c;
    let gram_norm = (0..n).map(|i| (0..n).map(|j| ctc[(i, j)].abs()).sum::<f64>()).fold(0.0, f64::max);
    let resolution = (128.0 * n.max(m) as f64 * f64::EPSILON * gram_norm).sqrt();
    let between: Vec<f64> =
        sigma.iter().copied().filter(|&s| s > 10.0 * dense_tolerance && s < resolution / 10.0).collect();
    assert_eq!(
        between.len(),
        28,
        "the lifted line modes: {between:?} (tolerance {dense_tolerance:e}, resolution {resolution:e})"
    );
    assert_eq!((n - rank, m - rank), (2, 2), "the dense rule on the twisted kagome");

    let model = NetworkModel::builder(&patch).build().unwrap();
    let counting = maxwell_calladine(&model, &model.reference(), None).unwrap();
    assert_eq!(counting.rank, rank);
    assert_eq!((counting.zero_modes.len(), counting.self_stresses.len()), (n - rank, m - rank));
    // The rule's tolerance: sigma_max by power iteration is a lower bound, within a few percent.
    assert!(counting.tolerance <= dense_tolerance * (1.0 + 1e-12));
    assert!(counting.tolerance >= 0.95 * dense_tolerance, "{:e} vs {dense_tolerance:e}", counting.tolerance);
    // The candidates' singular values are the dense SVD's lowest, to a few eps ||C||: the two
    // zeros, the lifted line modes' and the lowest phonons'.
    let mut reference: Vec<f64> = sigma.to_vec();
    reference.sort_by(f64::total_cmp);
    reference.truncate(counting.singular_values.len());
    reference.reverse();
    assert!(reference.len() >= 30);
    for (found, expected) in counting.singular_values.iter().zip(&reference) {
        assert!(
            (found - expected).abs() <= 64.0 * f64::EPSILON * sigma_max,
            "singular value {found:e}, the dense SVD's {expected:e}"
        );
    }

    // The zero modes are the translations: orthonormal, mapped to zero by the dense C.
    for (vectors, matrix, what) in
        [(&counting.zero_modes, &c, "C z"), (&counting.self_stresses, &c.transpose().to_owned(), "C^T s")]
    {
        let v = Mat::from_fn(matrix.ncols(), vectors.len(), |i, j| vectors[j][i]);
        let image = matrix * &v;
        assert!(image.norm_max() < 1e-12, "|{what}| = {:e}", image.norm_max());
        let gram = v.transpose() * &v;
        assert!((gram - Mat::<f64>::identity(vectors.len(), vectors.len())).norm_max() < 1e-12);
    }
}
