//! The tridiagonal linear algebra against dense nalgebra, exact Toeplitz spectra, a chain-like
//! near-degenerate cluster, and bad input.

use chain_core::banded::{tridiagonal_mul, tridiagonal_to_dmatrix};
use chain_core::linalg::{
    self, Eigenpair, Input, LinalgError, count_below, eigenpairs, eigenpairs_in_index_range, eigenpairs_near,
    eigenvalues, eigenvalues_in_index_range, eigenvalues_ql, lowest_eigenpairs, solve, solve_shifted,
    try_count_below,
};
use nalgebra::{DMatrix, SymmetricEigen};
use test_support::random::SplitMix;

// ---------------------------------------------------------------------------------------------
// Test models

/// A random symmetric tridiagonal matrix with entries in `[-1, 1)`.
fn random_tridiagonal(n: usize, seed: u64) -> (Vec<f64>, Vec<f64>) {
    let mut g = SplitMix(seed);
    let diag = (0..n).map(|_| g.symmetric()).collect();
    let off = (0..n.saturating_sub(1)).map(|_| g.symmetric()).collect();
    (diag, off)
}

/// `d` on the diagonal and `o` off it: eigenvalues `d + 2 o cos(j pi / (n + 1))`, `j = 1..=n`,
/// with eigenvectors `sin(i j pi / (n + 1))`.
fn toeplitz(n: usize, d: f64, o: f64) -> (Vec<f64>, Vec<f64>) {
    (vec![d; n], vec![o; n - 1])
}

/// The exact Toeplitz eigenvalues, ascending (for `o < 0`).
fn toeplitz_eigenvalues(n: usize, d: f64, o: f64) -> Vec<f64> {
    let h = std::f64::consts::PI / (n + 1) as f64;
    (1..=n).map(|j| d + 2.0 * o * (j as f64 * h).cos()).collect()
}

/// The exact unit Toeplitz eigenvector of the `j`-th smallest eigenvalue (0-based, `o < 0`).
fn toeplitz_vector(n: usize, j: usize) -> Vec<f64> {
    let h = std::f64::consts::PI / (n + 1) as f64;
    let v: Vec<f64> = (1..=n).map(|i| (i as f64 * (j + 1) as f64 * h).sin()).collect();
    let norm = dot(&v, &v).sqrt();
    v.iter().map(|x| x / norm).collect()
}

/// `C^T C` for the `(m - 1) x m` bidiagonal `C` with `alpha` on the diagonal and `beta` above it:
/// a chain's compatibility product, with the exact zero eigenvalue of the mechanism
/// `v_{i+1} = -(alpha / beta) v_i`. `blocks` such chains of `m` rotors are coupled by `coupling`.
fn chain_blocks(blocks: usize, m: usize, alpha: f64, beta: f64, coupling: f64) -> (Vec<f64>, Vec<f64>) {
    let mut diag = Vec::new();
    let mut off = Vec::new();
    for b in 0..blocks {
        if b > 0 {
            off.push(coupling);
        }
        for i in 0..m {
            let left = if i + 1 < m { alpha * alpha } else { 0.0 };
            let right = if i > 0 { beta * beta } else { 0.0 };
            diag.push(left + right);
            if i + 1 < m {
                off.push(alpha * beta);
            }
        }
    }
    (diag, off)
}

// ---------------------------------------------------------------------------------------------
// Measures

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `||T||_inf`, the largest absolute row sum.
fn norm(diag: &[f64], off: &[f64]) -> f64 {
    (0..diag.len())
        .map(|i| {
            diag[i].abs() + if i > 0 { off[i - 1].abs() } else { 0.0 } + off.get(i).map_or(0.0, |o| o.abs())
        })
        .fold(0.0, f64::max)
}

/// `||T v - lambda v||_2`.
fn residual(diag: &[f64], off: &[f64], lambda: f64, v: &[f64]) -> f64 {
    let mut tv = vec![0.0; v.len()];
    tridiagonal_mul(diag, off, v, &mut tv);
    tv.iter().zip(v).map(|(a, b)| (a - lambda * b).powi(2)).sum::<f64>().sqrt()
}

/// The dense eigenvalues (ascending) and eigenvectors (columns, same order).
fn dense_eigen(diag: &[f64], off: &[f64]) -> (Vec<f64>, DMatrix<f64>) {
    let eigen = SymmetricEigen::new(tridiagonal_to_dmatrix(diag, off));
    let mut order: Vec<usize> = (0..diag.len()).collect();
    order.sort_by(|&i, &j| eigen.eigenvalues[i].total_cmp(&eigen.eigenvalues[j]));
    let values = order.iter().map(|&i| eigen.eigenvalues[i]).collect();
    let vectors = DMatrix::from_fn(diag.len(), diag.len(), |r, c| eigen.eigenvectors[(r, order[c])]);
    (values, vectors)
}

fn assert_values_close(got: &[f64], want: &[f64], tolerance: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: count");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!((g - w).abs() <= tolerance, "{what}: eigenvalue {i}: {g} vs {w} (tolerance {tolerance:e})");
    }
}

/// Unit norm, pairwise orthogonal, and residuals below `tolerance`.
fn assert_orthonormal_pairs(diag: &[f64], off: &[f64], pairs: &[Eigenpair], tolerance: f64, what: &str) {
    for (i, p) in pairs.iter().enumerate() {
        assert_eq!(p.vector.len(), diag.len());
        let r = residual(diag, off, p.value, &p.vector);
        assert!(r <= tolerance, "{what}: residual of pair {i} is {r:e} (tolerance {tolerance:e})");
        for (j, q) in pairs.iter().enumerate().take(i + 1) {
            let want = if i == j { 1.0 } else { 0.0 };
            let got = dot(&p.vector, &q.vector);
            assert!((got - want).abs() <= 1e-12, "{what}: v{i} . v{j} = {got:e}");
        }
    }
}

/// Whether eigenvalue `i` is at least `gap` from its neighbours.
fn is_simple(values: &[f64], i: usize, gap: f64) -> bool {
    (i == 0 || values[i] - values[i - 1] > gap) && (i + 1 == values.len() || values[i + 1] - values[i] > gap)
}

/// Column `j` of a matrix as a vector.
fn column(m: &DMatrix<f64>, j: usize) -> Vec<f64> {
    m.column(j).iter().copied().collect()
}

const SIZES: [usize; 6] = [1, 2, 3, 10, 60, 200];

// ---------------------------------------------------------------------------------------------
// Against dense nalgebra

#[test]
fn eigenvalues_agree_with_dense_symmetric_eigen() {
    for &n in &SIZES {
        for seed in 1..4 {
            let (diag, off) = random_tridiagonal(n, seed * 7919 + n as u64);
            let scale = norm(&diag, &off);
            let (want, _) = dense_eigen(&diag, &off);
            let tolerance = 1e-10 * scale;
            assert_values_close(&eigenvalues_ql(&diag, &off).unwrap(), &want, tolerance, "QL");
            assert_values_close(&eigenvalues(&diag, &off).unwrap(), &want, tolerance, "eigenvalues");
            assert_values_close(
                &eigenvalues_in_index_range(&diag, &off, 0, n).unwrap(),
                &want,
                tolerance,
                "bisection",
            );
            let (lo, hi) = (n / 3, n - n / 3);
            assert_values_close(
                &eigenvalues_in_index_range(&diag, &off, lo, hi).unwrap(),
                &want[lo..hi],
                tolerance,
                "bisection, a middle range",
            );
        }
    }
}

#[test]
fn eigenvectors_agree_with_dense_symmetric_eigen() {
    for &n in &SIZES {
        for seed in 1..4 {
            let (diag, off) = random_tridiagonal(n, seed * 104729 + n as u64);
            let scale = norm(&diag, &off);
            let (want, dense_vectors) = dense_eigen(&diag, &off);
            let (values, vectors) = eigenpairs(&diag, &off).unwrap();
            assert_values_close(&values, &want, 1e-10 * scale, "QL with vectors");
            let ql: Vec<Eigenpair> =
                (0..n).map(|j| Eigenpair { value: values[j], vector: column(&vectors, j) }).collect();
            assert_orthonormal_pairs(&diag, &off, &ql, 1e-10 * scale, "QL");

            // Inverse iteration on the lowest third, and on a range in the middle.
            let lowest = lowest_eigenpairs(&diag, &off, n.div_ceil(3)).unwrap();
            let (lo, hi) = (n / 3, n - n / 3);
            let middle = eigenpairs_in_index_range(&diag, &off, lo, hi).unwrap();
            assert_orthonormal_pairs(&diag, &off, &lowest, 1e-10 * scale, "lowest");
            assert_orthonormal_pairs(&diag, &off, &middle, 1e-10 * scale, "middle");

            for (what, first, pairs) in [("QL", 0, &ql), ("lowest", 0, &lowest), ("middle", lo, &middle)] {
                for (t, p) in pairs.iter().enumerate() {
                    let j = first + t;
                    assert!((p.value - want[j]).abs() <= 1e-10 * scale, "{what}: eigenvalue {j}");
                    if is_simple(&want, j, 1e-5 * scale) {
                        let overlap = dot(&p.vector, &column(&dense_vectors, j)).abs();
                        assert!(
                            overlap > 1.0 - 1e-9,
                            "{what}, n = {n}: |v . w| = {overlap} for eigenvalue {j}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn eigenpairs_near_are_the_nearest() {
    for &n in &SIZES {
        let (diag, off) = random_tridiagonal(n, 31 + n as u64);
        let scale = norm(&diag, &off);
        let (want, _) = dense_eigen(&diag, &off);
        for sigma in [-3.0, -0.3, 0.0, 0.41, 5.0] {
            let k = n.min(4);
            let pairs = eigenpairs_near(&diag, &off, sigma, k).unwrap();
            assert_orthonormal_pairs(&diag, &off, &pairs, 1e-10 * scale, "near");
            let mut by_distance = want.clone();
            by_distance.sort_by(|a, b| (a - sigma).abs().total_cmp(&(b - sigma).abs()));
            let mut nearest = by_distance[..k].to_vec();
            nearest.sort_by(f64::total_cmp);
            let got: Vec<f64> = pairs.iter().map(|p| p.value).collect();
            assert_values_close(&got, &nearest, 1e-10 * scale, "near");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The Toeplitz matrix's exact spectrum

#[test]
fn every_method_finds_the_exact_toeplitz_spectrum() {
    let (n, d, o) = (2000, 3.0, -1.0);
    let (diag, off) = toeplitz(n, d, o);
    let exact = toeplitz_eigenvalues(n, d, o);
    // Eigenvalues lie in [1, 5]: "relative" is relative to each eigenvalue and to ||T|| at once.
    assert_values_close(&eigenvalues_ql(&diag, &off).unwrap(), &exact, 1e-12, "QL");
    assert_values_close(&eigenvalues_in_index_range(&diag, &off, 0, n).unwrap(), &exact, 1e-12, "bisection");
    let pairs = lowest_eigenpairs(&diag, &off, 10).unwrap();
    assert_orthonormal_pairs(&diag, &off, &pairs, 1e-12 * 5.0, "inverse iteration");
    for (j, p) in pairs.iter().enumerate() {
        assert!((p.value - exact[j]).abs() <= 1e-12, "inverse iteration: eigenvalue {j}");
        let overlap = dot(&p.vector, &toeplitz_vector(n, j)).abs();
        assert!(overlap > 1.0 - 1e-9, "eigenvector {j}: |v . w| = {overlap}");
    }
}

#[test]
fn ql_eigenvectors_of_a_toeplitz_matrix_are_its_sines() {
    let (n, d, o) = (300, 3.0, -1.0);
    let (diag, off) = toeplitz(n, d, o);
    let (values, vectors) = eigenpairs(&diag, &off).unwrap();
    assert_values_close(&values, &toeplitz_eigenvalues(n, d, o), 1e-12, "QL with vectors");
    for j in 0..n {
        let overlap = dot(&column(&vectors, j), &toeplitz_vector(n, j)).abs();
        assert!(overlap > 1.0 - 1e-9, "eigenvector {j}: |v . w| = {overlap}");
    }
}

#[test]
fn the_lowest_modes_of_a_long_chain() {
    let (n, d, o) = (100_000, 3.0, -1.0);
    let (diag, off) = toeplitz(n, d, o);
    let exact = toeplitz_eigenvalues(n, d, o);
    let pairs = lowest_eigenpairs(&diag, &off, 10).unwrap();
    // The ten are within 1e-7 of each other: one cluster, orthogonalised.
    assert_orthonormal_pairs(&diag, &off, &pairs, 1e-12, "n = 1e5");
    for (j, p) in pairs.iter().enumerate() {
        assert!((p.value - exact[j]).abs() <= 1e-12, "eigenvalue {j}: {} vs {}", p.value, exact[j]);
    }
    let x = 1.0 + 1e-8;
    assert_eq!(count_below(&diag, &off, x), exact.iter().filter(|&&v| v < x).count());
}

// ---------------------------------------------------------------------------------------------
// A near-degenerate cluster of near-zero eigenvalues

/// Three stiff chains (`alpha = -1`, `beta = 0.066`), each with an exact mechanism, coupled by
/// `coupling`: three eigenvalues within ~1e-16 of zero, the rest above `(|alpha| - |beta|)^2`.
fn check_near_zero_cluster(m: usize, coupling: f64) {
    let (diag, off) = chain_blocks(3, m, -1.0, 0.066, coupling);
    let scale = norm(&diag, &off);
    let pairs = lowest_eigenpairs(&diag, &off, 4).unwrap();
    for p in &pairs[..3] {
        assert!(p.value.abs() <= 1e-14 * scale, "a mechanism at {:e}", p.value);
    }
    assert!(pairs[3].value > 0.8, "the gap: {}", pairs[3].value);
    assert_orthonormal_pairs(&diag, &off, &pairs, 1e-13 * scale, "cluster");
    assert_eq!(count_below(&diag, &off, 1e-10), 3);
    assert_eq!(count_below(&diag, &off, -1e-10), 0);

    // The three span the dense solver's null space: the projectors agree.
    let (_, dense_vectors) = dense_eigen(&diag, &off);
    let dense = dense_vectors.columns(0, 3).into_owned();
    let ours = DMatrix::from_fn(diag.len(), 3, |i, j| pairs[j].vector[i]);
    let difference = (&ours * ours.transpose() - &dense * dense.transpose()).abs().max();
    assert!(difference < 1e-10, "projectors differ by {difference:e}");

    // QL sees the same cluster.
    let (values, vectors) = eigenpairs(&diag, &off).unwrap();
    let ql: Vec<Eigenpair> =
        (0..4).map(|j| Eigenpair { value: values[j], vector: column(&vectors, j) }).collect();
    assert_orthonormal_pairs(&diag, &off, &ql, 1e-13 * scale, "QL cluster");
}

#[test]
fn weakly_coupled_mechanisms_give_orthonormal_vectors() {
    check_near_zero_cluster(20, 1e-14);
    check_near_zero_cluster(40, 1e-14);
}

#[test]
fn decoupled_mechanisms_give_orthonormal_vectors() {
    check_near_zero_cluster(20, 0.0);
    check_near_zero_cluster(7, 0.0);
}

#[test]
fn exactly_repeated_eigenvalues_give_orthonormal_vectors() {
    // Five identical decoupled 1x1 blocks and a zero matrix: every eigenvalue repeated.
    let diag = vec![2.0; 5];
    let off = vec![0.0; 4];
    let pairs = lowest_eigenpairs(&diag, &off, 4).unwrap();
    assert_orthonormal_pairs(&diag, &off, &pairs, 1e-14, "identity");
    let zero = lowest_eigenpairs(&[0.0; 6], &[0.0; 5], 5).unwrap();
    assert_orthonormal_pairs(&[0.0; 6], &[0.0; 5], &zero, 1e-300, "zero");
    assert_eq!(eigenvalues(&[0.0; 6], &[0.0; 5]).unwrap(), vec![0.0; 6]);
}

// ---------------------------------------------------------------------------------------------
// Sturm counts

#[test]
fn sturm_counts_are_morse_indices() {
    for &n in &SIZES {
        for seed in 1..4 {
            let (diag, off) = random_tridiagonal(n, seed * 31337 + n as u64);
            let (values, _) = dense_eigen(&diag, &off);
            // Points between consecutive eigenvalues, and beyond both ends.
            let mut points = vec![values[0] - 1.0, values[n - 1] + 1.0];
            points.extend(values.windows(2).filter(|w| w[1] - w[0] > 1e-12).map(|w| 0.5 * (w[0] + w[1])));
            for x in points {
                let below = values.iter().filter(|&&v| v < x).count();
                assert_eq!(count_below(&diag, &off, x), below, "n = {n}, x = {x}");
                // The Morse index of the shifted, indefinite matrix.
                let shifted: Vec<f64> = diag.iter().map(|d| d - x).collect();
                assert_eq!(count_below(&shifted, &off, 0.0), below, "Morse index, n = {n}");
                assert_eq!(try_count_below(&shifted, &off, 0.0), Ok(below));
            }
        }
    }
}

#[test]
fn sturm_counts_survive_zero_pivots_and_extreme_scales() {
    // T - 0 I has a zero leading pivot; eigenvalues are -1, 0 (twice), 1... of [[0,1],[1,0]] etc.
    assert_eq!(count_below(&[0.0, 0.0], &[1.0], 0.0), 1);
    assert_eq!(count_below(&[0.0, 0.0, 0.0], &[1.0, 1.0], 0.0), 1);
    assert_eq!(count_below(&[0.0, 0.0, 0.0], &[1.0, 1.0], 1e-300), 2);
    // The same matrix in extreme units.
    for unit in [1e-300, 1e300] {
        let (diag, off) = random_tridiagonal(50, 5);
        let (values, _) = dense_eigen(&diag, &off);
        let big: Vec<f64> = diag.iter().map(|d| d * unit).collect();
        let big_off: Vec<f64> = off.iter().map(|o| o * unit).collect();
        let x = 0.5 * (values[20] + values[21]);
        assert_eq!(count_below(&big, &big_off, x * unit), 21);
        let got = eigenvalues_ql(&big, &big_off).unwrap();
        assert_values_close(
            &got.iter().map(|v| v / unit).collect::<Vec<_>>(),
            &values,
            1e-12,
            "QL in extreme units",
        );
        let pairs = lowest_eigenpairs(&big, &big_off, 3).unwrap();
        for (j, p) in pairs.iter().enumerate() {
            assert!((p.value / unit - values[j]).abs() < 1e-12);
            assert!((dot(&p.vector, &p.vector) - 1.0).abs() < 1e-14);
        }
    }
    assert_eq!(count_below(&[], &[], 0.0), 0);
    assert_eq!(count_below(&[-1.0], &[], 0.0), 1);
}

// ---------------------------------------------------------------------------------------------
// Solves

/// `||T x - b|| / (||T|| ||x||)`.
fn relative_residual(diag: &[f64], off: &[f64], shift: f64, x: &[f64], b: &[f64]) -> f64 {
    let mut tx = vec![0.0; x.len()];
    tridiagonal_mul(diag, off, x, &mut tx);
    let r = tx.iter().zip(x).zip(b).map(|((t, x), b)| (t - shift * x - b).powi(2)).sum::<f64>().sqrt();
    let shifted: Vec<f64> = diag.iter().map(|d| d - shift).collect();
    r / (norm(&shifted, off) * dot(x, x).sqrt())
}

#[test]
fn solves_indefinite_and_definite_systems() {
    for &n in SIZES.iter().chain(&[10_000]) {
        for seed in 1..4 {
            // Random entries in [-1, 1): indefinite.
            let (diag, off) = random_tridiagonal(n, seed * 4241 + n as u64);
            let b = random_tridiagonal(n, seed).0;
            let x = solve(&diag, &off, &b).unwrap();
            assert!(relative_residual(&diag, &off, 0.0, &x, &b) <= 1e-13, "indefinite, n = {n}");
            // Diagonally dominant, positive: definite.
            let spd: Vec<f64> = diag.iter().map(|d| d + 2.5).collect();
            let x = solve(&spd, &off, &b).unwrap();
            assert!(relative_residual(&spd, &off, 0.0, &x, &b) <= 1e-13, "definite, n = {n}");
            // Shifted into the middle of the spectrum.
            let x = solve_shifted(&spd, &off, 2.5, &b).unwrap();
            assert!(relative_residual(&spd, &off, 2.5, &x, &b) <= 1e-13, "shifted, n = {n}");
        }
    }
    // A zero leading pivot needs a row interchange.
    let x = solve(&[0.0, 0.0, 1.0], &[1.0, 1.0], &[1.0, 2.0, 3.0]).unwrap();
    assert!(relative_residual(&[0.0, 0.0, 1.0], &[1.0, 1.0], 0.0, &x, &[1.0, 2.0, 3.0]) <= 1e-15);
    assert_eq!(solve(&[], &[], &[]), Ok(vec![]));
    assert_eq!(solve(&[4.0], &[], &[2.0]), Ok(vec![0.5]));
}

#[test]
fn singular_systems_are_errors_not_nans() {
    let singular = solve(&[1.0, 1.0], &[1.0], &[1.0, 2.0]);
    assert!(matches!(singular, Err(LinalgError::Singular { row: 1, pivot }) if pivot == 0.0), "{singular:?}");
    assert!(matches!(solve(&[0.0], &[], &[1.0]), Err(LinalgError::Singular { row: 0, .. })));
    // At an exact eigenvalue of the Toeplitz matrix 2, -1 of order 3 (2 - sqrt 2, 2, 2 + sqrt 2).
    assert!(matches!(
        solve_shifted(&[2.0; 3], &[-1.0; 2], 2.0, &[1.0; 3]),
        Err(LinalgError::Singular { .. })
    ));
    // The chain's mechanism.
    let (diag, off) = chain_blocks(1, 10, -1.0, 0.066, 0.0);
    match solve(&diag, &off, &[1.0; 10]) {
        Err(LinalgError::Singular { .. }) => {}
        Ok(x) => assert!(x.iter().all(|v| v.is_finite()), "a solution must be finite"),
        Err(e) => panic!("unexpected {e}"),
    }
}

// ---------------------------------------------------------------------------------------------
// Bad input

/// Whether an error is `NotFinite` at `input[index]`.
fn not_finite(input: Input, index: usize) -> impl Fn(LinalgError) -> bool {
    move |e| matches!(e, LinalgError::NotFinite { input: i, index: j, .. } if (i, j) == (input, index))
}

#[test]
fn bad_input_gives_typed_errors() {
    let mismatch = Some(LinalgError::DimensionMismatch { diag: 3, off: 1 });
    let (diag, off) = ([1.0, 2.0, 3.0], [1.0]);
    assert_eq!(eigenvalues(&diag, &off).err(), mismatch);
    assert_eq!(eigenvalues_ql(&diag, &off).err(), mismatch);
    assert_eq!(eigenvalues_in_index_range(&diag, &off, 0, 1).err(), mismatch);
    assert_eq!(eigenpairs(&diag, &off).err(), mismatch);
    assert_eq!(lowest_eigenpairs(&diag, &off, 1).err(), mismatch);
    assert_eq!(eigenpairs_near(&diag, &off, 0.0, 1).err(), mismatch);
    assert_eq!(solve(&diag, &off, &[1.0; 3]).err(), mismatch);
    assert_eq!(try_count_below(&diag, &off, 0.0).err(), mismatch);
    assert_eq!(eigenvalues(&[], &[1.0]).err(), Some(LinalgError::DimensionMismatch { diag: 0, off: 1 }));
    assert_eq!(solve(&[1.0, 2.0], &[1.0], &[1.0]).err(), Some(LinalgError::RhsMismatch { n: 2, rhs: 1 }));

    assert!(eigenvalues(&[1.0, f64::NAN], &[1.0]).is_err_and(not_finite(Input::Diag, 1)));
    assert!(eigenpairs(&[1.0, 2.0], &[f64::INFINITY]).is_err_and(not_finite(Input::Off, 0)));
    assert!(lowest_eigenpairs(&[1.0, f64::NAN], &[1.0], 1).is_err_and(not_finite(Input::Diag, 1)));
    assert!(eigenvalues_in_index_range(&[f64::NAN], &[], 0, 1).is_err_and(not_finite(Input::Diag, 0)));
    assert!(solve(&[1.0, 2.0], &[1.0], &[1.0, f64::NAN]).is_err_and(not_finite(Input::Rhs, 1)));
    assert!(
        solve_shifted(&[1.0, 2.0], &[1.0], f64::NAN, &[1.0, 1.0]).is_err_and(not_finite(Input::Shift, 0))
    );
    assert!(
        eigenpairs_near(&[1.0, 2.0], &[1.0], f64::NEG_INFINITY, 1).is_err_and(not_finite(Input::Shift, 0))
    );
    assert!(try_count_below(&[1.0, 2.0], &[1.0], f64::NAN).is_err_and(not_finite(Input::Shift, 0)));
    // The unchecked count does not panic on bad input.
    let _ = count_below(&[1.0, f64::NAN, 3.0], &[1.0], f64::NAN);
    let _ = count_below(&[1.0], &[1.0, 2.0], 0.0);

    let range = |lo, hi, n| Some(LinalgError::IndexOutOfRange { lo, hi, n });
    assert_eq!(eigenvalues_in_index_range(&[1.0, 2.0], &[0.5], 1, 3).err(), range(1, 3, 2));
    assert_eq!(eigenvalues_in_index_range(&[1.0, 2.0], &[0.5], 2, 1).err(), range(2, 1, 2));
    assert_eq!(eigenpairs_in_index_range(&[1.0, 2.0], &[0.5], 0, 3).err(), range(0, 3, 2));
    assert_eq!(lowest_eigenpairs(&[1.0, 2.0], &[0.5], 3).err(), range(0, 3, 2));
    assert_eq!(eigenpairs_near(&[1.0, 2.0], &[0.5], 0.0, 3).err(), range(0, 3, 2));

    // The messages carry the numbers.
    let message = LinalgError::DimensionMismatch { diag: 3, off: 1 }.to_string();
    assert_eq!(message, "off has 1 value, but a matrix with 3 diagonal values needs 2");
    assert_eq!(
        LinalgError::NotFinite { input: Input::Rhs, index: 4, value: f64::NAN }.to_string(),
        "rhs[4] = NaN is not finite"
    );
}

#[test]
fn empty_and_one_by_one_matrices() {
    assert_eq!(eigenvalues(&[], &[]), Ok(vec![]));
    assert_eq!(eigenvalues_in_index_range(&[], &[], 0, 0), Ok(vec![]));
    assert_eq!(lowest_eigenpairs(&[], &[], 0), Ok(vec![]));
    assert_eq!(eigenpairs_near(&[], &[], 1.0, 0), Ok(vec![]));
    let (values, vectors) = eigenpairs(&[], &[]).unwrap();
    assert!(values.is_empty() && vectors.is_empty());

    assert_eq!(eigenvalues(&[-2.5], &[]), Ok(vec![-2.5]));
    assert_eq!(eigenvalues_in_index_range(&[-2.5], &[], 0, 1).unwrap().len(), 1);
    assert!((eigenvalues_in_index_range(&[-2.5], &[], 0, 1).unwrap()[0] + 2.5).abs() < 1e-15);
    let pairs = lowest_eigenpairs(&[-2.5], &[], 1).unwrap();
    assert_eq!(pairs[0].vector, vec![1.0]);
    let (values, vectors) = eigenpairs(&[-2.5], &[]).unwrap();
    assert_eq!((values, vectors[(0, 0)]), (vec![-2.5], 1.0));
    assert_eq!(count_below(&[-2.5], &[], 0.0), 1);
    assert_eq!(linalg::count_below(&[-2.5], &[], -2.5), 0);
}
