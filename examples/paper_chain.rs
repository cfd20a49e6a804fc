//! The paper's chain (r/a = 0.8, theta_bar = 0.58, k = 1e4, M = 1, n = 60): a zero-energy kink in
//! the middle, its energy, and the spectrum of its tangent stiffness.
//!
//! Run: `cargo run --release --example paper_chain`

use rotor_chain::nalgebra::SymmetricEigen;
use rotor_chain::prelude::*;

#[rotor_chain(n = 60, a = 1.0, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 1.0)]
struct Chain;

/// The kink centred on rotor `centre`: that rotor stands vertical (theta = 0), and the profile is
/// built outward with the forward branch map to the right and the inverse map to the left (paper
/// Sec. II, Appendix A). Both directions run into the attracting side of their map, so no
/// precision is lost however long the chain.
fn kink(chain: &Chain, centre: usize) -> Result<[f64; 60], BranchError> {
    let mut theta = [0.0; 60];
    for p in centre..59 {
        theta[p + 1] = chain.next_angles(p, theta[p])?[0];
    }
    for p in (0..centre).rev() {
        theta[p] = chain.previous_angles(p, theta[p + 1])?[0];
    }
    Ok(theta)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let chain = Chain;
    let (r, a, k, m) = (0.8f64, 1.0f64, 1.0e4f64, 1.0f64);
    let theta_bar = chain.theta_bar();
    println!(
        "Topological rotor chain: n = {}, r/a = {r}, theta_bar = {theta_bar}, k = {k}, M = {m}",
        Chain::N
    );
    println!("spring rest length lbar = {:.6} a", chain.rest_length(0));

    let theta = kink(&chain, 30)?;
    println!("\nKink centred on rotor 30 (theta from +theta_bar on the left to -theta_bar on the right):");
    for row in theta.chunks(10) {
        println!("  {}", row.iter().map(|t| format!("{t:+.4}")).collect::<Vec<_>>().join(" "));
    }
    let energy = chain.energy(&theta);
    let max_force = chain.gradient(&theta).iter().fold(0.0f64, |acc, g| acc.max(g.abs()));
    println!(
        "energy V = {energy:.3e} M a^2/t^2 (a zero-energy mechanism), max |dV/dtheta| = {max_force:.3e}"
    );

    let antikink = theta.map(|t| -t);
    println!(
        "its reflection (an unrelaxed antikink) costs V = {:.1} M a^2/t^2 (= {:.4} k a^2)",
        chain.energy(&antikink),
        chain.energy(&antikink) / k
    );

    let eig = SymmetricEigen::new(chain.hessian(&theta));
    let mut lambda: Vec<f64> = eig.eigenvalues.iter().copied().collect();
    lambda.sort_by(f64::total_cmp);
    println!("\nTangent stiffness spectrum around the kink, omega = sqrt(lambda / (M r^2)):");
    for (i, l) in lambda.iter().take(6).enumerate() {
        println!("  mode {i}: lambda = {l:+.6e}   omega = {:.6}", (l.max(0.0) / (m * r * r)).sqrt());
    }
    let (rl, s, c) = (r / a, theta_bar.sin(), theta_bar.cos());
    let shape = rl * (12.0 * k / m).sqrt() * s / (1.0 + 4.0 * rl * rl * c * c).sqrt();
    println!("  continuum shape-mode frequency (paper Eq. eq:continuumtheoryfrequency2): {shape:.4}");
    println!("  highest: lambda = {:.6e}", lambda[59]);
    Ok(())
}
