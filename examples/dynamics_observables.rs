//! Observables of a moving defect (paper Sec. V): the kinetic energy of a kink and of an antikink
//! (Fig. `fig:ketimeplot`: theta_bar = 0.58, v0 = 2.4), and Peierls-Nabarro trapping of a slow
//! antikink (Fig. `fig:akpntrapprofile`: v0 = 1.1), at the paper's stated angle 0.58 and at 0.575132,
//! the angle at which our lattice reproduces the paper's barrier 0.60 (docs/statics.md §3).
//!
//! Run: `cargo run --example dynamics_observables`

use rotor_chain::RuntimeChain;
use rotor_chain::dynamics::launch::Direction;
use rotor_chain::dynamics::observe::{Propagation, kinetic_energy_variation, propagation, stopping_point};
use rotor_chain::dynamics::run::RunOptions;
use rotor_chain::statics::antikink::{AntikinkOptions, peierls_nabarro};
use rotor_chain::statics::walls::Charge;

const K: f64 = 1.0e4;
/// The paper's Sec. V angle, and the one at which our barrier is the paper's 0.60.
const PAPER_ANGLE: f64 = 0.58;
const EFFECTIVE_ANGLE: f64 = 0.575132;

fn chain(theta_bar: f64) -> Result<RuntimeChain, Box<dyn std::error::Error>> {
    Ok(RuntimeChain::builder(60, 0.8, K, theta_bar).build()?)
}

/// `(max - min)` and mean of the kinetic energy over `[t_from, t_to]`.
fn spread(p: &Propagation, t_from: f64, t_to: f64) -> (f64, f64) {
    let window: Vec<f64> =
        p.run.kinetic.iter().filter(|(t, _)| *t >= t_from && *t <= t_to).map(|(_, k)| *k).collect();
    let (min, max) =
        window.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &k| (a.min(k), b.max(k)));
    (max - min, window.iter().sum::<f64>() / window.len() as f64)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    kinetic_energy()?;
    trapping()
}

/// Fig. fig:ketimeplot: launched from rotor 45 towards rotor 0, followed until 8 sites from the end.
fn kinetic_energy() -> Result<(), Box<dyn std::error::Error>> {
    let model = chain(PAPER_ANGLE)?;
    let options = RunOptions { t_max: 6.0, ..RunOptions::default() };
    let run = |charge| propagation(&model, charge, 45.0, 2.4, Direction::Left, Some(8.0), &options);
    let (kink, antikink) = (run(Charge::Kink)?, run(Charge::Antikink)?);
    println!(
        "Kinetic energy T(t), n = 60, r/a = 0.8, k = 1e4, theta_bar = 0.58, v0 = 2.4 (Fig. fig:ketimeplot)"
    );
    println!(
        "both launched from rotor 45 towards rotor 0; T in M a^2/t^2, M v0^2/2 = {:.3}\n",
        0.5 * 2.4 * 2.4
    );
    println!("{:>5} | {:>8} {:>8} | {:>8} {:>8}", "t", "T kink", "x kink", "T anti", "x anti");
    let at = |p: &Propagation, t: f64| {
        let k = p.run.kinetic.iter().find(|(s, _)| (s - t).abs() < 1e-9).map(|(_, k)| *k);
        let x = p.positions.iter().find(|(s, _)| (s - t).abs() < 1e-9).map(|(_, x)| *x);
        (k.unwrap_or(f64::NAN), x.unwrap_or(f64::NAN))
    };
    // Every 0.05 t over the first second: the antikink crosses about four sites.
    for i in 0..=20 {
        let t = 0.05 * i as f64;
        let ((tk, xk), (ta, xa)) = (at(&kink, t), at(&antikink, t));
        println!("{t:>5.2} | {tk:>8.4} {xk:>8.2} | {ta:>8.4} {xa:>8.2}");
    }
    println!(
        "\n{:>9} | {:>8} | {:>11} | {:>11} | {:>12} | {:>16}",
        "defect", "until t", "sites moved", "mean T", "max - min T", "(max-min)/mean"
    );
    for (name, p) in [("kink", &kink), ("antikink", &antikink)] {
        let (t_end, x_end) = *p.positions.last().ok_or("the defect was lost")?;
        // Skip the first 0.2 t, in which the launch sheds its phonons.
        let (range, mean) = spread(p, 0.2, t_end);
        println!(
            "{name:>9} | {t_end:>8.2} | {:>11.2} | {mean:>11.4} | {range:>12.4} | {:>16.4}",
            45.0 - x_end,
            kinetic_energy_variation(&p.run, 0.2, t_end)
        );
    }
    let pn = peierls_nabarro(&model, &AntikinkOptions::default())?;
    println!(
        "PN barrier at 0.58: ours {:.4}, paper 0.60 ('consistent with the magnitude of the K.E. fluctuations')",
        pn.barrier
    );
    Ok(())
}

/// Fig. fig:akpntrapprofile: a slow antikink launched from rotor 50 towards rotor 0, run to t = 40
/// (or until 4 sites from the end). Stopped: it stays within 0.75 sites for 3 t.
fn trapping() -> Result<(), Box<dyn std::error::Error>> {
    println!("\nPeierls-Nabarro trapping (Fig. fig:akpntrapprofile; paper: v0 = 1.1 at 0.58, trapped");
    println!("'around Time = 20 near Rotor #35'); antikink from rotor 50 towards rotor 0, t <= 40\n");
    println!(
        "{:>9} | {:>7} | {:>5} | {:>8} | {:>12} | {:>12} | {:>11} | {:>27} | {:>8}",
        "theta_bar",
        "barrier",
        "v0",
        "M v0^2/2",
        "T0 / barrier",
        "stopped at t",
        "sites moved",
        "x at t = 10, 20, 30, 40",
        "max|dE|"
    );
    let options = RunOptions { t_max: 40.0, output_interval: 0.05, ..RunOptions::default() };
    for theta_bar in [PAPER_ANGLE, EFFECTIVE_ANGLE] {
        let model = chain(theta_bar)?;
        let barrier = peierls_nabarro(&model, &AntikinkOptions::default())?.barrier;
        // The paper's v0, and a launch 1 % above the barrier's speed sqrt(2 V_PNB / M).
        let above = 1.01 * (2.0 * barrier).sqrt();
        for v0 in [1.1, above] {
            let p = propagation(&model, Charge::Antikink, 50.0, v0, Direction::Left, Some(4.0), &options)?;
            let (_, x_end) = *p.positions.last().ok_or("the antikink was lost")?;
            let at = |t: f64| p.positions.iter().find(|(s, _)| (s - t).abs() < 1e-9).map(|(_, x)| *x);
            let path: Vec<String> = [10.0, 20.0, 30.0, 40.0]
                .iter()
                .map(|&t| at(t).map_or("-".to_string(), |x| format!("{x:.2}")))
                .collect();
            let stop = match stopping_point(&p.positions, 3.0, 0.75) {
                Some((t, d)) => (format!("{t:.2}"), format!("{d:.2}")),
                None => ("no".to_string(), format!("{:.2}", 50.0 - x_end)),
            };
            let kinetic = 0.5 * v0 * v0;
            println!(
                "{theta_bar:>9} | {barrier:>7.4} | {v0:>5.3} | {kinetic:>8.4} | {:>12.4} | {:>12} | {:>11} | {:>27} | {:>8.1e}",
                kinetic / barrier,
                stop.0,
                stop.1,
                path.join(" "),
                p.run.report.max_energy_error
            );
        }
    }
    println!("('sites moved': to where it stopped, or to its last position if it never stopped; a run ends");
    println!(" early, '-', when the antikink comes within 4 sites of rotor 0; max|dE| in M a^2/t^2)");
    Ok(())
}
