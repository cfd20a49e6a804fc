//! Compares the firmware's output under QEMU with the same run on the host.
//!
//! ```text
//! compare-firmware RUN [COST...]   check RUN (kink-run's output) against the host, and the final
//!                                  energy printed in each COST (verlet-cost's or verlet-bare's
//!                                  output); exit status 1 on any mismatch
//! compare-firmware --host          print the host's run in the firmware's format
//! ```

use std::process::ExitCode;

use embedded_check::report::Header;
use embedded_check::{Chain16, Real, Scenario};
use embedded_host::{CompareError, Tolerated, compare, compare_final_energy, host_run};

const USAGE: &str = "usage: compare-firmware RUN [COST...] | --host";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.as_slice() {
        [flag] if flag == "--host" => print_host(),
        [flag] if flag == "-h" || flag == "--help" => {
            println!("{USAGE}");
            ExitCode::SUCCESS
        }
        [run, costs @ ..] if !run.starts_with('-') => match check(run, costs) {
            Ok(()) => ExitCode::SUCCESS,
            Err(message) => {
                eprintln!("{message}");
                ExitCode::FAILURE
            }
        },
        _ => {
            eprintln!("{USAGE}");
            ExitCode::from(2)
        }
    }
}

fn print_host() -> ExitCode {
    let scenario = Scenario::FIRMWARE;
    println!("{}", Header { n: Chain16::N, float: f64::NAME, scenario });
    match host_run::<f64, _, { Chain16::N }>(&Chain16, &scenario) {
        Ok((samples, summary)) => {
            samples.iter().for_each(|s| println!("{s}"));
            println!("{summary}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn read(path: &str) -> Result<String, String> {
    std::fs::read_to_string(path).map_err(|e| format!("cannot read {path}: {e}"))
}

fn check(run: &str, costs: &[String]) -> Result<(), String> {
    let disagree = |path: &str, e: CompareError| format!("{path}: firmware and host disagree: {e}");
    let agreement = compare::<f64, _, { Chain16::N }>(&Chain16, &read(run)?).map_err(|e| disagree(run, e))?;
    println!("{run}: firmware agrees with the host (f64): {agreement}");
    let (_, summary) =
        host_run::<f64, _, { Chain16::N }>(&Chain16, &Scenario::FIRMWARE).map_err(|e| e.to_string())?;
    for path in costs {
        let difference = compare_final_energy(&read(path)?, &summary).map_err(|e| disagree(path, e))?;
        println!("{path}: final energy agrees with the host's, difference {difference:.3e} of E0");
    }
    let tolerance = f64::TOLERANCE;
    println!(
        "tolerance: {:.0e} sites in wall position, {:.0e} of E0 in energy",
        tolerance.position, tolerance.energy
    );
    Ok(())
}
