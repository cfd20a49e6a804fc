//! The embedded kink run (docs/embedded.md): builds a kink with the branch solve, launches it
//! along its translation mode, steps it with velocity Verlet and prints wall positions and
//! energies through semihosting, in the format of `embedded_check::report`. The host harness
//! (`compare-firmware`) checks every printed number against the same run on the host.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use cortex_m_semihosting::hprintln;
use embedded_check::report::Header;
use embedded_check::{Real, Scenario, run};
use kink_firmware::{Chain, Float, N, exit};
use panic_semihosting as _;

#[entry]
fn main() -> ! {
    let scenario = Scenario::FIRMWARE;
    hprintln!("{}", Header { n: N, float: Float::NAME, scenario });
    match run::<Float, _, _, N>(&Chain, &scenario, |sample| hprintln!("{sample}")) {
        Ok(summary) => {
            hprintln!("{summary}");
            exit(true)
        }
        Err(error) => {
            hprintln!("error: {error}");
            exit(false)
        }
    }
}
