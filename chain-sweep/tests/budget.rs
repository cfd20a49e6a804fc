//! The energy budget of a phase-diagram point (`PhaseDiagram::compute_point`): every point reports
//! its energy error, a point over the tolerance is recomputed with DOP853 or recorded as failed
//! with the numbers, and an absurd launch never gets a normal label.

use chain_sweep::scattering::{BudgetError, Defect, Method, Outcome, PhaseDiagram, PointError, Recomputed};

fn antikinks() -> PhaseDiagram {
    PhaseDiagram::new(60, 0.8, 1.0e4, 0.28, Defect::Antikink).unwrap()
}

#[test]
fn a_point_reports_its_energy_error() {
    let d = antikinks();
    let record = d.compute_point(0.7, 4.0).unwrap();
    assert_eq!(record.outcome, Outcome::Trapped);
    assert_eq!(record.integrator, Recomputed::No(Method::Verlet));
    assert!(
        record.energy_error > 1e-7 && record.energy_error < d.energy_tolerance,
        "{}",
        record.energy_error
    );
}

#[test]
fn a_step_over_the_energy_tolerance_is_flagged() {
    // A step of a whole output interval, 5.2 times the default (a tenth of Verlet's Gershgorin
    // stability limit): the longest a diagram takes, since a step is shortened to divide the
    // output interval, which follows the chain's time unit sqrt(1e4 M / k) as the limit does. It
    // is stable (omega dt < 2) and within the default tolerance on this point (an error of
    // 3.6e-3 against 5e-3), so the tolerance asked for here is 1e-3, still five times the
    // default step's error.
    let stiff = || PhaseDiagram::new(60, 0.8, 1.0e5, 0.28, Defect::Antikink).unwrap();
    let reference = stiff().compute_point(0.7, 4.0).unwrap();
    assert!(reference.energy_error < 2e-4, "{}", reference.energy_error);
    let interval = stiff().setup(4.0, Method::Verlet).run.output_interval;
    let stable = {
        let model = stiff().chain(0.7).unwrap();
        rotor_chain::dynamics::integrate::VerletOptions::stable_for(&model, &[0.28; 60], 0.1).unwrap().dt
    };
    assert!(interval > 5.0 * stable, "{stable} against the output interval {interval}");
    let mut d = stiff();
    (d.dt, d.energy_tolerance) = (Some(interval), 1e-3);
    // Recorded as failed, with the numbers, when asked not to recompute.
    d.recompute = false;
    let err = d.compute_point(0.7, 4.0).unwrap_err();
    let text = err.to_string();
    match &err {
        PointError::Scatter(BudgetError::EnergyBudget { error, tolerance, integrator }) => {
            assert!(*error > *tolerance && *tolerance == 1e-3, "{err:?}");
            assert_eq!(*integrator, Method::Verlet);
            assert!(text.contains("above the tolerance 1.0e-3"), "{text}");
        }
        other => panic!("unexpected {other:?}"),
    }
    // Recomputed with DOP853 by default: the outcome of the default step, a small error, and the
    // record says so.
    d.recompute = true;
    let record = d.compute_point(0.7, 4.0).unwrap();
    assert_eq!(record.integrator, Recomputed::Dop853);
    assert_eq!(record.outcome, reference.outcome);
    assert!(record.energy_error < 1e-6, "{}", record.energy_error);
}

#[test]
fn an_absurd_launch_never_gets_a_normal_label() {
    // v0 = 1e3: 5e5 of kinetic energy on three rotors. Verlet's step cannot follow rotors
    // spinning at 1e3 / t and breaks its energy limit; DOP853 follows them and sees the defect
    // break into a train of walls at once.
    for defect in [Defect::Antikink, Defect::Kink] {
        let d = PhaseDiagram::new(60, 0.8, 1.0e4, 0.28, defect).unwrap();
        for v0 in [1e3, 300.0] {
            match d.compute_point(0.5, v0) {
                Ok(record) => {
                    assert!(
                        matches!(record.outcome, Outcome::Disintegrated | Outcome::PairCreation),
                        "{defect:?} v0 = {v0}: {record:?}"
                    );
                    assert!(record.energy_error < d.energy_tolerance);
                }
                Err(error) => assert!(
                    matches!(
                        error,
                        PointError::Scatter(
                            BudgetError::Recomputed { .. }
                                | BudgetError::SpunThroughPi { .. }
                                | BudgetError::EnergyBudget { .. }
                        )
                    ),
                    "{defect:?} v0 = {v0}: {error}"
                ),
            }
        }
    }
}
