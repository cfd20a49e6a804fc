//! The smallest program that does the work: builds the kink of `Scenario::FIRMWARE` with the
//! branch solve, launches it and takes the run's 1024 Verlet steps, with no `core::fmt` anywhere (errors
//! and panics only exit, the one output line is assembled by hand). `arm-none-eabi-size` on this
//! ELF is the flash and RAM of a 16-rotor chain with a Verlet stepper (docs/embedded.md); it
//! prints its peak stack and the final energy's bits, which the host checks.
#![no_std]
#![no_main]

use core::panic::PanicInfo;

use cortex_m_rt::entry;
use cortex_m_semihosting::hio;
use embedded_check::{DynamicsError, Real, Scenario, launched_kink};
use kink_firmware::{Chain, Float, N, exit, peak_stack_bytes};

/// The steps of the kink run (and of `verlet-cost`'s measured loop).
const STEPS: u32 = Scenario::FIRMWARE.steps;

#[entry]
fn main() -> ! {
    let Ok(energy) = run() else { exit(false) };
    let stack = peak_stack_bytes();
    let mut line = Line { bytes: [0; 96], len: 0 };
    line.push(b"verlet-bare peak_stack_bytes=");
    line.decimal(stack as u64);
    line.push(b" final energy_bits=0x");
    line.hex(energy.widen().to_bits());
    line.push(b"\n");
    let written = hio::hstdout().and_then(|mut out| out.write_all(&line.bytes[..line.len]));
    exit(written.is_ok())
}

/// `E = T + V` after `STEPS` steps of the launched kink.
fn run() -> Result<Float, DynamicsError> {
    let mut stepper = launched_kink::<Float, _, N>(&Chain, &Scenario::FIRMWARE)?;
    for _ in 0..STEPS {
        stepper.step(&Chain)?;
    }
    Ok(stepper.kinetic_energy(&Chain) + stepper.potential_energy(&Chain))
}

#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    exit(false)
}

/// One line of output, written by hand: `core::fmt` would add more flash than the chain itself.
struct Line {
    bytes: [u8; 96],
    len: usize,
}

impl Line {
    /// Appends what fits.
    fn push(&mut self, text: &[u8]) {
        for &b in text {
            if let Some(slot) = self.bytes.get_mut(self.len) {
                *slot = b;
                self.len += 1;
            }
        }
    }

    fn decimal(&mut self, mut value: u64) {
        let mut digits = [0u8; 20];
        let mut start = digits.len();
        loop {
            start -= 1;
            digits[start] = b'0' + (value % 10) as u8;
            value /= 10;
            if value == 0 {
                break;
            }
        }
        self.push(&digits[start..]);
    }

    /// Sixteen lowercase hex digits, as `{:016x}` prints them.
    fn hex(&mut self, value: u64) {
        let digits: [u8; 16] =
            core::array::from_fn(|i| b"0123456789abcdef"[(value >> (60 - 4 * i)) as usize & 0xf]);
        self.push(&digits);
    }
}
