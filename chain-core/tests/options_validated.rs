//! Every field of every public options struct of chain-core is validated (issue 37): each struct
//! is destructured without `..` (a new field does not compile until it is listed here), and each
//! field is given its invalid values (NaN, the infinities, the wrong sign, 0 where 0 is invalid,
//! a count below its minimum) and must fail [`Validate::validate`] with the error naming that
//! struct, that field and that value; the valid value it replaces must pass. A field that takes
//! every value says why. Then every entry point that takes a struct refuses it the same way
//! (`ScatterSetup::clear = NaN` used to run and return `Ok(Transmitted)`), and the numbers in
//! these errors and in other statics, dynamics and integration errors print short (`5e-324`,
//! `1e300`), never as hundreds of digits.

use chain_core::RuntimeChain;
use chain_core::dynamics::DynamicsError;
use chain_core::dynamics::integrate::{
    AdaptiveOptions, Flow, IntegrateError, Sponge, State, VerletOptions, adaptive, verlet,
};
use chain_core::dynamics::run::{Method, RunOptions, propagate};
use chain_core::dynamics::scatter::{
    BudgetError, EnergyBudget, ScatterSetup, scatter, scatter_within_budget,
};
use chain_core::statics::StaticsError;
use chain_core::statics::antikink::{AntikinkOptions, Ends, antikink_at, peierls_nabarro};
use chain_core::statics::equilibrium::{NewtonOptions, RelaxOptions, newton, relax};
use chain_core::statics::kink::kink;
use chain_core::statics::modes::{ModeOptions, modes};
use chain_core::statics::walls::Charge;
use chain_core::validate::Validate;

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

/// The struct, the field and the value an error names, wherever its `InvalidOption` sits.
trait Names {
    fn names(&self) -> Option<(&'static str, &'static str, f64)>;
}

impl Names for IntegrateError {
    fn names(&self) -> Option<(&'static str, &'static str, f64)> {
        match *self {
            IntegrateError::InvalidOption { options, name, value, .. } => Some((options, name, value)),
            _ => None,
        }
    }
}

impl Names for DynamicsError {
    fn names(&self) -> Option<(&'static str, &'static str, f64)> {
        match self {
            &DynamicsError::InvalidSetup { options, name, value, .. } => Some((options, name, value)),
            DynamicsError::Integrate(e) => e.names(),
            DynamicsError::Statics(e) => e.names(),
            _ => None,
        }
    }
}

impl Names for StaticsError {
    fn names(&self) -> Option<(&'static str, &'static str, f64)> {
        match *self {
            StaticsError::InvalidOption { options, name, value, .. } => Some((options, name, value)),
            _ => None,
        }
    }
}

impl Names for BudgetError {
    fn names(&self) -> Option<(&'static str, &'static str, f64)> {
        match self {
            BudgetError::InvalidOption(o) => Some((o.options, o.field, o.value)),
            BudgetError::Setup(source) => source.names(),
            _ => None,
        }
    }
}

/// `error` names `options`, `field` and exactly `value` (bit for bit; any NaN for a NaN).
fn assert_names<E: Names + std::fmt::Display>(error: &E, options: &str, field: &str, value: f64) {
    let (o, f, v) = error.names().unwrap_or_else(|| panic!("not an invalid option: {error}"));
    assert_eq!((o, f), (options, field), "{error}");
    assert!(v.to_bits() == value.to_bits() || (v.is_nan() && value.is_nan()), "{value} -> {error}");
    assert!(error.to_string().contains(&format!("{options}.{field} = ")), "{error}");
}

/// `make(valid)` validates, and `make(v)` for each `v` of `bad` fails naming `options.field = v`.
fn floats<S: Validate>(options: &str, field: &str, valid: f64, bad: &[f64], make: impl Fn(f64) -> S)
where
    S::Error: Names + std::fmt::Display + std::fmt::Debug,
{
    if let Err(e) = make(valid).validate() {
        panic!("{options}.{field} = {valid} is valid, got {e}");
    }
    for &v in bad {
        match make(v).validate() {
            Ok(()) => panic!("{options}.{field} = {v} passed"),
            Err(e) => assert_names(&e, options, field, v),
        }
    }
}

/// As [`floats`], for a count.
fn counts<S: Validate>(options: &str, field: &str, valid: u64, bad: &[u64], make: impl Fn(u64) -> S)
where
    S::Error: Names + std::fmt::Display + std::fmt::Debug,
{
    if let Err(e) = make(valid).validate() {
        panic!("{options}.{field} = {valid} is valid, got {e}");
    }
    for &v in bad {
        match make(v).validate() {
            Ok(()) => panic!("{options}.{field} = {v} passed"),
            Err(e) => assert_names(&e, options, field, v as f64),
        }
    }
}

/// A field that takes every value: two of them pass.
fn any_value<S: Validate>(what: &str, values: [S; 2])
where
    S::Error: std::fmt::Debug,
{
    for s in values {
        assert!(s.validate().is_ok(), "{what}: every value is valid");
    }
}

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
    counts(o, "max_outputs", max_outputs as u64, &[0], |v| RunOptions { max_outputs: v as usize, ..base });
    counts(o, "max_steps", max_steps, &[0], |v| RunOptions { max_steps: v, ..base });
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
    // Any width: 0 is no sponge, a width beyond half the chain overlaps the two.
    any_value("width", [Sponge { width: 0, strength }, Sponge { width: usize::MAX, strength }]);

    let base = VerletOptions::new(1e-3);
    let VerletOptions { dt, damping, sponge: _, max_steps, energy_limit } = base;
    let o = "VerletOptions";
    floats(o, "dt", dt, POSITIVE, |v| VerletOptions { dt: v, ..base });
    floats(o, "damping", damping, NON_NEGATIVE, |v| VerletOptions { damping: v, ..base });
    floats("Sponge", "strength", 1.0, NON_NEGATIVE, |v| VerletOptions {
        sponge: Some(Sponge { width: 3, strength: v }),
        ..base
    });
    counts(o, "max_steps", max_steps, &[0], |v| VerletOptions { max_steps: v, ..base });
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
    counts(o, "max_steps", max_steps as u64, &[0], |v| AdaptiveOptions { max_steps: v as usize, ..base });
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
    // Any count of turns (0: trapped after trap_time without turning).
    any_value("turns", [ScatterSetup { turns: 0, ..base }, ScatterSetup { turns: turns + 1000, ..base }]);
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
    // Any count: 0 iterations measures the start's residual; 0 held directions holds none.
    any_value(
        "max_iterations",
        [
            NewtonOptions { max_iterations: 0, ..base },
            NewtonOptions { max_iterations: max_iterations * 1000, ..base },
        ],
    );
    floats(o, "shift", shift, NON_NEGATIVE, |v| NewtonOptions { shift: v, ..base });
    floats(o, "null_tolerance", null_tolerance, NON_NEGATIVE, |v| NewtonOptions {
        null_tolerance: v,
        ..base
    });
    any_value("hold_ends", [NewtonOptions { hold_ends: !hold_ends, ..base }, base]);
    any_value(
        "max_held",
        [NewtonOptions { max_held: 0, ..base }, NewtonOptions { max_held: max_held + 100, ..base }],
    );

    let base = RelaxOptions::default();
    let RelaxOptions { tolerance, max_steps, time_step, damping, hold_ends } = base;
    let o = "RelaxOptions";
    floats(o, "tolerance", tolerance, POSITIVE, |v| RelaxOptions { tolerance: v, ..base });
    any_value(
        "max_steps",
        [RelaxOptions { max_steps: 0, ..base }, RelaxOptions { max_steps: max_steps * 10, ..base }],
    );
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
    // Any count (Some(0): no mode; None: all).
    any_value("count", [ModeOptions { count: Some(0), ..base }, ModeOptions { count: None, ..base }]);
    assert_eq!(count, Some(12));
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
