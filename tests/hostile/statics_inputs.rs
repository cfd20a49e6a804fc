//! Hostile inputs to the static analyses: every public analysis checks its inputs where it
//! starts and answers with a typed error carrying the value, never a panic, a hang or a NaN
//! returned as `Ok`. Several inputs per class: non-finite and mis-sized angles, springs the chain
//! does not have, settings out of range, models whose parameters are not finite, sizes too large
//! to hold.

use rotor_chain::linalg::{LinalgError, SymmetricMatrix};
use rotor_chain::prelude::*;
use rotor_chain::statics::StaticsError;
use rotor_chain::statics::antikink::{AntikinkOptions, antikink_at, antikink_relaxed, peierls_nabarro};
use rotor_chain::statics::classify::classify;
use rotor_chain::statics::cobweb::{MAX_COBWEB_SAMPLES, branch_slope, cobweb, fixed_points};
use rotor_chain::statics::counting::{maxwell_calladine, tensional_modes};
use rotor_chain::statics::equilibrium::{NewtonOptions, RelaxOptions, newton, relax};
use rotor_chain::statics::impurity::{critical_length, impurity_analysis, two_kink_configuration};
use rotor_chain::statics::kink::{MAX_PATH_STEPS, kink, mechanism_path};
use rotor_chain::statics::modes::{ModeOptions, modes};

const N: usize = 20;
const BAD: [f64; 3] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

fn chain() -> RuntimeChain {
    RuntimeChain::builder(N, 0.8, 1.0e4, 0.58).build().unwrap()
}

/// A chain whose stiffness is read from a field at run time, unchecked.
#[rotor_chain(n = 20, r = 0.8, theta_bar = 0.58, k = stiffness)]
struct FieldStiffness {
    stiffness: f64,
}

/// A chain whose rest length is read from a field: 5.0 admits no uniform state (theta_bar NaN).
#[rotor_chain(n = 20, r = 0.8, rest_length = lbar, k = 1.0e4)]
struct FieldRestLength {
    lbar: f64,
}

/// The kink, a valid configuration with one angle replaced by `bad`.
fn with_bad_angle(bad: f64, at: usize) -> Vec<f64> {
    let mut theta = kink(&chain(), 9.5).unwrap();
    theta[at] = bad;
    theta
}

fn is_not_finite(err: &StaticsError, bad: f64, at: usize) -> bool {
    matches!(err, StaticsError::NotFinite { what: "theta", index, value }
        if *index == at && (value.to_bits() == bad.to_bits()))
}

#[test]
fn non_finite_angles_are_errors_before_any_iteration() {
    let model = chain();
    for bad in BAD {
        for at in [0, 7, N - 1] {
            let theta = with_bad_angle(bad, at);
            let errors = [
                newton(&model, &theta, &NewtonOptions::default()).unwrap_err(),
                relax(&model, &theta, &RelaxOptions::default()).unwrap_err(),
                modes(&model, &theta, &ModeOptions::default()).unwrap_err(),
                maxwell_calladine(&model, &theta, None).unwrap_err(),
                tensional_modes(&model, &theta, 2).unwrap_err(),
                cobweb(&model, 3, &theta, 0.7, 11).unwrap_err(),
            ];
            for err in errors {
                assert!(is_not_finite(&err, bad, at), "{bad} at {at}: {err}");
                assert!(err.to_string().contains(&format!("{bad}")), "{err}");
            }
        }
        assert!(branch_slope(&model, 3, bad, 0.5).is_err());
        for centre in [bad, -1.0, N as f64] {
            assert!(matches!(kink(&model, centre), Err(StaticsError::CentreOutOfRange { .. })));
            assert!(matches!(
                antikink_at(&model, centre, &AntikinkOptions::default()),
                Err(StaticsError::CentreOutOfRange { .. })
            ));
        }
    }
}

#[test]
fn angles_of_the_wrong_length_are_errors() {
    let model = chain();
    for len in [0, 1, N - 1, N + 1] {
        let theta = vec![0.58; len];
        let expected = |err: StaticsError| matches!(err, StaticsError::WrongLength { len: l, expected: N, .. } if l == len);
        assert!(expected(newton(&model, &theta, &NewtonOptions::default()).unwrap_err()));
        assert!(expected(relax(&model, &theta, &RelaxOptions::default()).unwrap_err()));
        assert!(expected(modes(&model, &theta, &ModeOptions::default()).unwrap_err()));
        assert!(expected(maxwell_calladine(&model, &theta, None).unwrap_err()));
        assert!(expected(cobweb(&model, 3, &theta, 0.7, 11).unwrap_err()));
    }
}

#[test]
fn springs_the_chain_does_not_have_are_errors() {
    let model = chain();
    let theta = vec![0.58; N];
    for p in [N - 1, N, 1000, usize::MAX] {
        let no_such = |err: StaticsError| matches!(err, StaticsError::Branch(BranchError::NoSuchSpring { spring, springs }) if spring == p && springs == N - 1);
        assert!(no_such(critical_length(&model, p).unwrap_err()));
        assert!(no_such(two_kink_configuration(&model, p).unwrap_err()));
        assert!(no_such(impurity_analysis(&model, p).unwrap_err()));
        assert!(no_such(fixed_points(&model, p).unwrap_err()));
        assert!(no_such(branch_slope(&model, p, 0.5, 0.5).unwrap_err()));
        assert!(no_such(cobweb(&model, p, &theta, 0.7, 11).unwrap_err()));
    }
}

#[test]
fn settings_out_of_range_are_errors() {
    let model = chain();
    let theta = kink(&model, 9.0).unwrap();
    // A function's argument is `InvalidValue`, an options struct's field `InvalidOption`.
    let invalid = |err: StaticsError, name: &str| {
        let named = match &err {
            StaticsError::InvalidValue { what, .. } => what.contains(name),
            StaticsError::InvalidOption { name: field, .. } => *field == name,
            _ => false,
        };
        assert!(named, "{err}");
    };
    for bad in [f64::NAN, f64::INFINITY, -1.0] {
        let o = NewtonOptions { tolerance: bad, ..NewtonOptions::default() };
        invalid(newton(&model, &theta, &o).unwrap_err(), "tolerance");
        let o = NewtonOptions { shift: bad, ..NewtonOptions::default() };
        invalid(newton(&model, &theta, &o).unwrap_err(), "shift");
        let o = NewtonOptions { null_tolerance: bad, ..NewtonOptions::default() };
        invalid(newton(&model, &theta, &o).unwrap_err(), "null_tolerance");
        let o = RelaxOptions { time_step: bad, ..RelaxOptions::default() };
        invalid(relax(&model, &theta, &o).unwrap_err(), "time_step");
        let o = RelaxOptions { damping: bad, ..RelaxOptions::default() };
        invalid(relax(&model, &theta, &o).unwrap_err(), "damping");
        let o = ModeOptions { cluster: bad, ..ModeOptions::default() };
        invalid(modes(&model, &theta, &o).unwrap_err(), "cluster");
        let k = SymmetricMatrix::tridiagonal(&[1.0, 2.0], &[0.5]).unwrap();
        invalid(classify(&k, bad).unwrap_err(), "relative");
        invalid(maxwell_calladine(&model, &theta, Some(bad)).unwrap_err(), "tolerance");
        let o = AntikinkOptions { zero_tolerance: Some(bad), ..AntikinkOptions::default() };
        invalid(antikink_at(&model, 9.0, &o).unwrap_err(), "zero_tolerance");
        invalid(cobweb(&model, 3, &theta, bad, 11).unwrap_err(), "range");
    }
    // A zero tolerance would make the iteration's stopping test unreachable.
    let o = NewtonOptions { tolerance: 0.0, ..NewtonOptions::default() };
    invalid(newton(&model, &theta, &o).unwrap_err(), "tolerance");
    let o = RelaxOptions { time_step: 0.0, ..RelaxOptions::default() };
    invalid(relax(&model, &theta, &o).unwrap_err(), "time_step");
    // Bands with a NaN: the Sturm counts would be meaningless.
    let nan = SymmetricMatrix::tridiagonal(&[1.0, f64::NAN], &[0.5]).unwrap();
    assert!(matches!(classify(&nan, 1e-10), Err(StaticsError::Linalg(_))));
    // Bands of mismatched lengths are no matrix at all.
    assert!(matches!(
        SymmetricMatrix::tridiagonal(&[1.0, 2.0], &[0.5, 0.5]),
        Err(LinalgError::DimensionMismatch { .. })
    ));
}

#[test]
fn models_with_non_finite_parameters_give_errors_not_nan() {
    let theta = kink(&chain(), 9.5).unwrap();
    for stiffness in [f64::NAN, f64::INFINITY] {
        let model = FieldStiffness { stiffness };
        assert!(model.check().is_err());
        // Finite angles, but the forces and stiffness are not finite: no NaN comes back as Ok.
        assert!(newton(&model, &theta, &NewtonOptions::default()).is_err());
        assert!(modes(&model, &theta, &ModeOptions::default()).is_err());
        assert!(peierls_nabarro(&model, &AntikinkOptions::default()).is_err());
    }
    let model = FieldRestLength { lbar: 5.0 };
    assert!(model.check().is_err() && model.theta_bar().is_nan());
    let theta_bar = |err: StaticsError| matches!(err, StaticsError::InvalidValue { what, .. } if what.contains("theta_bar"));
    assert!(theta_bar(critical_length(&model, 3).unwrap_err()));
    assert!(theta_bar(two_kink_configuration(&model, 3).unwrap_err()));
    assert!(theta_bar(fixed_points(&model, 3).unwrap_err()));
}

#[test]
fn sizes_too_large_to_hold_are_errors_before_allocating() {
    let model = chain();
    let theta = vec![0.58; N];
    assert!(matches!(
        cobweb(&model, 3, &theta, 0.7, MAX_COBWEB_SAMPLES + 1),
        Err(StaticsError::TooLarge { what: "samples", .. })
    ));
    assert!(matches!(
        mechanism_path(&model, 2.0, 9.0, MAX_PATH_STEPS + 1),
        Err(StaticsError::TooLarge { what: "steps", .. })
    ));
    let long = RuntimeChain::builder(10_000, 0.8, 1.0e4, 0.58).build().unwrap();
    let theta = vec![0.58; 10_000];
    // The chain's count runs in O(n) on its Golub-Kahan tridiagonal (issue 37): 10 000 rotors are
    // counted, not refused (chain-core/tests/counting.rs checks it against a dense SVD); every
    // mode of them would not fit.
    let counting = maxwell_calladine(&long, &theta, None).unwrap();
    assert_eq!((counting.zero_modes.len(), counting.self_stresses.len()), (1, 0));
    let all = ModeOptions { count: None, ..ModeOptions::default() };
    assert!(matches!(modes(&long, &theta, &all), Err(StaticsError::TooLarge { .. })));
}

#[test]
fn a_chain_too_short_for_a_barrier_is_an_error_naming_the_minimum() {
    for n in [2, 3] {
        let model = RuntimeChain::builder(n, 0.8, 1.0e4, 0.58).build().unwrap();
        match peierls_nabarro(&model, &AntikinkOptions::default()) {
            Err(e @ StaticsError::InvalidValue { .. }) => {
                let text = e.to_string();
                assert!(text.contains(&format!("= {n} is invalid: expected at least 4")), "{text}");
            }
            other => panic!("n = {n}: expected InvalidValue, got {other:?}"),
        }
    }
    let model = RuntimeChain::builder(4, 0.8, 1.0e4, 0.58).build().unwrap();
    let pn = peierls_nabarro(&model, &AntikinkOptions::default()).unwrap();
    assert!(pn.barrier > 0.0, "{}", pn.barrier);
}

#[test]
fn the_shortest_chains_do_not_panic() {
    for n in [2, 3] {
        let model = RuntimeChain::builder(n, 0.8, 1.0e4, 0.58).build().unwrap();
        let centre = (n - 1) as f64 / 2.0;
        // Any outcome but a panic: an antikink may not fit, which is an error.
        let _ = antikink_relaxed(&model, centre, &AntikinkOptions::default());
        let _ = peierls_nabarro(&model, &AntikinkOptions::default());
        let _ = impurity_analysis(&model, 0);
        let theta = vec![0.58; n];
        assert!(modes(&model, &theta, &ModeOptions::default()).is_ok());
        assert!(maxwell_calladine(&model, &theta, None).is_ok());
    }
}
