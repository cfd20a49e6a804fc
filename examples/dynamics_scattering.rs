//! Scattering on a stiffness impurity (paper Sec. VI, Figs. `fig:k-scatter`, `fig:ak-scatter`): the
//! five named points of the paper at theta_bar = 0.28 (n = 60, r/a = 0.8, k = 1e4, the impurity on
//! the middle spring 29), each launched from 15 sites to the right of it. Our outcome, when it was
//! decided, the walls at the end of the run, beside the paper's outcome; then the walls over time
//! for the kink that splits.
//!
//! Run: `cargo run --example dynamics_scattering`

use rotor_chain::RuntimeChain;
use rotor_chain::dynamics::scatter::{ScatterSetup, Scattering, scatter};
use rotor_chain::dynamics::track::Snapshot;
use rotor_chain::statics::walls::Charge;

const K: f64 = 1.0e4;
const IMPURITY: usize = 29;

fn run(charge: Charge, v0: f64, ki_ratio: f64) -> Result<Scattering, Box<dyn std::error::Error>> {
    let model = RuntimeChain::builder(60, 0.8, K, 0.28).spring_constant(IMPURITY, ki_ratio * K).build()?;
    Ok(scatter(&model, &ScatterSetup::from_the_right(charge, v0, IMPURITY))?)
}

fn walls(s: &Snapshot) -> String {
    let walls: Vec<String> = s
        .walls
        .iter()
        .zip(&s.at_boundary)
        .map(|(w, b)| {
            let c = if w.charge == Charge::Kink { "K" } else { "A" };
            format!("{c}{:.1}{}", w.position, if *b { "(end)" } else { "" })
        })
        .collect();
    walls.join(" ")
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("Scattering at theta_bar = 0.28, n = 60, r/a = 0.8, k = 1e4, M = 1; impurity k_i on spring 29");
    println!(
        "(x_imp = 29.5); the defect starts 15 sites to its right (the antikink at the nearest PN minimum)\n"
    );
    println!(
        "{:>8} | {:>4} | {:>6} | {:>5} | {:>11} | {:>10} | {:>7} | {:>11} | {:>10} | {:>11}",
        "defect", "v0", "k_i/k", "from", "ours", "decided at", "kinks", "antikinks", "max|dE|/E0", "paper"
    );
    let points = [
        (Charge::Kink, 4.0, 0.10, "transmitted"),
        (Charge::Kink, 9.6, 0.01, "split"),
        (Charge::Antikink, 4.0, 0.80, "transmitted"),
        (Charge::Antikink, 4.0, 0.70, "trapped"),
        (Charge::Antikink, 4.8, 0.20, "reflected"),
    ];
    let mut finals = Vec::new();
    for (charge, v0, ki_ratio, paper) in points {
        let result = run(charge, v0, ki_ratio)?;
        let last = result.run.tracker.snapshots.last().ok_or("the run recorded nothing")?;
        let (kinks, antikinks) = last.counts();
        let from = result.run.tracker.snapshots[0].walls[0].position;
        let report = &result.run.report;
        println!(
            "{:>8} | {v0:>4} | {ki_ratio:>6.2} | {from:>5.1} | {:>11} | {:>10.2} | {kinks:>7} | {antikinks:>11} | {:>10.1e} | {paper:>11}",
            format!("{charge:?}").to_lowercase(),
            result.outcome.name(),
            result.decided_at,
            report.max_energy_error / report.energy_initial
        );
        let violations = result.run.tracker.violations.len();
        let name = format!("{charge:?}").to_lowercase();
        finals.push(format!("{name:>8} {v0:>4} {ki_ratio:>5.2} | {violations:>10} | {}", walls(last)));
    }
    println!(
        "(kinks, antikinks: walls at the end of the run, 1 t after the decision to confirm it; boundary walls included)"
    );
    println!(
        "\nWalls at the end of the run ('(end)': a boundary wall, Appendix C), and the outputs at which"
    );
    println!("N_K - N_A differed from its initial value (+1 kink, -1 antikink):");
    println!("{:>19} | {:>10} | walls", "", "violations");
    for line in &finals {
        println!("{line}");
    }

    // The split (Fig. fig:k-split-utn): one kink in, a kink out on each side, an antikink left on
    // the impurity.
    let result = run(Charge::Kink, 9.6, 0.01)?;
    println!("\nKink, v0 = 9.6, k_i/k = 0.01: walls every 0.1 t until the decision (outputs every 0.01 t)");
    for s in result.run.tracker.snapshots.iter().step_by(10) {
        println!("{:>5.2} | {}", s.time, walls(s));
    }
    let last = result.run.tracker.snapshots.last().ok_or("the run recorded nothing")?;
    println!("{:>5.2} | {}   <- {}", last.time, walls(last), result.outcome.name());
    Ok(())
}
