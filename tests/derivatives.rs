//! Gradient and tangent stiffness of generated chains against independent references: central
//! finite differences of the energy, and forward-mode autodiff (num-dual) of an independent
//! Cartesian statement of the energy (`common::Reference`).

mod common;

use common::{Reference, assert_close, wavy};
use proptest::prelude::*;
use rotor_chain::prelude::*;

#[rotor_chain(n = 12, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Small;

#[rotor_chain(n = 12, r = 0.8, theta_bar = 0.58, k = 1.0e4,
              law = k / (8.0 * l0 * l0) * (l * l - l0 * l0).powi(2))]
struct Quartic;

#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Paper;

/// A central difference with step `h` of an energy of size `|V|` is off by its truncation error
/// (`~h^2`, tiny here) plus rounding, `~eps |V| / h`: the tolerance has to scale with the energy,
/// not with the derivative being checked.
#[track_caller]
fn assert_fd(exact: f64, fd: f64, energy: f64, h: f64, what: &str) {
    let tolerance = 1e-8 * exact.abs().max(1.0) + 8.0 * f64::EPSILON * energy.abs().max(1.0) / h;
    assert!(
        (exact - fd).abs() <= tolerance,
        "{what}: {exact} vs {fd} (tolerance {tolerance:e}, energy {energy})"
    );
}

fn angles() -> impl Strategy<Value = [f64; 12]> {
    // |theta| <= 1.2 keeps every spring longer than 0.5 a (no coincident tips).
    proptest::array::uniform12(-1.2f64..1.2)
}

proptest! {
    // A fixed seed keeps CI deterministic; no regression files are written into the tree.
    #![proptest_config(ProptestConfig {
        cases: 64,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x5eed_c4a1),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn energy_matches_the_cartesian_reference(theta in angles()) {
        let reference = Reference::uniform(12, 0.58);
        assert_close(Small.energy(&theta), reference.energy(&theta), 1e-12, "energy");
    }

    #[test]
    fn gradient_matches_autodiff_and_finite_differences(theta in angles()) {
        let reference = Reference::uniform(12, 0.58);
        let g = Small.gradient(&theta);
        let exact = reference.gradient(&theta);
        for i in 0..12 {
            assert_close(g[i], exact[i], 1e-11, &format!("dV/dtheta_{i} vs num-dual"));
            let h = 1e-6;
            let (mut up, mut down) = (theta, theta);
            up[i] += h;
            down[i] -= h;
            let fd = (Small.energy(&up) - Small.energy(&down)) / (2.0 * h);
            assert_fd(g[i], fd, Small.energy(&theta), h, &format!("dV/dtheta_{i} vs central difference"));
        }
    }

    #[test]
    fn hessian_matches_hyperdual_autodiff_and_is_banded_and_symmetric(theta in angles()) {
        let reference = Reference::uniform(12, 0.58);
        let h = Small.hessian(&theta);
        for i in 0..12 {
            for j in 0..12 {
                assert_eq!(h[(i, j)], h[(j, i)], "symmetry at ({i}, {j})");
                if i.abs_diff(j) <= 1 {
                    assert_close(h[(i, j)], reference.hessian_entry(&theta, i, j), 1e-10, &format!("H[{i}][{j}]"));
                } else {
                    assert_eq!(h[(i, j)], 0.0, "a spring couples neighbours only");
                }
            }
        }
    }

    #[test]
    fn hessian_matches_central_differences_of_the_gradient(theta in angles()) {
        let t = Small.tangent_stiffness(&theta);
        let step = 1e-6;
        for j in 0..12 {
            let (mut up, mut down) = (theta, theta);
            up[j] += step;
            down[j] -= step;
            let (gu, gd) = (Small.gradient(&up), Small.gradient(&down));
            for i in j.saturating_sub(1)..(j + 2).min(12) {
                let fd = (gu[i] - gd[i]) / (2.0 * step);
                assert_close(t.get(i, j), fd, 1e-5, &format!("K[{i}][{j}]"));
            }
        }
    }

    #[test]
    fn material_part_plus_stress_matrix_is_the_tangent_stiffness(theta in angles()) {
        for (k, m, s) in [
            (Small.tangent_stiffness(&theta), Small.material_stiffness(&theta), Small.stress_matrix(&theta)),
            (Quartic.tangent_stiffness(&theta), Quartic.material_stiffness(&theta), Quartic.stress_matrix(&theta)),
        ] {
            for i in 0..12 {
                assert_close(m.diag[i] + s.diag[i], k.diag[i], 1e-11, &format!("diag {i}"));
            }
            for p in 0..11 {
                assert_close(m.off[p] + s.off[p], k.off[p], 1e-11, &format!("off {p}"));
            }
        }
    }

    #[test]
    fn custom_law_derivatives_match_finite_differences(theta in angles()) {
        let g = Quartic.gradient(&theta);
        let h = 1e-6;
        for i in 0..12 {
            let (mut up, mut down) = (theta, theta);
            up[i] += h;
            down[i] -= h;
            let fd = (Quartic.energy(&up) - Quartic.energy(&down)) / (2.0 * h);
            assert_fd(g[i], fd, Quartic.energy(&theta), h, &format!("quartic dV/dtheta_{i}"));
        }
    }
}

#[test]
fn custom_law_is_the_papers_quartic_energy() {
    // Eq. (eq:discretepotential): k (l^2 - l0^2)^2 / (8 l0^2), summed over springs.
    let theta = wavy(12, 0.58, 3);
    let theta: [f64; 12] = theta.try_into().unwrap();
    let reference = Reference::uniform(12, 0.58);
    let expected: f64 = (0..11)
        .map(|p| {
            let l = reference.length(p, theta[p], theta[p + 1]);
            let l0 = reference.l0[p];
            1.0e4 * (l * l - l0 * l0).powi(2) / (8.0 * l0 * l0)
        })
        .sum();
    assert_close(Quartic.energy(&theta), expected, 1e-12, "quartic energy");
}

#[test]
fn tensions_and_compatibility_follow_their_definitions() {
    let theta: [f64; 60] = wavy(60, 0.58, 7).try_into().unwrap();
    let reference = Reference::uniform(60, 0.58);
    let lengths = Paper.spring_lengths(&theta);
    let tensions = Paper.tensions(&theta);
    let c = Paper.compatibility(&theta);
    for p in 0..59 {
        let l = reference.length(p, theta[p], theta[p + 1]);
        assert_close(lengths[p], l, 1e-13, &format!("l_{p}"));
        assert_close(tensions[p], 1.0e4 * (l - reference.l0[p]), 1e-10, &format!("t_{p}"));
        // C[p][i] = dl_p / d(r theta_i), by a central difference of the reference length.
        let h = 1e-7;
        let dl1 = (reference.length(p, theta[p] + h, theta[p + 1])
            - reference.length(p, theta[p] - h, theta[p + 1]))
            / (2.0 * h);
        let dl2 = (reference.length(p, theta[p], theta[p + 1] + h)
            - reference.length(p, theta[p], theta[p + 1] - h))
            / (2.0 * h);
        assert_close(c.left[p], dl1 / 0.8, 1e-7, &format!("C[{p}][{p}]"));
        assert_close(c.right[p], dl2 / 0.8, 1e-7, &format!("C[{p}][{}]", p + 1));
        assert_eq!(c.get(p, p + 2), 0.0);
    }
    // The paper-size chain agrees with the reference too.
    assert_close(Paper.energy(&theta), reference.energy(&theta), 1e-12, "energy, n = 60");
}
