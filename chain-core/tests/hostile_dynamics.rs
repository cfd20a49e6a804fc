//! Hostile inputs to the dynamics (issue 10): every one ends quickly in a typed error that carries
//! the numbers, never in a hang, a panic, or an `Ok` for a run that went wrong. Each class is
//! tried with several inputs.

use std::time::{Duration, Instant};

use chain_core::Potential;
use chain_core::RuntimeChain;
use chain_core::dynamics::DynamicsError;
use chain_core::dynamics::integrate::{
    AdaptiveOptions, Flow, IntegrateError, Integrator, Schedule, State, VerletOptions, adaptive, verlet,
};
use chain_core::dynamics::launch::Direction;
use chain_core::dynamics::run::{Method, RunOptions, propagate};
use chain_core::dynamics::scatter::{ScatterSetup, scatter};
use chain_core::error::ParameterError;
use chain_core::statics::walls::Charge;

fn paper() -> RuntimeChain {
    RuntimeChain::builder(60, 0.8, 1.0e4, 0.28).build().unwrap()
}

/// A kink of the paper's chain, at rest.
fn at_rest(model: &RuntimeChain) -> State {
    State::at_rest(chain_core::statics::kink::kink(model, 30.0).unwrap())
}

/// Runs `f` and checks it returned within a second: the class "hangs" is about time.
fn quickly<T>(what: &str, f: impl FnOnce() -> T) -> T {
    let start = Instant::now();
    let result = f();
    assert!(start.elapsed() < Duration::from_secs(10), "{what} took {:?}", start.elapsed());
    result
}

fn run(model: &RuntimeChain, options: RunOptions) -> Result<(), DynamicsError> {
    propagate(model, at_rest(model), &options, &mut |_| false).map(|_| ())
}

#[test]
fn a_step_that_is_zero_negative_or_not_a_number_is_refused() {
    let model = paper();
    for dt in [0.0, -0.0, -1e-3, f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -f64::MIN_POSITIVE] {
        let e = quickly(&format!("dt {dt}"), || {
            run(&model, RunOptions { dt: Some(dt), ..RunOptions::default() })
        });
        assert!(
            matches!(e, Err(DynamicsError::Integrate(IntegrateError::InvalidOption { name: "dt", .. }))),
            "dt = {dt}: {e:?}"
        );
    }
}

/// A tip mass so small that `1 / (M r^2)` overflows is a bad inertia for every integrator, with
/// or without a step given (an early version reported "dt = 0 is invalid", a step the user never
/// gave); a stiffness so large for its inertia that the frequency bound overflows has no default
/// step, and says so with the numbers. Masses small but representable still run.
#[test]
fn an_inertia_too_small_for_any_stable_step_is_refused_with_the_reason() {
    // A runtime chain this light says at build that its scale underflowed (M r^2 below the
    // normal numbers), so no run of it starts; the integrators' own BadInertia check is for
    // models built otherwise. The lightest chain that builds still has a finite 1 / (M r^2).
    for mass in [1e-310, 5e-324] {
        let built = RuntimeChain::builder(60, 0.8, 1.0e4, 0.28).mass(mass).build();
        assert!(
            matches!(built, Err(ParameterError::ScaleUnderflow { quantity: "M r^2", value }) if value == mass * 0.64),
            "mass {mass}: {built:?}"
        );
    }
    let stiff = RuntimeChain::builder(60, 0.8, 1.0e305, 0.28).mass(1e-5).build().unwrap();
    match quickly("stiff, light", || run(&stiff, RunOptions::default())) {
        Err(DynamicsError::Integrate(IntegrateError::NoStableStep { norm, inverse_inertia })) => {
            let finite = norm > 0.0 && norm.is_finite();
            assert!(finite && inverse_inertia == 1.0 / stiff.inertia(0), "{norm} {inverse_inertia}");
            assert_eq!(norm * inverse_inertia, f64::INFINITY);
        }
        other => panic!("k = 1e305, M = 1e-5: {other:?}"),
    }
    let light = RuntimeChain::builder(60, 0.8, 1.0e4, 0.28).mass(1e-6).build().unwrap();
    run(&light, RunOptions { t_max: 1e-4, output_interval: 1e-5, ..RunOptions::default() }).unwrap();
}

#[test]
fn runs_too_long_for_their_budgets_are_refused_before_they_start() {
    let model = paper();
    // An output interval far below the step: the step is cut to the interval, and the outputs
    // (and steps) needed exceed the budgets.
    for interval in [1e-300, 1e-12, 1e-8] {
        let e = quickly("tiny interval", || {
            run(&model, RunOptions { output_interval: interval, ..RunOptions::default() })
        });
        assert!(
            matches!(e, Err(DynamicsError::Integrate(IntegrateError::OutputBudget { .. }))),
            "interval {interval}: {e:?}"
        );
    }
    // A step far below the span, with outputs rare enough to fit their budget: the step budget.
    for dt in [1e-12, 1e-9, 1e-7] {
        let options = RunOptions { dt: Some(dt), output_interval: 1.0, ..RunOptions::default() };
        let e = quickly("tiny step", || run(&model, options));
        match e {
            Err(DynamicsError::Integrate(IntegrateError::StepBudget { steps, budget, dt: step, .. })) => {
                assert!(steps > budget as f64 && step == dt, "{steps} {budget}");
            }
            other => panic!("dt {dt}: {other:?}"),
        }
    }
    // An output interval longer than the run: one output, at `start + interval`, whose steps
    // the budget refuses, with that span in the error (not 0).
    for interval in [1e6, 1e300] {
        let options = RunOptions { t_max: 1.0, output_interval: interval, ..RunOptions::default() };
        match quickly("long interval", || run(&model, options)) {
            Err(DynamicsError::Integrate(IntegrateError::StepBudget { span, steps, budget, .. })) => {
                assert!(span == interval && steps > budget as f64, "{span} {steps} {budget}");
            }
            other => panic!("interval {interval}: {other:?}"),
        }
    }
    // A stiffness so large that the stable step is ~1e-22 (and others): refused, not run.
    for k in [1e20, 1e30, 1e44] {
        let stiff = RuntimeChain::builder(60, 0.8, k, 0.28).build().unwrap();
        let options = RunOptions { output_interval: 1.0, ..RunOptions::default() };
        let e = quickly("stiff chain", || run(&stiff, options));
        assert!(
            matches!(e, Err(DynamicsError::Integrate(IntegrateError::StepBudget { .. }))),
            "k = {k}: {e:?}"
        );
        // DOP853 refuses it too, from its own step budget.
        let options = RunOptions { method: Method::dop853(), output_interval: 1.0, ..RunOptions::default() };
        let mut state = at_rest(&stiff);
        state.omega[30] = 1.0;
        let e =
            quickly("stiff chain, DOP853", || propagate(&stiff, state, &options, &mut |_| false).map(|_| ()));
        assert!(
            matches!(e, Err(DynamicsError::Integrate(IntegrateError::StepBudget { .. }))),
            "k = {k}: {e:?}"
        );
    }
    // The budgets themselves come from the options.
    let options = RunOptions { max_outputs: 10, ..RunOptions::default() };
    let e = run(&model, options);
    assert!(
        matches!(e, Err(DynamicsError::Integrate(IntegrateError::OutputBudget { budget: 10, .. }))),
        "{e:?}"
    );
    let options = RunOptions { max_steps: 1000, ..RunOptions::default() };
    let e = run(&model, options);
    assert!(
        matches!(e, Err(DynamicsError::Integrate(IntegrateError::StepBudget { budget: 1000, .. }))),
        "{e:?}"
    );
}

#[test]
fn a_space_time_image_beyond_its_budget_is_refused_before_the_run() {
    use chain_core::dynamics::run::MAX_SPACE_TIME_VALUES;
    // 2 000 rotors and 100 001 outputs: 2.0e8 angles, past 2^27 = 1.34e8 (1.6 GB of f64).
    let long = RuntimeChain::builder(2000, 0.8, 1.0e4, 0.28).build().unwrap();
    let options =
        RunOptions { t_max: 100.0, output_interval: 1e-3, space_time: true, ..RunOptions::default() };
    match quickly("space-time budget", || run(&long, options)) {
        Err(DynamicsError::Integrate(IntegrateError::SpaceTimeBudget {
            outputs,
            rotors,
            values,
            budget,
        })) => {
            assert_eq!((outputs, rotors, budget), (100_001, 2000, 1 << 27));
            assert_eq!(values, 100_001.0 * 2000.0);
            assert!(values > MAX_SPACE_TIME_VALUES as f64);
        }
        other => panic!("{other:?}"),
    }
    // Without the image the same outputs are within every budget (the run is cut short here).
    let options = RunOptions { space_time: false, ..options };
    let mut outputs = 0;
    propagate(&long, at_rest(&long), &options, &mut |_| {
        outputs += 1;
        outputs == 3
    })
    .unwrap();
    assert_eq!(outputs, 3);
}

#[test]
fn bad_times_are_refused() {
    let model = paper();
    for (t_max, interval) in
        [(f64::NAN, 0.01), (f64::INFINITY, 0.01), (-1.0, 0.01), (20.0, 0.0), (20.0, -0.01), (20.0, f64::NAN)]
    {
        let e = quickly("bad times", || {
            run(&model, RunOptions { t_max, output_interval: interval, ..RunOptions::default() })
        });
        assert!(matches!(e, Err(DynamicsError::Integrate(_))), "t_max {t_max}, interval {interval}: {e:?}");
    }
    for damping in [-1.0, f64::NAN, f64::INFINITY] {
        let e = run(&model, RunOptions { damping, ..RunOptions::default() });
        assert!(
            matches!(e, Err(DynamicsError::Integrate(IntegrateError::InvalidOption { name: "damping", .. }))),
            "{e:?}"
        );
    }
    for energy_limit in [0.0, -1.0, f64::NAN] {
        let e = run(&model, RunOptions { energy_limit, ..RunOptions::default() });
        assert!(
            matches!(
                e,
                Err(DynamicsError::Integrate(IntegrateError::InvalidOption { name: "energy_limit", .. }))
            ),
            "{e:?}"
        );
    }
}

#[test]
fn an_infinite_starting_energy_is_an_error_not_a_zero_error() {
    // Springs so stiff that the energy of a stretched chain overflows.
    let model = RuntimeChain::builder(20, 0.8, f64::MAX, 0.28).build().unwrap();
    let state = State::at_rest((0..20).map(|i| if i % 2 == 0 { 1.2 } else { -1.2 }).collect());
    assert!(model.energy(&state.theta).is_infinite());
    let options = VerletOptions::new(1e-3);
    let e = verlet(&model, &mut state.clone(), 1.0, &options, 1, &mut |_| Flow::Continue).unwrap_err();
    assert!(matches!(e, IntegrateError::NotFinite { what: "energy", .. }), "{e}");
    let e =
        adaptive(&model, &mut state.clone(), &[1.0], &AdaptiveOptions::default(), &mut |_| Flow::Continue)
            .unwrap_err();
    assert!(matches!(e, IntegrateError::NotFinite { what: "energy", .. }), "{e}");
    // An infinite velocity is caught as such.
    let mut fast = State::at_rest(vec![0.28; 20]);
    fast.omega[3] = f64::INFINITY;
    let e = verlet(&model, &mut fast, 1.0, &options, 1, &mut |_| Flow::Continue).unwrap_err();
    assert!(matches!(e, IntegrateError::NotFinite { what: "omega", index: 3, .. }), "{e}");
}

#[test]
fn a_step_longer_than_the_span_still_reaches_the_end() {
    let model = paper();
    for (dt, span) in [(1e-3, 1e-12), (1.0, 1e-6), (1e-3, 5e-10), (0.5, 0.3)] {
        let mut state = at_rest(&model);
        state.time = 2.0;
        let report =
            verlet(&model, &mut state, 2.0 + span, &VerletOptions::new(dt), 1, &mut |_| Flow::Continue)
                .unwrap();
        assert_eq!(state.time, 2.0 + span, "dt {dt}, span {span}");
        assert!(report.steps >= 1);
    }
    // And a zero span is no step at all.
    let mut state = at_rest(&model);
    let report =
        verlet(&model, &mut state, 0.0, &VerletOptions::new(1e-3), 1, &mut |_| Flow::Continue).unwrap();
    assert_eq!((report.steps, state.time), (0, 0.0));
}

#[test]
fn the_energy_limit_stops_a_run_that_went_wrong_at_any_output_rate() {
    // The trait's Verlet with a step past the stability limit: a typed error with the numbers,
    // whatever the output interval, for the paper's moving antikink.
    let model = paper();
    let launched =
        chain_core::dynamics::launch::launch(&model, Charge::Antikink, 40.0, 4.0, Direction::Left).unwrap();
    let limit = VerletOptions::stable_for(&model, &launched.state.theta, 1.0).unwrap().dt;
    for factor in [1.5, 3.0, 30.0] {
        for interval in [limit * factor, 0.5, 2.0] {
            let options = VerletOptions::new(factor * limit);
            let schedule = Schedule::covering(0.0, 4.0, interval, 1_000_000).unwrap();
            let mut state = launched.state.clone();
            let e = options.integrate(&model, &mut state, &schedule, &mut |_| Flow::Continue).unwrap_err();
            assert!(
                matches!(e, IntegrateError::EnergyNotConserved { .. } | IntegrateError::NotFinite { .. }),
                "{factor}x, interval {interval}: {e}"
            );
        }
    }
}

#[test]
fn impossible_scattering_setups_are_refused() {
    let model = paper();
    let good = ScatterSetup::from_the_right(Charge::Antikink, 4.0, 29);
    let cases: Vec<(&str, ScatterSetup)> = vec![
        ("impurity", ScatterSetup { impurity: 59, ..good }),
        ("impurity", ScatterSetup { impurity: usize::MAX, ..good }),
        ("impurity", ScatterSetup { impurity: 58, start: 70.0, ..good }),
        ("reach", ScatterSetup { reach: f64::NAN, ..good }),
        ("reach", ScatterSetup { reach: 0.0, ..good }),
        ("persistence", ScatterSetup { persistence: -1.0, ..good }),
        ("confirm", ScatterSetup { confirm: f64::INFINITY, ..good }),
        ("start", ScatterSetup { start: 100.0, ..good }),
        ("start", ScatterSetup { start: f64::NAN, ..good }),
        // Within `edge_margin` (3) of an end: the wall would have reached it at once.
        ("start", ScatterSetup { start: 56.5, ..good }),
        ("start", ScatterSetup { start: 2.5, direction: Direction::Right, ..good }),
        ("v0", ScatterSetup { v0: f64::NAN, ..good }),
        ("t_max", ScatterSetup { run: RunOptions { t_max: f64::NAN, ..good.run }, ..good }),
    ];
    for (what, setup) in cases {
        let e = quickly(what, || scatter(&model, &setup));
        assert!(e.is_err(), "{what}: {:?}", e.map(|s| s.outcome));
    }
    // Set-ups whose outcome would mean nothing are refused by name, before any run: a defect
    // launched at the impurity (29.5) or from its far side, and an impurity whose range (reach 4)
    // meets an end zone (edge_margin 3), where no wall can pass it. They were run and labelled
    // "reflected" and "trapped".
    let refused: Vec<(&str, f64, ScatterSetup)> = vec![
        ("start", 29.5, ScatterSetup { start: 29.5, ..good }),
        ("start", 32.0, ScatterSetup { start: 32.0, ..good }),
        ("start", 20.0, ScatterSetup { start: 20.0, ..good }),
        ("start", 40.0, ScatterSetup { start: 40.0, direction: Direction::Right, ..good }),
        ("impurity", 0.0, ScatterSetup { impurity: 0, start: 15.5, ..good }),
        ("impurity", 6.0, ScatterSetup { impurity: 6, start: 21.5, ..good }),
        ("impurity", 52.0, ScatterSetup { impurity: 52, start: 40.0, direction: Direction::Right, ..good }),
    ];
    // `clear` was never checked: NaN, infinity or a negative value ran and gave `Transmitted`.
    let mut refused = refused;
    for clear in [f64::NAN, f64::INFINITY, -1.0, 3.9] {
        refused.push(("clear", clear, ScatterSetup { clear, ..good }));
    }
    refused.push(("v0", -1.0, ScatterSetup { v0: -1.0, ..good }));
    for (name, value, setup) in refused {
        match quickly(name, || scatter(&model, &setup)) {
            Err(DynamicsError::InvalidSetup { name: got, value: v, .. }) => {
                assert_eq!((got, v.to_bits()), (name, value.to_bits()), "{setup:?}");
            }
            other => panic!("{name} = {value}: {:?}", other.map(|s| s.outcome)),
        }
    }
    // The nearest set-ups that keep the rules are accepted: an impurity at spring 7 (range 3.5 ..
    // 11.5), a start just beyond reach, launched right.
    for setup in [
        ScatterSetup { impurity: 7, start: 22.5, ..good },
        ScatterSetup { start: 33.6, ..good },
        ScatterSetup { start: 25.4, direction: Direction::Right, ..good },
    ] {
        assert!(setup.check(60).is_ok(), "{setup:?}");
    }
}
