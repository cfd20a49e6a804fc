//! Labels that a second integrator would not change (issue 34): where Verlet and DOP853 decide a
//! scattering point differently, `cross_checked` labels it unresolved with both outcomes, never
//! with a confident one.
//!
//! The point is from the region (antikink, k_i/k = 0.01, v0 = 1.1, the paper's chain of
//! Sec. VI as `chain_sweep`'s phase diagram sets it up), where a kink-antikink pair nucleates at
//! the impurity before the antikink arrives. The two integrators' outcomes are computed here
//! separately, each through the energy budget.

use chain_sweep::scattering::{Defect, PhaseDiagram};
use rotor_chain::dynamics::scatter::{
    CrossChecked, EnergyBudget, Outcome, Unresolved, cross_checked, scatter_within_budget,
};
use rotor_chain::integrate::Method;

#[test]
fn a_point_the_integrators_label_differently_is_unresolved_and_a_robust_one_is_not() {
    let diagram = PhaseDiagram::new(60, 0.8, 1.0e4, 0.28, Defect::Antikink).unwrap();
    let budget = EnergyBudget::default();
    let model = diagram.chain(0.01).unwrap();
    let outcome = |method: Method| {
        let run = scatter_within_budget(&model, &diagram.setup(1.1, method), &budget).unwrap();
        run.scattering.outcome
    };
    let (verlet, dop853) = (outcome(Method::Verlet), outcome(Method::dop853()));
    assert_ne!(verlet, dop853, "the integrators agree here");
    match cross_checked(&model, &diagram.setup(1.1, Method::Verlet), &budget).unwrap() {
        CrossChecked::Unresolved {
            reason: Unresolved::IntegratorsDisagree { verlet: v, dop853: d }, ..
        } => {
            assert_eq!((v.0, d.0), (verlet, dop853));
            assert!(v.1 > 0.0 && d.1 > 0.0);
        }
        other => panic!("labelled although the integrators disagree: {other:?}"),
    }
    // The paper's reflected antikink (k_i/k = 0.2, v0 = 4.8, Sec. VI) is robust.
    let model = diagram.chain(0.2).unwrap();
    match cross_checked(&model, &diagram.setup(4.8, Method::Verlet), &budget).unwrap() {
        CrossChecked::Resolved(run) => assert_eq!(run.scattering.outcome, Outcome::Reflected),
        other => panic!("{other:?}"),
    }
}
