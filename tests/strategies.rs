//! The three ways to get a chain agree to 1e-12 relative: the macro's unrolled code, the macro's
//! looped per-spring kernel, and the runtime-sized `RuntimeChain` built from the same kernel.

mod common;

use common::{assert_close, wavy};
use rotor_chain::prelude::*;

#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 1.0, unroll = 128,
              spring(29, k = k_imp), spring(7, l0 = 2.30), rotor(12, r = 0.7))]
struct Unrolled {
    k_imp: f64,
}

#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 1.0, unroll = 0,
              spring(29, k = k_imp), spring(7, l0 = 2.30), rotor(12, r = 0.7))]
struct Looped {
    k_imp: f64,
}

fn runtime(k_imp: f64) -> RuntimeChain {
    RuntimeChain::builder(60, 0.8, 1.0e4, 0.58)
        .spring_constant(29, k_imp)
        .spring_rest_length(7, 2.30)
        .rotor(12, 0.7)
        .build()
        .expect("valid chain")
}

/// Every output of a chain through the trait, flattened with labels.
fn outputs(model: &impl ChainModel, theta: &[f64]) -> Vec<(String, f64)> {
    let n = model.rotor_count();
    let mut out = vec![("energy".to_owned(), model.energy(theta))];
    let mut v = vec![0.0; n];
    model.gradient_into(theta, &mut v);
    out.extend(v.iter().enumerate().map(|(i, x)| (format!("gradient[{i}]"), *x)));
    let mut k = vec![0.0; 2 * n - 1];
    for name in ["stiffness", "material", "stress"] {
        match name {
            "stiffness" => model.tangent_stiffness_into(theta, &mut k),
            "material" => model.material_stiffness_into(theta, &mut k),
            _ => model.stress_matrix_into(theta, &mut k),
        }
        let (d, o) = k.split_at(n);
        out.extend(d.iter().enumerate().map(|(i, x)| (format!("{name}.diag[{i}]"), *x)));
        out.extend(o.iter().enumerate().map(|(i, x)| (format!("{name}.off[{i}]"), *x)));
    }
    let mut s = vec![0.0; n - 1];
    model.spring_lengths_into(theta, &mut s);
    out.extend(s.iter().enumerate().map(|(i, x)| (format!("length[{i}]"), *x)));
    model.tensions_into(theta, &mut s);
    out.extend(s.iter().enumerate().map(|(i, x)| (format!("tension[{i}]"), *x)));
    let mut c = vec![0.0; 2 * (n - 1)];
    model.compatibility_into(theta, &mut c);
    let (l, r) = c.split_at(n - 1);
    out.extend(l.iter().enumerate().map(|(i, x)| (format!("C.left[{i}]"), *x)));
    out.extend(r.iter().enumerate().map(|(i, x)| (format!("C.right[{i}]"), *x)));
    out
}

#[test]
fn unrolled_looped_and_runtime_agree_to_1e12() {
    let (u, l, r) = (Unrolled { k_imp: 100.0 }, Looped { k_imp: 100.0 }, runtime(100.0));
    for seed in 0..5 {
        let theta = wavy(60, 0.58, seed);
        let (ou, ol, or) = (outputs(&u, &theta), outputs(&l, &theta), outputs(&r, &theta));
        assert_eq!(ou.len(), ol.len());
        for ((name, a), ((_, b), (_, c))) in ou.iter().zip(ol.iter().zip(&or)) {
            assert_close(*a, *b, 1e-12, &format!("{name}: unrolled vs looped"));
            assert_close(*a, *c, 1e-12, &format!("{name}: unrolled vs runtime"));
        }
    }
}

#[test]
fn parameters_agree_between_macro_and_runtime() {
    let (u, r) = (Unrolled { k_imp: 100.0 }, runtime(100.0));
    assert_eq!(u.rotor_count(), r.rotor_count());
    for p in 0..59 {
        assert_eq!(u.spring_constant(p), r.spring_constant(p), "k_{p}");
        assert_close(u.rest_length(p), r.rest_length(p), 1e-15, &format!("l0_{p}"));
    }
    for i in 0..60 {
        assert_eq!(u.rotor_length(i), r.rotor_length(i), "r_{i}");
        assert_eq!(u.inertia(i), r.inertia(i), "M r_{i}^2");
    }
    assert_eq!(u.theta_bar(), r.theta_bar());
}

#[test]
fn a_large_looped_chain_matches_the_runtime_chain() {
    #[rotor_chain(n = 2000, r = 0.8, theta_bar = 0.3, k = 1.0e4)]
    struct Long;
    let runtime = RuntimeChain::builder(2000, 0.8, 1.0e4, 0.3).build().unwrap();
    let theta = wavy(2000, 0.3, 11);
    let mut g1 = vec![0.0; 2000];
    let mut g2 = vec![0.0; 2000];
    Long.gradient_into(&theta, &mut g1);
    runtime.gradient_into(&theta, &mut g2);
    for i in 0..2000 {
        assert_close(g1[i], g2[i], 1e-12, &format!("gradient[{i}]"));
    }
    // Inherent methods take `&[f64; N]`; through the trait they take slices.
    assert_close(Potential::energy(&Long, &theta), runtime.energy(&theta), 1e-12, "energy");
}
