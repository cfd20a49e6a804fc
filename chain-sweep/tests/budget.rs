//! The energy budget of a phase-diagram point (`PhaseDiagram::compute_point`): every point reports
//! its energy error, a point over the tolerance is recomputed with DOP853 or recorded as failed
//! with the numbers, and an absurd launch never gets a normal label.

use chain_sweep::scattering::{Defect, Integrator, Outcome, PhaseDiagram, PointError, Recomputed};

fn antikinks() -> PhaseDiagram {
    PhaseDiagram::new(60, 0.8, 1.0e4, 0.28, Defect::Antikink).unwrap()
}

#[test]
fn a_point_reports_its_energy_error() {
    let d = antikinks();
    let record = d.compute_point(0.7, 4.0).unwrap();
    assert_eq!(record.outcome, Outcome::Trapped);
    assert_eq!(record.integrator, Recomputed::No(Integrator::Verlet));
    assert!(
        record.energy_error > 1e-7 && record.energy_error < d.energy_tolerance,
        "{}",
        record.energy_error
    );
}

#[test]
fn a_deliberately_too_large_step_is_flagged() {
    // A stiffer chain (k = 1e5, omega_max ~ 400 / t), so that steps past Verlet's stability
    // limit are shorter than the output interval (0.01) and reach the integrator unshortened. The
    // default step is a tenth of the (Gershgorin) limit, omega dt <= 0.2; these are 11 and 15
    // times longer. (Nine times longer, omega dt = 1.8, is still stable and stays within the
    // tolerance on this point: a stated tolerance, not a rule on the step.)
    let stiff = || PhaseDiagram::new(60, 0.8, 1.0e5, 0.28, Defect::Antikink).unwrap();
    let reference = stiff().compute_point(0.7, 4.0).unwrap();
    let stable = {
        let model = stiff().chain(0.7).unwrap();
        rotor_chain::dynamics::integrate::VerletOptions::stable_for(&model, &[0.28; 60], 0.1).unwrap().dt
    };
    assert!(15.0 * stable < 0.01, "{stable}");
    for factor in [11.0, 15.0] {
        let mut d = stiff();
        d.dt = Some(factor * stable);
        // Recorded as failed, with the numbers, when asked not to recompute.
        d.recompute = false;
        let err = d.compute_point(0.7, 4.0).unwrap_err();
        let text = err.to_string();
        match &err {
            PointError::EnergyBudget { error, tolerance, integrator } => {
                assert!(*error > *tolerance && *tolerance == 5e-3, "{factor}x: {err:?}");
                assert_eq!(*integrator, Integrator::Verlet);
                assert!(text.contains("above the tolerance 5.0e-3"), "{text}");
            }
            PointError::Run { integrator: Integrator::Verlet, .. } => {
                assert!(text.contains("the energy changed") || text.contains("not finite"), "{text}");
            }
            other => panic!("{factor}x: unexpected {other:?}"),
        }
        // Recomputed with DOP853 by default: the outcome of the default step, a small error, and
        // the record says so. (Once: DOP853 on a stiff chain is slow in a debug build.)
        if factor > 11.0 {
            continue;
        }
        d.recompute = true;
        let record = d.compute_point(0.7, 4.0).unwrap();
        assert_eq!(record.integrator, Recomputed::Dop853, "{factor}x");
        assert_eq!(record.outcome, reference.outcome, "{factor}x");
        assert!(record.energy_error < 1e-6, "{factor}x: {}", record.energy_error);
    }
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
                        PointError::Recomputed { .. }
                            | PointError::SpunThroughPi { .. }
                            | PointError::EnergyBudget { .. }
                    ),
                    "{defect:?} v0 = {v0}: {error}"
                ),
            }
        }
    }
}
