//! Tracking domain walls through a run (paper Appendix C): a kink launched from rotor 20 towards the
//! free left end (n = 60, r/a = 0.8, k = 1e4, theta_bar = 0.58, v0 = 2.4) walks out through the
//! end and back in. At each output: the interior walls, the boundary walls that stand for a wall
//! gone through an end, and the conserved charge `N_kink - N_antikink`. Then a space-time image of
//! `sign(theta)` (rows: times, columns: rotors).
//!
//! Run: `cargo run --example dynamics_tracking`

use rotor_chain::RuntimeChain;
use rotor_chain::dynamics::launch::Direction;
use rotor_chain::dynamics::observe::propagation;
use rotor_chain::dynamics::run::RunOptions;
use rotor_chain::dynamics::track::Snapshot;
use rotor_chain::statics::walls::Charge;

const T_MAX: f64 = 12.0;
/// Rows of the printed trajectory and of the image, in time units.
const EVERY: f64 = 0.5;
const IMAGE_EVERY: f64 = 0.25;

fn list(s: &Snapshot, boundary: bool) -> String {
    let walls: Vec<String> = s
        .walls
        .iter()
        .zip(&s.at_boundary)
        .filter(|(_, b)| **b == boundary)
        .map(|(w, _)| format!("{}{:.2}", if w.charge == Charge::Kink { "K" } else { "A" }, w.position))
        .collect();
    if walls.is_empty() { "-".into() } else { walls.join(" ") }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let chain = RuntimeChain::builder(60, 0.8, 1.0e4, 0.58).build()?;
    let options = RunOptions { t_max: T_MAX, space_time: true, ..RunOptions::default() };
    let p = propagation(&chain, Charge::Kink, 20.0, 2.4, Direction::Left, None, &options)?;
    let tracker = &p.run.tracker;
    println!(
        "Kink from rotor 20 towards the left end: n = 60, r/a = 0.8, k = 1e4, theta_bar = 0.58, v0 = 2.4"
    );
    println!("walls at their Appendix C positions (rotor index); K kink, A antikink; outputs every 0.01 t\n");
    println!("{:>6} | {:>24} | {:>16} | {:>9}", "t", "interior walls", "boundary walls", "N_K - N_A");
    let stride = (EVERY / options.output_interval).round() as usize;
    for s in tracker.snapshots.iter().step_by(stride) {
        println!("{:>6.2} | {:>24} | {:>16} | {:>9}", s.time, list(s, false), list(s, true), s.net_charge());
    }
    let closest = p.positions.iter().fold(f64::INFINITY, |m, (_, x)| m.min(*x));
    let (t_last, x_last) = p.positions.last().ok_or("the kink was lost")?;
    println!(
        "\nthe launched kink came within {closest:.2} of rotor 0 and is at {x_last:.2} at t = {t_last:.2}"
    );
    println!(
        "N_K - N_A = {} at every one of {} outputs ({} violations)",
        tracker.charge(),
        tracker.snapshots.len(),
        tracker.violations.len()
    );
    let report = &p.run.report;
    println!(
        "energy: E0 = {:.6} M a^2/t^2, max |dE|/E0 = {:.1e} (Verlet, {} steps)",
        report.energy_initial,
        report.max_energy_error / report.energy_initial,
        report.steps
    );

    println!("\nsign(theta): '#' theta > 0, '.' theta < 0; rotor 0 on the left, one row per {IMAGE_EVERY} t");
    let image = &p.run.space_time;
    let stride = (IMAGE_EVERY / options.output_interval).round() as usize;
    for (t, theta) in image.times.iter().zip(&image.theta).step_by(stride) {
        let row: String = theta.iter().map(|&x| if x > 0.0 { '#' } else { '.' }).collect();
        println!("{t:>6.2} {row}");
    }
    Ok(())
}
