//! Every field of every public options struct of chain-core is validated (issue 37): each struct
//! is destructured without `..` (a new field does not compile until it is listed here), and each
//! field is given its invalid values (NaN, the infinities, the wrong sign, 0 where 0 is invalid,
//! a count below its minimum) and must fail [`Validate::validate`] with the error naming that
//! struct, that field and that value; the valid value it replaces must pass. A field that takes
//! every value says why; a count is enumerated at both ends of its documented range (the bound
//! passes, the bound + 1 and the invalid low values fail, and the rule states the bound). The
//! checks are test-support's (`options`), shared with chain-network's and chain-sweep's tests.
//! Then every entry point that takes a struct refuses it the same way
//! (`ScatterSetup::clear = NaN` used to run and return `Ok(Transmitted)`), and the numbers in
//! these errors and in other statics, dynamics and integration errors print short (`5e-324`,
//! `1e300`), never as hundreds of digits.

use chain_core::RuntimeChain;
use chain_core::dynamics::integrate::{
    AdaptiveOptions, Flow, Sponge, State, VerletOptions, adaptive, verlet,
};
use chain_core::dynamics::run::MAX_SPACE_TIME_VALUES;
use chain_core::dynamics::run::{Method, RunOptions, propagate};
use chain_core::dynamics::scatter::{EnergyBudget, ScatterSetup, scatter, scatter_within_budget};
use chain_core::geometry::MAX_ROTORS;
use chain_core::integrate::MAX_STEP_BUDGET;
use chain_core::statics::MAX_DENSE_VALUES;
use chain_core::statics::antikink::{AntikinkOptions, Ends, antikink_at, peierls_nabarro};
use chain_core::statics::equilibrium::{NewtonOptions, RelaxOptions, newton, relax};
use chain_core::statics::kink::kink;
use chain_core::statics::modes::{ModeOptions, modes};
use chain_core::statics::walls::Charge;
use chain_core::validate::Validate;
use test_support::options::{any_value, assert_names, count_range, rule_states, values as floats};

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;
/// The smallest subnormal: negated, the smallest violation of a sign.
const TINY: f64 = 5e-324;
/// What a field that must be finite and `>= 0` refuses.
const NON_NEGATIVE: &[f64] = &[NAN, INF, -INF, -1.0, -TINY];
/// What a field that must be finite and `> 0` refuses.
const POSITIVE: &[f64] = &[NAN, INF, -INF, -1.0, -TINY, 0.0];
/// What a field that must be finite refuses.
const FINITE: &[f64] = &[NAN, INF, -INF];

#[test]
fn every_field_of_run_options_is_validated() {
    let base = RunOptions::default();
    let RunOptions {
        t_max,
        output_interval,
        method: _,
        dt: _,
        damping,
        absorbing_ends: _,
        space_time,
        max_outputs,
        max_steps,
        energy_limit,
    } = base;
    let o = "RunOptions";
    floats(o, "t_max", t_max, FINITE, |v| RunOptions { t_max: v, ..base });
    floats(o, "output_interval", output_interval, POSITIVE, |v| RunOptions { output_interval: v, ..base });
    // The method's tolerances, named `method.rtol` and `method.atol`.
    let dop = |rtol, atol| RunOptions { method: Method::Dop853 { rtol, atol }, ..base };
    floats(o, "method.rtol", 1e-10, NON_NEGATIVE, |v| dop(v, 1e-11));
    floats(o, "method.atol", 1e-11, POSITIVE, |v| dop(1e-10, v));
    floats(o, "dt", 1e-3, POSITIVE, |v| RunOptions { dt: Some(v), ..base });
    floats(o, "damping", damping, NON_NEGATIVE, |v| RunOptions { damping: v, ..base });
    // The sponge names itself.
    let sponge = |strength| RunOptions { absorbing_ends: Some(Sponge { width: 10, strength }), ..base };
    floats("Sponge", "strength", 30.0, NON_NEGATIVE, sponge);
    any_value("space_time", [RunOptions { space_time: !space_time, ..base }, base]);
    // Between 1 and the space-time image's bound (an output records at least one value).
    assert!((1..=MAX_SPACE_TIME_VALUES).contains(&max_outputs));
    let most = MAX_SPACE_TIME_VALUES as u64;
    let o_max = count_range(o, "max_outputs", 1, most, |v| RunOptions { max_outputs: v as usize, ..base });
    rule_states(o_max, most);
    // Between 1 and every integrator's step budget bound.
    assert!((1..=MAX_STEP_BUDGET).contains(&max_steps));
    rule_states(
        count_range(o, "max_steps", 1, MAX_STEP_BUDGET, |v| RunOptions { max_steps: v, ..base }),
        MAX_STEP_BUDGET,
    );
    // Infinite switches the energy check off; NaN, 0 and below are refused.
    floats(o, "energy_limit", energy_limit, &[NAN, -INF, -1.0, 0.0], |v| RunOptions {
        energy_limit: v,
        ..base
    });
    assert!(RunOptions { energy_limit: INF, ..base }.validate().is_ok());
}

#[test]
fn every_field_of_the_integrators_options_is_validated() {
    let Sponge { width, strength } = Sponge { width: 10, strength: 30.0 };
    floats("Sponge", "strength", strength, NON_NEGATIVE, |v| Sponge { width, strength: v });
    // 0 is no sponge, a width beyond half the chain overlaps the two; no chain has more than
    // MAX_ROTORS rotors.
    assert!(width <= MAX_ROTORS);
    let o_width =
        count_range("Sponge", "width", 0, MAX_ROTORS as u64, |v| Sponge { width: v as usize, strength });
    rule_states(o_width, MAX_ROTORS as u64);

    let base = VerletOptions::new(1e-3);
    let VerletOptions { dt, damping, sponge: _, max_steps, energy_limit } = base;
    let o = "VerletOptions";
    floats(o, "dt", dt, POSITIVE, |v| VerletOptions { dt: v, ..base });
    floats(o, "damping", damping, NON_NEGATIVE, |v| VerletOptions { damping: v, ..base });
    floats("Sponge", "strength", 1.0, NON_NEGATIVE, |v| VerletOptions {
        sponge: Some(Sponge { width: 3, strength: v }),
        ..base
    });
    assert!((1..=MAX_STEP_BUDGET).contains(&max_steps));
    let o_steps = count_range(o, "max_steps", 1, MAX_STEP_BUDGET, |v| VerletOptions { max_steps: v, ..base });
    rule_states(o_steps, MAX_STEP_BUDGET);
    floats(o, "energy_limit", energy_limit, &[NAN, -1.0, 0.0], |v| VerletOptions { energy_limit: v, ..base });

    let base = AdaptiveOptions::default();
    let AdaptiveOptions {
        rtol,
        atol,
        initial_step: _,
        max_step,
        min_step,
        max_steps,
        damping,
        sponge: _,
        energy_limit,
        omega_max: _,
    } = base;
    let o = "AdaptiveOptions";
    floats(o, "rtol", rtol, NON_NEGATIVE, |v| AdaptiveOptions { rtol: v, ..base });
    floats(o, "atol", atol, POSITIVE, |v| AdaptiveOptions { atol: v, ..base });
    floats(o, "initial_step", 1e-3, POSITIVE, |v| AdaptiveOptions { initial_step: Some(v), ..base });
    // Infinite: no limit.
    floats(o, "max_step", max_step, &[NAN, -INF, -1.0, 0.0], |v| AdaptiveOptions { max_step: v, ..base });
    // At most max_step: 2 when the longest step is 1.
    let capped = AdaptiveOptions { max_step: 1.0, ..base };
    floats(o, "min_step", min_step, &[NAN, INF, -1.0, 2.0], |v| AdaptiveOptions { min_step: v, ..capped });
    assert!((1..=MAX_STEP_BUDGET).contains(&(max_steps as u64)));
    let o_steps = count_range(o, "max_steps", 1, MAX_STEP_BUDGET, |v| AdaptiveOptions {
        max_steps: v as usize,
        ..base
    });
    rule_states(o_steps, MAX_STEP_BUDGET);
    floats(o, "damping", damping, NON_NEGATIVE, |v| AdaptiveOptions { damping: v, ..base });
    floats("Sponge", "strength", 1.0, NON_NEGATIVE, |v| AdaptiveOptions {
        sponge: Some(Sponge { width: 3, strength: v }),
        ..base
    });
    floats(o, "energy_limit", energy_limit, &[NAN, -1.0, 0.0], |v| AdaptiveOptions {
        energy_limit: v,
        ..base
    });
    floats(o, "omega_max", 100.0, POSITIVE, |v| AdaptiveOptions { omega_max: Some(v), ..base });
}

#[test]
fn every_field_of_the_scattering_setup_and_budget_is_validated() {
    let base = ScatterSetup::from_the_right(Charge::Antikink, 4.8, 29);
    let ScatterSetup {
        charge: _,
        v0,
        impurity,
        start,
        direction: _,
        reach,
        clear,
        edge_margin,
        persistence,
        progress,
        trap_time,
        trap_crossings,
        turns,
        turn_band,
        entry_window,
        cluster_gap,
        pair_age,
        pair_extent,
        break_time,
        grace,
        max_jump,
        confirm,
        watch,
        run,
    } = base;
    let o = "ScatterSetup";
    floats(o, "v0", v0, NON_NEGATIVE, |v| ScatterSetup { v0: v, ..base });
    // Any spring index: whether the chain has it is `check(n)`'s (tested below).
    any_value(
        "impurity",
        [ScatterSetup { impurity: 0, ..base }, ScatterSetup { impurity: usize::MAX, ..base }],
    );
    // Any finite start: where it lies on the chain is `check(n)`'s.
    floats(o, "start", start, FINITE, |v| ScatterSetup { start: v, ..base });
    floats(o, "reach", reach, POSITIVE, |v| ScatterSetup { reach: v, ..base });
    // At least reach (4): the NaN, infinity and negative values, and anything below 4.
    floats(o, "clear", clear, &[NAN, INF, -INF, -1.0, 0.0, TINY, 3.999], |v| ScatterSetup {
        clear: v,
        ..base
    });
    floats(o, "edge_margin", edge_margin, NON_NEGATIVE, |v| ScatterSetup { edge_margin: v, ..base });
    floats(o, "persistence", persistence, NON_NEGATIVE, |v| ScatterSetup { persistence: v, ..base });
    floats(o, "progress", progress, NON_NEGATIVE, |v| ScatterSetup { progress: v, ..base });
    floats(o, "trap_time", trap_time, NON_NEGATIVE, |v| ScatterSetup { trap_time: v, ..base });
    floats(o, "trap_crossings", trap_crossings, NON_NEGATIVE, |v| ScatterSetup { trap_crossings: v, ..base });
    // Between 0 (trapped after trap_time without turning) and the run's max_outputs (a turn is
    // seen at an output): the default's million, and 10 for a run of at most 10 outputs.
    assert!(turns as u64 <= run.max_outputs as u64);
    count_range(o, "turns", 0, run.max_outputs as u64, |v| ScatterSetup { turns: v as usize, ..base });
    let short_run = RunOptions { max_outputs: 10, ..run };
    count_range(o, "turns", 0, 10, |v| ScatterSetup { turns: v as usize, run: short_run, ..base });
    floats(o, "turn_band", turn_band, NON_NEGATIVE, |v| ScatterSetup { turn_band: v, ..base });
    floats(o, "entry_window", entry_window, NON_NEGATIVE, |v| ScatterSetup { entry_window: v, ..base });
    floats(o, "cluster_gap", cluster_gap, POSITIVE, |v| ScatterSetup { cluster_gap: v, ..base });
    floats(o, "pair_age", pair_age, NON_NEGATIVE, |v| ScatterSetup { pair_age: v, ..base });
    floats(o, "pair_extent", pair_extent, NON_NEGATIVE, |v| ScatterSetup { pair_extent: v, ..base });
    floats(o, "break_time", break_time, NON_NEGATIVE, |v| ScatterSetup { break_time: v, ..base });
    floats(o, "grace", grace, NON_NEGATIVE, |v| ScatterSetup { grace: v, ..base });
    floats(o, "max_jump", max_jump, POSITIVE, |v| ScatterSetup { max_jump: v, ..base });
    floats(o, "confirm", confirm, NON_NEGATIVE, |v| ScatterSetup { confirm: v, ..base });
    floats(o, "watch", watch, NON_NEGATIVE, |v| ScatterSetup { watch: v, ..base });
    // The run's settings are RunOptions' (every field tested above), reached through the setup.
    floats("RunOptions", "t_max", run.t_max, FINITE, |v| ScatterSetup {
        run: RunOptions { t_max: v, ..run },
        ..base
    });
    let _ = impurity;

    let budget = EnergyBudget::default();
    let EnergyBudget { tolerance, recompute } = budget;
    floats("EnergyBudget", "tolerance", tolerance, POSITIVE, |v| EnergyBudget { tolerance: v, ..budget });
    any_value("recompute", [EnergyBudget { recompute: !recompute, ..budget }, budget]);
}

#[test]
fn every_field_of_the_statics_options_is_validated() {
    let base = NewtonOptions::default();
    let NewtonOptions { tolerance, max_iterations, shift, null_tolerance, hold_ends, max_held } = base;
    let o = "NewtonOptions";
    floats(o, "tolerance", tolerance, POSITIVE, |v| NewtonOptions { tolerance: v, ..base });
    // 0 iterations measures the start's residual; a thousand is far beyond quadratic
    // convergence's handful.
    let most = NewtonOptions::MAX_ITERATIONS as u64;
    assert!(max_iterations as u64 <= most && most == 1000);
    let o_iterations =
        count_range(o, "max_iterations", 0, most, |v| NewtonOptions { max_iterations: v as usize, ..base });
    rule_states(o_iterations, most);
    floats(o, "shift", shift, NON_NEGATIVE, |v| NewtonOptions { shift: v, ..base });
    floats(o, "null_tolerance", null_tolerance, NON_NEGATIVE, |v| NewtonOptions {
        null_tolerance: v,
        ..base
    });
    any_value("hold_ends", [NewtonOptions { hold_ends: !hold_ends, ..base }, base]);
    // 0 holds none; one more direction is held per step at most, so no more than the steps.
    assert!(max_held as u64 <= most);
    rule_states(
        count_range(o, "max_held", 0, most, |v| NewtonOptions { max_held: v as usize, ..base }),
        most,
    );

    let base = RelaxOptions::default();
    let RelaxOptions { tolerance, max_steps, time_step, damping, hold_ends } = base;
    let o = "RelaxOptions";
    floats(o, "tolerance", tolerance, POSITIVE, |v| RelaxOptions { tolerance: v, ..base });
    // 0: the start, if it meets the tolerance; at most every integrator's step budget bound.
    assert!(max_steps as u64 <= MAX_STEP_BUDGET);
    let o_steps =
        count_range(o, "max_steps", 0, MAX_STEP_BUDGET, |v| RelaxOptions { max_steps: v as usize, ..base });
    rule_states(o_steps, MAX_STEP_BUDGET);
    // Below 2: velocity Verlet's stability limit in units of 1 / omega_max.
    floats(o, "time_step", time_step, &[NAN, INF, -1.0, 0.0, 2.0, 1e300], |v| RelaxOptions {
        time_step: v,
        ..base
    });
    floats(o, "damping", damping, NON_NEGATIVE, |v| RelaxOptions { damping: v, ..base });
    any_value("hold_ends", [RelaxOptions { hold_ends: !hold_ends, ..base }, base]);

    let base = ModeOptions::default();
    let ModeOptions { count, cluster, localised_fraction, localised_widths, reach, hold_ends } = base;
    let o = "ModeOptions";
    // Some(0): no mode; None: all; at most MAX_DENSE_VALUES, the bound on the modes' count x n
    // values (so no chain gives more modes).
    assert_eq!(count, Some(12));
    let most = MAX_DENSE_VALUES as u64;
    rule_states(count_range(o, "count", 0, most, |v| ModeOptions { count: Some(v as usize), ..base }), most);
    assert!(ModeOptions { count: None, ..base }.validate().is_ok());
    floats(o, "cluster", cluster, NON_NEGATIVE, |v| ModeOptions { cluster: v, ..base });
    // A fraction of the rotors: in [0, 1].
    floats(o, "localised_fraction", localised_fraction, &[NAN, INF, -TINY, 1.0 + f64::EPSILON], |v| {
        ModeOptions { localised_fraction: v, ..base }
    });
    floats(o, "localised_widths", localised_widths, NON_NEGATIVE, |v| ModeOptions {
        localised_widths: v,
        ..base
    });
    floats(o, "reach", reach, NON_NEGATIVE, |v| ModeOptions { reach: v, ..base });
    any_value("hold_ends", [ModeOptions { hold_ends: !hold_ends, ..base }, base]);

    let base = AntikinkOptions::default();
    let AntikinkOptions { newton, relax, zero_tolerance: _, ends } = base;
    // The nested settings are NewtonOptions' and RelaxOptions' (every field tested above).
    floats("NewtonOptions", "shift", newton.shift, NON_NEGATIVE, |v| AntikinkOptions {
        newton: NewtonOptions { shift: v, ..newton },
        ..base
    });
    floats("RelaxOptions", "damping", relax.damping, NON_NEGATIVE, |v| AntikinkOptions {
        relax: RelaxOptions { damping: v, ..relax },
        ..base
    });
    floats("AntikinkOptions", "zero_tolerance", 1e-9, NON_NEGATIVE, |v| AntikinkOptions {
        zero_tolerance: Some(v),
        ..base
    });
    any_value("ends", [AntikinkOptions { ends: Ends::Free, ..base }, AntikinkOptions { ends, ..base }]);
}

fn paper() -> RuntimeChain {
    RuntimeChain::builder(60, 0.8, 1.0e4, 0.28).build().unwrap()
}

#[test]
fn every_entry_point_refuses_an_invalid_struct() {
    let chain = paper();
    // The case: `clear` NaN, infinite or negative ran and returned Ok(Transmitted).
    for clear in [NAN, INF, -1.0] {
        let setup = ScatterSetup { clear, ..ScatterSetup::from_the_right(Charge::Kink, 2.0, 29) };
        assert_names(&scatter(&chain, &setup).unwrap_err(), "ScatterSetup", "clear", clear);
        let budget = EnergyBudget::default();
        assert_names(
            &scatter_within_budget(&chain, &setup, &budget).unwrap_err(),
            "ScatterSetup",
            "clear",
            clear,
        );
    }
    let setup = ScatterSetup::from_the_right(Charge::Kink, 2.0, 29);
    let budget = EnergyBudget { tolerance: NAN, ..EnergyBudget::default() };
    assert_names(
        &scatter_within_budget(&chain, &setup, &budget).unwrap_err(),
        "EnergyBudget",
        "tolerance",
        NAN,
    );

    let theta = kink(&chain, 30.0).unwrap();
    let options = RunOptions { output_interval: -TINY, ..RunOptions::default() };
    let e = propagate(&chain, State::at_rest(theta.clone()), &options, &mut |_| false).unwrap_err();
    assert_names(&e, "RunOptions", "output_interval", -TINY);

    let options = VerletOptions { energy_limit: NAN, ..VerletOptions::new(1e-3) };
    let e = verlet(&chain, &mut State::at_rest(theta.clone()), 0.1, &options, 1, &mut |_| Flow::Continue);
    assert_names(&e.unwrap_err(), "VerletOptions", "energy_limit", NAN);
    let options = AdaptiveOptions { atol: 0.0, ..AdaptiveOptions::default() };
    let e = adaptive(&chain, &mut State::at_rest(theta.clone()), &[0.1], &options, &mut |_| Flow::Continue);
    assert_names(&e.unwrap_err(), "AdaptiveOptions", "atol", 0.0);

    let options = NewtonOptions { null_tolerance: INF, ..NewtonOptions::default() };
    assert_names(&newton(&chain, &theta, &options).unwrap_err(), "NewtonOptions", "null_tolerance", INF);
    let options = RelaxOptions { time_step: 3.0, ..RelaxOptions::default() };
    assert_names(&relax(&chain, &theta, &options).unwrap_err(), "RelaxOptions", "time_step", 3.0);
    let options = ModeOptions { localised_fraction: 2.0, ..ModeOptions::default() };
    assert_names(&modes(&chain, &theta, &options).unwrap_err(), "ModeOptions", "localised_fraction", 2.0);
    // Counts past their bounds: refused before any step (a relaxation of usize::MAX steps
    // towards a tolerance it cannot meet would never end in practice).
    let options = RelaxOptions { max_steps: usize::MAX, tolerance: TINY, ..RelaxOptions::default() };
    let e = relax(&chain, &theta, &options).unwrap_err();
    assert_names(&e, "RelaxOptions", "max_steps", usize::MAX as f64);
    let options = NewtonOptions { max_iterations: 1001, ..NewtonOptions::default() };
    assert_names(&newton(&chain, &theta, &options).unwrap_err(), "NewtonOptions", "max_iterations", 1001.0);
    let options = ModeOptions { count: Some(usize::MAX), ..ModeOptions::default() };
    assert_names(&modes(&chain, &theta, &options).unwrap_err(), "ModeOptions", "count", usize::MAX as f64);
    let options = RunOptions { max_steps: MAX_STEP_BUDGET + 1, ..RunOptions::default() };
    let e = propagate(&chain, State::at_rest(theta.clone()), &options, &mut |_| false).unwrap_err();
    assert_names(&e, "RunOptions", "max_steps", (MAX_STEP_BUDGET + 1) as f64);
    let options = AntikinkOptions { zero_tolerance: Some(-1.0), ..AntikinkOptions::default() };
    assert_names(
        &antikink_at(&chain, 30.0, &options).unwrap_err(),
        "AntikinkOptions",
        "zero_tolerance",
        -1.0,
    );
    let options = AntikinkOptions {
        relax: RelaxOptions { tolerance: NAN, ..RelaxOptions::default() },
        ..AntikinkOptions::default()
    };
    assert_names(&peierls_nabarro(&chain, &options).unwrap_err(), "RelaxOptions", "tolerance", NAN);
}

/// No run of hundreds of digits: the text of `error` holds `expected` and no run of 20 digits.
fn short(error: &dyn std::fmt::Display, expected: &str) {
    let text = error.to_string();
    assert!(text.contains(expected), "{text}");
    let longest = text.split(|c: char| !c.is_ascii_digit()).map(str::len).max().unwrap_or(0);
    assert!(longest < 20, "a number of {longest} digits in {text}");
}

#[test]
fn numbers_in_the_errors_print_short() {
    let chain = paper();
    // Validation errors.
    let setup = ScatterSetup { clear: TINY, ..ScatterSetup::from_the_right(Charge::Kink, 2.0, 29) };
    short(&setup.validate().unwrap_err(), "ScatterSetup.clear = 5e-324 is invalid");
    let options = RelaxOptions { time_step: 1e300, ..RelaxOptions::default() };
    short(&options.validate().unwrap_err(), "RelaxOptions.time_step = 1e300 is invalid");
    let options = RunOptions { dt: Some(-1e300), ..RunOptions::default() };
    short(&options.validate().unwrap_err(), "RunOptions.dt = -1e300 is invalid");
    // A statics error (a centre off the chain), a dynamics error (a start off the chain) and an
    // integration error (an end before the start), with the same numbers.
    short(&kink(&chain, 1e300).unwrap_err(), "centre 1e300 is outside the chain");
    let setup = ScatterSetup { start: 1e300, ..ScatterSetup::from_the_right(Charge::Kink, 2.0, 29) };
    short(&scatter(&chain, &setup).unwrap_err(), "ScatterSetup.start = 1e300 is invalid");
    let mut state = State { time: 1e300, ..State::at_rest(kink(&chain, 30.0).unwrap()) };
    let e =
        verlet(&chain, &mut state, TINY, &VerletOptions::new(1e-3), 1, &mut |_| Flow::Continue).unwrap_err();
    short(&e, "the end time 5e-324 lies before the start time 1e300");
}
