//! The dense and the sparse paths of `SymmetricMatrix` side by side on the stiffness pattern of a
//! 2D lattice (the periodic 5-point grid, `n = side^2` rows): an inertia count, the lowest 12
//! eigenpairs and a shifted solve. Where the sparse path wins decides `DENSE_LIMIT`.
//!
//! Run: `cargo bench -p rotor-chain-core --bench sparse`

use chain_core::linalg::SymmetricMatrix;
use chain_core::model::Pattern;
use divan::black_box;

fn main() {
    divan::main();
}

/// The periodic grid Laplacian plus `1e-3 I` (positive definite, lattice-like spectrum).
fn grid(side: usize) -> SymmetricMatrix {
    let n = side * side;
    let mut rows: Vec<Vec<(usize, f64)>> = (0..n).map(|i| vec![(i, 4.001)]).collect();
    for i in 0..n {
        let (x, y) = (i % side, i / side);
        for j in [y * side + (x + 1) % side, ((y + 1) % side) * side + x] {
            rows[i.min(j)].push((i.max(j), -1.0));
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

const SIDES: [usize; 4] = [16, 24, 32, 48];

fn path(side: usize, sparse: bool) -> SymmetricMatrix {
    grid(side).with_dense_limit(if sparse { 0 } else { usize::MAX })
}

#[divan::bench(args = SIDES, sample_count = 5)]
fn count_dense(b: divan::Bencher, side: usize) {
    let k = path(side, false);
    b.bench(|| black_box(&k).count_below(0.5).unwrap());
}

#[divan::bench(args = SIDES, sample_count = 5)]
fn count_sparse(b: divan::Bencher, side: usize) {
    let k = path(side, true);
    b.bench(|| black_box(&k).count_below(0.5).unwrap());
}

#[divan::bench(args = SIDES, sample_count = 5)]
fn lowest_12_dense(b: divan::Bencher, side: usize) {
    let k = path(side, false);
    b.bench(|| black_box(&k).lowest_eigenpairs(12).unwrap());
}

#[divan::bench(args = SIDES, sample_count = 5)]
fn lowest_12_sparse(b: divan::Bencher, side: usize) {
    let k = path(side, true);
    b.bench(|| black_box(&k).lowest_eigenpairs(12).unwrap());
}

#[divan::bench(args = SIDES, sample_count = 5)]
fn solve_dense(b: divan::Bencher, side: usize) {
    let k = path(side, false);
    let rhs = vec![1.0; side * side];
    b.bench(|| black_box(&k).solve_shifted(-1e-3, &rhs).unwrap());
}

#[divan::bench(args = SIDES, sample_count = 5)]
fn solve_sparse(b: divan::Bencher, side: usize) {
    let k = path(side, true);
    let rhs = vec![1.0; side * side];
    b.bench(|| black_box(&k).solve_shifted(-1e-3, &rhs).unwrap());
}
