//! The full-spectrum QL path's `n x n` matrices are allocated fallibly (issue 37): under an
//! address-space limit set on this test process by `prlimit` (util-linux), 64 MiB above what it
//! has mapped, `linalg::eigenpairs` of a 20 000 x 20 000 tridiagonal matrix is
//! `LinalgError::OutOfMemory` with the bytes of one matrix, never an abort. This file holds one
//! test, so no other test shares the limit.

use chain_core::linalg::{LinalgError, eigenpairs};
use test_support::memory::with_headroom;

#[test]
fn the_eigenvectors_of_a_matrix_too_large_for_the_limit_are_an_out_of_memory_error() {
    let n = 20_000;
    let (diag, off) = (vec![2.0; n], vec![-1.0; n - 1]);
    let result = with_headroom(64 << 20, || eigenpairs(&diag, &off));
    assert_eq!(result.unwrap_err(), LinalgError::OutOfMemory { bytes: n * n * 8, what: "the eigenvectors" });
    // A matrix that fits: the 1D Laplacian's eigenvalues 2 - 2 cos(k pi / (n + 1)), closed form.
    let n = 50;
    let (values, vectors) = eigenpairs(&vec![2.0; n], &vec![-1.0; n - 1]).unwrap();
    for (k, value) in values.iter().enumerate() {
        let exact = 2.0 - 2.0 * (((k + 1) as f64) * std::f64::consts::PI / (n + 1) as f64).cos();
        assert!((value - exact).abs() < 1e-13, "{k}: {value} vs {exact}");
    }
    // Each column is the eigenvector of its value: sin(j k pi / (n + 1)), up to sign and scale.
    for k in 0..n {
        let v = vectors.column(k);
        let exact: Vec<f64> =
            (1..=n).map(|j| ((j * (k + 1)) as f64 * std::f64::consts::PI / (n + 1) as f64).sin()).collect();
        let norm = exact.iter().map(|x| x * x).sum::<f64>().sqrt();
        let dot: f64 = v.iter().zip(&exact).map(|(a, b)| a * b).sum::<f64>() / norm;
        assert!((dot.abs() - 1.0).abs() < 1e-12, "{k}: {dot}");
    }
}
