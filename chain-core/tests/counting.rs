//! The chain's Maxwell-Calladine counting through the Golub-Kahan tridiagonal (O(n) per Sturm
//! count, `linalg/golub_kahan.rs`) against a dense SVD written here (nalgebra's, of the dense
//! compatibility matrix), on random configurations, the paper's kink, antikink and uniform
//! state, and a chain at `l_critical` with its state of self-stress; a count at n = 8192 (the
//! size the issue found unbounded) finishes, and a stop question stops it.

use chain_core::RuntimeChain;
use chain_core::linalg::LinalgError;
use chain_core::statics::StaticsError;
use chain_core::statics::antikink::{AntikinkOptions, antikink_at};
use chain_core::statics::counting::{Counting, compatibility, maxwell_calladine, maxwell_calladine_with};
use chain_core::statics::impurity::two_kink_configuration;
use chain_core::statics::kink::kink;
use nalgebra::{DMatrix, DVector};
use test_support::random::SplitMix;

/// The dense `(n - 1) x n` compatibility matrix from the chain's bands.
fn dense(chain: &RuntimeChain, theta: &[f64]) -> DMatrix<f64> {
    let (left, right) = compatibility(chain, theta);
    let m = left.len();
    let mut c = DMatrix::zeros(m, m + 1);
    for p in 0..m {
        c[(p, p)] = left[p];
        c[(p, p + 1)] = right[p];
    }
    c
}

/// The counting against the dense SVD: every singular value to `1e-13 sigma_max`, the rank by
/// the same rule from the dense values, `n - rank` orthonormal zero modes and `m - rank`
/// self-stresses that `C` and `C^T` map to within the tolerance of zero.
fn check_against_dense(what: &str, chain: &RuntimeChain, theta: &[f64], counting: &Counting) {
    let c = dense(chain, theta);
    let (m, n) = (c.nrows(), c.ncols());
    let mut reference: Vec<f64> = c.clone().singular_values().iter().copied().collect();
    reference.sort_by(|a, b| b.total_cmp(a));
    let sigma_max = reference[0];
    assert_eq!(counting.singular_values.len(), reference.len(), "{what}");
    for (i, (got, want)) in counting.singular_values.iter().zip(&reference).enumerate() {
        assert!((got - want).abs() <= 1e-13 * sigma_max, "{what}: sigma_{i} {got:e} vs dense {want:e}");
    }
    let tolerance = n as f64 * f64::EPSILON * sigma_max;
    let rank = reference.iter().filter(|&&s| s > tolerance).count();
    assert_eq!(counting.rank, rank, "{what}: rank");
    assert_eq!((counting.zero_modes.len(), counting.self_stresses.len()), (n - rank, m - rank), "{what}");
    let orthonormal = |vectors: &[Vec<f64>]| {
        for (i, a) in vectors.iter().enumerate() {
            for (j, b) in vectors.iter().enumerate() {
                let dot: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
                assert!((dot - f64::from(u8::from(i == j))).abs() < 1e-12, "{what}: <{i}, {j}> = {dot}");
            }
        }
    };
    orthonormal(&counting.zero_modes);
    orthonormal(&counting.self_stresses);
    let bound = tolerance.max(1e-13 * sigma_max);
    for z in &counting.zero_modes {
        let cz = (&c * DVector::from_column_slice(z)).norm();
        assert!(cz <= bound, "{what}: |C z| = {cz:e} above {bound:e}");
    }
    for s in &counting.self_stresses {
        let cts = (c.transpose() * DVector::from_column_slice(s)).norm();
        assert!(cts <= bound, "{what}: |C^T s| = {cts:e} above {bound:e}");
    }
}

#[test]
fn the_golub_kahan_counting_equals_a_dense_svd_on_random_and_paper_chains() {
    let mut random = SplitMix(37);
    for (n, theta_bar) in [(2, 0.4), (7, 0.58), (40, 0.3), (121, 0.58)] {
        let chain = RuntimeChain::builder(n, 0.8, 1.0e4, theta_bar).build().unwrap();
        for draw in 0..4 {
            let theta = random.fill(n, -1.5, 1.5);
            let counting = maxwell_calladine(&chain, &theta, None).unwrap();
            check_against_dense(&format!("n = {n}, draw {draw}"), &chain, &theta, &counting);
        }
    }
    // The symmetric antikink has a state of self-stress whose singular value is 2.7e-34: a
    // cluster of three eigenvalues of the Golub-Kahan matrix at zero, tighter than eps.
    let paper = RuntimeChain::builder(60, 0.8, 1.0e4, 0.58).build().unwrap();
    let antikink = antikink_at(&paper, 30.0, &AntikinkOptions::default()).unwrap().theta;
    for (what, theta) in
        [("kink", kink(&paper, 20.3).unwrap()), ("antikink", antikink), ("uniform", vec![0.58; 60])]
    {
        let counting = maxwell_calladine(&paper, &theta, None).unwrap();
        check_against_dense(what, &paper, &theta, &counting);
        assert_eq!(counting.index(), 1, "{what}");
    }
}

#[test]
fn a_spring_at_l_critical_has_its_self_stress_and_two_zero_modes() {
    // Paper Sec. VII-A: at l_critical = sqrt((2 r sin theta_bar + a)^2 + (2 r cos theta_bar)^2)
    // the impurity spring of the two-kink state is straight across its rotors, and its tension
    // is a state of self-stress.
    let (s, c) = 0.58f64.sin_cos();
    let l_critical = ((2.0 * 0.8 * s + 1.0).powi(2) + (2.0 * 0.8 * c).powi(2)).sqrt();
    let chain =
        RuntimeChain::builder(60, 0.8, 1.0e4, 0.58).spring_rest_length(29, l_critical).build().unwrap();
    let theta = two_kink_configuration(&chain, 29).unwrap();
    let counting = maxwell_calladine(&chain, &theta, None).unwrap();
    check_against_dense("l_critical", &chain, &theta, &counting);
    assert_eq!((counting.zero_modes.len(), counting.self_stresses.len()), (2, 1));
    // The self-stress lives on the impurity spring.
    let stress = &counting.self_stresses[0];
    let peak = (0..stress.len()).max_by(|&i, &j| stress[i].abs().total_cmp(&stress[j].abs())).unwrap();
    assert_eq!(peak, 29);
}

#[test]
fn a_count_at_8192_rotors_finishes_and_a_stop_question_stops_it() {
    // The size: the dense SVD it replaced did not finish in 60 s (release 1.4 s now,
    // AMD EPYC Zen 4; examples/counting_time.rs).
    let n = 8192;
    let chain = RuntimeChain::builder(n, 0.8, 1.0e4, 0.58).build().unwrap();
    let theta = kink(&chain, 0.4 * n as f64).unwrap();
    let counting = maxwell_calladine(&chain, &theta, None).unwrap();
    assert_eq!((counting.rank, counting.zero_modes.len(), counting.self_stresses.len()), (n - 1, 1, 0));
    let (left, right) = compatibility(&chain, &theta);
    let z = &counting.zero_modes[0];
    let residual =
        (0..n - 1).map(|p| left[p] * z[p] + right[p] * z[p + 1]).map(|x| x * x).sum::<f64>().sqrt();
    assert!(residual < 1e-13 * counting.singular_values[0], "|C z| = {residual:e}");
    // A stop question that answers yes on its fourth asking ends the count with Stopped.
    let mut asked = 0;
    let stopped = maxwell_calladine_with(&chain, &theta, None, &mut || {
        asked += 1;
        asked > 3
    });
    assert!(matches!(stopped, Err(StaticsError::Linalg(LinalgError::Stopped { .. }))), "{stopped:?}");
}
