//! The two integrators of `M r_i^2 thetadd_i = -dV/dtheta_i` (paper Secs. V, VI, Appendix B) on the
//! paper's moving kink: n = 60, r/a = 0.8, k = 1e4, theta_bar = 0.58, launched along its translation
//! mode with v0 = 2.4 and integrated to t = 20. Velocity Verlet at two fixed steps and DOP853 at
//! two tolerances: energy errors, steps, rejected steps, force evaluations; then Verlet's energy
//! error window by window (bounded, no drift) against DOP853's (a slow drift).
//!
//! Run: `cargo run --example dynamics_integrators`

use std::time::Instant;

use rotor_chain::RuntimeChain;
use rotor_chain::dynamics::integrate::{
    AdaptiveOptions, Flow, Report, State, VerletOptions, adaptive, total_energy, verlet,
};
use rotor_chain::dynamics::launch::{Direction, launch};
use rotor_chain::statics::walls::{Charge, domain_walls};

const T_END: f64 = 20.0;
/// Energy samples, and the windows in which their errors are compared.
const SAMPLE: f64 = 0.05;
const WINDOWS: usize = 4;

/// A finished run: its report, `|E(t) - E0| / E0` at every sample, the final state, and the
/// number of force (gradient) evaluations.
struct Run {
    report: Report,
    /// Wall-clock time of the run (of this build: use `--release` for representative numbers).
    seconds: f64,
    errors: Vec<f64>,
    end: State,
    forces: usize,
}

fn run_verlet(
    chain: &RuntimeChain,
    start: &State,
    safety: f64,
) -> Result<(Run, f64), Box<dyn std::error::Error>> {
    let options = VerletOptions::stable_for(chain, &start.theta, safety)?;
    let e0 = total_energy(chain, start);
    let every = (SAMPLE / options.dt).round().max(1.0) as usize;
    let mut errors = Vec::new();
    let mut end = start.clone();
    let clock = Instant::now();
    let report = verlet(chain, &mut end, T_END, &options, every, &mut |s: &State| {
        errors.push((total_energy(chain, s) - e0).abs() / e0);
        Flow::Continue
    })?;
    let seconds = clock.elapsed().as_secs_f64();
    // One gradient per step, plus the one before the first step.
    let forces = report.steps + 1;
    Ok((Run { report, seconds, errors, end, forces }, options.dt))
}

fn run_dop853(
    chain: &RuntimeChain,
    start: &State,
    tolerance: f64,
) -> Result<Run, Box<dyn std::error::Error>> {
    let options = AdaptiveOptions { rtol: tolerance, atol: 0.1 * tolerance, ..AdaptiveOptions::default() };
    let outputs: Vec<f64> = (0..=(T_END / SAMPLE).round() as usize).map(|i| i as f64 * SAMPLE).collect();
    let e0 = total_energy(chain, start);
    let mut errors = Vec::new();
    let mut end = start.clone();
    let clock = Instant::now();
    let report = adaptive(chain, &mut end, &outputs, &options, &mut |s: &State| {
        errors.push((total_energy(chain, s) - e0).abs() / e0);
        Flow::Continue
    })?;
    let seconds = clock.elapsed().as_secs_f64();
    // 11 new stages per attempt and one more, f(y_new), per accepted step (it is the next step's
    // first stage); the dense output's 3 extra stages for steps holding an output are not counted.
    let forces = 12 * report.steps + 11 * report.rejected;
    Ok(Run { report, seconds, errors, end, forces })
}

/// The largest error in each of `WINDOWS` equal windows of the run.
fn by_window(errors: &[f64]) -> Vec<f64> {
    let size = errors.len().div_ceil(WINDOWS);
    errors.chunks(size).map(|w| w.iter().fold(0.0, |m: f64, &x| m.max(x))).collect()
}

/// The walls at the end: `K` kink, `A` antikink, at their Appendix C positions.
fn walls(state: &State) -> String {
    let walls: Vec<String> = domain_walls(&state.theta)
        .iter()
        .map(|w| format!("{}{:.2}", if w.charge == Charge::Kink { "K" } else { "A" }, w.position))
        .collect();
    walls.join(" ")
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let chain = RuntimeChain::builder(60, 0.8, 1.0e4, 0.58).build()?;
    let launched = launch(&chain, Charge::Kink, 20.0, 2.4, Direction::Right)?;
    let start = launched.state;
    let e0 = total_energy(&chain, &start);
    println!("Moving kink: n = 60, r/a = 0.8, k = 1e4, theta_bar = 0.58, M = 1; time unit t (Appendix B)");
    println!(
        "launched at {:.2} towards rotor 59 with v0 = 2.4: E0 = {e0:.6} M a^2/t^2 (M v0^2/2 = {:.6}); run to t = {T_END}\n",
        launched.position,
        0.5 * 2.4 * 2.4
    );

    println!(
        "{:<22} | {:>9} | {:>7} | {:>8} | {:>6} | {:>13} | {:>13} | {:>15} | {:>9}",
        "method",
        "dt or tol",
        "steps",
        "rejected",
        "forces",
        "max |dE|/E0",
        "end |dE|/E0",
        "walls at t = 20",
        "time"
    );
    // The default Verlet step and the default DOP853 tolerances are kept for the comparisons below.
    let mut default_verlet = None;
    for safety in [0.2, VerletOptions::DEFAULT_SAFETY] {
        let (run, dt) = run_verlet(&chain, &start, safety)?;
        print_row(&format!("Verlet, safety {safety}"), &format!("{dt:.3e}"), &run, e0);
        default_verlet = Some(run);
    }
    let mut default_dop853 = None;
    for tolerance in [1e-8, AdaptiveOptions::default().rtol] {
        let run = run_dop853(&chain, &start, tolerance)?;
        print_row(&format!("DOP853, rtol {tolerance:.0e}"), &format!("{tolerance:.0e}"), &run, e0);
        default_dop853 = Some(run);
    }
    let (verlet_run, dop853_run) = default_verlet.zip(default_dop853).ok_or("no runs")?;
    println!("(safety s: dt = 2 s / omega_bound, omega_bound = sqrt(||K||_inf / (M r^2)) >= omega_max;");
    println!(" DOP853: atol = rtol / 10, the defaults rtol = 1e-10, atol = 1e-11; 'forces' = gradient");
    println!(" evaluations; time: wall clock of this build, with the energy monitor. The kink reaches");
    println!(" rotor 59 at t ~ 9 and comes back; an antikink stays at 58.17, the end rotor flipped over.)");

    let dtheta = verlet_run
        .end
        .theta
        .iter()
        .zip(&dop853_run.end.theta)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    println!("\nVerlet (safety 0.1) against DOP853 (rtol 1e-10) at t = 20: max |dtheta| = {dtheta:.2e} rad");

    println!("\nLargest |dE|/E0 in each quarter of the run (Verlet bounded, DOP853 drifting):");
    println!("{:<22} | {:>11} | {:>11} | {:>11} | {:>11}", "method", "t in 0-5", "5-10", "10-15", "15-20");
    for (label, run) in [("Verlet, safety 0.1", &verlet_run), ("DOP853, rtol 1e-10", &dop853_run)] {
        let w = by_window(&run.errors);
        println!("{label:<22} | {:>11.3e} | {:>11.3e} | {:>11.3e} | {:>11.3e}", w[0], w[1], w[2], w[3]);
    }
    Ok(())
}

fn print_row(label: &str, step: &str, run: &Run, e0: f64) {
    let r = &run.report;
    println!(
        "{label:<22} | {step:>9} | {:>7} | {:>8} | {:>6} | {:>13.3e} | {:>13.3e} | {:>15} | {:>6.1} ms",
        r.steps,
        r.rejected,
        run.forces,
        r.max_energy_error / e0,
        (r.energy_final - e0).abs() / e0,
        walls(&run.end),
        1e3 * run.seconds
    );
}
