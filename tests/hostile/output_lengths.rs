//! A slice of the wrong length given to a `ChainModel` method of `RuntimeChain` is a programming
//! error, so it panics; the panic names the slice and both counts, and points at the caller's line
//! (not into the library).

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
    let theta = [0.3; 6];
    let cases: Vec<Case> = vec![
        (
            Box::new(|| {
                chain.energy(&theta[..5]);
            }),
            "theta has 5 values, the chain has 6 rotors (one value per rotor)",
        ),
        (
            Box::new(|| chain.gradient_into(&theta, &mut zeros(5))),
            "out has 5 values, the chain has 6 rotors (one value per rotor)",
        ),
        (
            Box::new(|| chain.compatibility_into(&theta, &mut zeros(5), &mut zeros(6))),
            "right has 6 values, the chain has 5 springs (one value per spring)",
        ),
        (
            Box::new(|| chain.tangent_stiffness_into(&theta, &mut zeros(6), &mut zeros(4))),
            "off has 4 values, the chain has 5 springs (one value per spring)",
        ),
        (
            Box::new(|| {
                chain.energy_gradient_stiffness_into(&theta, &mut zeros(6), &mut zeros(5), &mut zeros(4));
            }),
            "diag has 5 values, the chain has 6 rotors (one value per rotor)",
        ),
        (
            Box::new(|| chain.batch_gradient_into(&[0.3; 13], &mut zeros(13))),
            "thetas has 13 angles, not a whole number of configurations of 6 rotors",
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
    // The right lengths still work.
    let mut gradient = zeros(6);
    chain.gradient_into(&theta, &mut gradient);
    assert!(gradient.iter().all(|g| g.is_finite()) && gradient.iter().any(|&g| g != 0.0));
}
