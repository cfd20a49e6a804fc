//! A spring-length impurity on the middle spring (paper Sec. VII-A, Fig. `fig:longbar`): the
//! zero-energy two-kink state, its zero mode and soft mode, the soft tensional mode, and
//! `l_critical`, where the soft mode becomes a second zero mode and the tensional mode a state of
//! self-stress.
//!
//! Run: `cargo run --example statics_impurity`

use rotor_chain::RuntimeChain;
use rotor_chain::linalg::SymmetricMatrix;
use rotor_chain::prelude::*;
use rotor_chain::statics::continuum::ContinuumChain;
use rotor_chain::statics::impurity::{ImpurityAnalysis, critical_length, impurity_analysis};
use rotor_chain::statics::walls::domain_walls;

const K: f64 = 1.0e4;
/// The paper's frequency unit (r/a) sqrt(k/M), in 1/t.
const UNIT: f64 = 0.8 * 100.0;

/// The chain of `n` rotors with the middle spring `n / 2 - 1` of rest length `l0`.
fn chain(n: usize, l0: f64) -> Result<RuntimeChain, ParameterError> {
    RuntimeChain::builder(n, 0.8, K, 0.58).spring_rest_length(n / 2 - 1, l0).build()
}

fn analyse(n: usize, l0: f64) -> Result<ImpurityAnalysis, Box<dyn std::error::Error>> {
    Ok(impurity_analysis(&chain(n, l0)?, n / 2 - 1)?)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let continuum = ContinuumChain::new(1.0, 0.8, 0.58, K, 1.0)?;
    let l_critical = continuum.l_critical();
    println!("Spring-length impurity on spring 29 of the n = 60 chain, r/a = 0.8, theta_bar = 0.58, k = 1e4");
    println!(
        "l_critical = sqrt((2 r sin theta_bar + a)^2 + (2 r cos theta_bar)^2) = {l_critical:.12} a; \
         critical_length(spring 29) = {:.12} a; paper 2.31",
        critical_length(&chain(60, 2.0)?, 29)?
    );
    println!("frequencies in 1/t and in the paper's unit (r/a) sqrt(k/M) = 80 / t\n");
    println!(
        "{:>8} | {:>15} | {:>10} | {:>10} | {:>10} | {:>11} | {:>10} | {:>7} | {:>9}",
        "l0 / a",
        "kinks at",
        "zero mode",
        "soft mode",
        "soft/unit",
        "soft/(lc-l0)",
        "tension ev",
        "at",
        "zero/self"
    );
    for l0 in [1.8, 2.0, 2.2, 2.25, 2.28, 2.30, l_critical] {
        let a = match analyse(60, l0) {
            Ok(a) => a,
            Err(e) => {
                println!("{l0:>8.4} | {e}");
                continue;
            }
        };
        let walls = domain_walls(&a.theta);
        let kinks: Vec<String> = walls.iter().map(|w| format!("{:.2}", w.position)).collect();
        let soft = a.modes[1].frequency;
        let peak = a
            .tensional
            .tensions
            .iter()
            .enumerate()
            .max_by(|x, y| x.1.abs().total_cmp(&y.1.abs()))
            .map_or(0, |(p, _)| p);
        println!(
            "{l0:>8.4} | {:>15} | {:>10.2e} | {soft:>10.3e} | {:>10.3e} | {:>11.1} | {:>10.3e} | {:>7} | {:>9}",
            kinks.join(" "),
            a.modes[0].frequency,
            soft / UNIT,
            soft / (l_critical - l0),
            a.tensional.eigenvalue,
            format!("spr {peak}"),
            format!("{}/{}", a.counting.zero_modes.len(), a.counting.self_stresses.len())
        );
    }
    println!("('kinks at' lists every sign change: kink, the impurity's own -phi/+phi pair at 29.5, kink)");
    println!(
        "paper Fig. fig:longbar: soft mode 7.7e-9 (r/a) sqrt(k/M) at l0 = 2.30 (n not stated; 16 in Fig. fig:defectiveKL)"
    );

    // Does the chain length set the soft mode? n = 16 against n = 60, as l0 -> l_critical.
    println!("\nSoft mode against l_critical - l0, n = 16 (spring 7) and n = 60 (spring 29)");
    println!(
        "{:>9} | {:>12} | {:>12} | {:>12} | {:>12}",
        "lc - l0", "n=16 soft/u", "n=16 kinks", "n=60 soft/u", "n=60 kinks"
    );
    for delta in [l_critical - 2.30, 1e-3, 1e-5, 1e-7, 1e-8, 1e-9] {
        let mut cells = Vec::new();
        for n in [16, 60] {
            let a = analyse(n, l_critical - delta)?;
            cells.push(format!("{:>12.3e}", a.modes[1].frequency / UNIT));
            cells.push(format!("{:>12}", domain_walls(&a.theta).len()));
        }
        println!("{delta:>9.1e} | {}", cells.join(" | "));
    }
    // An eigenvalue omega^2 is accurate to about eps ||K|| / (M r^2): below that, omega is noise.
    let model = chain(60, 2.30)?;
    let k = SymmetricMatrix::tangent_stiffness(&model, &analyse(60, 2.30)?.theta)?;
    println!(
        "resolution of omega from a double-precision omega^2: sqrt(eps ||K|| / (M r^2)) = {:.1e} (r/a) sqrt(k/M)",
        (f64::EPSILON * k.inf_norm() / 0.64).sqrt() / UNIT
    );
    Ok(())
}
