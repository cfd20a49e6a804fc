//! The network model (issue 36) against an independent statement of a patch's energy (written
//! here from the cell's nodes and the patch's bonds, endpoint by endpoint), finite differences,
//! the linear analyses of this crate, a closed-form spectrum, and chain-core's analyses run on it.

use chain_core::linalg::SymmetricMatrix;
use chain_core::simd::{Level, with_level};
use chain_core::statics::counting::maxwell_calladine;
use chain_core::statics::equilibrium::{RelaxOptions, relax};
use chain_core::statics::modes::{ModeOptions, normal_modes};
use chain_core::{Law, Potential, SpringNetwork, Stiffness};
use chain_network::cell::{NodeKind, ready};
use chain_network::counts::counts;
use chain_network::patch::{Boundary, Patch};
use chain_network::{Cell, NetworkError, NetworkModel};
use test_support::random::SplitMix;

/// Joints and rotors with every bond type and both orientations of a joint-rotor bond: `a -> p`
/// (joint to rotor), `p -> c` (rotor to joint), `c -> a` (joints), `p -> p` (a rotor to its
/// image, rotor-rotor).
fn mixed() -> Cell {
    Cell::builder(2, &[[1.0, 0.1], [0.2, 1.3]])
        .joint("a", [0.1, 0.2])
        .rotor("p", [0.5, 0.4], 0.3, 0.7)
        .joint("c", [0.7, 0.9])
        .bond("a", "p", &[0, 0])
        .bond("p", "c", &[1, 0])
        .bond("c", "a", &[0, 1])
        .bond("p", "p", &[1, -1])
        .build()
        .unwrap()
}

/// The energy of a law at length `l`, and its derivative (the tension).
fn law_energy(law: Law, k: f64, l0: f64, l: f64) -> (f64, f64) {
    match law {
        Law::Quartic => {
            (k * (l * l - l0 * l0).powi(2) / (8.0 * l0 * l0), k * l * (l * l - l0 * l0) / (2.0 * l0 * l0))
        }
        _ => (0.5 * k * (l - l0).powi(2), k * (l - l0)),
    }
}

/// The attachment point of node `n` of cell `c` at `x`, placed in cell `at` (the unwrapped cell
/// of a bond's `to` end): a joint's position from `x` moved by the lattice shift from `c` to
/// `at`, a rotor's tip from its pivot in `at` and its angle in `x`.
fn point(patch: &Patch, x: &[f64], c: [usize; 2], n: usize, at: [i64; 2]) -> [f64; 2] {
    let cell = patch.cell();
    let d = patch.column(c, cell.dof_offset(n));
    match cell.nodes()[n].kind {
        NodeKind::Joint { .. } => {
            let (s, home) = (cell.shift(at), cell.shift([c[0] as i64, c[1] as i64]));
            [x[d] + s[0] - home[0], x[d + 1] + s[1] - home[1]]
        }
        NodeKind::Rotor { pivot, length, .. } => {
            let s = cell.shift(at);
            [pivot[0] + s[0] + length * x[d].cos(), pivot[1] + s[1] + length * x[d].sin()]
        }
    }
}

/// Every bond's length at `x`, endpoint by endpoint.
fn lengths(patch: &Patch, x: &[f64]) -> Vec<f64> {
    let cell = patch.cell();
    patch
        .bonds()
        .iter()
        .map(|pb| {
            let bond = &cell.bonds()[pb.bond];
            let from = [pb.from_cell[0] as i64, pb.from_cell[1] as i64];
            let to = [from[0] + bond.cell[0], from[1] + bond.cell[1]];
            let p = point(patch, x, pb.from_cell, bond.from, from);
            let q = point(patch, x, pb.to_cell, bond.to, to);
            (q[0] - p[0]).hypot(q[1] - p[1])
        })
        .collect()
}

fn energy(patch: &Patch, law: Law, x: &[f64], springs: &[[f64; 2]]) -> f64 {
    lengths(patch, x).iter().zip(springs).map(|(&l, s)| law_energy(law, s[0], s[1], l).0).sum()
}

fn springs_of(model: &NetworkModel) -> Vec<[f64; 2]> {
    (0..model.spring_count()).map(|p| [model.spring_constant(p), model.rest_length(p)]).collect()
}

/// A random configuration near the reference (joints moved by up to `size`, rotors turned by up
/// to `size` radians).
fn perturbed(model: &NetworkModel, size: f64, seed: u64) -> Vec<f64> {
    let mut rng = SplitMix(seed);
    model.reference().iter().map(|x| x + size * rng.symmetric()).collect()
}

/// The dense matrix of an upper-triangle layout.
fn dense(model: &NetworkModel, values: &[f64]) -> Vec<Vec<f64>> {
    SymmetricMatrix::upper(
        match model.stiffness_layout() {
            chain_core::model::StiffnessLayout::Upper(p) => p,
            other => panic!("a network's stiffness is an upper triangle, not {other:?}"),
        },
        values.to_vec(),
    )
    .map(|k| {
        let n = k.dim();
        (0..n).map(|i| (0..n).map(|j| k.get(i, j)).collect()).collect()
    })
    .unwrap()
}

#[test]
fn energy_gradient_stiffness_and_rows_match_the_endpoints_statement() {
    let cell = mixed();
    for boundary in [Boundary::Periodic, Boundary::Free] {
        let patch = Patch::new(&cell, [3, 3], boundary).unwrap();
        for law in [Law::Harmonic, Law::Quartic] {
            // Rest lengths away from the reference, so every bond carries tension.
            let mut builder = NetworkModel::builder(&patch).law(law);
            for p in 0..patch.bonds().len() {
                builder = builder.rest_length(p, 0.6 + 0.05 * p as f64 % 0.4);
            }
            let model = builder.build().unwrap();
            let springs = springs_of(&model);
            let x = perturbed(&model, 0.1, 7);
            let n = x.len();
            let e = |x: &[f64]| energy(&patch, law, x, &springs);
            let ours = model.energy(&x);
            assert!((ours - e(&x)).abs() < 1e-12 * e(&x), "{boundary:?} {law:?}: {ours} vs {}", e(&x));
            let mut grad = vec![0.0; n];
            let fused = model.energy_and_gradient_into(&x, &mut grad);
            // The fused pass sums the energy in vector lanes: equal to rounding.
            assert!((fused - ours).abs() <= 1e-14 * ours, "fused energy {fused} vs {ours}");
            let h = 1e-6;
            for i in 0..n {
                let (mut up, mut down) = (x.clone(), x.clone());
                up[i] += h;
                down[i] -= h;
                let fd = (e(&up) - e(&down)) / (2.0 * h);
                assert!((grad[i] - fd).abs() < 1e-7 * (1.0 + fd.abs()), "gradient {i}: {} vs {fd}", grad[i]);
            }
            // The Hessian against central differences of the gradient; material + stress.
            let values = model.stiffness_values();
            let (mut k, mut km, mut ks) = (vec![0.0; values], vec![0.0; values], vec![0.0; values]);
            model.tangent_stiffness_into(&x, &mut k);
            model.material_stiffness_into(&x, &mut km);
            model.stress_matrix_into(&x, &mut ks);
            let (mut g2, mut k2) = (vec![0.0; n], vec![0.0; values]);
            let e2 = model.energy_gradient_stiffness_into(&x, &mut g2, &mut k2);
            assert_eq!((e2.to_bits(), &k2), (ours.to_bits(), &k), "fused = separate");
            // At every vector level the vector driver's gradient (fused or alone: bit for bit the
            // same) is the scalar stiffness pass's to rounding (each bond's arithmetic is lane for
            // lane IEEE; the driver adds a degree of freedom's terms run by run, not in bond
            // order); levels differ only through that order and the rotors' sin_cos (2 ulp).
            for level in [Level::Scalar, Level::Avx2, Level::Avx512] {
                let Some((e, g, alone, g2)) = with_level(level, || {
                    let (mut g, mut g2, mut k2) = (vec![0.0; n], vec![0.0; n], vec![0.0; values]);
                    let e = model.energy_and_gradient_into(&x, &mut g);
                    model.energy_gradient_stiffness_into(&x, &mut g2, &mut k2);
                    (e, g, model.gradient(&x), g2)
                }) else {
                    continue;
                };
                assert_eq!(g, alone, "{level:?}: fused and alone");
                assert!(g.iter().zip(&g2).all(|(a, b)| (a - b).abs() <= 1e-14), "{level:?}: {g:?} vs {g2:?}");
                assert!((e - ours).abs() <= 1e-14 * ours, "{level:?}: {e} vs {ours}");
                assert!(g.iter().zip(&grad).all(|(a, b)| (a - b).abs() <= 1e-14), "{level:?}");
            }
            for v in 0..values {
                assert!(
                    (km[v] + ks[v] - k[v]).abs() < 1e-12 * (1.0 + k[v].abs()),
                    "material + stress at {v}"
                );
            }
            let kd = dense(&model, &k);
            let h = 1e-5;
            for j in 0..n {
                let (mut up, mut down) = (x.clone(), x.clone());
                up[j] += h;
                down[j] -= h;
                let (gu, gd) = (model.gradient(&up), model.gradient(&down));
                for i in 0..n {
                    let fd = (gu[i] - gd[i]) / (2.0 * h);
                    assert!(
                        (kd[i][j] - fd).abs() < 1e-6 * (1.0 + fd.abs()),
                        "K[{i}][{j}]: {} vs {fd}",
                        kd[i][j]
                    );
                }
            }
            // Lengths, tensions and the compatibility rows (a rotor's column per `r dphi`).
            let m = model.spring_count();
            let (mut l, mut t) = (vec![0.0; m], vec![0.0; m]);
            model.spring_lengths_into(&x, &mut l);
            model.tensions_into(&x, &mut t);
            let direct = lengths(&patch, &x);
            for p in 0..m {
                assert!((l[p] - direct[p]).abs() < 1e-13);
                let tension = law_energy(law, springs[p][0], springs[p][1], direct[p]).1;
                assert!((t[p] - tension).abs() < 1e-12 * (1.0 + tension.abs()));
            }
            let mut c = vec![0.0; model.compatibility_values()];
            model.compatibility_into(&x, &mut c);
            let pattern = match model.compatibility_layout() {
                chain_core::model::CompatibilityLayout::Sparse(p) => p,
                other => panic!("a network's compatibility is sparse, not {other:?}"),
            };
            for p in 0..m {
                for (v, &j) in pattern.row(p).iter().enumerate() {
                    let (mut up, mut down) = (x.clone(), x.clone());
                    up[j] += 1e-6;
                    down[j] -= 1e-6;
                    let r = if model.is_rotor(j) { rotor_length(&patch, j) } else { 1.0 };
                    let fd = (lengths(&patch, &up)[p] - lengths(&patch, &down)[p]) / 2e-6 / r;
                    let ours = c[pattern.row_starts[p] + v];
                    assert!((ours - fd).abs() < 1e-8, "C[{p}][{j}]: {ours} vs {fd}");
                }
            }
        }
    }
}

/// The length of the rotor whose angle is degree of freedom `j`.
fn rotor_length(patch: &Patch, j: usize) -> f64 {
    let cell = patch.cell();
    let local = j % cell.dof();
    let node = cell.dof_nodes()[local];
    match cell.nodes()[node].kind {
        NodeKind::Rotor { length, .. } => length,
        NodeKind::Joint { .. } => 1.0,
    }
}

/// At the reference the cell's rest lengths leave every bond unstressed, and the model's
/// compatibility matrix is the patch's (the linear analyses' own), so chain-core's
/// Maxwell-Calladine counting on the model gives this crate's counts.
#[test]
fn the_reference_is_stress_free_and_its_counts_are_the_patchs() {
    let cells = [ready::kagome(), ready::deformed_kagome(0.1, -0.05, 0.02, 0.1).unwrap(), mixed()];
    for cell in &cells {
        for boundary in [Boundary::Periodic, Boundary::Free] {
            let patch = Patch::new(cell, [3, 3], boundary).unwrap();
            let model = NetworkModel::builder(&patch).build().unwrap();
            let x = model.reference();
            let mut g = vec![0.0; x.len()];
            let e = model.energy_and_gradient_into(&x, &mut g);
            assert!(e.abs() < 1e-28 && g.iter().all(|g| g.abs() < 1e-14), "energy {e}");
            let dense = patch.compatibility_matrix().unwrap();
            let mut c = vec![0.0; model.compatibility_values()];
            model.compatibility_into(&x, &mut c);
            let chain_core::model::CompatibilityLayout::Sparse(pattern) = model.compatibility_layout() else {
                panic!("sparse")
            };
            let mut ours = vec![vec![0.0; x.len()]; model.spring_count()];
            for (p, row) in ours.iter_mut().enumerate() {
                for (v, &j) in pattern.row(p).iter().enumerate() {
                    row[j] = c[pattern.row_starts[p] + v];
                }
            }
            for (p, row) in ours.iter().enumerate() {
                for (j, &v) in row.iter().enumerate() {
                    assert!((v - dense[(p, j)]).abs() < 1e-12, "C[{p}][{j}]: {v} vs {}", dense[(p, j)]);
                }
            }
            let theirs = counts(&patch).unwrap();
            let mc = maxwell_calladine(&model, &x, None).unwrap();
            assert_eq!(
                (mc.rank, mc.zero_modes.len(), mc.self_stresses.len()),
                (theirs.rank, theirs.zero_modes, theirs.self_stresses),
                "{boundary:?}"
            );
        }
    }
}

/// A periodic square lattice of unit masses and unit springs: its dynamical matrix is diagonal in
/// the polarizations, `omega^2 = 2 (1 - cos q)` along each axis with `q = 2 pi n / N`. The lowest
/// modes are `2N` zero modes (`q = 0` along the polarization: a row of joints sliding along
/// itself costs nothing at first order), `4N` at `2 (1 - cos(2 pi / N))`, then `2 (1 - cos(4 pi /
/// N))`.
#[test]
fn the_square_lattices_modes_are_its_closed_form() {
    let cell = ready::square();
    let n = 6;
    let patch = Patch::new(&cell, [n, n], Boundary::Periodic).unwrap();
    let model = NetworkModel::builder(&patch).build().unwrap();
    let options = ModeOptions { count: Some(6 * n + 2), ..ModeOptions::default() };
    let modes = normal_modes(&model, &model.reference(), &options).unwrap();
    assert_eq!(modes.len(), 6 * n + 2);
    let shell = |m: f64| 2.0 * (1.0 - (m * std::f64::consts::TAU / n as f64).cos());
    for (i, mode) in modes.iter().enumerate() {
        let expected = match i {
            _ if i < 2 * n => 0.0,
            _ if i < 6 * n => shell(1.0),
            _ => shell(2.0),
        };
        assert!(
            (mode.omega_squared - expected).abs() < 1e-10,
            "mode {i}: {} vs {expected}",
            mode.omega_squared
        );
    }
}

/// Relaxation (dissipative dynamics) from a perturbed periodic kagome patch reaches an
/// equilibrium, its forces below the tolerance, having shed all but a millionth of the energy
/// (the patch's floppy modes and states of self-stress leave it near, not at, a zero-energy
/// state: the last digits along the floppy modes are quartic).
#[test]
fn relax_brings_a_perturbed_kagome_patch_to_rest() {
    let cell = ready::kagome();
    let patch = Patch::new(&cell, [4, 4], Boundary::Periodic).unwrap();
    let model = NetworkModel::builder(&patch).build().unwrap();
    let x = perturbed(&model, 0.05, 11);
    assert!(model.energy(&x) > 1e-3);
    let options = RelaxOptions { tolerance: 1e-8, ..RelaxOptions::default() };
    let (relaxed, _steps) = relax(&model, &x, &options).unwrap();
    let g = model.gradient(&relaxed);
    assert!(
        g.iter().all(|g| g.abs() < 1e-7),
        "largest force {}",
        g.iter().fold(0.0f64, |m, g| m.max(g.abs()))
    );
    let (e0, e1) = (model.energy(&x), model.energy(&relaxed));
    assert!(e1 < 1e-6 * e0, "energy {e0} -> {e1}");
}

/// Inertia: a joint's two degrees of freedom share its mass, a rotor's is `M r^2`; overrides
/// change one node or one spring; bad overrides are errors that carry their numbers.
#[test]
fn masses_overrides_and_their_errors() {
    let cell = mixed();
    let patch = Patch::new(&cell, [3, 3], Boundary::Free).unwrap();
    let model = NetworkModel::builder(&patch)
        .mass(2.0)
        .node_mass([1, 2], 1, 5.0)
        .spring_constant(4, 9.0)
        .build()
        .unwrap();
    // Node order per cell: a (2 dof), p (1), c (2).
    let base = |c: [usize; 2]| patch.column(c, 0);
    assert_eq!((model.inertia(base([0, 0])), model.inertia(base([0, 0]) + 1)), (2.0, 2.0));
    assert!((model.inertia(base([0, 0]) + 2) - 2.0 * 0.3 * 0.3).abs() < 1e-15);
    assert!((model.inertia(base([1, 2]) + 2) - 5.0 * 0.3 * 0.3).abs() < 1e-15);
    assert_eq!((model.spring_constant(4), model.spring_constant(3)), (9.0, 1.0));
    let errors = [
        NetworkModel::builder(&patch).mass(0.0).build().unwrap_err(),
        NetworkModel::builder(&patch).node_mass([3, 0], 0, 1.0).build().unwrap_err(),
        NetworkModel::builder(&patch).spring_constant(10_000, 1.0).build().unwrap_err(),
        NetworkModel::builder(&patch).rest_length(0, f64::NAN).build().unwrap_err(),
    ];
    let texts: Vec<String> = errors.iter().map(|e| e.to_string()).collect();
    assert!(errors.iter().all(|e| matches!(e, NetworkError::Argument { .. })));
    assert!(texts[0].contains("mass") && texts[0].contains('0'), "{}", texts[0]);
    assert!(texts[1].contains("[3, 0]") && texts[1].contains("3 x 3"), "{}", texts[1]);
    assert!(
        texts[2].contains("10000") && texts[2].contains(&patch.bonds().len().to_string()),
        "{}",
        texts[2]
    );
    assert!(texts[3].contains("NaN") && texts[3].contains("spring 0"), "{}", texts[3]);
}
