//! Issue 36, demonstration 1 as a figure: the paper's chain declared as a rotor network beside the
//! chain code (`chain_paper::network::demonstration`), rendered to PNG, SVG and CSV.
//!
//! ```text
//! cargo run --release -p rotor-chain-paper --example network_chain -- docs/figures
//! ```
//! (about 20 s in release: eight scattering runs and two Peierls-Nabarro analyses at n = 60).

use std::path::PathBuf;
use std::process::ExitCode;

use chain_paper::figures::Params;
use chain_paper::network::demonstration::chain_as_network;

fn main() -> ExitCode {
    let out = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "docs/figures".to_owned()));
    let figure = match chain_as_network(&Params::default()) {
        Ok(figure) => figure,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    for row in &figure.rows {
        println!("{} | chain code: {} | network: {} | {}", row.quantity, row.paper, row.ours, row.note);
    }
    if let Err(e) = std::fs::create_dir_all(&out) {
        eprintln!("error: cannot create {}: {e}", out.display());
        return ExitCode::FAILURE;
    }
    let written =
        chain_paper::render::render(&figure, &out).map_err(|e| e.to_string()).and_then(|mut files| {
            files.extend(chain_paper::data::write_csv(&figure, &out).map_err(|e| e.to_string())?);
            Ok(files)
        });
    match written {
        Ok(files) => {
            for f in files {
                println!("{}", f.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
