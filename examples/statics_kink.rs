//! The zero-energy kink at any centre (paper Sec. II, Fig. `fig:kcobweb`): built outward from its
//! centre, it costs no energy wherever it sits, and its wall (Appendix C coordinate) is where it
//! was asked to be. The mechanism path moves it along the chain at zero energy.
//!
//! Run: `cargo run --example statics_kink`

use rotor_chain::prelude::*;
use rotor_chain::statics::kink::{kink, mechanism_path};
use rotor_chain::statics::walls::domain_walls;

#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Chain;

const K: f64 = 1.0e4;

/// `max_p |l_p - l0_p|`, in units of `a`.
fn largest_stretch(chain: &Chain, theta: &[f64]) -> f64 {
    let mut lengths = vec![0.0; Chain::N - 1];
    chain.spring_lengths_into(theta, &mut lengths);
    lengths.iter().enumerate().map(|(p, l)| (l - chain.rest_length(p)).abs()).fold(0.0, f64::max)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let chain = Chain;
    println!("Zero-energy kink, n = 60, r/a = 0.8, theta_bar = 0.58 rad, k = 1e4 (energies in k a^2)");
    println!("requirement: V <= 1e-20 k a^2 at every centre; g = dV/dtheta (units of energy per rad)\n");
    println!(
        "{:>7} | {:>11} | {:>10} | {:>12} | {:>12} | {:>9} | {:>9} | {:>8}",
        "centre", "V / (k a^2)", "<= 1e-20", "max|l - l0|/a", "max|g|/k", "theta_0", "theta_59", "wall at"
    );
    for centre in [10.0, 29.5, 41.25] {
        let theta = kink(&chain, centre)?;
        let energy = Potential::energy(&chain, &theta) / K;
        let mut gradient = vec![0.0; Chain::N];
        chain.gradient_into(&theta, &mut gradient);
        let force = gradient.iter().fold(0.0f64, |m, g| m.max(g.abs())) / K;
        let walls = domain_walls(&theta);
        let wall = walls.iter().map(|w| format!("{:.6} {:?}", w.position, w.charge)).collect::<Vec<_>>();
        println!(
            "{centre:>7} | {energy:>11.2e} | {:>10} | {:>13.2e} | {force:>12.2e} | {:>+9.6} | {:>+9.6} | {}",
            if energy <= 1e-20 { "yes" } else { "NO" },
            largest_stretch(&chain, &theta),
            theta[0],
            theta[59],
            wall.join(", ")
        );
    }

    // The mechanism (paper Sec. II): the kink moved by one lattice spacing, then across the chain.
    println!("\nMechanism path: kink centres 29.0 -> 30.0 in 4 steps");
    println!(
        "{:>7} | {:>11} | {:>10} | {:>10} | {:>10}",
        "centre", "V / (k a^2)", "wall at", "theta_29", "theta_30"
    );
    for (centre, theta) in mechanism_path(&chain, 29.0, 30.0, 4)? {
        println!(
            "{centre:>7.2} | {:>11.2e} | {:>10.6} | {:>+10.6} | {:>+10.6}",
            Potential::energy(&chain, &theta) / K,
            domain_walls(&theta)[0].position,
            theta[29],
            theta[30]
        );
    }
    let long = mechanism_path(&chain, 2.0, 57.0, 220)?;
    let worst = long.iter().map(|(_, t)| Potential::energy(&chain, t) / K).fold(0.0, f64::max);
    println!(
        "centres 2 -> 57 in 220 steps of a/4: largest V = {worst:.2e} k a^2 over {} configurations",
        long.len()
    );
    Ok(())
}
