//! The no-alloc pieces of the embedded run against chain-core's analyses, which build the same
//! things with a heap by other routes: the statics' kink builder, the launch along the lowest
//! eigenvector of the tangent stiffness, the library's Verlet and its DOP853.

use embedded_check::{
    Chain16, ChainGeometry, DomainWalls, Scenario, Verlet, kink_into, kink_launch_velocities,
    kink_translation_mode, run,
};
use rotor_chain::SpringNetwork;
use rotor_chain::dynamics::launch::{Direction, launch};
use rotor_chain::integrate::IntegrateError;
use rotor_chain::integrate::{self, AdaptiveOptions, Flow, Phase, State, VerletOptions};
use rotor_chain::statics::walls::Charge;
use rotor_chain::{ChainModel, RuntimeChain};

/// A second chain unlike `Chain16`: longer, another angle, one shorter rotor with its springs' rest
/// lengths left at the default (so those springs are not at rest in the uniform state).
fn runtime_chain() -> RuntimeChain {
    RuntimeChain::builder(40, 0.8, 1.0e4, 0.4).rotor(25, 0.75).build().expect("valid chain")
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// The largest `|l_p - l0_p|` over the springs: zero for a kink built by the branch solve.
fn worst_stretch(model: &impl ChainModel, theta: &[f64]) -> f64 {
    let mut lengths = vec![0.0; theta.len() - 1];
    model.spring_lengths_into(theta, &mut lengths);
    lengths.iter().enumerate().map(|(p, l)| (l - model.rest_length(p)).abs()).fold(0.0, f64::max)
}

/// `statics::kink::kink` is this builder collected into a `Vec`, so the checks here are the
/// kink's own properties (paper Sec. II): every spring at rest, zero energy, the wall at the centre.
#[test]
fn kink_has_every_spring_at_rest_at_integer_and_fractional_centres() {
    let chain = runtime_chain();
    for centre in [0.0, 0.5, 3.0, 4.25, 7.999, 14.5, 15.0] {
        let mut ours = [0.0; 16];
        kink_into(&Chain16, centre, &mut ours).unwrap();
        assert!(worst_stretch(&Chain16, &ours) <= 1e-13, "centre {centre}: {ours:?}");
        // The kink costs no energy (paper Sec. II).
        assert!(rotor_chain::Potential::energy(&Chain16, &ours) < 1e-20, "centre {centre}");
    }
    for centre in [2.0, 11.3, 20.0, 38.75] {
        let mut ours = [0.0; 40];
        kink_into(&chain, centre, &mut ours).unwrap();
        assert!(worst_stretch(&chain, &ours) <= 1e-13, "n = 40, centre {centre}");
        let wall = DomainWalls::of(&ours).next().unwrap();
        if centre <= 38.0 {
            assert!((wall.position - centre).abs() < 1e-9, "wall at {} for centre {centre}", wall.position);
        }
    }
}

#[test]
fn a_centre_outside_the_chain_is_an_error_with_the_numbers() {
    let mut theta = [0.0; 16];
    let error = kink_into(&Chain16, 15.5, &mut theta).unwrap_err();
    assert_eq!(error.to_string(), "centre 15.5 is outside the chain: it must lie in [0, 15] for 16 rotors");
    assert!(kink_into(&Chain16, f64::NAN, &mut theta).is_err());
    let error = kink_into(&Chain16, 3.0, &mut [0.0; 15]).unwrap_err();
    assert_eq!(error.to_string(), "theta has 15 values, the chain needs 16");
}

#[test]
fn launch_equals_the_library_launch_along_the_lowest_eigenvector() {
    // chain-core takes the translation mode from the eigenvectors of the tangent stiffness; we
    // take the null vector of the compatibility matrix. For the kink (every spring at rest, so
    // no stress matrix) the two must coincide.
    let mut theta = [0.0; 16];
    kink_into(&Chain16, 4.25, &mut theta).unwrap();
    let ours = kink_launch_velocities(&Chain16, &theta, 2.0).unwrap();
    let reference = launch(&Chain16, Charge::Kink, 4.25, 2.0, Direction::Right).unwrap();
    assert!(max_difference(&reference.state.theta, &theta) <= 1e-14);
    assert!(max_difference(&ours, &reference.state.omega) <= 1e-8, "{ours:?} vs {:?}", reference.state.omega);

    let chain = runtime_chain();
    let mut theta = [0.0; 40];
    kink_into(&chain, 24.6, &mut theta).unwrap();
    let ours = kink_launch_velocities(&chain, &theta, 3.0).unwrap();
    let reference = launch(&chain, Charge::Kink, 24.6, 3.0, Direction::Right).unwrap();
    assert!(max_difference(&ours, &reference.state.omega) <= 1e-8);
}

#[test]
fn translation_mode_stretches_no_spring_to_first_order() {
    // Independent of the compatibility matrix: move the rotors by h along the mode and measure
    // the spring lengths. A first-order change would be of size h; along the mode it is O(h^2).
    let mut theta = [0.0; 16];
    kink_into(&Chain16, 6.7, &mut theta).unwrap();
    let e = kink_translation_mode(&Chain16, &theta).unwrap();
    assert!((e.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-14);
    let h = 1e-6;
    let lengths = |theta: &[f64]| {
        let mut l = [0.0; 15];
        Chain16.spring_lengths_into(theta, &mut l);
        l
    };
    let moved: Vec<f64> =
        (0..16).map(|i| theta[i] + h * e[i] / ChainGeometry::rotor_length(&Chain16, i)).collect();
    let stretch = max_difference(&lengths(&moved), &lengths(&theta));
    assert!(stretch < 1e-10, "springs stretched by {stretch} for a displacement of {h}");
    // A generic direction stretches them at first order.
    let tilted: Vec<f64> = (0..16).map(|i| theta[i] + h * (1.0 + i as f64) / 16.0).collect();
    assert!(max_difference(&lengths(&tilted), &lengths(&theta)) > 1e-8);
    // The mode is localised at the kink: it decays away from it (paper Sec. II).
    assert!(
        e[0].abs() < 1e-3 * e[7].abs().max(e[6].abs()) && e[15].abs() < 1e-3 * e[7].abs().max(e[6].abs())
    );
}

#[test]
fn launch_has_the_kinetic_energy_of_appendix_b() {
    // r_i thetadot_i = v0 e_i with sum e_i^2 = 1: T = M v0^2 / 2.
    let stepper =
        embedded_check::launched_kink::<f64, _, 16>(&Chain16, &Scenario { v0: 3.0, ..Scenario::FIRMWARE })
            .unwrap();
    let kinetic = stepper.kinetic_energy(&Chain16);
    assert!((kinetic - 4.5).abs() < 1e-13, "{kinetic}");
}

#[test]
fn verlet_follows_the_library_verlet_step_for_step() {
    let scenario = Scenario::FIRMWARE;
    let mut stepper = embedded_check::launched_kink::<f64, _, 16>(&Chain16, &scenario).unwrap();
    let mut state = State { time: 0.0, theta: stepper.theta().to_vec(), omega: stepper.omega().to_vec() };
    let steps = 300;
    for _ in 0..steps {
        stepper.step(&Chain16).unwrap();
    }
    let options = VerletOptions::new(scenario.dt);
    integrate::verlet(&Chain16, &mut state, scenario.time(steps), &options, 1000, &mut |_| Flow::Continue)
        .unwrap();
    assert!(max_difference(stepper.theta(), &state.theta) <= 1e-13);
    assert!(max_difference(stepper.omega(), &state.omega) <= 1e-11);
}

/// Wall positions of the firmware scenario's samples, run with time step `dt`.
fn wall_track(dt_divisor: u32) -> Vec<f64> {
    let base = Scenario::FIRMWARE;
    let scenario = Scenario {
        dt: base.dt / f64::from(dt_divisor),
        steps: base.steps * dt_divisor,
        every: base.every * dt_divisor,
        ..base
    };
    let mut walls = Vec::new();
    run::<f64, _, _, 16>(&Chain16, &scenario, |s| walls.push(s.walls()[0].position)).unwrap();
    walls
}

#[test]
fn firmware_trajectory_converges_to_an_independent_integrator_at_second_order() {
    // The reference: chain-core's adaptive DOP853 at tight tolerances, observed at the same times.
    let scenario = Scenario::FIRMWARE;
    let start = embedded_check::launched_kink::<f64, _, 16>(&Chain16, &scenario).unwrap();
    let mut state = State { time: 0.0, theta: start.theta().to_vec(), omega: start.omega().to_vec() };
    let outputs: Vec<f64> =
        (1..=scenario.steps / scenario.every).map(|k| scenario.time(k * scenario.every)).collect();
    let mut reference = vec![DomainWalls::of(&state.theta).next().unwrap().position];
    let options = AdaptiveOptions { rtol: 1e-12, atol: 1e-13, ..AdaptiveOptions::default() };
    integrate::adaptive(&Chain16, &mut state, &outputs, &options, &mut |s| {
        reference.push(DomainWalls::of(&s.theta).next().unwrap().position);
        Flow::Continue
    })
    .unwrap();

    let error = |walls: &[f64]| max_difference(walls, &reference);
    let (coarse, fine) = (error(&wall_track(1)), error(&wall_track(2)));
    // The firmware's own step tracks the kink to 6.2e-5 sites over t = 2 (measured) ...
    assert!(coarse < 5e-4, "wall position error {coarse}");
    // ... and halving the step divides the error by about 4: velocity Verlet is second order.
    let ratio = coarse / fine;
    println!("wall position error against DOP853: dt {coarse:.3e}, dt/2 {fine:.3e}, ratio {ratio:.2}");
    assert!((3.0..5.0).contains(&ratio), "error ratio {ratio} ({coarse} / {fine})");
}

#[test]
fn firmware_scenario_moves_one_kink_across_the_chain_and_keeps_its_energy() {
    let mut samples = Vec::new();
    let summary = run::<f64, _, _, 16>(&Chain16, &Scenario::FIRMWARE, |s| samples.push(*s)).unwrap();
    assert_eq!(samples.len(), 17);
    for pair in samples.windows(2) {
        assert_eq!(pair[1].wall_count, 1, "one wall at every sample");
        assert!(pair[1].walls()[0].position > pair[0].walls()[0].position, "the kink moves right");
    }
    let end = samples.last().unwrap().walls()[0].position;
    assert!(end > 11.0 && end < 14.0, "the kink ends at {end}");
    // Verlet's energy error oscillates at O((omega dt)^2); at omega_max dt <= 0.2 and for the slow
    // kink it stays far inside the 1 % bound of that estimate.
    let relative = summary.max_energy_error / summary.energy_initial;
    assert!(relative < 1e-4, "energy error {relative}");
}

#[test]
fn firmware_time_step_is_within_the_accuracy_bound() {
    let mut theta = [0.0; 16];
    kink_into(&Chain16, Scenario::FIRMWARE.centre, &mut theta).unwrap();
    let bound = VerletOptions::stable_for(&Chain16, &theta, VerletOptions::DEFAULT_SAFETY).unwrap();
    assert!(Scenario::FIRMWARE.dt <= bound.dt, "dt {} above {}", Scenario::FIRMWARE.dt, bound.dt);
    assert!(Scenario::FIRMWARE.dt.log2().fract() == 0.0, "dt is a power of two");
}

#[test]
fn a_non_finite_state_or_step_is_an_error_with_the_numbers() {
    let mut theta = [0.0; 16];
    kink_into(&Chain16, 4.25, &mut theta).unwrap();
    let mut omega = kink_launch_velocities(&Chain16, &theta, 2.0).unwrap();
    let error = Verlet::new(&Chain16, Phase { time: 0.0, theta, omega }, 0.0).unwrap_err();
    assert_eq!(error.to_string(), "Verlet.dt = 0 is invalid: it must be positive and finite");
    omega[3] = f64::NAN;
    let error = Verlet::new(&Chain16, Phase { time: 0.0, theta, omega }, 1e-3).unwrap_err();
    assert_eq!(error.to_string(), "omega[3] is not finite (NaN) at t = 0");
    theta[5] = f64::INFINITY;
    assert!(Verlet::new(&Chain16, Phase { time: 0.0, theta, omega }, 1e-3).is_err());
}

#[test]
fn an_unstable_step_is_caught_by_the_energy_check_before_any_number_overflows() {
    let launched = |dt: f64| {
        let start = embedded_check::launched_kink::<f64, _, 16>(&Chain16, &Scenario::FIRMWARE).unwrap();
        Verlet::new(&Chain16, Phase { time: 0.0, theta: *start.theta(), omega: *start.omega() }, dt).unwrap()
    };
    let reference = launched(Scenario::FIRMWARE.dt).check_energy(&Chain16, 0.0, f64::INFINITY).unwrap();
    let tolerance = 0.05 * reference;
    // The firmware's step (omega_max dt <= 0.2) stays within 5 % over the whole run.
    let mut stable = launched(Scenario::FIRMWARE.dt);
    for _ in 0..Scenario::FIRMWARE.steps {
        stable.step(&Chain16).unwrap();
        stable.check_energy(&Chain16, reference, tolerance).unwrap();
    }
    // Past the stability limit (Gershgorin: omega_max <= 101.5 / t on this kink, so dt = 0.05
    // is omega_max dt ~ 5; dt = 10 far beyond), `step` keeps returning Ok with a finite state
    // while the energy runs away; the check says so with the numbers.
    for dt in [0.05, 10.0] {
        let mut stepper = launched(dt);
        let mut caught = None;
        for _ in 0..1000 {
            stepper.step(&Chain16).unwrap();
            if let Err(e) = stepper.check_energy(&Chain16, reference, tolerance) {
                caught = Some(e);
                break;
            }
        }
        let Some(IntegrateError::EnergyDrift { step, energy, reference: r, tolerance: t, dt: d }) = caught
        else {
            panic!("dt = {dt}: no energy drift found in 1000 steps: {caught:?}");
        };
        assert!(step < 1000 && (energy - r).abs() > t && (r, t, d) == (reference, tolerance, dt));
        assert!(stepper.theta().iter().chain(stepper.omega()).all(|x| x.is_finite()), "dt = {dt}");
        let message = caught.unwrap().to_string();
        assert!(message.contains(&format!("dt = {dt} within the stability limit")), "{message}");
    }
    // A NaN tolerance or reference never passes.
    assert!(stable.check_energy(&Chain16, reference, f64::NAN).is_err());
    assert!(stable.check_energy(&Chain16, f64::NAN, tolerance).is_err());
}

#[test]
fn a_negative_launch_speed_sends_the_kink_the_other_way() {
    let mut theta = [0.0; 16];
    kink_into(&Chain16, 7.5, &mut theta).unwrap();
    let right = kink_launch_velocities(&Chain16, &theta, 2.0).unwrap();
    let left = kink_launch_velocities(&Chain16, &theta, -2.0).unwrap();
    assert!(right.iter().zip(&left).all(|(r, l)| *l == -*r));
    // Followed for t = 0.5, the two walls move by the same distance in opposite directions.
    let walk = |omega: [f64; 16]| {
        let mut stepper =
            Verlet::new(&Chain16, Phase { time: 0.0, theta, omega }, Scenario::FIRMWARE.dt).unwrap();
        for _ in 0..256 {
            stepper.step(&Chain16).unwrap();
        }
        DomainWalls::of(stepper.theta()).next().unwrap().position - 7.5
    };
    let (to_the_right, to_the_left) = (walk(right), walk(left));
    assert!(to_the_right > 1.0 && to_the_left < -1.0, "{to_the_right}, {to_the_left}");
}
