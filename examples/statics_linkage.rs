//! The linkage limit (paper Sec. VII-B, Figs. `fig:defectiveKL`, `fig:orbit`, `fig:ELdiagram`): two
//! rigid sub-chains of 8 rotors joined head to head by a soft impurity spring of rest length `l0`,
//! reduced to the two kink positions `x1`, `x2`. The equilibria of one kink (a pitchfork as
//! `l0 -> l_critical`), the separatrix energy `E_c`, two-kink trajectories below and above `E_c`,
//! and the `(E, l0)` diagram.
//!
//! Run: `cargo run --example statics_linkage`

use rotor_chain::statics::continuum::ContinuumChain;
use rotor_chain::statics::linkage::{LinkageChain, PhaseState, Region, TrajectoryPoint, el_diagram};

const K: f64 = 1.0e4;
const ROTORS: usize = 8; // per sub-chain, as in the paper's Fig. fig:defect-chain-conf

/// Minima of one kink (the other at x2 = 0): their positions, or "none".
fn minima(model: &LinkageChain) -> String {
    let xs: Vec<String> =
        model.equilibria().iter().filter(|e| e.stable).map(|e| format!("{:+.4}", e.x)).collect();
    if xs.is_empty() { "none".into() } else { xs.join(" ") }
}

/// A state at `(x1, x2)` with `p2 = 0` and `p1 > 0` chosen so that `H = energy`.
fn start(model: &LinkageChain, x1: f64, x2: f64, energy: f64) -> PhaseState {
    let kinetic = (energy - model.potential(x1, x2)).max(0.0);
    PhaseState { x1, x2, p1: (2.0 * model.kink_mass(x1) * kinetic).sqrt(), p2: 0.0 }
}

fn summary(
    label: &str,
    model: &LinkageChain,
    run: &[TrajectoryPoint],
) -> Result<(), Box<dyn std::error::Error>> {
    let e0 = run[0].energy;
    let drift = run.iter().map(|p| (p.energy - e0).abs()).fold(0.0, f64::max) / e0;
    // The square annulus excludes both kinks near their far ends at once: min over t of max(|x1|, |x2|).
    let inner = run.iter().map(|p| p.x1.abs().max(p.x2.abs())).fold(f64::INFINITY, f64::min);
    let crossings =
        |x: fn(&TrajectoryPoint) -> f64| run.windows(2).filter(|w| x(&w[0]) * x(&w[1]) < 0.0).count();
    println!(
        "{label:>14} | {:>9.3} | {:>7.2} | {:>9} | {:>10.3} | {:>5} | {:>5} | {:>7.1e}",
        e0,
        e0 / model.critical_energy(),
        format!("{:?}", model.region(e0)?),
        inner,
        crossings(|p| p.x1),
        crossings(|p| p.x2),
        drift
    );
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let chain = ContinuumChain::new(1.0, 0.8, 0.58, K, 1.0)?;
    let l_critical = chain.l_critical();
    println!(
        "Linkage limit, two sub-chains of {ROTORS} rotors, r/a = 0.8, theta_bar = 0.58, k = 1e4 (energies in M a^2/t^2)"
    );
    println!("lbar = {:.6} a, l_critical = {l_critical:.6} a (paper 1.68 and 2.31)\n", chain.rest_length());

    // Fig. fig:KLphaseportrait: one kink (x2 = 0) has minima at +-x_eq and a maximum E_c at 0;
    // they merge at 0 as l0 -> l12(0, 0) = l_critical (supercritical pitchfork).
    let top = LinkageChain::new(chain, ROTORS, 2.0)?.impurity_length(0.0, 0.0);
    println!(
        "Equilibria of kink 1 with kink 2 at x2 = 0 (head at x = {ROTORS}); paper: x_eq ~ +-8 below l_critical"
    );
    println!(
        "{:>12} | {:>19} | {:>19} | {:>11} | {:>11}",
        "l0 / a", "minima (width w)", "minima (width 2w)", "V(0,0)", "E_c (paper)"
    );
    for l0 in [1.8, 2.0, 2.15, 2.2, 2.25, 2.28, 2.30, 2.304, top - 1e-6, top + 1e-9, 2.4] {
        let model = LinkageChain::new(chain, ROTORS, l0)?;
        let printed = model.with_profile_width(model.printed_profile_width())?;
        println!(
            "{l0:>12.7} | {:>19} | {:>19} | {:>11.4} | {:>11.4}",
            minima(&model),
            minima(&printed),
            model.separatrix_energy(),
            model.critical_energy()
        );
    }
    println!(
        "l12(0, 0) = {top:.10} a: l_critical up to the head's tanh tail (l_critical = {l_critical:.10})"
    );

    // Fig. fig:orbit: two kinks, l0 = 2.15 < l_critical, below and above E_c.
    let model = LinkageChain::new(chain, ROTORS, 2.15)?;
    let x_eq = model.equilibria()[2].x;
    let e_c = model.separatrix_energy();
    let (dt, steps) = (4.0e-4, 10_000);
    println!(
        "\nTwo-kink trajectories, l0 = 2.15, E_c = {e_c:.3}, x_eq = {x_eq:.4}; {steps} leapfrog steps of dt = {dt}"
    );
    println!(
        "{:>14} | {:>9} | {:>7} | {:>9} | {:>10} | {:>5} | {:>5} | {:>7}",
        "start", "E", "E / E_c", "region", "min max|x|", "x1 0s", "x2 0s", "|dE|/E"
    );
    // Below E_c: kink 1 near the impurity, kink 2 mid-way; the kinks take turns (square annulus).
    let run = model.trajectory(start(&model, x_eq - 1.0, 4.0, 0.7 * e_c), dt, steps, 1)?;
    summary("E = 0.7 E_c", &model, &run)?;
    // On the diagonal, both kinks heading for their far ends together.
    for factor in [0.9, 1.2] {
        let x = 6.0;
        let kinetic = factor * e_c - model.potential(x, x);
        let p = -(model.kink_mass(x) * kinetic).sqrt();
        let run = model.trajectory(PhaseState { x1: x, x2: x, p1: p, p2: p }, dt, steps, 1)?;
        summary(&format!("diag, {factor} E_c"), &model, &run)?;
    }
    println!(
        "('min max|x|': how close both kinks come to their far ends at once; 'x 0s': far-end crossings)"
    );

    // Fig. fig:ELdiagram: the parabola E_c(l0) and the regions on either side.
    println!("\n(E, l0) diagram (Fig. fig:ELdiagram): E_c = k (l0 - l_critical)^2 / 2");
    println!(
        "{:>8} | {:>10} | {:>12} | {:>12} | {:>12}",
        "l0 / a", "E_c", "at 0.5 E_c", "at 1.5 E_c", "at E_c + 1"
    );
    let l0s = [1.8, 2.0, 2.2, 2.3, l_critical, 2.4, 2.6];
    for [l0, e_c] in el_diagram(&chain, &l0s)? {
        let region = |e: f64| -> Result<String, Box<dyn std::error::Error>> {
            Ok(format!("{:?}", Region::classify(&chain, l0, e)?))
        };
        println!(
            "{l0:>8.4} | {e_c:>10.3} | {:>12} | {:>12} | {:>12}",
            region(0.5 * e_c)?,
            region(1.5 * e_c)?,
            region(e_c + 1.0)?
        );
    }
    Ok(())
}
