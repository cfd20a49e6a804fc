//! Setting a kink and an antikink in motion along their translation modes (paper Sec. V and
//! Appendix B): `r_i thetadot_i = v0 e_i` with `sum_i e_i^2 = 1`, so the kinetic energy is
//! `M v0^2 / 2`. For each defect and direction: the norm of `e`, the kinetic energy, where the mode
//! lives (its centre and participation number), and the way the defect moves in the first 0.5 t.
//! Then the near-zero modes of the antikink: its translation mode beside the edge modes of its
//! two domains, which mix in a finite chain; the launch separates them (issue 8's case, antikink
//! at rotor 44 at theta_bar = 0.28), and the leakage of launch energy away from the wall over the
//! paper's whole range.
//!
//! Run: `cargo run --example dynamics_launch`

use rotor_chain::ChainGeometry;
use rotor_chain::RuntimeChain;
use rotor_chain::dynamics::integrate::kinetic_energy;
use rotor_chain::dynamics::launch::{Direction, launch, static_defect, wall_width};
use rotor_chain::dynamics::observe::propagation;
use rotor_chain::dynamics::run::RunOptions;
use rotor_chain::statics::modes::{ModeKind, ModeOptions, modes};
use rotor_chain::statics::walls::Charge;

const V0: f64 = 2.4;
const START: f64 = 30.0;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let chain = RuntimeChain::builder(60, 0.8, 1.0e4, 0.58).build()?;
    println!("Launch (Appendix B): n = 60, r/a = 0.8, k = 1e4, theta_bar = 0.58, M = 1, v0 = {V0} a/t");
    println!("e: translation mode in tip displacements; participation 1 / sum e_i^4 = rotors taking part\n");
    println!(
        "{:>8} | {:>5} | {:>8} | {:>17} | {:>14} | {:>11} | {:>13} | {:>14} | {:>10}",
        "defect",
        "to",
        "starts at",
        "|e|",
        "T / (M v0^2/2)",
        "mode centre",
        "participation",
        "|e|^2 within 2",
        "at t = 0.5"
    );
    let short = RunOptions { t_max: 0.5, ..RunOptions::default() };
    for charge in [Charge::Kink, Charge::Antikink] {
        for direction in [Direction::Left, Direction::Right] {
            let l = launch(&chain, charge, START, V0, direction)?;
            let norm = l.mode.iter().map(|e| e * e).sum::<f64>().sqrt();
            let kinetic = kinetic_energy(&chain, &l.state.omega);
            let weights: Vec<f64> = l.mode.iter().map(|e| e * e).collect();
            let centre: f64 = weights.iter().enumerate().map(|(i, w)| i as f64 * w).sum();
            let participation = 1.0 / weights.iter().map(|w| w * w).sum::<f64>();
            let near: f64 = weights
                .iter()
                .enumerate()
                .filter(|(i, _)| (*i as f64 - l.position).abs() <= 2.0)
                .map(|(_, w)| w)
                .sum();
            // Where the launched defect is half a time unit later.
            let moved = propagation(&chain, charge, START, V0, direction, None, &short)?;
            let (_, x) = moved.positions.last().ok_or("the defect was lost")?;
            println!(
                "{:>8} | {:>5} | {:>8.3} | {:>17.15} | {:>14.12} | {:>11.3} | {:>13.3} | {:>14.6} | {:>10.3}",
                format!("{charge:?}").to_lowercase(),
                format!("{direction:?}").to_lowercase(),
                l.position,
                norm,
                kinetic / (0.5 * chain.mass() * V0 * V0),
                centre,
                participation,
                near,
                x
            );
        }
    }
    println!("('|e|^2 within 2': the share of the mode on the 5 rotors nearest the wall)");

    // The kink's ends are rigid; each domain of the antikink has a zero-energy edge mode at its
    // free end (docs/theory.md §6: the uniform zero mode decays away from that end).
    for (charge, theta_bar) in [(Charge::Kink, 0.58), (Charge::Antikink, 0.58), (Charge::Antikink, 0.28)] {
        let chain = RuntimeChain::builder(60, 0.8, 1.0e4, theta_bar).build()?;
        let theta = static_defect(&chain, charge, START)?;
        let found = modes(&chain, &theta, &ModeOptions { count: Some(4), ..ModeOptions::default() })?;
        let name = format!("{charge:?}").to_lowercase();
        println!("\nLowest modes of the {name} at {START}, theta_bar = {theta_bar} (Sec. IV; omega in 1/t):");
        println!(
            "{:>4} | {:>12} | {:>12} | {:>10} | {:>13} | {:>15}",
            "mode", "omega^2", "omega", "centre", "participation", "kind"
        );
        for (j, m) in found.iter().enumerate() {
            let kind = match m.kind {
                ModeKind::Translation => "translation".to_string(),
                ModeKind::Shape => "shape".to_string(),
                ModeKind::Edge { left } => format!("edge ({})", if left { "left" } else { "right" }),
                ModeKind::Extended => "extended".to_string(),
                _ => "unlabelled".to_string(),
            };
            println!(
                "{j:>4} | {:>+12.4e} | {:>12.4e} | {:>10.3} | {:>13.3} | {kind:>15}",
                m.omega_squared, m.frequency, m.position, m.participation
            );
        }
    }
    // The launch separates the translation from the edge modes: the most localised vector of the
    // near-null subspace (launch.rs). Issue 8's case first, then the whole range.
    let chain = RuntimeChain::builder(60, 0.8, 1.0e4, 0.28).build()?;
    let theta = static_defect(&chain, Charge::Antikink, 44.0)?;
    let found = modes(&chain, &theta, &ModeOptions { count: Some(3), ..ModeOptions::default() })?;
    let share = |e: &[f64]| e[54..].iter().map(|x| x * x).sum::<f64>() / e.iter().map(|x| x * x).sum::<f64>();
    let eigenvector = found.iter().find(|m| m.kind == ModeKind::Translation).ok_or("no translation mode")?;
    let tips: Vec<f64> =
        eigenvector.shape.iter().enumerate().map(|(i, v)| v * chain.rotor_length(i)).collect();
    let launched = launch(&chain, Charge::Antikink, 44.0, V0, Direction::Left)?;
    println!("\nAntikink at rotor 44, theta_bar = 0.28: share of sum e_i^2 on rotors 54-59");
    println!("  the eigenvector classified as its translation mode: {:.3}", share(&tips));
    println!("  the launch (most localised vector of the 3 lowest modes): {:.2e}", share(&launched.mode));

    println!(
        "\nLargest fraction of the launch kinetic energy farther than 3 wall widths (>= 3 sites) from the wall,"
    );
    println!("over starts from rotor 8 to 50.5 in steps of 2.5, both directions (n = 60):");
    println!("{:>10} | {:>6} | {:>10} | {:>10}", "theta_bar", "3w", "kink", "antikink");
    for k in 0..12 {
        let theta_bar = 0.1 + 0.05 * k as f64;
        let chain = RuntimeChain::builder(60, 0.8, 1.0e4, theta_bar).build()?;
        let distance = (3.0 * wall_width(&chain)).max(3.0);
        let mut worst = [0.0_f64; 2];
        for (c, charge) in [Charge::Kink, Charge::Antikink].into_iter().enumerate() {
            for s in 0..=17 {
                for direction in [Direction::Left, Direction::Right] {
                    let l = launch(&chain, charge, 8.0 + 2.5 * s as f64, V0, direction)?;
                    worst[c] = worst[c].max(l.kinetic_energy_beyond(distance));
                }
            }
        }
        println!("{theta_bar:>10.2} | {distance:>6.2} | {:>10.2e} | {:>10.2e}", worst[0], worst[1]);
    }
    Ok(())
}
