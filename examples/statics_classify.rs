//! Classifying equilibria by the tangent stiffness (paper Secs. IV, V): Morse index (negative
//! eigenvalues) and nullity (eigenvalues within `1e-10 ||K||` of zero) from Sturm counts, for the
//! uniform state, a kink, and the antikink's minimum and saddle (paper Fig. `fig:akconfigpn`).
//!
//! Run: `cargo run --example statics_classify`

use rotor_chain::linalg::SymmetricMatrix;
use rotor_chain::linalg::eigenvalues_in_index_range;
use rotor_chain::prelude::*;
use rotor_chain::statics::antikink::{AntikinkOptions, peierls_nabarro};
use rotor_chain::statics::classify::classify;
use rotor_chain::statics::kink::kink;

#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Chain;

const K: f64 = 1.0e4;
const ZERO: f64 = 1e-10; // eigenvalues within ZERO * ||K|| of zero count as zero

/// One table row: the classification of `theta` with free or held end rotors.
fn row(what: &str, theta: &[f64], hold_ends: bool) -> Result<(), Box<dyn std::error::Error>> {
    let k = SymmetricMatrix::tangent_stiffness(&Chain, theta)?;
    let k = if hold_ends { k.principal(1..theta.len() - 1) } else { k };
    let c = classify(&k, ZERO)?;
    let (diag, off) = k.bands().expect("a chain's stiffness is tridiagonal");
    let lowest = eigenvalues_in_index_range(diag, off, 0, 3)?;
    println!(
        "{what:>22} | {:>5} | {:>5} | {:>7} | {:>32} | {:>10.2e} | {:>+10.3e} {:>+10.3e} {:>+10.3e}",
        if hold_ends { "held" } else { "free" },
        c.index,
        c.nullity,
        format!("{:?}", c.kind),
        c.tolerance / K,
        lowest[0] / K,
        lowest[1] / K,
        lowest[2] / K
    );
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("Equilibria of the n = 60 chain, r/a = 0.8, theta_bar = 0.58 rad, k = 1e4");
    println!("index = eigenvalues of K below -tol, nullity = eigenvalues in [-tol, tol], tol = 1e-10 ||K||");
    println!("eigenvalues lambda of K = d2V/dtheta2 in units of k a^2 (per rad^2)\n");
    println!(
        "{:>22} | {:>5} | {:>5} | {:>7} | {:>32} | {:>10} | {:>32}",
        "configuration", "ends", "index", "nullity", "kind", "tol/(k a^2)", "three lowest lambda / (k a^2)"
    );
    let uniform = vec![0.58; Chain::N];
    row("uniform +theta_bar", &uniform, false)?;
    row("kink at 29.5", &kink(&Chain, 29.5)?, false)?;
    row("kink at 10", &kink(&Chain, 10.0)?, false)?;
    let pn = peierls_nabarro(&Chain, &AntikinkOptions::default())?;
    for (what, a) in [("antikink minimum (29)", pn.minimum()?), ("antikink saddle (29.5)", pn.saddle()?)] {
        row(what, &a.theta, true)?;
        row(what, &a.theta, false)?;
    }
    println!(
        "\nthe antikink analysis's own classification (held ends): minimum {:?}, saddle {:?}",
        pn.minimum()?.classification.kind,
        pn.saddle()?.classification.kind
    );
    Ok(())
}
