//! Maxwell-Calladine counting (paper Sec. VII-A): rank of the compatibility matrix, zero modes,
//! states of self-stress and their difference, which is `n - (n - 1) = 1` on every configuration,
//! and the extra zero mode and self-stress of a spring-length impurity at `l0 = l_critical`.
//!
//! Run: `cargo run --example statics_counting`

use rotor_chain::RuntimeChain;
use rotor_chain::prelude::*;
use rotor_chain::statics::antikink::{AntikinkOptions, peierls_nabarro};
use rotor_chain::statics::continuum::ContinuumChain;
use rotor_chain::statics::counting::maxwell_calladine;
use rotor_chain::statics::impurity::two_kink_configuration;
use rotor_chain::statics::kink::{kink, reflected_kink};

#[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
struct Chain;

const K: f64 = 1.0e4;

/// Where a vector is largest (its index).
fn peak(v: &[f64]) -> usize {
    v.iter().enumerate().max_by(|a, b| a.1.abs().total_cmp(&b.1.abs())).map_or(0, |(i, _)| i)
}

fn row<M: ChainModel>(what: &str, model: &M, theta: &[f64]) -> Result<(), Box<dyn std::error::Error>> {
    let c = maxwell_calladine(model, theta, None)?;
    let sigma_max = c.singular_values[0];
    let sigma_min = *c.singular_values.last().unwrap_or(&0.0);
    let places = |vs: &[Vec<f64>]| vs.iter().map(|v| peak(v).to_string()).collect::<Vec<_>>().join(",");
    println!(
        "{what:>32} | {:>3} | {:>4} | {:>4} | {:>5} | {:>5} | {:>9.2e} | {:>9.2e} | {:>8} | {:>8}",
        c.rotors,
        c.rank,
        c.zero_modes.len(),
        c.self_stresses.len(),
        c.index(),
        sigma_min / sigma_max,
        c.tolerance / sigma_max,
        places(&c.zero_modes),
        places(&c.self_stresses)
    );
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("Maxwell-Calladine counting: N_zero - N_selfstress = n - (n - 1) = 1 (paper Sec. VII-A)");
    println!(
        "C = dl_p / d(r_i theta_i), (n - 1) x n; rank from its singular values, tol = max(n, n-1) eps sigma_max"
    );
    println!("'peak at': the rotor (zero mode) or spring (self-stress) where each basis vector is largest\n");
    println!(
        "{:>32} | {:>3} | {:>4} | {:>4} | {:>5} | {:>5} | {:>9} | {:>9} | {:>8} | {:>8}",
        "configuration", "n", "rank", "zero", "self", "index", "smin/smax", "tol/smax", "zero at", "self at"
    );
    row("uniform +theta_bar", &Chain, &[0.58; 60])?;
    row("uniform -theta_bar", &Chain, &[-0.58; 60])?;
    row("kink at 29.5", &Chain, &kink(&Chain, 29.5)?)?;
    row("kink at 10.25", &Chain, &kink(&Chain, 10.25)?)?;
    row("reflected kink at 29 (not eq.)", &Chain, &reflected_kink(&Chain, 29.0)?)?;
    let pn = peierls_nabarro(&Chain, &AntikinkOptions::default())?;
    row("antikink minimum", &Chain, &pn.minimum()?.theta)?;
    row("antikink saddle", &Chain, &pn.saddle()?.theta)?;

    // The spring-length impurity on the middle spring (paper Fig. fig:longbar).
    let l_critical = ContinuumChain::new(1.0, 0.8, 0.58, K, 1.0)?.l_critical();
    for (n, l0, label) in [
        (60, 2.30, "two kinks, l0 = 2.30"),
        (60, l_critical, "l0 = l_critical"),
        (16, 2.30, "two kinks, l0 = 2.30"),
        (16, l_critical, "l0 = l_critical"),
    ] {
        let middle = n / 2 - 1;
        let model = RuntimeChain::builder(n, 0.8, K, 0.58).spring_rest_length(middle, l0).build()?;
        row(&format!("{label} (spring {middle})"), &model, &two_kink_configuration(&model, middle)?)?;
    }
    println!("\nl_critical = {l_critical:.10} a (paper 2.31)");
    Ok(())
}
