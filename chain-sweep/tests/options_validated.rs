//! Every field of [`PhaseDiagram`] is validated (issue 37): destructured without `..` (a new
//! field does not compile until it is listed here), each field given its invalid values, which
//! must fail [`Validate::validate`] with the `InvalidOption` naming `PhaseDiagram`, the field and
//! the value, while the valid value they replace passes, and `n` is enumerated at both ends of its
//! range (test-support's `options` checks, shared with chain-core's and chain-network's tests);
//! `check` and `compute_point` refuse them the same way. [`SweepOptions`] is non-exhaustive, so
//! its fields are enumerated in its crate (`sweep::validation`); a [`Grid`]'s fields are private
//! and established by its constructors, checked again by `validate` where a sweep starts
//! (enumerated in `grid`'s unit tests). A sweep with an invalid thread count reports
//! `SweepOptions.threads` as every other option.

use chain_sweep::grid::{Axis, Grid};
use chain_sweep::scattering::{Defect, PhaseDiagram, PointError};
use chain_sweep::{SweepError, SweepOptions, run_sweep};
use rotor_chain::dynamics::launch::Direction;
use rotor_chain::dynamics::scatter::Outcome;
use rotor_chain::geometry::MAX_ROTORS;
use rotor_chain::integrate::Method;
use rotor_chain::validate::{OptionError, Validate};
use test_support::options::{self, count_range, rule_states};

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;
const TINY: f64 = 5e-324;
const POSITIVE: &[f64] = &[NAN, INF, -INF, -1.0, -TINY, 0.0];

/// `make(valid)` validates, and `make(v)` for each `v` of `bad` fails naming `PhaseDiagram.field = v`.
fn values(field: &str, valid: f64, bad: &[f64], make: impl Fn(f64) -> PhaseDiagram) {
    options::values("PhaseDiagram", field, valid, bad, make);
}

fn assert_names<E: OptionError + std::fmt::Display>(error: &E, field: &str, value: f64) {
    options::assert_names(error, "PhaseDiagram", field, value);
}

fn paper() -> PhaseDiagram {
    PhaseDiagram::new(60, 0.8, 1.0e4, 0.28, Defect::Antikink).unwrap()
}

#[test]
fn every_field_of_the_phase_diagram_is_validated() {
    let base = paper();
    let PhaseDiagram {
        n,
        r,
        k,
        theta_bar,
        mass,
        defect,
        ends,
        integrator: _,
        dt: _,
        energy_tolerance,
        recompute,
        t_max,
        impurity_spring: _,
        impurity_rest_length: _,
        direction,
        start: _,
        damping,
        cross_check,
    } = base.clone();
    let with = |f: &dyn Fn(&mut PhaseDiagram)| {
        let mut d = base.clone();
        f(&mut d);
        d
    };
    values("r", r, POSITIVE, |v| with(&|d| d.r = v));
    values("k", k, POSITIVE, |v| with(&|d| d.k = v));
    values("theta_bar", theta_bar, POSITIVE, |v| with(&|d| d.theta_bar = v));
    values("mass", mass, POSITIVE, |v| with(&|d| d.mass = v));
    values("energy_tolerance", energy_tolerance, POSITIVE, |v| with(&|d| d.energy_tolerance = v));
    values("t_max", t_max, POSITIVE, |v| with(&|d| d.t_max = v));
    let dop = |rtol, atol| with(&|d| d.integrator = Method::Dop853 { rtol, atol });
    values("integrator.rtol", 1e-10, &[NAN, INF, -TINY], |v| dop(v, 1e-11));
    values("integrator.atol", 1e-11, POSITIVE, |v| dop(1e-10, v));
    values("dt", 1e-3, POSITIVE, |v| with(&|d| d.dt = Some(v)));
    values("impurity_rest_length", 0.9, POSITIVE, |v| with(&|d| d.impurity_rest_length = Some(v)));
    values("start", 44.5, &[NAN, INF, -INF], |v| with(&|d| d.start = Some(v)));
    values("damping", damping, &[NAN, INF, -INF, -1.0, -TINY], |v| with(&|d| d.damping = v));
    // Between 2 and MAX_ROTORS, the chain builder's rule (a chain too short for the experiment is
    // `check`'s `Experiment` error, naming the shortest).
    assert!((2..=MAX_ROTORS).contains(&n));
    let most = MAX_ROTORS as u64;
    rule_states(count_range("PhaseDiagram", "n", 2, most, |v| with(&|d| d.n = v as usize)), most);
    // Choices and indices: any value passes `validate` (an impurity the chain lacks is `check`'s).
    for d in [
        with(&|d| d.defect = if defect == Defect::Kink { Defect::Antikink } else { Defect::Kink }),
        with(&|d| d.ends = ends),
        with(&|d| d.recompute = !recompute),
        with(&|d| d.impurity_spring = Some(usize::MAX)),
        with(&|d| {
            d.direction = if direction == Direction::Left { Direction::Right } else { Direction::Left }
        }),
        with(&|d| d.cross_check = !cross_check),
    ] {
        assert!(d.validate().is_ok());
    }
}

#[test]
fn the_sweep_entry_points_refuse_an_invalid_setting() {
    let d = PhaseDiagram { damping: NAN, ..paper() };
    assert_names(&d.check().unwrap_err(), "damping", NAN);
    match d.compute_point(0.2, 4.8) {
        Err(PointError::Config(e)) => assert_names(&e, "damping", NAN),
        other => panic!("expected the invalid damping, got {other:?}"),
    }
    // The valid diagram computes the point (the paper's reflection at k_i/k = 0.2, v0 = 4.8).
    assert_eq!(paper().compute_point(0.2, 4.8).unwrap().outcome, Outcome::Reflected);

    // A sweep with an invalid thread count starts nothing, and writes no file.
    let grid = Grid::new(Axis::linspace(0.1, 0.2, 2).unwrap(), Axis::linspace(1.0, 2.0, 2).unwrap()).unwrap();
    assert!(grid.validate().is_ok());
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("points.csv");
    let mut sweep = SweepOptions::new("t", "run");
    (sweep.threads, sweep.progress) = (Some(0), false);
    let e = run_sweep(&grid, &path, |_, _| paper().compute_point(0.2, 4.8), &sweep).unwrap_err();
    assert!(matches!(e, SweepError::Threads { .. }), "{e}");
    options::assert_names(&e, "SweepOptions", "threads", 0.0);
    assert!(!path.exists());
}
