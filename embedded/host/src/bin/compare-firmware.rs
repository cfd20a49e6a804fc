//! Compares the firmware's output under QEMU with the same run on the host.
//!
//! ```text
//! compare-firmware RUN [COST...]   check RUN (kink-run's output) against the host, in the float
//!                                  type its header names (`float=f64` or `float=f32`), and the
//!                                  final energy printed in each COST (verlet-cost's or
//!                                  verlet-bare's output); an f32 run is also checked against the
//!                                  host's f64 run; exit status 1 on any mismatch
//! compare-firmware --host [f64|f32] print the host's run in the firmware's format
//! ```

use std::process::ExitCode;

use embedded_check::report::{Header, Record};
use embedded_check::{Chain16, Chain16F32, ChainGeometry, Scenario};
use embedded_host::{
    Agreement, CompareError, Tolerance, Tolerated, compare, compare_accuracy, compare_final_energy, host_run,
};

const USAGE: &str = "usage: compare-firmware RUN [COST...] | --host [f64|f32]";

/// Rotors of the firmware's chains.
const N: usize = Chain16::N;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.as_slice() {
        [flag] if flag == "--host" => print_host::<f64, _>(&Chain16),
        [flag, float] if flag == "--host" && float == "f64" => print_host::<f64, _>(&Chain16),
        [flag, float] if flag == "--host" && float == "f32" => print_host::<f32, _>(&Chain16F32),
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

fn print_host<T: Tolerated, M: ChainGeometry<T>>(chain: &M) -> ExitCode {
    let scenario = Scenario::FIRMWARE;
    println!("{}", Header { n: N, float: T::NAME, scenario });
    match host_run::<T, _, N>(chain, &scenario) {
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

/// The float type named in the header of the firmware's output.
fn float_of(text: &str) -> Option<&str> {
    text.lines().find_map(|line| match Record::<f64>::parse(line) {
        Ok(Record::Header(header)) => Some(header.float),
        _ => None,
    })
}

fn check(run: &str, costs: &[String]) -> Result<(), String> {
    let text = read(run)?;
    match float_of(&text) {
        Some("f64") => check_float::<f64, _>(&Chain16, run, &text, costs),
        Some("f32") => {
            check_float::<f32, _>(&Chain16F32, run, &text, costs)?;
            let agreement = compare_accuracy::<f32, _, N>(&Chain16, &text)
                .map_err(|e| format!("{run}: the f32 firmware is less accurate than documented: {e}"))?;
            println!("{run}: f32 firmware against the host's f64 run: {agreement}");
            print_tolerance("accuracy of f32", &f32::ACCURACY);
            Ok(())
        }
        Some(other) => Err(format!("{run}: the firmware ran float={other}; the host knows f64 and f32")),
        // No header: the comparison reports it.
        None => check_float::<f64, _>(&Chain16, run, &text, costs),
    }
}

/// `text` (from the file `run`) against the host's run in `T`, and the final energy of each cost
/// file.
fn check_float<T: Tolerated, M: ChainGeometry<T>>(
    chain: &M,
    run: &str,
    text: &str,
    costs: &[String],
) -> Result<(), String> {
    let disagree = |path: &str, e: CompareError| format!("{path}: firmware and host disagree: {e}");
    let agreement: Agreement = compare::<T, _, N>(chain, text).map_err(|e| disagree(run, e))?;
    println!("{run}: firmware agrees with the host ({}): {agreement}", T::NAME);
    let (_, summary) = host_run::<T, _, N>(chain, &Scenario::FIRMWARE).map_err(|e| e.to_string())?;
    for path in costs {
        let difference = compare_final_energy(&read(path)?, &summary).map_err(|e| disagree(path, e))?;
        println!("{path}: final energy agrees with the host's, difference {difference:.3e} of E0");
    }
    print_tolerance(&format!("tolerance ({})", T::NAME), &T::TOLERANCE);
    Ok(())
}

fn print_tolerance(what: &str, tolerance: &Tolerance) {
    println!(
        "{what}: {:.1e} sites in wall position, {:.1e} of E0 in energy",
        tolerance.position, tolerance.energy
    );
}
