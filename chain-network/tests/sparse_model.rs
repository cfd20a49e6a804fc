//! The sparse path of the stiffness (issue 36 item 4) on network models: Newton, modes and
//! classification on prestressed periodic square patches, against the closed-form spectrum of a
//! stressed square lattice and the dense path.
//!
//! A bond of constant `k` held at length `l` with tension `t = k (l - l0)` has the Hessian block
//! `k n n^T + (t / l) (I - n n^T)` (material part plus stress matrix): on a periodic `N x N` square
//! patch of unit cells, unit masses and rest length `l0` at its regular configuration, the
//! dynamical matrix is diagonal in the polarizations, with
//! `omega^2 = k (2 - 2 cos q_x) + (t / l)(2 - 2 cos q_y)` for the `x` displacements (and `x, y`
//! exchanged for `y`), `q = 2 pi m / N`.

use chain_core::Potential;
use chain_core::linalg::SymmetricMatrix;
use chain_core::statics::classify::classify;
use chain_core::statics::equilibrium::{NewtonOptions, newton, polish};
use chain_core::statics::modes::{ModeOptions, normal_modes};
use chain_network::NetworkModel;
use chain_network::cell::ready;
use chain_network::patch::{Boundary, Patch};
use std::f64::consts::TAU;
use test_support::random::SplitMix;

/// A periodic `n x n` square patch with unit springs of rest length `l0` (tension `1 - l0`).
fn stressed_square(patch: &Patch, l0: f64) -> NetworkModel {
    let bonds = patch.bonds().len();
    (0..bonds).fold(NetworkModel::builder(patch), |b, p| b.rest_length(p, l0)).build().unwrap()
}

/// The closed-form `omega^2` of the stressed square patch, ascending.
fn spectrum(n: usize, tension: f64) -> Vec<f64> {
    let s = |m: usize| 2.0 - 2.0 * (TAU * m as f64 / n as f64).cos();
    let mut values: Vec<f64> = (0..n)
        .flat_map(|a| (0..n).flat_map(move |b| [s(a) + tension * s(b), tension * s(a) + s(b)]))
        .collect();
    values.sort_by(f64::total_cmp);
    values
}

fn largest(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// 66 x 66 cells, 8712 degrees of freedom: beyond the dense bound (8192), so every step of Newton
/// (inertia counts, the near-null eigenpairs, the shifted solves) and the modes take the sparse
/// path. Newton from a perturbed start returns to force balance at the rounding of the gradient,
/// and the lowest modes there are the closed form's.
#[test]
fn newton_and_modes_on_a_patch_beyond_the_dense_bound() {
    let cell = ready::square();
    let n = 66;
    let patch = Patch::new(&cell, [n, n], Boundary::Periodic).unwrap();
    let model = stressed_square(&patch, 0.9);
    assert!(model.dof_count() > 8192);
    assert!(SymmetricMatrix::tangent_stiffness(&model, &model.reference()).unwrap().is_sparse_path());
    let mut rng = SplitMix(7);
    let start: Vec<f64> = model.reference().iter().map(|x| x + 1e-3 * rng.symmetric()).collect();
    assert!(largest(&model.gradient(&start)) > 1e-4);
    let options = NewtonOptions::default();
    let solution = newton(&model, &start, &options).unwrap();
    assert!(largest(&model.gradient(&solution.theta)) < options.tolerance * 4.5);
    // Polished to force balance at the rounding of the forces (each a sum of four tensions of
    // 0.1, ~1e-17) and of the Newton step.
    let solution = polish(&model, solution, &options).unwrap();
    let g = model.gradient(&solution.theta);
    assert!(largest(&g) < 1e-13, "largest force {}", largest(&g));
    assert!(solution.iterations <= 10, "{} Newton steps", solution.iterations);
    let exact = spectrum(n, 0.1 / 1.0);
    let modes =
        normal_modes(&model, &solution.theta, &ModeOptions { count: Some(10), ..ModeOptions::default() })
            .unwrap();
    for (mode, e) in modes.iter().zip(&exact) {
        assert!((mode.omega_squared - e).abs() < 1e-10, "{} against {e}", mode.omega_squared);
    }
    // Not only zeros: the two translations, then two shells of four soft shear modes.
    assert!(exact[1] < 1e-15 && exact[2] > 9e-4 && exact[9] > 3.6e-3);
}

/// Under compression (`l0 > 1`) the stress matrix is negative: the regular patch is a saddle whose
/// Morse index is the closed form's count of negative `omega^2`. The sparse path (forced) and the
/// dense path classify it alike, and both match.
#[test]
fn classify_counts_the_closed_form_index_on_both_paths() {
    let cell = ready::square();
    let n = 8;
    let patch = Patch::new(&cell, [n, n], Boundary::Periodic).unwrap();
    let model = stressed_square(&patch, 1.1);
    let x = model.reference();
    assert!(largest(&model.gradient(&x)) < 1e-14, "the regular patch is an equilibrium");
    let exact = spectrum(n, -0.1);
    let k = SymmetricMatrix::tangent_stiffness(&model, &x).unwrap();
    let relative = 1e-9;
    let tolerance = relative * k.inf_norm();
    let index = exact.iter().filter(|&&v| v < -tolerance).count();
    let nullity = exact.iter().filter(|&&v| v.abs() <= tolerance).count();
    assert!(index > 0 && nullity == 2);
    let dense = classify(&k, relative).unwrap();
    let sparse = classify(&k.clone().with_dense_limit(0), relative).unwrap();
    assert_eq!((dense.index, dense.nullity), (index, nullity));
    assert_eq!((sparse.index, sparse.nullity), (index, nullity));
}
