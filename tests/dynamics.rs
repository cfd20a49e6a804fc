//! Dynamics acceptance (paper Secs. V, VI; n = 60, r/a = 0.8, k = 1e4, M = 1): scattering outcomes at
//! the paper's named points, outcomes that last, the same outcomes from a second integrator and
//! with absorbing ends, the stiff impurity's reflection regime, the slowing of transmitted
//! antikinks, the antikink's stability against v0, kinetic-energy fluctuations, the trapping of a
//! slow antikink (and the damping it needs), reflection at a free end.

use rotor_chain::RuntimeChain;
use rotor_chain::dynamics::launch::Direction;
use rotor_chain::dynamics::observe::{
    damping_to_stop_at, kinetic_energy_variation, passage_speeds, propagation, stability, stopping_point,
};
use rotor_chain::dynamics::run::{ABSORBING_ENDS, Method, RunOptions};
use rotor_chain::dynamics::scatter::{LaterEvent, Outcome, ScatterSetup, Scattering, scatter, scatter_with};
use rotor_chain::statics::walls::Charge;

const K: f64 = 1.0e4;
const MIDDLE: usize = 29;
const X_IMP: f64 = 29.5;

fn impure(theta_bar: f64, ki_ratio: f64) -> RuntimeChain {
    RuntimeChain::builder(60, 0.8, K, theta_bar).spring_constant(MIDDLE, ki_ratio * K).build().unwrap()
}

fn run(charge: Charge, v0: f64, ki_ratio: f64, change: impl FnOnce(&mut ScatterSetup)) -> Scattering {
    let model = impure(0.28, ki_ratio);
    let mut setup = ScatterSetup::from_the_right(charge, v0, MIDDLE);
    change(&mut setup);
    let result = scatter(&model, &setup).unwrap();
    eprintln!(
        "{charge:?} v0 = {v0}, k_i/k = {ki_ratio}: {:?} at t = {:.3} (later {:?}, {} energy error {:.1e})",
        result.outcome,
        result.decided_at,
        result.later,
        result.run.integrator,
        result.run.report.relative_energy_error()
    );
    result
}

fn outcome(charge: Charge, v0: f64, ki_ratio: f64) -> Outcome {
    run(charge, v0, ki_ratio, |_| {}).outcome
}

/// Points of both diagrams away from their boundaries, one or more per regime.
const ROBUST: [(Charge, f64, f64, Outcome); 12] = [
    (Charge::Kink, 2.0, 0.5, Outcome::Transmitted),
    (Charge::Kink, 6.0, 2.0, Outcome::Transmitted),
    (Charge::Kink, 11.0, 0.012, Outcome::Split),
    (Charge::Kink, 8.0, 0.015, Outcome::Split),
    (Charge::Antikink, 4.0, 0.85, Outcome::Transmitted),
    (Charge::Antikink, 10.0, 1.3, Outcome::Transmitted),
    (Charge::Antikink, 2.0, 0.4, Outcome::Trapped),
    (Charge::Antikink, 8.0, 0.5, Outcome::Trapped),
    (Charge::Antikink, 6.0, 0.05, Outcome::Reflected),
    (Charge::Antikink, 10.0, 0.1, Outcome::Reflected),
    (Charge::Antikink, 2.0, 2.0, Outcome::Reflected),
    (Charge::Antikink, 8.0, 2.8, Outcome::Reflected),
];

#[test]
fn scattering_outcomes_at_the_papers_points() {
    // Paper Figs. fig:k-scatter and fig:ak-scatter (theta_bar = 0.28, impurity on the middle spring).
    assert_eq!(outcome(Charge::Kink, 4.0, 0.10), Outcome::Transmitted);
    assert_eq!(outcome(Charge::Kink, 9.6, 0.01), Outcome::Split);
    assert_eq!(outcome(Charge::Antikink, 4.0, 0.80), Outcome::Transmitted);
    assert_eq!(outcome(Charge::Antikink, 4.0, 0.70), Outcome::Trapped);
    assert_eq!(outcome(Charge::Antikink, 4.8, 0.20), Outcome::Reflected);
}

#[test]
fn the_kink_is_never_trapped_or_reflected_by_a_stiffness_impurity() {
    for ki_ratio in [0.05, 0.3, 1.0, 3.0] {
        for v0 in [1.0, 3.0, 6.0] {
            let o = outcome(Charge::Kink, v0, ki_ratio);
            assert!(
                matches!(o, Outcome::Transmitted | Outcome::Split),
                "k_i/k = {ki_ratio}, v0 = {v0}: {o:?}"
            );
        }
    }
}

#[test]
fn labels_hold_when_the_run_goes_on_for_twice_the_decision_time() {
    // Each label, decided and confirmed, is watched for twice its decision time more: it must
    // be the label of the longer run too, and what it says must still be true at the end, unless
    // a later event (recorded beside it) explains why not.
    for &(charge, v0, ki, expected) in ROBUST.iter().chain(&[
        (Charge::Antikink, 4.0, 0.7, Outcome::Trapped),
        (Charge::Antikink, 0.5, 0.5, Outcome::Trapped),
        (Charge::Antikink, 4.8, 0.2, Outcome::Reflected),
    ]) {
        let first = run(charge, v0, ki, |_| {});
        assert_eq!(first.outcome, expected, "{charge:?} {v0} {ki}");
        let watched = run(charge, v0, ki, |s| s.watch = 2.0 * first.decided_at);
        assert_eq!(watched.outcome, first.outcome, "{charge:?} {v0} {ki}");
        assert_eq!(watched.decided_at, first.decided_at, "{charge:?} {v0} {ki}");
        let end = watched.run.final_state.time;
        assert!(
            end >= 3.0 * first.decided_at - 0.02 || end >= 19.99,
            "{charge:?} {v0} {ki}: watched to {end}"
        );
        // What the label says must stay true through the watch: a trapped wall stays at the
        // impurity unless a later event is recorded; a transmitted (reflected) wall stays on the
        // far (incoming) side until it reaches the end it was heading for, where a free end may
        // send it back.
        let after: Vec<_> =
            watched.run.tracker.snapshots.iter().filter(|s| s.time >= first.decided_at).collect();
        let mut x = first_position(after[0], charge);
        for s in &after {
            let Some(now) = s.interior(charge).min_by(|a, b| (a - x).abs().total_cmp(&(b - x).abs())) else {
                break;
            };
            if (now - x).abs() > 3.0 {
                break;
            }
            x = now;
            let d = x - X_IMP;
            match watched.outcome {
                Outcome::Trapped if watched.later.is_none() => {
                    assert!(d.abs() <= 8.0, "{charge:?} {v0} {ki}: {d} at {}", s.time)
                }
                Outcome::Transmitted => {
                    assert!(d < -4.0, "{charge:?} {v0} {ki}: {d} at {}", s.time);
                    if x < 4.0 {
                        break;
                    }
                }
                Outcome::Reflected => {
                    assert!(d > 4.0, "{charge:?} {v0} {ki}: {d} at {}", s.time);
                    if x > 55.0 {
                        break;
                    }
                }
                _ => {}
            }
        }
        if let Some((event, t)) = watched.later {
            assert!(matches!(event, LaterEvent::Annihilated | LaterEvent::Escaped) && t > first.decided_at);
        }
    }
}

/// The interior wall of `charge` of a snapshot nearest the impurity.
fn first_position(s: &rotor_chain::dynamics::track::Snapshot, charge: Charge) -> f64 {
    s.interior(charge).min_by(|a, b| (a - X_IMP).abs().total_cmp(&(b - X_IMP).abs())).unwrap_or(f64::NAN)
}

#[test]
fn a_second_integrator_and_absorbing_ends_give_the_same_labels() {
    // DOP853 at its default tolerances (energy error ~1e-9 against Verlet's ~1e-4), and a damping
    // sponge on the last 10 rotors at each end, which removes every wall that a free end would
    // send in: the robust points keep their labels.
    for &(charge, v0, ki, expected) in &ROBUST {
        let dop = run(charge, v0, ki, |s| s.run.method = Method::dop853());
        assert_eq!(dop.outcome, expected, "DOP853: {charge:?} {v0} {ki}");
        assert!(dop.run.report.relative_energy_error() < 1e-7);
        let absorbing = run(charge, v0, ki, |s| s.run.absorbing_ends = Some(ABSORBING_ENDS));
        assert_eq!(absorbing.outcome, expected, "absorbing ends: {charge:?} {v0} {ki}");
    }
}

#[test]
fn a_split_whose_kinks_leave_through_the_ends_is_a_split_with_either_integrator() {
    // The kink diagram's point (k_i/k = 0.04317, v0 = 10.23): the kink splits at t ~ 0.8, the
    // transmitted kink leaves through the left end at t ~ 1.5 and the reflected one through the
    // right end at t ~ 2.26, the antikink stays at the impurity. While a leaving wall was unseen
    // (the grace time before it counts as gone through the end) the split's pattern broke and
    // its clock restarted, so the label hung on which output the right kink left at: DOP853 said
    // split at t = 2.25, Verlet, one output later, pair-creation at 5.28 (found by an independent
    // model's audit; the two runs' walls agree within 0.04 sites throughout).
    let (ki, v0) = (0.01 * 300f64.powf(10.0 / 39.0), 0.5 + 11.5 * 33.0 / 39.0);
    let verlet = run(Charge::Kink, v0, ki, |_| {});
    let dop = run(Charge::Kink, v0, ki, |s| s.run.method = Method::dop853());
    assert_eq!(verlet.outcome, Outcome::Split);
    assert_eq!(dop.outcome, Outcome::Split);
    // Decided from the same pattern at nearly the same time.
    assert!((verlet.decided_at - dop.decided_at).abs() < 0.05, "{} {}", verlet.decided_at, dop.decided_at);
}

/// The same along the kink's whole split boundary, not only at the audited point: on every
/// third `v0` row of the 40 x 40 diagram from 4.9 up, the two grid columns where Verlet's label
/// changes get the same labels from DOP853 (both `split` or `transmitted`, never
/// `pair-creation`).
#[test]
fn along_the_kinks_split_boundary_both_integrators_agree() {
    let ki = |i: usize| 0.01 * 300f64.powf(i as f64 / 39.0);
    for j in (15..40).step_by(3) {
        let v0 = 0.5 + 11.5 * j as f64 / 39.0;
        let labels: Vec<Outcome> = (0..15).map(|i| outcome(Charge::Kink, v0, ki(i))).collect();
        let edge = labels.iter().position(|&o| o != Outcome::Split).expect("a split boundary in the row");
        assert!(edge > 0 && labels[edge] == Outcome::Transmitted, "v0 = {v0}: {labels:?}");
        for i in [edge - 1, edge] {
            let dop = run(Charge::Kink, v0, ki(i), |s| s.run.method = Method::dop853());
            assert_eq!(dop.outcome, labels[i], "v0 = {v0}, k_i/k = {}", ki(i));
        }
    }
}

#[test]
fn a_stiff_impurity_reflects_slow_antikinks_and_the_boundary_rises_with_v0() {
    // Paper Sec. VI: "a stiffer impurity acts like a repulsive potential ... the higher the
    // barrier is, the faster the antikink needs to be to get transmitted". For each v0 the
    // smallest reflecting k_i/k in [1, 3] by bisection (transmitted just below, reflected above).
    let mut boundary = Vec::new();
    for v0 in [1.0, 4.0, 8.0, 12.0] {
        let (mut low, mut high) = (1.0, 3.0);
        assert_eq!(outcome(Charge::Antikink, v0, high), Outcome::Reflected, "v0 = {v0} at k_i/k = 3");
        assert_ne!(outcome(Charge::Antikink, v0, 0.95), Outcome::Reflected, "v0 = {v0} at k_i/k = 0.95");
        for _ in 0..5 {
            let mid = 0.5 * (low + high);
            if outcome(Charge::Antikink, v0, mid) == Outcome::Reflected { high = mid } else { low = mid }
        }
        eprintln!("v0 = {v0}: reflected from k_i/k = {high:.3}");
        boundary.push(high);
    }
    assert!(boundary.windows(2).all(|w| w[1] > w[0]), "the boundary must rise with v0: {boundary:?}");
    assert!(boundary[3] > 1.5 && boundary[0] < 1.3, "{boundary:?}");
}

/// A defect launched at rest, 15 sites from the impurity, drifts but does not reach the
/// impurity's range (`reach` = 4 sites) by t = 25: whatever the impurity (none, soft, stiff),
/// nothing was reflected, transmitted or trapped. (An earlier rule took the antikink's first drift
/// away from the impurity for a repulsion from afar and called it reflected.)
/// `scatter_with`'s stop question ends the run where it says so, and the result reports only what
/// was seen by then: undecided before the decision, unconfirmed between decision and
/// confirmation; a stop that never says yes gives `scatter`'s result exactly.
#[test]
fn a_stopped_scattering_run_reports_what_it_saw() {
    let model = impure(0.28, 0.2);
    let setup = ScatterSetup::from_the_right(Charge::Antikink, 4.8, MIDDLE);
    let whole = scatter(&model, &setup).unwrap();
    assert_eq!((whole.outcome, whole.confirmed), (Outcome::Reflected, true));
    let never = scatter_with(&model, &setup, &mut |_| false).unwrap();
    assert_eq!(never, whole);
    let at = |t_stop: f64| scatter_with(&model, &setup, &mut |s| s.time >= t_stop).unwrap();
    let early = at(0.5 * whole.decided_at);
    assert_eq!((early.outcome, early.confirmed), (Outcome::Undecided, false));
    let end = early.run.final_state.time;
    assert!(end >= 0.5 * whole.decided_at && end < 0.5 * whole.decided_at + 0.011, "stopped at {end}");
    assert_eq!(early.decided_at, end);
    let between = at(whole.decided_at);
    assert_eq!(
        (between.outcome, between.decided_at, between.confirmed),
        (Outcome::Reflected, whole.decided_at, false)
    );
    assert!(between.run.final_state.time < whole.run.final_state.time);
}

#[test]
fn a_defect_launched_at_rest_far_from_the_impurity_meets_nothing() {
    for charge in [Charge::Antikink, Charge::Kink] {
        for ki_ratio in [0.5, 1.0, 3.0] {
            let result = run(charge, 0.0, ki_ratio, |s| s.run.t_max = 25.0);
            assert_eq!(result.outcome, Outcome::Undecided, "{charge:?} at rest, k_i/k = {ki_ratio}");
            let snapshots = &result.run.tracker.snapshots;
            let nearest = snapshots
                .iter()
                .flat_map(|s| s.interior(charge).map(|x| (x - X_IMP).abs()))
                .fold(f64::INFINITY, f64::min);
            eprintln!("nearest approach {nearest:.2}");
            assert!(nearest > 4.0, "{charge:?}, k_i/k = {ki_ratio}: came within {nearest} of the impurity");
        }
    }
}

#[test]
fn transmitted_antikinks_slow_down_near_but_not_at_equal_stiffness() {
    // Paper Sec. VI: "for k_i/k near 1, the antikink gets transmitted with energy dissipation and
    // thus slows down". Speeds fitted more than 8 sites before and after the impurity.
    let ratio = |v0: f64, ki: f64| {
        let p = propagation(
            &impure(0.28, ki),
            Charge::Antikink,
            44.5,
            v0,
            Direction::Left,
            Some(4.0),
            &RunOptions::default(),
        )
        .unwrap();
        let (a, b) = passage_speeds(&p.positions, X_IMP, 8.0, 59.0, 8.0, 0.1);
        b.unwrap() / a.unwrap()
    };
    let control = ratio(4.0, 1.0);
    let softer = ratio(4.0, 0.8);
    let stiffer = ratio(8.0, 1.2);
    eprintln!("v_out / v_in: k_i = k {control:.4}, (4, 0.8) {softer:.4}, (8, 1.2) {stiffer:.4}");
    assert!((control - 1.0).abs() < 2e-3, "no impurity, no slowing: {control}");
    assert!(softer < 0.85, "{softer}");
    assert!(stiffer < 0.97, "{stiffer}");
}

#[test]
fn the_antikink_stays_one_wall_up_to_v0_20_and_breaks_up_by_25() {
    // Paper Sec. VI: "the maximum initial velocity with which we can launch an antikink is around
    // v0 = 12; above this, the antikink itself becomes unstable". Our clean launch keeps it one
    // wall to v0 = 21 (docs/dynamics.md §6); at 25 it sheds kink-antikink pairs at once.
    let model = RuntimeChain::builder(60, 0.8, K, 0.28).build().unwrap();
    let options = RunOptions { t_max: 5.0, ..RunOptions::default() };
    for v0 in [12.0, 16.0, 20.0] {
        let s = stability(&model, Charge::Antikink, 44.5, v0, Direction::Left, 8.0, &options).unwrap();
        assert_eq!(s.most_walls, 1, "v0 = {v0}: {s:?}");
        assert!(s.reached < 8.0, "v0 = {v0}: it crossed the chain: {s:?}");
    }
    let s = stability(&model, Charge::Antikink, 44.5, 25.0, Direction::Left, 8.0, &options).unwrap();
    assert!(s.most_walls >= 3 && s.longest_extra >= 0.2, "v0 = 25: {s:?}");
    assert_eq!(outcome(Charge::Antikink, 25.0, 1.0), Outcome::Disintegrated);
}

#[test]
fn the_kinks_kinetic_energy_is_steady_the_antikinks_is_not() {
    // Paper Fig. fig:ketimeplot: theta_bar = 0.58, v0 = 2.4, no impurity.
    let model = RuntimeChain::builder(60, 0.8, K, 0.58).build().unwrap();
    let options = RunOptions { t_max: 3.0, ..RunOptions::default() };
    let kink = propagation(&model, Charge::Kink, 45.0, 2.4, Direction::Left, Some(8.0), &options).unwrap();
    let antikink =
        propagation(&model, Charge::Antikink, 45.0, 2.4, Direction::Left, Some(8.0), &options).unwrap();
    let t_end = |p: &rotor_chain::dynamics::observe::Propagation| p.positions.last().unwrap().0;
    let dk = kinetic_energy_variation(&kink.run, 0.0, t_end(&kink));
    let da = kinetic_energy_variation(&antikink.run, 0.0, t_end(&antikink));
    eprintln!("kinetic energy variation: kink {dk:.4}, antikink {da:.4}");
    assert!(dk < 0.02, "kink: {dk}");
    assert!(da > 5.0 * dk, "antikink {da} vs kink {dk}");
}

#[test]
fn a_slow_antikink_is_trapped_only_with_damping() {
    // Paper Fig. fig:akpntrapprofile: v0 = 1.1, trapped "around Time = 20 near Rotor #35". At the
    // stated theta_bar = 0.58 our barrier (0.668) exceeds M v0^2 / 2 = 0.605: it never leaves its
    // well. At 0.575132, where our barrier is the paper's 0.60, a conservative antikink runs on
    // (its washboard frequency is far below the phonon band, so it radiates almost nothing);
    // a viscous damping of a few 1e-4 stops it near rotor 35.
    let stated = RuntimeChain::builder(60, 0.8, K, 0.58).build().unwrap();
    let options = RunOptions { t_max: 10.0, output_interval: 0.05, ..RunOptions::default() };
    let p = propagation(&stated, Charge::Antikink, 50.0, 1.1, Direction::Left, Some(4.0), &options).unwrap();
    let (_, distance) = stopping_point(&p.positions, 3.0, 0.75).expect("stuck in its first well");
    assert!(distance < 1.0, "{distance}");

    let paper = RuntimeChain::builder(60, 0.8, K, 0.575132).build().unwrap();
    let options = RunOptions { t_max: 36.0, output_interval: 0.05, ..RunOptions::default() };
    let free =
        propagation(&paper, Charge::Antikink, 50.0, 1.1, Direction::Left, Some(4.0), &options).unwrap();
    assert!(stopping_point(&free.positions, 3.0, 0.75).is_none(), "the conservative antikink runs on");
    let search = damping_to_stop_at(
        &paper,
        Charge::Antikink,
        50.0,
        1.1,
        Direction::Left,
        35.0,
        (1e-5, 1e-1),
        10,
        3.0,
        0.75,
        &options,
    )
    .unwrap();
    let (t, x) = search.stopped_at;
    eprintln!("damping {:.3e}: stopped at t = {t:.2} near rotor {x:.2}", search.damping);
    assert!(search.damping > 1e-4 && search.damping < 1e-3, "{}", search.damping);
    // The time is the paper's claim (the search aims only at the place).
    assert!(t > 15.0 && t < 25.0, "t = {t}, x = {x}");
    // The search's bracket, checked by plain runs: with the damping just below the one found,
    // the antikink gets past rotor 35 (it stops beyond it or not at all).
    let below = RunOptions { damping: search.bracket.0, ..options };
    let run = propagation(&paper, Charge::Antikink, 50.0, 1.1, Direction::Left, Some(4.0), &below).unwrap();
    if let Some((_, x_below)) = stopping_point(&run.positions, 3.0, 0.75) {
        assert!(x_below < 35.0, "with damping {:.3e} it stops at {x_below}", search.bracket.0);
    }
    assert!(
        search.bracket.0 < search.damping && search.damping < 1.1 * search.bracket.0,
        "{:?}",
        search.bracket
    );
}

#[test]
fn a_kink_reflects_from_a_free_end() {
    let model = RuntimeChain::builder(60, 0.8, K, 0.58).build().unwrap();
    let options = RunOptions { t_max: 8.0, ..RunOptions::default() };
    let p = propagation(&model, Charge::Kink, 20.0, 2.4, Direction::Left, None, &options).unwrap();
    let min = p.positions.iter().fold(f64::INFINITY, |m, (_, x)| m.min(*x));
    let last = p.positions.last().unwrap().1;
    eprintln!("kink: closest approach to the left end {min:.2}, final position {last:.2}");
    assert!(min < 3.0, "the kink reaches the end");
    assert!(last > min + 8.0, "and comes back");
    assert!(p.run.tracker.violations.is_empty(), "kink number minus antikink number is conserved");
}
