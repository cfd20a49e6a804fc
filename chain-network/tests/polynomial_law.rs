//! The run-time polynomial law `k sum_j c_j e^j / j` (`e = l - l0`) in the network model, on a
//! cell with every bond type (joint-joint, joint-rotor both ways, rotor-rotor): against the
//! harmonic kernel when only `c2 = 1` is set, against the law summed term by term in this test
//! at the model's bond lengths, against finite differences of the energy (gradient) and of the
//! gradient (Hessian), and read from a cell file's `law` keys.

use chain_core::linalg::SymmetricMatrix;
use chain_core::model::StiffnessLayout;
use chain_core::{Potential, SpringNetwork, Stiffness};
use chain_network::patch::{Boundary, Patch};
use chain_network::{BondLaw, Cell, NetworkError, NetworkModel, Polynomial};
use test_support::random::SplitMix;

/// Joints and rotors with every bond type: `a -> p` (joint to rotor), `p -> c` (rotor to
/// joint), `c -> a` (joints), `p -> p` (a rotor to its image, rotor-rotor).
const MIXED: &str = r#"
dimension = 2
lattice = [[1.0, 0.1], [0.2, 1.3]]
law = { polynomial = [1.0, -2.0, 3.0, 0.5, 0.25] }
[[node]]
name = "a"
kind = "joint"
position = [0.1, 0.2]
[[node]]
name = "p"
kind = "rotor"
pivot = [0.5, 0.4]
length = 0.3
angle = 0.7
[[node]]
name = "c"
kind = "joint"
position = [0.7, 0.9]
[[bond]]
from = "a"
to = "p"
[[bond]]
from = "p"
to = "c"
cell = [1, 0]
law = { polynomial = [0.3, 0.0, -1.5] }
[[bond]]
from = "c"
to = "a"
cell = [0, 1]
k = 2.0
law = "harmonic"
[[bond]]
from = "p"
to = "p"
cell = [1, -1]
"#;

fn perturbed(model: &NetworkModel, size: f64, seed: u64) -> Vec<f64> {
    let mut rng = SplitMix(seed);
    model.reference().iter().map(|x| x + size * rng.symmetric()).collect()
}

/// The tangent stiffness at `x` as a dense matrix.
fn dense_stiffness(model: &NetworkModel, x: &[f64]) -> Vec<Vec<f64>> {
    let mut values = vec![0.0; model.stiffness_values()];
    model.tangent_stiffness_into(x, &mut values);
    let StiffnessLayout::Upper(pattern) = model.stiffness_layout() else {
        panic!("a network's stiffness is an upper triangle");
    };
    let k = SymmetricMatrix::upper(pattern, values).unwrap();
    let n = k.dim();
    (0..n).map(|i| (0..n).map(|j| k.get(i, j)).collect()).collect()
}

/// Rest lengths away from the reference, so every bond is stretched or compressed.
fn stressed<'p, 'c>(patch: &'p Patch<'c>) -> chain_network::NetworkModelBuilder<'p, 'c> {
    let mut builder = NetworkModel::builder(patch);
    for p in 0..patch.bonds().len() {
        builder = builder.rest_length(p, 0.5 + 0.07 * (p % 5) as f64);
    }
    builder
}

#[test]
fn only_c2_is_the_harmonic_kernel_for_every_bond_type() {
    let cell = Cell::from_toml_str(MIXED).unwrap();
    let patch = Patch::new(&cell, [3, 3], Boundary::Periodic).unwrap();
    let harmonic = stressed(&patch).law(BondLaw::Harmonic).build().unwrap();
    let as_polynomial = stressed(&patch).law(Polynomial::harmonic()).build().unwrap();
    for seed in 0..4 {
        let x = perturbed(&harmonic, 0.15, seed);
        let (e_h, e_p) = (harmonic.energy(&x), as_polynomial.energy(&x));
        assert!((e_h - e_p).abs() <= 4.0 * f64::EPSILON * e_h, "energy {e_h} vs {e_p}");
        let scale = harmonic.gradient(&x).iter().fold(0.0f64, |m, g| m.max(g.abs()));
        for (i, (a, b)) in harmonic.gradient(&x).iter().zip(as_polynomial.gradient(&x)).enumerate() {
            assert!((a - b).abs() <= 8.0 * f64::EPSILON * scale, "gradient {i}: {a} vs {b}");
        }
        let (kh, kp) = (dense_stiffness(&harmonic, &x), dense_stiffness(&as_polynomial, &x));
        let scale = kh.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        for (i, (rh, rp)) in kh.iter().zip(&kp).enumerate() {
            for (j, (a, b)) in rh.iter().zip(rp).enumerate() {
                assert!((a - b).abs() <= 16.0 * f64::EPSILON * scale, "K[{i}][{j}]: {a} vs {b}");
            }
        }
    }
}

#[test]
fn the_cell_files_laws_reach_the_model_and_its_derivatives_are_the_energys() {
    let cell = Cell::from_toml_str(MIXED).unwrap();
    let written = [
        [1.0, -2.0, 3.0, 0.5, 0.25], // the cell's law
        [0.3, 0.0, -1.5, 0.0, 0.0],  // bond 1's own
        [1.0, 0.0, 0.0, 0.0, 0.0],   // bond 2: harmonic, evaluated as c2 = 1
        [1.0, -2.0, 3.0, 0.5, 0.25],
    ];
    assert_eq!(cell.bonds()[2].law, BondLaw::Harmonic);
    for boundary in [Boundary::Periodic, Boundary::Free] {
        let patch = Patch::new(&cell, [3, 3], boundary).unwrap();
        let model = stressed(&patch).build().unwrap();
        let m = model.spring_count();
        let c = |p: usize| written[patch.bonds()[p].bond];
        for p in 0..m {
            assert_eq!(model.spring_law(p), Some(BondLaw::Polynomial(Polynomial { coefficients: c(p) })));
        }
        assert_eq!(model.spring_law(m), None);
        for seed in 0..3 {
            let x = perturbed(&model, 0.1, 10 + seed);
            let n = x.len();
            // The energy and tensions summed term by term at the model's lengths.
            let mut l = vec![0.0; m];
            model.spring_lengths_into(&x, &mut l);
            let mut t = vec![0.0; m];
            model.tensions_into(&x, &mut t);
            let mut expected = 0.0;
            for p in 0..m {
                let (k, e) = (model.spring_constant(p), l[p] - model.rest_length(p));
                let terms = (0..5).map(|j| c(p)[j] * e.powi(j as i32 + 2) / (j + 2) as f64);
                expected += k * terms.sum::<f64>();
                let tension = k * (0..5).map(|j| c(p)[j] * e.powi(j as i32 + 1)).sum::<f64>();
                assert!((t[p] - tension).abs() <= 1e-13 * (1.0 + tension.abs()), "tension {p}");
            }
            let ours = model.energy(&x);
            assert!((ours - expected).abs() <= 1e-13 * expected.abs(), "{ours} vs {expected}");
            // Gradient: central differences of the energy; Hessian: of the gradient.
            let grad = model.gradient(&x);
            let h = 1e-6;
            for i in 0..n {
                let (mut up, mut down) = (x.clone(), x.clone());
                up[i] += h;
                down[i] -= h;
                let fd = (model.energy(&up) - model.energy(&down)) / (2.0 * h);
                assert!((grad[i] - fd).abs() < 1e-7 * (1.0 + fd.abs()), "gradient {i}: {} vs {fd}", grad[i]);
            }
            let k = dense_stiffness(&model, &x);
            let h = 1e-5;
            for j in 0..n {
                let (mut up, mut down) = (x.clone(), x.clone());
                up[j] += h;
                down[j] -= h;
                let (gu, gd) = (model.gradient(&up), model.gradient(&down));
                for i in 0..n {
                    let fd = (gu[i] - gd[i]) / (2.0 * h);
                    assert!(
                        (k[i][j] - fd).abs() < 1e-6 * (1.0 + fd.abs()),
                        "K[{i}][{j}]: {} vs {fd}",
                        k[i][j]
                    );
                }
            }
        }
    }
}

#[test]
fn a_quartic_bond_among_polynomial_ones_and_a_bad_law_key_are_refused() {
    let cell = Cell::from_toml_str(MIXED).unwrap();
    let patch = Patch::new(&cell, [2, 2], Boundary::Free).unwrap();
    let e = NetworkModel::builder(&patch).spring_law(1, BondLaw::Quartic).build().unwrap_err();
    assert!(matches!(&e, NetworkError::Argument { what: "law", .. }), "{e}");
    assert!(e.to_string().contains("spring 1 is quartic"), "{e}");
    let e = NetworkModel::builder(&patch).spring_law(99, BondLaw::Quartic).build().unwrap_err();
    assert!(matches!(&e, NetworkError::Argument { what: "spring law", .. }), "{e}");
    // Every spring quartic is one kernel again.
    let quartic = NetworkModel::builder(&patch).law(BondLaw::Quartic).build().unwrap();
    assert_eq!(quartic.spring_law(0), Some(BondLaw::Quartic));

    for (law, line, says) in [
        ("law = \"cubic\"", 4, "unknown law `cubic`"),
        ("law = { polynomial = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0] }", 4, "expected 5 entries, found 6"),
        ("law = { polynomial = [1.0, nan] }", 4, "not a finite number"),
        ("law = 3", 4, "is not a law"),
    ] {
        let text = MIXED.replace("law = { polynomial = [1.0, -2.0, 3.0, 0.5, 0.25] }", law);
        let e = Cell::from_toml_str(&text).unwrap_err();
        assert_eq!(e.line(), Some(line), "{law}: {e}");
        assert!(e.to_string().contains(says), "{law}: {e}");
    }
    // And the law is written back by `to_toml`.
    assert_eq!(Cell::from_toml_str(&cell.to_toml()).unwrap(), cell);
}
