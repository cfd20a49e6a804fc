//! Vibrational modes about the kink and the antikink (paper Sec. IV, Figs. `fig:mode-config`,
//! `fig:w-th`): the lowest modes with their kind, position and participation number, the shape and
//! translation frequencies against the continuum (Eq. `eq:continuumtheoryfrequency2`), and the
//! uniform chain's spectrum against its exact dispersion.
//!
//! Run: `cargo run --example statics_modes`

use rotor_chain::RuntimeChain;
use rotor_chain::prelude::*;
use rotor_chain::statics::antikink::{AntikinkOptions, peierls_nabarro};
use rotor_chain::statics::continuum::ContinuumChain;
use rotor_chain::statics::kink::kink;
use rotor_chain::statics::modes::{Mode, ModeKind, ModeOptions, modes};

const N: usize = 60;
const K: f64 = 1.0e4;
/// The paper's frequency unit (r/a) sqrt(k/M) (Sec. VII-A), in 1/t.
const UNIT: f64 = 0.8 * 100.0;

fn chain(theta_bar: f64) -> Result<RuntimeChain, ParameterError> {
    RuntimeChain::builder(N, 0.8, K, theta_bar).build()
}

fn print_modes(title: &str, list: &[Mode]) {
    println!("{title}");
    println!(
        "{:>4} | {:>12} | {:>12} | {:>13} | {:>14} | {:>8} | {:>13}",
        "mode", "omega (1/t)", "omega / unit", "omega^2", "kind", "position", "participation"
    );
    for (i, m) in list.iter().enumerate() {
        println!(
            "{i:>4} | {:>12.5e} | {:>12.5e} | {:>+13.5e} | {:>14} | {:>8.2} | {:>13.2}",
            m.frequency,
            m.frequency / UNIT,
            m.omega_squared,
            format!("{:?}", m.kind),
            m.position,
            m.participation
        );
    }
}

fn first(list: &[Mode], kind: ModeKind) -> f64 {
    list.iter().find(|m| m.kind == kind).map_or(f64::NAN, |m| m.frequency)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!(
        "Modes K v = omega^2 M r^2 v, n = 60, r/a = 0.8, k = 1e4, M = 1; unit = (r/a) sqrt(k/M) = 80 / t\n"
    );
    let lowest = ModeOptions { count: Some(6), ..ModeOptions::default() };
    // The antikink is computed with its end rotors held (AntikinkOptions::default), so its modes are too.
    let held = ModeOptions { hold_ends: true, ..lowest };
    for theta_bar in [0.58, 0.1] {
        let model = chain(theta_bar)?;
        let shape = ContinuumChain::new(1.0, 0.8, theta_bar, K, 1.0)?.shape_mode_frequency();
        print_modes(
            &format!("kink at 29.5, theta_bar = {theta_bar} (continuum shape mode {shape:.4} / t):"),
            &modes(&model, &kink(&model, 29.5)?, &lowest)?,
        );
        let pn = peierls_nabarro(&model, &AntikinkOptions::default())?;
        print_modes(
            &format!("antikink minimum at {:.3}, theta_bar = {theta_bar}, ends held:", pn.minimum()?.centre),
            &modes(&model, &pn.minimum()?.theta, &held)?,
        );
        println!();
    }

    // Fig. fig:w-th: localised-mode frequencies against theta_bar.
    println!("Localised modes vs theta_bar (Fig. fig:w-th), frequencies in 1/t");
    println!(
        "{:>5} | {:>10} | {:>10} | {:>10} | {:>10} | {:>10} | {:>10} | {:>10}",
        "theta", "kink w_t", "kink w_s", "ak w_t", "ak w_s", "continuum", "kink/cont", "ak/cont"
    );
    for theta_bar in [0.1, 0.2, 0.3, 0.4, 0.5, 0.58, 0.65] {
        let model = chain(theta_bar)?;
        let continuum = ContinuumChain::new(1.0, 0.8, theta_bar, K, 1.0)?.shape_mode_frequency();
        let k_modes = modes(&model, &kink(&model, 29.5)?, &lowest)?;
        let pn = peierls_nabarro(&model, &AntikinkOptions::default())?;
        let a_modes = modes(&model, &pn.minimum()?.theta, &held)?;
        let (ks, a_s) = (first(&k_modes, ModeKind::Shape), first(&a_modes, ModeKind::Shape));
        println!(
            "{theta_bar:>5.2} | {:>10.3e} | {ks:>10.4} | {:>10.3e} | {a_s:>10.4} | {continuum:>10.4} | {:>10.4} | {:>10.4}",
            first(&k_modes, ModeKind::Translation),
            first(&a_modes, ModeKind::Translation),
            ks / continuum,
            a_s / continuum
        );
    }

    // The uniform chain: every mode against the exact finite-chain dispersion.
    let model = chain(0.58)?;
    let all = modes(&model, &[0.58; N], &ModeOptions { count: None, ..ModeOptions::default() })?;
    let continuum = ContinuumChain::new(1.0, 0.8, 0.58, K, 1.0)?;
    let exact = continuum.finite_chain_frequencies(N)?;
    // The zero mode is exact only to rounding (omega ~ sqrt(eps ||K||)); the band to many digits.
    let worst =
        all.iter().zip(&exact).skip(1).map(|(m, e)| (m.frequency / e - 1.0).abs()).fold(0.0, f64::max);
    let [bottom, top] = continuum.phonon_band_edges();
    println!(
        "\nUniform chain, theta_bar = 0.58: all {} modes vs omega_j = omega(j pi / n) (exact)",
        all.len()
    );
    println!("{:>4} | {:>14} | {:>14} | {:>14}", "j", "ours (1/t)", "exact (1/t)", "kind");
    for j in [0, 1, 2, 3, N - 2, N - 1] {
        println!(
            "{j:>4} | {:>14.9} | {:>14.9} | {:>14}",
            all[j].frequency,
            exact[j],
            format!("{:?}", all[j].kind)
        );
    }
    println!(
        "largest relative difference over the 59 band modes = {worst:.2e}; band edges omega(0) = {bottom:.6}, \
         omega(pi) = {top:.6} / t"
    );
    Ok(())
}
