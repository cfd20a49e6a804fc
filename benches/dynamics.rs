//! Speed of the dynamics (issue targets: one scattering run, n = 60, to its confirmed decision,
//! <= 5 ms with Verlet on one core; the cost per step linear in n), and of a launch (static
//! defect, its near-null modes, the launch vector).
//!
//! Run: `cargo bench --bench dynamics`

use divan::{Bencher, black_box};
use rotor_chain::RuntimeChain;
use rotor_chain::dynamics::integrate::{Flow, State, VerletOptions, verlet};
use rotor_chain::dynamics::launch::{Direction, launch};
use rotor_chain::dynamics::scatter::{ScatterSetup, scatter};
use rotor_chain::statics::walls::Charge;

fn main() {
    divan::main();
}

/// 100 velocity-Verlet steps (one gradient and two sweeps each) for n rotors: the time divided by
/// 100 is the cost of a step, whose inverse is the steps per second.
#[divan::bench(args = [60, 1000, 100_000], sample_count = 20)]
fn verlet_100_steps(bencher: Bencher, n: usize) {
    let model = RuntimeChain::builder(n, 0.8, 1.0e4, 0.58).build().unwrap();
    let theta: Vec<f64> = (0..n).map(|i| 0.58 + 0.01 * (0.3 * i as f64).sin()).collect();
    let options = VerletOptions::stable_for(&model, &theta, VerletOptions::DEFAULT_SAFETY).unwrap();
    let mut state = State::at_rest(theta);
    bencher.bench_local(|| {
        let t_end = state.time + 100.0 * options.dt;
        verlet(&model, &mut state, t_end, &options, 100, &mut |_| Flow::Continue).unwrap();
        black_box(state.theta[0])
    });
}

/// A launch as in the paper's scattering runs: n = 60, theta_bar = 0.28, from rotor 44.5.
#[divan::bench(args = ["kink", "antikink"], sample_count = 20)]
fn launch_defect(bencher: Bencher, defect: &str) {
    let model = RuntimeChain::builder(60, 0.8, 1.0e4, 0.28).spring_constant(29, 0.7e4).build().unwrap();
    let charge = if defect == "kink" { Charge::Kink } else { Charge::Antikink };
    bencher.bench_local(|| launch(black_box(&model), charge, 44.5, 4.0, Direction::Left).unwrap().position);
}

/// One scattering run as in the paper (Sec. VI): n = 60, theta_bar = 0.28, impurity on the
/// middle spring, launched from 15 sites away, run until the outcome is decided and confirmed
/// (1 t after the decision).
#[divan::bench(args = [("kink", 4.0, 0.10), ("antikink", 4.0, 0.70)], sample_count = 20)]
fn scattering_run_to_decision(bencher: Bencher, (defect, v0, ki): (&str, f64, f64)) {
    let model = RuntimeChain::builder(60, 0.8, 1.0e4, 0.28).spring_constant(29, ki * 1.0e4).build().unwrap();
    let charge = if defect == "kink" { Charge::Kink } else { Charge::Antikink };
    let setup = ScatterSetup::from_the_right(charge, v0, 29);
    bencher.bench_local(|| scatter(black_box(&model), &setup).unwrap().decided_at);
}
