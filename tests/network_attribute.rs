//! `#[rotor_network]` against the run-time `NetworkModel` on the same cell, patch and law
//! (harmonic: the same derivation, so bit for bit; quartic written as the attribute's law
//! expression: to rounding), a custom law against finite differences and an energy summed in the
//! test from the patch's bond lengths, and the analyses (relaxation, modes, counts, Verlet) run
//! on an attribute struct.

use rotor_chain::integrate::{Phase, Verlet};
use rotor_chain::network::NetworkModel;
use rotor_chain::network::cell::{Cell, ready};
use rotor_chain::network::patch::{Boundary, Patch};
use rotor_chain::statics::counting::maxwell_calladine;
use rotor_chain::statics::equilibrium::{RelaxOptions, relax};
use rotor_chain::statics::modes::{ModeOptions, normal_modes};
use rotor_chain::{Law, Potential, SpringNetwork, Stiffness, rotor_network};
use test_support::random::SplitMix;

/// A free kagome patch from the guide's cell file, harmonic, with overrides.
#[rotor_network(
    cell = "docs/cells/kagome.toml",
    cells = (6, 5),
    boundary = "free",
    mass = 1.5,
    spring(7, k = 3.0, l0 = 0.55),
    spring(20, k = 0.5),
    node((2, 3), "c", mass = 4.0),
    node((0, 0), 0, mass = 0.25)
)]
struct KagomeHarmonic;

/// Every bond type, prestressed, periodic, the quartic law written as an expression.
#[rotor_network(
    cell = "tests/cells/rotors.toml",
    cells = (3, 4),
    boundary = "periodic",
    law = k / (8.0 * l0 * l0) * (l * l - l0 * l0).powi(2)
)]
struct RotorsQuartic;

/// A custom law no checked-in kernel has: `k (exp(l - l0) - 1 - (l - l0))`.
#[rotor_network(
    cell = "tests/cells/rotors.toml",
    cells = (3, 3),
    boundary = "free",
    law = k * ((l - l0).exp() - 1.0 - (l - l0))
)]
struct RotorsExponential;

/// A ready cell, periodic.
#[rotor_network(ready = "kagome", cells = (4, 4), boundary = "periodic")]
struct ReadyKagome;

/// The last spring of a free 4 x 4 kagome patch (66 bonds; `spring(66, ..)` is a compile error,
/// ui-tests/tests/ui/compile_fail/network.rs).
#[rotor_network(ready = "kagome", cells = (4, 4), boundary = "free", spring(65, k = 2.0, l0 = 0.6))]
struct LastSpring;

fn rotors_cell() -> Cell {
    Cell::from_toml_file(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/cells/rotors.toml")).unwrap()
}

fn kagome_file_cell() -> Cell {
    Cell::from_toml_file(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/cells/kagome.toml")).unwrap()
}

/// The reference disturbed by up to `amplitude` per degree of freedom.
fn disturbed(x0: &[f64], amplitude: f64, seed: u64) -> Vec<f64> {
    let mut rng = SplitMix(seed);
    x0.iter().map(|x| x + rng.range(-amplitude, amplitude)).collect()
}

/// Every output of the three rungs at `x`, in a fixed order, for comparisons.
fn outputs<M: SpringNetwork>(m: &M, x: &[f64]) -> Vec<Vec<f64>> {
    let n = m.dof_count();
    let (h, c, s) = (m.stiffness_values(), m.compatibility_values(), m.spring_count());
    let mut gradient = vec![0.0; n];
    m.gradient_into(x, &mut gradient);
    let mut fused = vec![0.0; n];
    let e_fused = m.energy_and_gradient_into(x, &mut fused);
    let mut stiffness = vec![0.0; h];
    m.tangent_stiffness_into(x, &mut stiffness);
    let (mut g3, mut k3) = (vec![0.0; n], vec![0.0; h]);
    let e3 = m.energy_gradient_stiffness_into(x, &mut g3, &mut k3);
    let (mut material, mut stress) = (vec![0.0; h], vec![0.0; h]);
    m.material_stiffness_into(x, &mut material);
    m.stress_matrix_into(x, &mut stress);
    let mut compatibility = vec![0.0; c];
    m.compatibility_into(x, &mut compatibility);
    let (mut lengths, mut tensions) = (vec![0.0; s], vec![0.0; s]);
    m.spring_lengths_into(x, &mut lengths);
    m.tensions_into(x, &mut tensions);
    let inertia = (0..n).map(|i| m.inertia(i)).collect();
    let springs = (0..s).flat_map(|p| [m.spring_constant(p), m.rest_length(p)]).collect();
    vec![
        vec![m.energy(x), e_fused, e3, m.energy_floor()],
        gradient,
        fused,
        stiffness,
        g3,
        k3,
        material,
        stress,
        compatibility,
        lengths,
        tensions,
        inertia,
        springs,
    ]
}

fn same_layouts<A: SpringNetwork, B: SpringNetwork>(a: &A, b: &B) {
    assert_eq!(format!("{:?}", a.stiffness_layout()), format!("{:?}", b.stiffness_layout()));
    assert_eq!(format!("{:?}", a.compatibility_layout()), format!("{:?}", b.compatibility_layout()));
}

#[test]
fn harmonic_attribute_is_the_runtime_model_bit_for_bit() {
    let cell = kagome_file_cell();
    let patch = Patch::new(&cell, [6, 5], Boundary::Free).unwrap();
    let runtime = NetworkModel::builder(&patch)
        .mass(1.5)
        .spring_constant(7, 3.0)
        .rest_length(7, 0.55)
        .spring_constant(20, 0.5)
        .node_mass([2, 3], 2, 4.0)
        .node_mass([0, 0], 0, 0.25)
        .build()
        .unwrap();
    assert_eq!(KagomeHarmonic.reference(), runtime.reference());
    same_layouts(&KagomeHarmonic, &runtime);
    // The node overrides reached the model: node "c" (the cell's third joint: its dof 4 and 5)
    // of cell (2, 3), node 0 of cell (0, 0); every other node has `mass`.
    for (c, j, m) in
        [([2, 3], 4, 4.0), ([2, 3], 5, 4.0), ([0, 0], 0, 0.25), ([0, 0], 1, 0.25), ([2, 3], 3, 1.5)]
    {
        assert_eq!(KagomeHarmonic.inertia(patch.column(c, j)), m, "cell {c:?}, dof {j}");
    }
    for seed in 0..3 {
        let x = disturbed(&runtime.reference(), 0.05, seed);
        let (a, b) = (outputs(&KagomeHarmonic, &x), outputs(&runtime, &x));
        for (i, (a, b)) in a.iter().zip(&b).enumerate() {
            assert_eq!(a.len(), b.len(), "output {i}");
            for (j, (u, v)) in a.iter().zip(b).enumerate() {
                assert_eq!(u.to_bits(), v.to_bits(), "output {i}[{j}]: attribute {u}, run time {v}");
            }
        }
    }
}

#[test]
fn quartic_law_expression_matches_the_runtime_quartic_model_to_rounding() {
    let cell = rotors_cell();
    let patch = Patch::new(&cell, [3, 4], Boundary::Periodic).unwrap();
    let runtime = NetworkModel::builder(&patch).law(Law::Quartic).build().unwrap();
    same_layouts(&RotorsQuartic, &runtime);
    // Every bond type is in the patch.
    assert!(runtime.rotor_count() == 24 && RotorsQuartic.dof_count() == 3 * 4 * 4);
    for seed in 0..3 {
        let x = disturbed(&runtime.reference(), 0.1, 10 + seed);
        let (a, b) = (outputs(&RotorsQuartic, &x), outputs(&runtime, &x));
        assert!(a[0][0] > 1e-3, "the patch is strained: E = {}", a[0][0]);
        for (i, (a, b)) in a.iter().zip(&b).enumerate() {
            let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (j, (u, v)) in a.iter().zip(b).enumerate() {
                assert!((u - v).abs() <= 1e-13 * scale, "output {i}[{j}]: attribute {u}, run time {v}");
            }
        }
    }
}

#[test]
fn custom_law_energy_gradient_and_stiffness_match_finite_differences_and_its_lengths() {
    let m = &RotorsExponential;
    let n = m.dof_count();
    let x = disturbed(&m.reference(), 0.1, 21);
    // The energy summed here from the bond lengths (the run-time harmonic model's, which the law
    // does not change) and the law written in f64.
    let cell = rotors_cell();
    let patch = Patch::new(&cell, [3, 3], Boundary::Free).unwrap();
    let lengths_model = NetworkModel::builder(&patch).build().unwrap();
    let mut lengths = vec![0.0; lengths_model.spring_count()];
    lengths_model.spring_lengths_into(&x, &mut lengths);
    let expected: f64 = lengths
        .iter()
        .enumerate()
        .map(|(p, &l)| {
            let (k, l0) = (m.spring_constant(p), m.rest_length(p));
            k * ((l - l0).exp() - 1.0 - (l - l0))
        })
        .sum();
    let energy = m.energy(&x);
    assert!(energy > 1e-4, "strained: {energy}");
    assert!((energy - expected).abs() <= 1e-13 * expected, "{energy} vs {expected}");

    let h = 1e-6;
    let at = |i: usize, s: f64| {
        let mut y = x.clone();
        y[i] += s;
        y
    };
    let mut grad = vec![0.0; n];
    m.gradient_into(&x, &mut grad);
    let gnorm = grad.iter().fold(0.0f64, |a, g| a.max(g.abs()));
    for (i, &g) in grad.iter().enumerate() {
        let fd = (m.energy(&at(i, h)) - m.energy(&at(i, -h))) / (2.0 * h);
        assert!((g - fd).abs() <= 1e-7 * gnorm, "gradient {i}: {g} vs {fd}");
    }
    // The stiffness against central differences of the gradient, entry by entry of the pattern.
    let mut values = vec![0.0; m.stiffness_values()];
    m.tangent_stiffness_into(&x, &mut values);
    let rotor_chain::model::StiffnessLayout::Upper(pattern) = m.stiffness_layout() else {
        panic!("a network's stiffness is an upper-triangle pattern")
    };
    let knorm = values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    for j in 0..n {
        let (mut gp, mut gm) = (vec![0.0; n], vec![0.0; n]);
        m.gradient_into(&at(j, h), &mut gp);
        m.gradient_into(&at(j, -h), &mut gm);
        for r in 0..n {
            let row = pattern.row_starts[r]..pattern.row_starts[r + 1];
            for (&column, &value) in pattern.columns[row.clone()].iter().zip(&values[row]) {
                if column == j {
                    let fd = (gp[r] - gm[r]) / (2.0 * h);
                    assert!((value - fd).abs() <= 1e-6 * knorm, "K[{r}, {j}]: {value} vs {fd}");
                }
            }
        }
    }
}

#[test]
fn relaxation_modes_counts_and_verlet_run_on_an_attribute_struct() {
    let m = &ReadyKagome;
    let x0 = m.reference();
    assert!(m.energy(&x0).abs() < 1e-28);
    // The periodic N x N kagome patch has 3N zero modes and 3N states of self-stress (issue 33).
    let mc = maxwell_calladine(m, &x0, None).unwrap();
    assert_eq!((mc.zero_modes.len(), mc.self_stresses.len()), (12, 12));
    let modes = normal_modes(m, &x0, &ModeOptions { count: Some(14), ..ModeOptions::default() }).unwrap();
    assert!(modes[..12].iter().all(|mode| mode.omega_squared.abs() < 1e-9));
    assert!(modes[12].omega_squared > 1e-3);

    let x = disturbed(&x0, 0.02, 5);
    let options = RelaxOptions { tolerance: 1e-8, ..RelaxOptions::default() };
    let (relaxed, _steps) = relax(m, &x, &options).unwrap();
    assert!(m.energy(&relaxed) < 1e-6 * m.energy(&x));

    let e0 = m.energy(&x);
    let phase = Phase { time: 0.0, theta: x, omega: vec![0.0; m.dof_count()] };
    let mut verlet = Verlet::new(m, phase, 0.01).unwrap();
    for _ in 0..1000 {
        verlet.step(m).unwrap();
    }
    let e1 = verlet.kinetic_energy(m) + verlet.potential_energy(m);
    assert!((e1 - e0).abs() < 1e-3 * e0, "{e0} -> {e1}");

    // The same patch built at run time from the ready cell gives the same counts' inputs.
    let cell = ready::kagome();
    let patch = Patch::new(&cell, [4, 4], Boundary::Periodic).unwrap();
    let runtime = NetworkModel::builder(&patch).build().unwrap();
    assert_eq!(runtime.reference(), x0);
}

#[test]
fn the_attribute_counts_a_free_patch_s_bonds_as_the_patch_does() {
    let cell = ready::kagome();
    let patch = Patch::new(&cell, [4, 4], Boundary::Free).unwrap();
    assert_eq!(patch.bonds().len(), 66);
    assert_eq!(LastSpring.spring_count(), 66);
    assert_eq!((LastSpring.spring_constant(65), LastSpring.rest_length(65)), (2.0, 0.6));
    assert_eq!(LastSpring.spring_constant(64), 1.0);
    assert!((LastSpring.rest_length(64) - 0.5).abs() < 1e-15);
}

/// The attribute checks the patch's rules at compile time with these values of its own
/// (chain-macros/src/network/valid.rs): they must stay the library's.
#[test]
fn the_attribute_s_patch_rules_are_the_library_s() {
    use rotor_chain::network::patch::{MAX_PATCH_BONDS, MIN_PERIODIC_CELLS};
    assert_eq!((MAX_PATCH_BONDS, MIN_PERIODIC_CELLS), (1 << 25, 3));
}
