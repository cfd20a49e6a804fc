//! A slice of the wrong length given to a `ChainModel` method of `RuntimeChain` or of a
//! `#[rotor_chain]` chain is a programming error, so it panics; the panic names the slice and both
//! counts, and points at the caller's line (not into the library).

use std::panic::{self, AssertUnwindSafe};
use std::sync::Mutex;

use rotor_chain::prelude::*;

/// Serialises the tests that swap the panic hook (it is global).
static HOOK: Mutex<()> = Mutex::new(());

/// The message and file of the panic of `f`.
fn panic_of(f: impl FnOnce()) -> (String, String) {
    let _guard = HOOK.lock().unwrap_or_else(|e| e.into_inner());
    let seen = std::sync::Arc::new(Mutex::new(String::new()));
    let store = std::sync::Arc::clone(&seen);
    let previous = panic::take_hook();
    panic::set_hook(Box::new(move |info| {
        *store.lock().unwrap() = info.location().map(|l| l.file().to_owned()).unwrap_or_default();
    }));
    let result = panic::catch_unwind(AssertUnwindSafe(f));
    panic::set_hook(previous);
    let payload = result.expect_err("the call should panic");
    let message = payload
        .downcast_ref::<String>()
        .cloned()
        .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_default();
    let file = seen.lock().unwrap().clone();
    (message, file)
}

/// A call that should panic, and the message it should give.
type Case<'a> = (Box<dyn FnOnce() + 'a>, &'static str);

/// `len` zeros.
fn zeros(len: usize) -> Vec<f64> {
    vec![0.0; len]
}

#[test]
fn a_wrong_slice_length_names_the_slice_and_points_at_the_caller() {
    let chain = RuntimeChain::builder(6, 0.8, 1.0e4, 0.58).build().unwrap();
    check_slice_lengths(&chain);
    // The batch methods count configurations.
    let cases: Vec<Case> = vec![
        (
            Box::new(|| chain.batch_gradient_into(&[0.3; 13], &mut zeros(13))),
            "the batch has 13 values, not a whole number of configurations of 6 degrees of freedom",
        ),
        (
            Box::new(|| chain.batch_energy_and_gradient_into(&[0.3; 12], &mut zeros(3), &mut zeros(12))),
            "energies has 3 values, the batch 2 configurations: one energy per configuration",
        ),
    ];
    for (call, expected) in cases {
        let (message, file) = panic_of(call);
        assert_eq!(message, expected);
        assert!(file.ends_with("output_lengths.rs"), "{expected}: the panic points at {file}");
    }
    // One spring: the singular.
    let two = RuntimeChain::builder(2, 0.8, 1.0e4, 0.58).build().unwrap();
    let (message, _) = panic_of(|| two.tensions_into(&[0.3, 0.3], &mut zeros(6)));
    assert_eq!(message, "out has 6 values, the chain has 1 spring (one value per spring)");
}

/// Six rotors in straight-line code (`n <= unroll`).
#[rotor_chain(n = 6, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Unrolled;

/// Six rotors through the kernel loop (`unroll = 0`).
#[rotor_chain(n = 6, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0)]
struct Looped;

/// Every slice method of a chain of 6 rotors names a wrong slice with both counts, at the
/// caller's line: `RuntimeChain` and the `#[rotor_chain]` chains, whichever way their code is
/// generated. `energy_and_gradient_into`, the integrators' hot path, goes without
/// `#[track_caller]` (docs/benchmarks.md), so only its words are checked.
fn check_slice_lengths(chain: &impl ChainModel) {
    let theta = [0.3; 6];
    let cases: Vec<Case> = vec![
        (
            Box::new(|| {
                chain.energy(&theta[..5]);
            }),
            "theta has 5 values, the chain has 6 rotors (one value per rotor)",
        ),
        (
            Box::new(|| chain.gradient_into(&[0.3; 7], &mut zeros(6))),
            "theta has 7 values, the chain has 6 rotors (one value per rotor)",
        ),
        (
            Box::new(|| chain.gradient_into(&theta, &mut zeros(5))),
            "out has 5 values, the chain has 6 rotors (one value per rotor)",
        ),
        (
            Box::new(|| chain.tangent_stiffness_into(&theta, &mut zeros(10))),
            "values has 10 values, a tridiagonal matrix of 6 rows needs 11",
        ),
        (
            Box::new(|| chain.material_stiffness_into(&theta, &mut zeros(12))),
            "values has 12 values, a tridiagonal matrix of 6 rows needs 11",
        ),
        (
            Box::new(|| chain.stress_matrix_into(&theta, &mut zeros(6))),
            "values has 6 values, a tridiagonal matrix of 6 rows needs 11",
        ),
        (
            Box::new(|| chain.spring_lengths_into(&theta, &mut zeros(6))),
            "out has 6 values, the chain has 5 springs (one value per spring)",
        ),
        (
            Box::new(|| chain.tensions_into(&theta, &mut zeros(1))),
            "out has 1 value, the chain has 5 springs (one value per spring)",
        ),
        (
            Box::new(|| chain.compatibility_into(&theta, &mut zeros(11))),
            "values has 11 values, a bidiagonal matrix of 5 springs needs 10",
        ),
        (
            Box::new(|| {
                chain.energy_and_gradient_into(&theta, &mut zeros(60));
            }),
            "out has 60 values, the chain has 6 rotors (one value per rotor)",
        ),
        (
            Box::new(|| {
                chain.energy_gradient_stiffness_into(&theta, &mut zeros(0), &mut zeros(11));
            }),
            "grad has 0 values, the chain has 6 rotors (one value per rotor)",
        ),
    ];
    for (call, expected) in cases {
        let (message, file) = panic_of(call);
        assert_eq!(message, expected);
        // The fused method's case (its panic points into the chain's own code).
        if !expected.starts_with("out has 60") {
            assert!(file.ends_with("output_lengths.rs"), "{expected}: the panic points at {file}");
        }
    }
    // The right lengths work.
    let (mut g, mut k) = (zeros(6), zeros(11));
    let e = chain.energy_gradient_stiffness_into(&theta, &mut g, &mut k);
    assert!(e > 0.0 && g.iter().any(|&x| x != 0.0) && k.iter().all(|x| x.is_finite()));
}

#[test]
fn a_macro_chain_names_a_wrong_slice_as_the_runtime_chain_does() {
    check_slice_lengths(&Unrolled);
    check_slice_lengths(&Looped);
    // The same values from both strategies and the runtime chain, through the trait.
    let runtime = RuntimeChain::builder(6, 0.8, 1.0e4, 0.58).build().unwrap();
    let theta = [0.1, 0.5, -0.2, 0.58, 0.3, -0.58];
    let gradient = |c: &dyn ChainModel| {
        let mut g = zeros(6);
        c.gradient_into(&theta, &mut g);
        g
    };
    let reference = gradient(&runtime);
    for g in [gradient(&Unrolled), gradient(&Looped)] {
        for (a, b) in g.iter().zip(&reference) {
            assert!((a - b).abs() <= 1e-9 * b.abs().max(1.0), "{a} vs {b}");
        }
    }
}
