//! Why the paper's slow antikink is trapped (Fig. `fig:akpntrapprofile`: v0 = 1.1, "trapped in its
//! Peierls-Nabarro barrier around Time = 20 near Rotor #35"), and what it takes to reproduce it.
//!
//! At theta_bar = 0.575132, where our Peierls-Nabarro barrier equals the paper's 0.60, an antikink
//! launched with v0 = 1.1 has 0.44 % more kinetic energy than the barrier. Conservative, it keeps
//! running: it could only slow down by radiating phonons, and the frequency at which it shakes the
//! lattice, the washboard frequency 2 pi v / a, lies far below the phonon band. With a viscous
//! damping gamma (Appendix B mentions none) it stops; a bisection on gamma finds the damping that
//! stops it at rotor 35.
//!
//! Run: `cargo run --release --example dynamics_trapping`

use rotor_chain::RuntimeChain;
use rotor_chain::dynamics::integrate::total_energy;
use rotor_chain::dynamics::launch::Direction;
use rotor_chain::dynamics::observe::{damping_to_stop_at, mean_speed, propagation, stopping_point};
use rotor_chain::dynamics::run::RunOptions;
use rotor_chain::statics::antikink::{AntikinkOptions, peierls_nabarro};
use rotor_chain::statics::continuum::ContinuumChain;
use rotor_chain::statics::walls::Charge;

const THETA_BAR: f64 = 0.575132;
const V0: f64 = 1.1;
const START: f64 = 50.0;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let chain = RuntimeChain::builder(60, 0.8, 1.0e4, THETA_BAR).build()?;
    let barrier = peierls_nabarro(&chain, &AntikinkOptions::default())?.barrier;
    println!(
        "theta_bar = {THETA_BAR}: PN barrier {barrier:.4}, launch energy M v0^2/2 = {:.4}",
        0.5 * V0 * V0
    );

    // Conservative: the speed over the run, the energy, the radiation it would need.
    let options = RunOptions { t_max: 40.0, output_interval: 0.02, ..RunOptions::default() };
    let free = propagation(&chain, Charge::Antikink, START, V0, Direction::Left, Some(4.0), &options)?;
    println!(
        "\nconservative run to t = 40 (Verlet, max |dE|/E0 = {:.1e}):",
        free.run.report.relative_energy_error()
    );
    println!("{:>12} | {:>16}", "t window", "speed (sites/t)");
    for (a, b) in [(2.0, 10.0), (10.0, 20.0), (20.0, 30.0), (30.0, 40.0)] {
        let v = mean_speed(&free.positions, a, b).map_or(f64::NAN, f64::abs);
        println!("{:>5}-{:<6} | {v:>16.4}", a, b);
    }
    let v = mean_speed(&free.positions, 20.0, 40.0).map_or(f64::NAN, f64::abs);
    let washboard = 2.0 * std::f64::consts::PI * v;
    let band = ContinuumChain::new(1.0, 0.8, THETA_BAR, 1.0e4, 1.0)?.phonon_band_edges();
    println!(
        "washboard frequency 2 pi v / a = {washboard:.2} /t; phonon band {:.1} to {:.1} /t: the {:.0}th harmonic \
         is the first that could radiate",
        band[0],
        band[1],
        (band[0] / washboard).ceil()
    );
    match stopping_point(&free.positions, 3.0, 0.75) {
        Some((t, d)) => println!("conservative: stopped at t = {t:.2} after {d:.1} sites"),
        None => println!(
            "conservative: not stopped (at rotor {:.1} at t = 40)",
            free.positions.last().map_or(f64::NAN, |p| p.1)
        ),
    }

    // The damping that stops it at rotor 35.
    let search_options = RunOptions { output_interval: 0.05, ..options };
    let search = damping_to_stop_at(
        &chain,
        Charge::Antikink,
        START,
        V0,
        Direction::Left,
        35.0,
        (1e-5, 1e-1),
        14,
        3.0,
        0.75,
        &search_options,
    )?;
    let (t, x) = search.stopped_at;
    println!(
        "\nbisection on ln gamma over [1e-5, 1e-1], 14 halvings: gamma = {:.4e} /t (bracket {:.4e}..{:.4e})",
        search.damping, search.bracket.0, search.bracket.1
    );
    println!("damped: stopped at t = {t:.2} near rotor {x:.2}");
    for gamma in [1e-4, 2e-4, search.damping, 1e-3, 1e-2] {
        let o = RunOptions { damping: gamma, ..search_options };
        let p = propagation(&chain, Charge::Antikink, START, V0, Direction::Left, Some(4.0), &o)?;
        let lost = p.run.report.energy_initial - total_energy(&chain, &p.run.final_state);
        match stopping_point(&p.positions, 3.0, 0.75) {
            Some((t, d)) => println!(
                "  gamma {gamma:.2e}: stops at t = {t:5.2}, {d:5.1} sites from rotor 50 (energy lost {lost:.4})"
            ),
            None => println!("  gamma {gamma:.2e}: not stopped by t = 40 (energy lost {lost:.4})"),
        }
    }
    Ok(())
}
