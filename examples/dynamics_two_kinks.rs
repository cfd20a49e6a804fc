//! Two-kink dynamics in the linkage limit (paper Sec. VII-B, Fig. `fig:orbit`): two rigid
//! sub-chains of 8 rotors joined head to head by a soft impurity spring of rest length `l0`, reduced
//! to the kink positions `x1`, `x2` (Appendix C coordinates: 0 at a far end, 8 at the head) and
//! integrated with the symplectic generalised Stormer-Verlet method of `statics::linkage`. The four
//! panels of the figure: `l0 < l_critical` below and above `E_c`, `l0 = l_critical`, and
//! `l0 > l_critical`. For each: whether the trajectory enters the central square of the `(x1, x2)`
//! plane (both kinks more than half a sub-chain from the impurity at once, which the square annulus
//! below `E_c` forbids), the energy error, and a picture of where it went.
//!
//! Run: `cargo run --example dynamics_two_kinks`

use rotor_chain::statics::continuum::ContinuumChain;
use rotor_chain::statics::linkage::{LinkageChain, PhaseState, TrajectoryPoint};

const K: f64 = 1.0e4;
const ROTORS: usize = 8;
const DT: f64 = 4.0e-4;
const STEPS: usize = 10_000;
/// The central square: both `|x_i| < CENTRE` (more than `ROTORS - CENTRE` sites from the impurity).
const CENTRE: f64 = 4.0;
/// The picture: `CELLS` cells over `-LIMIT..LIMIT` in both coordinates.
const LIMIT: f64 = 9.0;
const CELLS: usize = 19;

/// A state at `(x1, x2)` moving with `p1 = p2 <= 0` (towards the far ends) and energy `energy`.
fn heading_out(model: &LinkageChain, x1: f64, x2: f64, energy: f64) -> PhaseState {
    let kinetic = (energy - model.potential(x1, x2)).max(0.0);
    // Share the kinetic energy equally: p_i^2 / (2 m(x_i)) = kinetic / 2.
    let p = |x: f64| -(model.kink_mass(x) * kinetic).sqrt();
    PhaseState { x1, x2, p1: p(x1), p2: p(x2) }
}

/// Which cells of the `(x1, x2)` plane the trajectory visited.
fn picture(run: &[TrajectoryPoint]) -> Vec<String> {
    let cell =
        |x: f64| (((x + LIMIT) / (2.0 * LIMIT) * CELLS as f64).floor().max(0.0) as usize).min(CELLS - 1);
    let mut grid = vec![vec![' '; CELLS]; CELLS];
    for p in run {
        grid[CELLS - 1 - cell(p.x2)][cell(p.x1)] = '*';
    }
    let centre = CELLS / 2;
    if grid[centre][centre] == ' ' {
        grid[centre][centre] = '+';
    }
    grid.into_iter().map(|row| row.into_iter().collect()).collect()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let chain = ContinuumChain::new(1.0, 0.8, 0.58, K, 1.0)?;
    let l_critical = chain.l_critical();
    println!(
        "Linkage limit (Sec. VII-B): two sub-chains of {ROTORS} rotors, r/a = 0.8, theta_bar = 0.58, k = 1e4,"
    );
    println!(
        "M = 1; l_critical = {l_critical:.6} a; {STEPS} symplectic steps of dt = {DT} t; energies in M a^2/t^2\n"
    );
    let below = LinkageChain::new(chain, ROTORS, 2.15)?;
    let e_c = below.separatrix_energy();
    let x_eq = below.equilibria().iter().filter(|e| e.stable).map(|e| e.x).fold(0.0, f64::max);
    let at_critical = LinkageChain::new(chain, ROTORS, l_critical)?;
    let above = LinkageChain::new(chain, ROTORS, 2.4)?;
    let e_min = above.critical_energy();
    let cases = [
        // (a) the kinks take turns: kink 1 next to its equilibrium, kink 2 half-way out.
        ("(a) l0 = 2.15, E = 0.7 E_c", &below, {
            let kinetic = 0.7 * e_c - below.potential(x_eq - 1.0, 4.0);
            let p1 = (2.0 * below.kink_mass(x_eq - 1.0) * kinetic).sqrt();
            PhaseState { x1: x_eq - 1.0, x2: 4.0, p1, p2: 0.0 }
        }),
        // (b) both kinks leave the impurity at once.
        ("(b) l0 = 2.15, E = 1.2 E_c", &below, heading_out(&below, 6.0, 6.0, 1.2 * e_c)),
        // (c) E_c = 0: any energy reaches the centre. Away from the heads V is flat, so the kinks
        // fly straight and bounce off the impurity: a billiard.
        ("(c) l0 = l_critical, E = 20", &at_critical, heading_out(&at_critical, 6.0, 4.0, 20.0)),
        // (d) the impurity pushes both kinks to the far ends; E >= E_min.
        ("(d) l0 = 2.4, E = 1.2 E_min", &above, heading_out(&above, 3.0, 2.0, 1.2 * e_min)),
    ];
    println!(
        "l0 = 2.15: E_c = {e_c:.3} (V(0,0)), kink minima at +-{x_eq:.3}; l0 = 2.4: E_min = {e_min:.3}\n"
    );
    println!(
        "{:<29} | {:>8} | {:>9} | {:>14} | {:>17} | {:>13} | {:>9}",
        "case", "E", "region", "k(l0-l_c)^2/2", "min_t max|x1|,|x2|", "enters centre", "max|dE|/E"
    );
    let mut panels = Vec::new();
    for (label, model, start) in cases {
        let run = model.trajectory(start, DT, STEPS, 1)?;
        let e0 = run[0].energy;
        let error = run.iter().map(|p| (p.energy - e0).abs()).fold(0.0, f64::max) / e0;
        let inner = run.iter().map(|p| p.x1.abs().max(p.x2.abs())).fold(f64::INFINITY, f64::min);
        println!(
            "{label:<29} | {e0:>8.3} | {:>9} | {:>14.3} | {inner:>17.3} | {:>13} | {error:>9.1e}",
            format!("{:?}", model.region(e0)?),
            model.critical_energy(),
            if inner < CENTRE { "yes" } else { "no" }
        );
        panels.push(picture(&run));
    }
    println!(
        "('enters centre': both |x_i| < {CENTRE} at the same time, i.e. both kinks away from the impurity)"
    );

    println!(
        "\nWhere each trajectory went: x1 across (-{LIMIT} to {LIMIT}), x2 up; '+' the centre if not visited"
    );
    println!("{:^21}{:^21}{:^21}{:^21}", "(a)", "(b)", "(c)", "(d)");
    for row in 0..CELLS {
        let line: Vec<String> = panels.iter().map(|p| format!("|{}|", p[row])).collect();
        println!("{}", line.join(""));
    }
    Ok(())
}
