//! What a Verlet step of the 16-rotor chain costs on the Cortex-M4F (docs/embedded.md):
//! instructions per step and per gradient evaluation, and the peak stack.
//!
//! **Instructions, not cycles.** Run under `qemu-system-arm -icount shift=0`, QEMU's virtual clock
//! advances exactly 1 ns per executed guest instruction, and SysTick, clocked from the board's
//! 25 MHz core clock, advances one tick per 40 ns: one tick per 40 instructions. The firmware does
//! not assume that ratio: it measures it on a calibration loop of known length (`subs; bne`, two
//! instructions per pass). The loops below read SysTick after every step, so the ticks of the
//! steps telescope: the total is exact to one tick (40 instructions) over the whole loop, and the
//! cost of the read itself is measured on an empty loop and subtracted. QEMU models no pipeline,
//! caches or flash wait states, so cycles on real silicon differ (docs/embedded.md).
//!
//! The peak stack depth is read right after the measured loops ([`peak_stack_bytes`]).
#![no_std]
#![no_main]

use core::hint::black_box;

use cortex_m::peripheral::SYST;
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m_rt::entry;
use cortex_m_semihosting::hprintln;
use embedded_check::{DynamicsError, Potential, Real, Scenario, launched_kink};
use kink_firmware::{Chain, Float, N, exit, peak_stack_bytes};
use panic_semihosting as _;

/// Steps (and gradient evaluations) measured: those of the kink run, so that the final energy is
/// the one `kink-run` prints and the host computes.
const STEPS: u32 = Scenario::FIRMWARE.steps;
/// Passes of the two-instruction calibration loop.
const CALIBRATION_PASSES: u32 = 1_000_000;
/// SysTick counts down through 24 bits.
const SYSTICK_MASK: u32 = 0x00FF_FFFF;

/// SysTick ticks of the measured loops.
struct Costs {
    calibration: u64,
    overhead: u64,
    step: u64,
    gradient: u64,
    /// `E = T + V` after the measured steps.
    energy: Float,
}

#[entry]
fn main() -> ! {
    let Some(mut core) = cortex_m::Peripherals::take() else {
        hprintln!("error: core peripherals already taken");
        exit(false)
    };
    core.SYST.set_clock_source(SystClkSource::Core);
    core.SYST.set_reload(SYSTICK_MASK);
    core.SYST.clear_current();
    core.SYST.enable_counter();

    let measured = measure();
    // Before any formatting: core::fmt's own frames would otherwise count.
    let stack = peak_stack_bytes();
    let costs = match measured {
        Ok(costs) => costs,
        Err(error) => {
            hprintln!("error: {error}");
            exit(false)
        }
    };
    hprintln!("verlet-cost n={} float={} steps={}", N, Float::NAME, STEPS);
    hprintln!("calibration instructions={} ticks={}", 2 * u64::from(CALIBRATION_PASSES), costs.calibration);
    hprintln!("overhead ticks={}", costs.overhead);
    print_per_call("verlet-step", costs.step - costs.overhead, costs.calibration);
    print_per_call("gradient", costs.gradient - costs.overhead, costs.calibration);
    hprintln!("stack peak_bytes={}", stack);
    // Keeps the trajectory observable (and so computed): the energy after the steps, bit for bit.
    hprintln!("final energy_bits={:#018x}", costs.energy.widen().to_bits());
    exit(true)
}

/// Calibrates, then times `STEPS` Verlet steps of the launched kink of `Scenario::FIRMWARE` and
/// `STEPS` gradient evaluations at the state they reach.
fn measure() -> Result<Costs, DynamicsError> {
    let calibration = calibration_ticks();
    let overhead = ticks_of(|| Ok(()))?;
    let mut stepper = launched_kink::<Float, _, N>(&Chain, &Scenario::FIRMWARE)?;
    let step = ticks_of(|| Ok(stepper.step(&Chain)?))?;
    let theta = *stepper.theta();
    let mut out = [Float::of(0.0); N];
    let gradient = ticks_of(|| {
        Potential::gradient_into(&Chain, black_box(&theta), &mut out);
        black_box(&out);
        Ok(())
    })?;
    let energy = stepper.kinetic_energy(&Chain) + stepper.potential_energy(&Chain);
    Ok(Costs { calibration, overhead, step, gradient, energy })
}

/// SysTick ticks of `STEPS` calls of `work`, read after every call.
#[inline(never)]
fn ticks_of(mut work: impl FnMut() -> Result<(), DynamicsError>) -> Result<u64, DynamicsError> {
    let mut total = 0u64;
    let mut last = SYST::get_current();
    for _ in 0..STEPS {
        work()?;
        let now = SYST::get_current();
        total += u64::from(last.wrapping_sub(now) & SYSTICK_MASK);
        last = now;
    }
    Ok(total)
}

/// SysTick ticks of `CALIBRATION_PASSES` passes of a loop of exactly two instructions.
#[inline(never)]
fn calibration_ticks() -> u64 {
    let start = SYST::get_current();
    // SAFETY: a register-only countdown loop; it touches no memory and no stack.
    unsafe {
        core::arch::asm!(
            "2:",
            "subs {n}, #1",
            "bne 2b",
            n = inout(reg) CALIBRATION_PASSES => _,
            options(nomem, nostack),
        );
    }
    u64::from(start.wrapping_sub(SYST::get_current()) & SYSTICK_MASK)
}

/// Prints instructions per call, to a hundredth, from the ticks of `STEPS` calls.
fn print_per_call(what: &str, ticks: u64, calibration: u64) {
    // instructions = ticks * (2 * passes / calibration ticks); per call, in hundredths.
    let hundredths = ticks * 2 * u64::from(CALIBRATION_PASSES) * 100 / (calibration * u64::from(STEPS));
    hprintln!("{} ticks={} instructions_per_call={}.{:02}", what, ticks, hundredths / 100, hundredths % 100);
}
