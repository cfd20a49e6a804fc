//! The sparse path of `SymmetricMatrix` (sparse LBL^T inertia and solves, shift-invert subspace
//! iteration) against closed forms: grid Laplacians (Dirichlet and periodic) whose spectra are
//! sums of cosines, shifted to make them indefinite. The sparse path is forced on small matrices
//! with `with_dense_limit(0)` and compared with the dense path too; one matrix exceeds the dense
//! bound and takes the sparse path by default.

use chain_core::linalg::{LinalgError, SymmetricMatrix};
use chain_core::model::Pattern;
use std::f64::consts::PI;

/// `L - shift I` for the 5-point Laplacian of an `nx x ny` grid (`L = 4 I - neighbours`); a
/// periodic grid wraps both ways (`nx, ny >= 3`), a Dirichlet one does not.
fn laplacian(nx: usize, ny: usize, periodic: bool, shift: f64) -> SymmetricMatrix {
    let n = nx * ny;
    let index = |x: usize, y: usize| y * nx + x;
    let mut rows: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    for y in 0..ny {
        for x in 0..nx {
            let i = index(x, y);
            rows[i].push((i, 4.0 - shift));
            let mut neighbours = Vec::new();
            if x + 1 < nx {
                neighbours.push(index(x + 1, y));
            } else if periodic {
                neighbours.push(index(0, y));
            }
            if y + 1 < ny {
                neighbours.push(index(x, y + 1));
            } else if periodic {
                neighbours.push(index(x, 0));
            }
            for j in neighbours {
                let (a, b) = (i.min(j), i.max(j));
                rows[a].push((b, -1.0));
            }
        }
    }
    let (mut starts, mut columns, mut values) = (vec![0], Vec::new(), Vec::new());
    for mut row in rows {
        row.sort_by_key(|e| e.0);
        for (j, v) in row {
            columns.push(j);
            values.push(v);
        }
        starts.push(columns.len());
    }
    let pattern = Pattern { columns_count: n, row_starts: &starts, columns: &columns };
    SymmetricMatrix::upper(pattern, values).unwrap()
}

/// The closed-form spectrum, ascending: `4 - 2 cos(theta_a) - 2 cos(phi_b) - shift` with
/// `theta_a = pi a / (nx + 1)` (Dirichlet, a = 1..nx) or `2 pi a / nx` (periodic, a = 0..nx-1).
fn spectrum(nx: usize, ny: usize, periodic: bool, shift: f64) -> Vec<f64> {
    let angles = |m: usize| -> Vec<f64> {
        if periodic {
            (0..m).map(|a| 2.0 * PI * a as f64 / m as f64).collect()
        } else {
            (1..=m).map(|a| PI * a as f64 / (m + 1) as f64).collect()
        }
    };
    let mut values: Vec<f64> = angles(nx)
        .iter()
        .flat_map(|t| angles(ny).into_iter().map(move |p| 4.0 - 2.0 * t.cos() - 2.0 * p.cos() - shift))
        .collect();
    values.sort_by(f64::total_cmp);
    values
}

fn residual(k: &SymmetricMatrix, value: f64, vector: &[f64]) -> f64 {
    let mut kv = vec![0.0; vector.len()];
    k.mul_vec(vector, &mut kv);
    kv.iter().zip(vector).fold(0.0f64, |m, (a, v)| m.max((a - value * v).abs()))
}

fn check_orthonormal(vectors: &[&[f64]]) {
    for (i, a) in vectors.iter().enumerate() {
        for (j, b) in vectors.iter().enumerate() {
            let dot: f64 = a.iter().zip(*b).map(|(x, y)| x * y).sum();
            let expected = if i == j { 1.0 } else { 0.0 };
            assert!((dot - expected).abs() < 1e-10, "<v{i}, v{j}> = {dot}");
        }
    }
}

#[test]
fn counts_below_a_shift_are_the_closed_form_counts_on_an_indefinite_grid() {
    // Dirichlet 11 x 9 grid shifted by 3: eigenvalues from -2.9 to 4.9, about 40 % negative.
    let (nx, ny, shift) = (11, 9, 3.1);
    let sparse = laplacian(nx, ny, false, shift).with_dense_limit(0);
    let dense = laplacian(nx, ny, false, shift);
    assert!(sparse.is_sparse_path() && !dense.is_sparse_path());
    let exact = spectrum(nx, ny, false, shift);
    for x in [-3.5, -2.0, -1e-3, 0.0, 0.37, 1.0, 2.5, 5.0] {
        // The closed form's count, away from every eigenvalue (checked: no eigenvalue within 1e-6).
        assert!(exact.iter().all(|v| (v - x).abs() > 1e-6), "x = {x} is too near an eigenvalue");
        let expected = exact.iter().filter(|&&v| v < x).count();
        assert_eq!(sparse.count_below(x).unwrap(), expected, "sparse count below {x}");
        assert_eq!(dense.count_below(x).unwrap(), expected, "dense count below {x}");
    }
}

#[test]
fn lowest_eigenpairs_match_the_closed_form_with_repeated_eigenvalues() {
    // Periodic 10 x 10 grid: eigenvalue 0 once, then clusters of multiplicity 4 and 8.
    let (nx, ny) = (10, 10);
    let k = laplacian(nx, ny, true, 0.0).with_dense_limit(0);
    let exact = spectrum(nx, ny, true, 0.0);
    let pairs = k.lowest_eigenpairs(13).unwrap();
    assert_eq!(pairs.len(), 13);
    for (p, e) in pairs.iter().zip(&exact) {
        assert!((p.value - e).abs() < 1e-10, "{} against {e}", p.value);
        assert!(residual(&k, p.value, &p.vector) < 1e-10);
    }
    check_orthonormal(&pairs.iter().map(|p| p.vector.as_slice()).collect::<Vec<_>>());
    // The same values as the dense path.
    let dense = laplacian(nx, ny, true, 0.0).lowest_eigenpairs(13).unwrap();
    pairs.iter().zip(&dense).for_each(|(a, b)| assert!((a.value - b.value).abs() < 1e-10));
}

#[test]
fn eigenpairs_near_an_interior_value_match_the_closed_form() {
    let (nx, ny, shift) = (12, 8, 0.0);
    let k = laplacian(nx, ny, false, shift).with_dense_limit(0);
    let exact = spectrum(nx, ny, false, shift);
    let sigma = 3.3;
    let mut nearest = exact.clone();
    nearest.sort_by(|a, b| (a - sigma).abs().total_cmp(&(b - sigma).abs()));
    let mut wanted = nearest[..5].to_vec();
    wanted.sort_by(f64::total_cmp);
    let pairs = k.eigenpairs_near(sigma, 5).unwrap();
    for (p, e) in pairs.iter().zip(&wanted) {
        assert!((p.value - e).abs() < 1e-10, "{} against {e}", p.value);
        assert!(residual(&k, p.value, &p.vector) < 1e-10);
    }
    check_orthonormal(&pairs.iter().map(|p| p.vector.as_slice()).collect::<Vec<_>>());
}

#[test]
fn a_zero_eigenvalue_at_the_target_is_found() {
    // The periodic grid's constant vector: eigenvalue exactly 0, the shift itself.
    let k = laplacian(9, 9, true, 0.0).with_dense_limit(0);
    let pairs = k.eigenpairs_near(0.0, 1).unwrap();
    assert!(pairs[0].value.abs() < 1e-12);
    let c = 1.0 / 9.0;
    assert!(pairs[0].vector.iter().all(|v| (v - c).abs() < 1e-10));
}

#[test]
fn shifted_solves_agree_with_the_dense_path_and_satisfy_the_system() {
    let (nx, ny) = (10, 7);
    let sparse = laplacian(nx, ny, false, 0.0).with_dense_limit(0);
    let dense = laplacian(nx, ny, false, 0.0);
    let rhs: Vec<f64> = (0..nx * ny).map(|i| ((i * 37) % 11) as f64 - 5.0).collect();
    // An indefinite shift between eigenvalues, and the Newton solves' small negative one.
    for shift in [2.05, -1e-3] {
        let x = sparse.solve_shifted(shift, &rhs).unwrap();
        let y = dense.solve_shifted(shift, &rhs).unwrap();
        let scale = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        x.iter().zip(&y).for_each(|(a, b)| assert!((a - b).abs() < 1e-11 * scale, "{a} against {b}"));
        let mut kx = vec![0.0; x.len()];
        sparse.mul_vec(&x, &mut kx);
        kx.iter().zip(&x).zip(&rhs).for_each(|((k, x), b)| assert!((k - shift * x - b).abs() < 1e-11));
    }
}

#[test]
fn a_singular_shift_and_bad_input_are_typed_errors() {
    let k = laplacian(9, 9, true, 0.0).with_dense_limit(0);
    let rhs = vec![1.0; 81];
    // An exactly zero pivot: diag(1, ..., 1, 0, 1, ...) shifted by 0.
    let diag: Vec<f64> = (0..81).map(|i| if i == 40 { 0.0 } else { 1.0 + i as f64 }).collect();
    let (starts, columns): (Vec<usize>, Vec<usize>) = ((0..=81).collect(), (0..81).collect());
    let pattern = Pattern { columns_count: 81, row_starts: &starts, columns: &columns };
    let singular = SymmetricMatrix::upper(pattern, diag).unwrap().with_dense_limit(0);
    assert!(matches!(singular.solve_shifted(0.0, &rhs), Err(LinalgError::Singular { pivot: 0.0, .. })));
    // One eigenvalue at the shift is neither below nor above it.
    assert_eq!(singular.count_below(0.0).unwrap(), 0);
    assert_eq!(singular.count_below(1e-300).unwrap(), 1);
    assert!(matches!(k.count_below(f64::NAN), Err(LinalgError::NotFinite { .. })));
    assert!(matches!(k.lowest_eigenpairs(82), Err(LinalgError::IndexOutOfRange { .. })));
    assert!(matches!(k.solve_shifted(0.5, &rhs[..80]), Err(LinalgError::RhsMismatch { .. })));
}

#[test]
fn a_grid_beyond_the_dense_bound_takes_the_sparse_path_by_default() {
    // 92 x 92 periodic: 8464 rows, more than the dense bound's 8192.
    let (nx, ny) = (92, 92);
    let k = laplacian(nx, ny, true, 0.0);
    assert!(k.is_sparse_path());
    assert!(matches!(k.to_dense(), Err(LinalgError::TooLarge { .. })));
    let exact = spectrum(nx, ny, true, 0.0);
    let pairs = k.lowest_eigenpairs(5).unwrap();
    for (p, e) in pairs.iter().zip(&exact) {
        assert!((p.value - e).abs() < 1e-10, "{} against {e}", p.value);
    }
    // Counts: the zero eigenvalue, then the first cluster of four at 2 - 2 cos(2 pi / 92).
    let first = 2.0 - 2.0 * (2.0 * PI / 92.0).cos();
    assert_eq!(k.count_below(0.5 * first).unwrap(), 1);
    assert_eq!(k.count_below(1.5 * first).unwrap(), 5);
}
