//! The template of a firmware of one's own (docs/embedded.md §3, "Your own firmware"): it uses
//! `rotor-chain` directly, as a user's crate would, not this crate's harness. A chain declared
//! for the microcontroller's FPU, a kink built by the branch solve, launched, stepped with
//! velocity Verlet and its energy checked, and the wall's position printed through semihosting.
#![no_std]
#![no_main]

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use panic_semihosting as _;
use rotor_chain::embedded::{DomainWalls, DynamicsError, Phase, Verlet, kink_into, kink_launch_velocities};
use rotor_chain::rotor_chain;

/// 24 rotors in single precision (the Cortex-M4F's FPU); the paper's geometry, `theta_bar = 0.58`.
#[rotor_chain(n = 24, r = 0.8, theta_bar = 0.58, k = 1.0e4, float = f32)]
pub struct Chain;

#[entry]
fn main() -> ! {
    let ok = match run() {
        Ok((position, energy)) => {
            hprintln!("first-chain: the kink is at {} after t = 4, energy {}", position, energy);
            true
        }
        Err(e) => {
            hprintln!("first-chain: error: {}", e);
            false
        }
    };
    debug::exit(if ok { debug::EXIT_SUCCESS } else { debug::EXIT_FAILURE });
    // Only reached without a debugger or QEMU to end the program.
    loop {
        cortex_m::asm::wfi();
    }
}

/// The kink at rotor 6, launched at `v0 = 1` towards rotor 23 and followed for `t = 4` (2048 steps
/// of `2^-9`); returns its wall position and the energy.
fn run() -> Result<(f32, f32), DynamicsError> {
    let mut theta = [0.0f32; 24];
    kink_into(&Chain, 6.0, &mut theta)?;
    let omega = kink_launch_velocities(&Chain, &theta, 1.0)?;
    let mut verlet = Verlet::new(&Chain, Phase { time: 0.0, theta, omega }, 1.0 / 512.0)?;
    let launched = verlet.kinetic_energy(&Chain) + verlet.potential_energy(&Chain);
    let mut energy = launched;
    for step in 1..=2048 {
        verlet.step(&Chain)?;
        if step % 256 == 0 {
            // A step too long for the chain would run the energy away: stop with the numbers.
            energy = verlet.check_energy(&Chain, launched, 0.01 * launched)?;
        }
    }
    // The kink: one wall, between the rotors. `NaN` would mean it left the chain.
    let position = DomainWalls::of(verlet.theta()).next().map_or(f32::NAN, |wall| wall.position);
    Ok((position, energy))
}
