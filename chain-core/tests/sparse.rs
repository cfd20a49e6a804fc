//! The analyses on a model whose tangent stiffness is sparse (`StiffnessLayout::Upper`), not a
//! chain's tridiagonal fast path.
//!
//! 1. The paper's chain reported in the sparse layout: every analysis bound on `Stiffness`
//!    (Newton, relaxation, the modes, the classification, the step bound) must give what the
//!    tridiagonal path gives, through other algorithms (dense decompositions instead of Sturm
//!    counts, bisection and inverse iteration).
//! 2. A planar spring network written out by hand, a wheel (a hub joined to six rim joints, the
//!    rim closed): Maxwell-Calladine counts it has exactly the three rigid motions of the plane
//!    as zero modes and one state of self-stress (2 N - 3 = 11 bonds make it rigid, it has 12),
//!    its modes are those three plus positive ones, and relaxation and Newton bring a disturbed
//!    wheel back to rest.

use chain_core::RuntimeChain;
use chain_core::integrate::omega_bound;
use chain_core::linalg::SymmetricMatrix;
use chain_core::model::{CompatibilityLayout, Pattern, Potential, SpringNetwork, Stiffness, StiffnessLayout};
use chain_core::statics::classify::classify;
use chain_core::statics::counting::maxwell_calladine;
use chain_core::statics::equilibrium::{NewtonOptions, RelaxOptions, newton, relax};
use chain_core::statics::kink::reflected_kink;
use chain_core::statics::modes::{ModeOptions, normal_modes};

/// The paper's chain with its tangent stiffness in the sparse layout: the same numbers, row by
/// row (`(i, i)` then `(i, i + 1)`).
struct SparseChain {
    chain: RuntimeChain,
    row_starts: Vec<usize>,
    columns: Vec<usize>,
}

impl SparseChain {
    fn new(chain: RuntimeChain) -> Self {
        let n = chain.dof_count();
        let (mut row_starts, mut columns) = (vec![0], Vec::new());
        for i in 0..n {
            columns.push(i);
            if i + 1 < n {
                columns.push(i + 1);
            }
            row_starts.push(columns.len());
        }
        Self { chain, row_starts, columns }
    }
}

impl Potential for SparseChain {
    fn dof_count(&self) -> usize {
        self.chain.dof_count()
    }
    fn inertia(&self, i: usize) -> f64 {
        self.chain.inertia(i)
    }
    fn energy(&self, x: &[f64]) -> f64 {
        self.chain.energy(x)
    }
    fn gradient_into(&self, x: &[f64], out: &mut [f64]) {
        self.chain.gradient_into(x, out);
    }
}

impl Stiffness for SparseChain {
    fn stiffness_layout(&self) -> StiffnessLayout<'_> {
        let n = self.dof_count();
        StiffnessLayout::Upper(Pattern {
            columns_count: n,
            row_starts: &self.row_starts,
            columns: &self.columns,
        })
    }
    fn tangent_stiffness_into(&self, x: &[f64], values: &mut [f64]) {
        let n = self.dof_count();
        let mut bands = vec![0.0; 2 * n - 1];
        self.chain.tangent_stiffness_into(x, &mut bands);
        for i in 0..n {
            values[self.row_starts[i]] = bands[i];
            if i + 1 < n {
                values[self.row_starts[i] + 1] = bands[n + i];
            }
        }
    }
}

#[test]
fn every_stiffness_analysis_agrees_on_the_two_layouts() {
    let chain = RuntimeChain::builder(40, 0.8, 1.0e4, 0.58).build().unwrap();
    let sparse = SparseChain::new(chain.clone());
    let guess = reflected_kink(&chain, 19.0).unwrap();
    // The step bound.
    assert_eq!(omega_bound(&chain, &guess).unwrap(), omega_bound(&sparse, &guess).unwrap());
    // Relaxation (the held ends) and Newton's method land on the same antikink.
    let relax_options = RelaxOptions { hold_ends: true, ..RelaxOptions::default() };
    let (a, steps_a) = relax(&chain, &guess, &relax_options).unwrap();
    let (b, steps_b) = relax(&sparse, &guess, &relax_options).unwrap();
    assert_eq!((a.clone(), steps_a), (b, steps_b), "relaxation steps only on the gradient");
    let newton_options = NewtonOptions { hold_ends: true, ..NewtonOptions::default() };
    let x = newton(&chain, &a, &newton_options).unwrap();
    let y = newton(&sparse, &a, &newton_options).unwrap();
    assert!(y.residual <= newton_options.tolerance && y.held == x.held);
    let distance = x.theta.iter().zip(&y.theta).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
    assert!(distance < 1e-9, "the two Newton solutions are {distance} apart");
    // The classification of the held-ends equilibrium: the same counts.
    let k_tri = SymmetricMatrix::tangent_stiffness(&chain, &x.theta).unwrap().principal(1..39);
    let k_sparse = SymmetricMatrix::tangent_stiffness(&sparse, &x.theta).unwrap().principal(1..39);
    assert!(k_tri.bands().is_some() && k_sparse.bands().is_none());
    let (c_tri, c_sparse) = (classify(&k_tri, 1e-10).unwrap(), classify(&k_sparse, 1e-10).unwrap());
    assert_eq!((c_tri.index, c_tri.nullity), (c_sparse.index, c_sparse.nullity));
    // The lowest modes: the same frequencies and (up to sign) shapes.
    let options = ModeOptions { count: Some(6), hold_ends: true, ..ModeOptions::default() };
    let (m_tri, m_sparse) = (
        normal_modes(&chain, &x.theta, &options).unwrap(),
        normal_modes(&sparse, &x.theta, &options).unwrap(),
    );
    for (p, q) in m_tri.iter().zip(&m_sparse) {
        assert!((p.omega_squared - q.omega_squared).abs() < 1e-9 * m_tri[5].omega_squared);
        let dot: f64 =
            p.shape.iter().zip(&q.shape).zip(0..).map(|((u, v), i)| chain.inertia(i) * u * v).sum();
        assert!((dot.abs() - 1.0).abs() < 1e-6, "mode shapes differ: overlap {dot}");
    }
}

/// A wheel in the plane: joint 0 the hub at the origin, joints 1..=6 on the unit circle, each
/// rim joint tied to the hub (spokes 0..6) and to the next rim joint (rim bonds 6..12). Unit
/// masses, harmonic springs of constant `k`, rest lengths those of the regular wheel. Degrees of
/// freedom `2 j` and `2 j + 1` are joint `j`'s `x` and `y`.
struct Wheel {
    k: f64,
    bonds: Vec<(usize, usize)>,
    rest: Vec<f64>,
    /// The stiffness pattern (upper triangle) and, for each bond, where its four 2x2 blocks sit.
    row_starts: Vec<usize>,
    columns: Vec<usize>,
    /// The compatibility pattern: bond `p`'s four entries, columns ascending.
    c_starts: Vec<usize>,
    c_columns: Vec<usize>,
}

impl Wheel {
    fn new(k: f64) -> Self {
        let mut bonds: Vec<(usize, usize)> = (1..=6).map(|j| (0, j)).collect();
        bonds.extend((1..=6).map(|j| (j, j % 6 + 1)).map(|(a, b)| (a.min(b), a.max(b))));
        let reference = Self::regular();
        let rest = bonds.iter().map(|&(a, b)| Self::distance(&reference, a, b)).collect();
        // Every entry (r, c), r <= c, that some bond touches.
        let mut entries = std::collections::BTreeSet::new();
        for &(a, b) in &bonds {
            for u in [2 * a, 2 * a + 1, 2 * b, 2 * b + 1] {
                for v in [2 * a, 2 * a + 1, 2 * b, 2 * b + 1] {
                    if u <= v {
                        entries.insert((u, v));
                    }
                }
            }
        }
        let (mut row_starts, mut columns) = (vec![0], Vec::new());
        for r in 0..14 {
            columns.extend(entries.iter().filter(|e| e.0 == r).map(|e| e.1));
            row_starts.push(columns.len());
        }
        let (mut c_starts, mut c_columns) = (vec![0], Vec::new());
        for &(a, b) in &bonds {
            c_columns.extend([2 * a, 2 * a + 1, 2 * b, 2 * b + 1]);
            c_starts.push(c_columns.len());
        }
        Self { k, bonds, rest, row_starts, columns, c_starts, c_columns }
    }

    /// The regular wheel's positions.
    fn regular() -> Vec<f64> {
        let mut x = vec![0.0, 0.0];
        for j in 0..6 {
            let phi = std::f64::consts::PI / 3.0 * j as f64;
            x.extend([phi.cos(), phi.sin()]);
        }
        x
    }

    fn distance(x: &[f64], a: usize, b: usize) -> f64 {
        (x[2 * b] - x[2 * a]).hypot(x[2 * b + 1] - x[2 * a + 1])
    }

    /// Bond `p`'s unit vector from `a` to `b` and length.
    fn direction(&self, x: &[f64], p: usize) -> ([f64; 2], f64) {
        let (a, b) = self.bonds[p];
        let l = Self::distance(x, a, b);
        ([(x[2 * b] - x[2 * a]) / l, (x[2 * b + 1] - x[2 * a + 1]) / l], l)
    }

    /// Adds `value` to the stiffness entry `(u, v)` of the upper layout; the lower triangle's
    /// `(u, v)`, `u > v`, is the same stored entry and is skipped (its mirror adds it once).
    fn add(&self, values: &mut [f64], u: usize, v: usize, value: f64) {
        if u > v {
            return;
        }
        let row = &self.columns[self.row_starts[u]..self.row_starts[u + 1]];
        values[self.row_starts[u] + row.binary_search(&v).unwrap()] += value;
    }

    /// Bond `p`'s contribution `g e e^T + t/l (I - e e^T)` (material and stress parts, each
    /// when asked) to a symmetric matrix over its four degrees of freedom.
    fn bond_blocks(&self, x: &[f64], p: usize, material: bool, stress: bool, values: &mut [f64]) {
        let (e, l) = self.direction(x, p);
        let t = self.k * (l - self.rest[p]);
        let (a, b) = self.bonds[p];
        let dofs = [2 * a, 2 * a + 1, 2 * b, 2 * b + 1];
        let sign = [-1.0, -1.0, 1.0, 1.0];
        for (m, &u) in dofs.iter().enumerate() {
            for (q, &v) in dofs.iter().enumerate() {
                let (i, j) = (m % 2, q % 2);
                let ee = e[i] * e[j];
                let identity = if i == j { 1.0 } else { 0.0 };
                let mut block = 0.0;
                if material {
                    block += self.k * ee;
                }
                if stress {
                    block += t / l * (identity - ee);
                }
                self.add(values, u, v, sign[m] * sign[q] * block);
            }
        }
    }
}

impl Potential for Wheel {
    fn dof_count(&self) -> usize {
        14
    }
    fn inertia(&self, _: usize) -> f64 {
        1.0
    }
    fn energy(&self, x: &[f64]) -> f64 {
        (0..self.bonds.len()).map(|p| 0.5 * self.k * (self.direction(x, p).1 - self.rest[p]).powi(2)).sum()
    }
    fn gradient_into(&self, x: &[f64], out: &mut [f64]) {
        out.fill(0.0);
        for p in 0..self.bonds.len() {
            let (e, l) = self.direction(x, p);
            let t = self.k * (l - self.rest[p]);
            let (a, b) = self.bonds[p];
            for i in 0..2 {
                out[2 * a + i] -= t * e[i];
                out[2 * b + i] += t * e[i];
            }
        }
    }
}

impl Stiffness for Wheel {
    fn stiffness_layout(&self) -> StiffnessLayout<'_> {
        StiffnessLayout::Upper(Pattern {
            columns_count: 14,
            row_starts: &self.row_starts,
            columns: &self.columns,
        })
    }
    fn tangent_stiffness_into(&self, x: &[f64], values: &mut [f64]) {
        values.fill(0.0);
        (0..self.bonds.len()).for_each(|p| self.bond_blocks(x, p, true, true, values));
    }
}

impl SpringNetwork for Wheel {
    fn spring_count(&self) -> usize {
        self.bonds.len()
    }
    fn spring_constant(&self, _: usize) -> f64 {
        self.k
    }
    fn rest_length(&self, p: usize) -> f64 {
        self.rest[p]
    }
    fn spring_lengths_into(&self, x: &[f64], out: &mut [f64]) {
        (0..self.bonds.len()).for_each(|p| out[p] = self.direction(x, p).1);
    }
    fn tensions_into(&self, x: &[f64], out: &mut [f64]) {
        (0..self.bonds.len()).for_each(|p| out[p] = self.k * (self.direction(x, p).1 - self.rest[p]));
    }
    fn compatibility_layout(&self) -> CompatibilityLayout<'_> {
        CompatibilityLayout::Sparse(Pattern {
            columns_count: 14,
            row_starts: &self.c_starts,
            columns: &self.c_columns,
        })
    }
    fn compatibility_into(&self, x: &[f64], values: &mut [f64]) {
        for p in 0..self.bonds.len() {
            let (e, _) = self.direction(x, p);
            // Columns a_x, a_y, b_x, b_y (a < b, so ascending): -e on a, +e on b.
            values[4 * p..4 * p + 4].copy_from_slice(&[-e[0], -e[1], e[0], e[1]]);
        }
    }
    fn material_stiffness_into(&self, x: &[f64], values: &mut [f64]) {
        values.fill(0.0);
        (0..self.bonds.len()).for_each(|p| self.bond_blocks(x, p, true, false, values));
    }
    fn stress_matrix_into(&self, x: &[f64], values: &mut [f64]) {
        values.fill(0.0);
        (0..self.bonds.len()).for_each(|p| self.bond_blocks(x, p, false, true, values));
    }
}

#[test]
fn the_wheels_stiffness_is_the_hessian_of_its_energy() {
    // An independent check of the hand-written model: central differences of the gradient.
    let wheel = Wheel::new(3.0);
    let x: Vec<f64> =
        Wheel::regular().iter().enumerate().map(|(i, v)| v + 0.05 * (0.7 * i as f64).sin()).collect();
    let k = SymmetricMatrix::tangent_stiffness(&wheel, &x).unwrap().to_dense().unwrap();
    let h = 1e-6;
    for j in 0..14 {
        let (mut plus, mut minus) = (x.clone(), x.clone());
        plus[j] += h;
        minus[j] -= h;
        let (gp, gm) = (wheel.gradient(&plus), wheel.gradient(&minus));
        for i in 0..14 {
            let fd = (gp[i] - gm[i]) / (2.0 * h);
            assert!((k[(i, j)] - fd).abs() < 1e-6, "K[{i}][{j}] = {} vs {fd}", k[(i, j)]);
        }
    }
}

#[test]
fn the_wheel_has_the_rigid_motions_as_zero_modes_and_one_self_stress() {
    let wheel = Wheel::new(3.0);
    let x = Wheel::regular();
    // Maxwell-Calladine: 14 degrees of freedom, 12 bonds, rank 11 (a rigid framework in the plane
    // has rank 2 N - 3): 3 zero modes and 1 state of self-stress.
    let counting = maxwell_calladine(&wheel, &x, None).unwrap();
    assert_eq!((counting.rank, counting.zero_modes.len(), counting.self_stresses.len()), (11, 3, 1));
    // The self-stress: tension on the rim, compression on the spokes (the rim pulls inward), and
    // in equilibrium, C^T s = 0, checked here with C built independently from the geometry.
    let s = &counting.self_stresses[0];
    let signs: Vec<bool> = s.iter().map(|v| *v > 0.0).collect();
    assert!(signs[..6].iter().all(|&p| p == signs[0]) && signs[6..].iter().all(|&p| p != signs[0]));
    let mut force = [0.0; 14];
    for (p, &(a, b)) in wheel.bonds.iter().enumerate() {
        let (e, _) = wheel.direction(&x, p);
        for i in 0..2 {
            force[2 * a + i] -= s[p] * e[i];
            force[2 * b + i] += s[p] * e[i];
        }
    }
    assert!(force.iter().all(|f| f.abs() < 1e-12), "{force:?}");
    // The modes: three zero frequencies (two translations and the rotation), then positive ones.
    let modes = normal_modes(&wheel, &x, &ModeOptions { count: Some(14), ..ModeOptions::default() }).unwrap();
    let scale = modes[13].omega_squared;
    assert!(modes[..3].iter().all(|m| m.omega_squared.abs() < 1e-12 * scale));
    assert!(modes[3].omega_squared > 1e-3 * scale);
    let k = SymmetricMatrix::tangent_stiffness(&wheel, &x).unwrap();
    let c = classify(&k, 1e-10).unwrap();
    assert_eq!((c.index, c.nullity), (0, 3));
}

#[test]
fn a_disturbed_wheel_relaxes_back_to_rest() {
    let wheel = Wheel::new(3.0);
    let x: Vec<f64> =
        Wheel::regular().iter().enumerate().map(|(i, v)| v + 0.03 * (1.3 * i as f64).cos()).collect();
    assert!(wheel.energy(&x) > 1e-3);
    let (relaxed, steps) = relax(&wheel, &x, &RelaxOptions::default()).unwrap();
    let polished = newton(&wheel, &relaxed, &NewtonOptions::default()).unwrap();
    assert!(steps > 0 && polished.residual <= 1e-11);
    // Back at rest: every bond at its rest length (the wheel is rigid, so the shape is regular up
    // to a rigid motion).
    let mut lengths = [0.0; 12];
    wheel.spring_lengths_into(&polished.theta, &mut lengths);
    assert!(lengths.iter().zip(&wheel.rest).all(|(l, l0)| (l - l0).abs() < 1e-9), "{lengths:?}");
}
