//! `RuntimeChain::builder` applies the macro's rules (chain-geometry's, one set for both) and
//! returns a typed error for every hostile size or override: never a panic, an abort or a
//! silently accepted override. The compile-time side of the same rules is in `ui-tests/tests/ui/`.

use rotor_chain::geometry::{IndexKind, MAX_ROTORS};
use rotor_chain::prelude::*;

fn builder(n: usize) -> rotor_chain::ChainBuilder {
    RuntimeChain::builder(n, 0.8, 1.0e4, 0.58)
}

#[test]
fn absurd_sizes_are_errors_with_the_numbers() {
    for n in [MAX_ROTORS + 1, 1 << 40, 1 << 62, usize::MAX / 8, usize::MAX - 1, usize::MAX] {
        match builder(n).build() {
            Err(ParameterError::TooManyRotors { n: got, max }) => {
                assert_eq!((got, max), (n, MAX_ROTORS));
                let message = ParameterError::TooManyRotors { n, max }.to_string();
                assert!(message.contains(&n.to_string()) && message.contains(&MAX_ROTORS.to_string()));
            }
            other => panic!("n = {n}: {other:?}"),
        }
    }
    for n in [0, 1] {
        assert_eq!(builder(n).build(), Err(ParameterError::TooFewRotors { n }));
    }
    // The limit itself is accepted (chain-geometry's unit test; allocating it here would take
    // 2.4 GB).
    assert_eq!(rotor_chain::geometry::check_rotor_count(MAX_ROTORS), Ok(MAX_ROTORS));
}

#[test]
fn an_override_that_gives_nothing_is_an_error() {
    for p in [0, 3, 8] {
        assert_eq!(
            builder(10).spring(p, None, None).build(),
            Err(ParameterError::EmptyOverride { kind: IndexKind::Spring, index: p })
        );
    }
}

#[test]
fn an_override_repeated_is_an_error_whatever_it_gives() {
    let cases = [
        builder(10).spring_constant(3, 2.0).spring_rest_length(3, 1.7),
        builder(10).spring_constant(3, 2.0).spring_constant(3, 2.0),
        builder(10).spring_constant(4, 2.0).spring(3, Some(1.0), Some(1.8)).spring_constant(3, 2.0),
    ];
    for case in cases {
        assert_eq!(case.build(), Err(ParameterError::OverriddenTwice { kind: IndexKind::Spring, index: 3 }));
    }
    assert_eq!(
        builder(10).rotor(2, 0.7).rotor(5, 0.7).rotor(2, 0.6).build(),
        Err(ParameterError::OverriddenTwice { kind: IndexKind::Rotor, index: 2 })
    );
}

#[test]
fn overrides_of_missing_springs_and_rotors_are_errors() {
    for (p, springs) in [(9, 9), (100, 9), (usize::MAX, 9)] {
        assert_eq!(
            builder(10).spring_constant(p, 1.0).build(),
            Err(ParameterError::IndexOutOfRange { kind: IndexKind::Spring, index: p, count: springs })
        );
    }
    assert_eq!(
        builder(10).rotor(10, 0.7).build(),
        Err(ParameterError::IndexOutOfRange { kind: IndexKind::Rotor, index: 10, count: 10 })
    );
}

#[test]
fn the_runtime_error_says_what_the_compile_error_says() {
    // The texts of the modules spring_overrides_nothing and spring_overridden_twice in
    // ui-tests/tests/ui/compile_fail/keys.stderr, from the same Display.
    let empty = builder(10).spring(3, None, None).build().unwrap_err().to_string();
    assert_eq!(
        empty,
        "the override of spring 3 changes nothing: give a stiffness `k` and/or a rest length `l0`"
    );
    let twice = builder(10).spring_constant(3, 1.0).spring_rest_length(3, 1.7).build().unwrap_err();
    assert_eq!(twice.to_string(), "spring 3 is overridden twice: give all of its values in one override");
}

#[test]
fn valid_overrides_still_apply() {
    let chain = builder(10).spring_constant(3, 2.0).spring_rest_length(4, 1.9).rotor(2, 0.7).build().unwrap();
    assert_eq!((chain.spring_constant(3), chain.rest_length(4), chain.rotor_length(2)), (2.0, 1.9, 0.7));
    assert_eq!(chain.spring_constant(4), 1.0e4);
}

#[test]
fn messages_count_in_the_singular_and_name_a_nan() {
    // A two-rotor chain has one spring: the message says so in the singular.
    let one = RuntimeChain::builder(2, 0.8, 1.0e4, 0.58).spring_constant(1, 1.0).build().unwrap_err();
    assert_eq!(one.to_string(), "spring index 1 is out of range: the chain has 1 spring, numbered 0 to 0");
    let many = builder(10).rotor(10, 0.7).build().unwrap_err();
    assert_eq!(many.to_string(), "rotor index 10 is out of range: the chain has 10 rotors, numbered 0 to 9");
    // A NaN equilibrium angle is not "<= 0": the message says it must be a number.
    let nan = RuntimeChain::builder(10, 0.8, 1.0e4, f64::NAN).build().unwrap_err().to_string();
    assert!(nan.starts_with("theta_bar = NaN is outside the flipper phase: it must be a number"), "{nan}");
    let zero = RuntimeChain::builder(10, 0.8, 1.0e4, 0.0).build().unwrap_err().to_string();
    assert!(zero.contains("it must be > 0"), "{zero}");
    // The branch solve's error counts the same way.
    let spring = BranchError::NoSuchSpring { spring: 1, springs: 1 }.to_string();
    assert_eq!(spring, "spring index 1 is out of range: the chain has 1 spring");
}
