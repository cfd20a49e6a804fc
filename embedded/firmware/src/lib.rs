//! What the two firmware binaries share: the chain and float type they run, and the exit to
//! QEMU.
//!
//! The chain is chosen here, once, by the cargo feature `f32`: without it the `f64` chain
//! [`embedded_check::Chain16`] (soft-float on the Cortex-M4F), with it the same chain declared with
//! `float = f32`, [`embedded_check::Chain16F32`] (the M4F's single-precision FPU). The binaries
//! and the host harness are generic over the float type; `embedded/qemu-check` builds and runs
//! both.
#![no_std]

use cortex_m_semihosting::debug;

/// The chain the firmware runs.
#[cfg(not(feature = "f32"))]
pub use embedded_check::Chain16 as Chain;
/// The chain the firmware runs.
#[cfg(feature = "f32")]
pub use embedded_check::Chain16F32 as Chain;

/// The float type [`Chain`] computes in.
#[cfg(not(feature = "f32"))]
pub type Float = f64;
/// The float type [`Chain`] computes in.
#[cfg(feature = "f32")]
pub type Float = f32;

/// Rotors of [`Chain`].
pub const N: usize = Chain::N;

/// Ends the program: under QEMU with semihosting, QEMU exits with status 0 if `ok`, else 1.
pub fn exit(ok: bool) -> ! {
    debug::exit(if ok { debug::EXIT_SUCCESS } else { debug::EXIT_FAILURE });
    // Without a semihosting host (a real board, no debugger) the call above returns: stop here.
    loop {
        cortex_m::asm::wfi();
    }
}

/// The peak stack depth so far, in bytes: from the top of the stack down to the deepest word
/// that no longer holds the paint cortex-m-rt (feature `paint-stack`) writes over the whole stack
/// region before `main`.
pub fn peak_stack_bytes() -> usize {
    unsafe extern "C" {
        static _stack_start: u32;
        static _stack_end: u32;
    }
    let (top, bottom) = (&raw const _stack_start as usize, &raw const _stack_end as usize);
    let mut address = bottom;
    // SAFETY: [bottom, top) is the stack region of cortex-m-rt's linker script, word-aligned and
    // painted at reset; reading it is reading our own RAM.
    while address < top
        && unsafe { core::ptr::read_volatile(address as *const u32) } == cortex_m_rt::STACK_PAINT_VALUE
    {
        address += 4;
    }
    top - address
}
