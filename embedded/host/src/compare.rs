//! Firmware output against the host's run of the same computation.
//!
//! Both sides call [`embedded_check::run()`] with [`Scenario::FIRMWARE`] on the same chain, so the
//! only differences left are the machines' arithmetic and elementary functions. For `f64` they
//! are the same IEEE-754 operations (soft-float on the Cortex-M4F, SSE2 on x86-64, both correctly
//! rounded; Rust contracts nothing into FMAs), and `sin`/`cos`/`atan2`/`sqrt` come from the `libm`
//! crate on the firmware and, on the host, from `libm` too, or from the platform's C library when
//! `rotor-chain`'s `std` feature is on (feature `platform-math`, or any build that unifies `std`
//! in). The tolerance is per float type: [`Tolerated::TOLERANCE`].
//!
//! An `f32` run is also compared with the host's `f64` run of the same chain ([`compare_accuracy`]),
//! within [`Tolerated::ACCURACY`]: what computing in `f32` costs in accuracy.

use core::fmt;

use embedded_check::report::{Header, ParseError, Record};
use embedded_check::{ChainGeometry, DynamicsError, Real, Sample, Scenario, Summary, run};

/// How far the firmware's numbers may lie from the host's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Wall positions, in rotor spacings.
    pub position: f64,
    /// Energies (kinetic, potential, total and the summary's), relative to the initial energy.
    pub energy: f64,
}

/// A float type with a documented firmware-against-host tolerance.
pub trait Tolerated: Real {
    /// How far firmware and host may differ for this float type.
    const TOLERANCE: Tolerance;
    /// The firmware against the host's `f64` run of the same chain: the accuracy of this type.
    const ACCURACY: Tolerance;
}

/// `f64`: measured on [`Scenario::FIRMWARE`] (1024 steps, 17 samples; `docs/embedded.md`). With
/// `libm` on both sides every number is bit-identical. With the platform's (glibc's) `sin`, `cos`
/// and `atan2` on the host, their last-bit differences from `libm` reach the output as at most
/// 1.8e-15 sites in wall position and 6.3e-15 of `E0` in energy. The tolerance, 1e-12 for both,
/// is 150 to 500 times that, and still far below anything physical: the Verlet energy error
/// itself is 8e-6 of `E0` at this step.
impl Tolerated for f64 {
    const TOLERANCE: Tolerance = Tolerance { position: 1e-12, energy: 1e-12 };
    const ACCURACY: Tolerance = Self::TOLERANCE;
}

/// `f32`: against the host's `f32` run, measured on [`Scenario::FIRMWARE`] as for `f64`: with
/// `libm` on both sides every number is bit-identical (the M4F's FPU and SSE2 are both IEEE single
/// precision, and `sinf`/`cosf`/`atan2f`/`sqrtf` are the same Rust code). The tolerance, 16 f32
/// ulps of the largest quantity in each comparison, covers the platform's `sinf`/`cosf` on the host
/// (feature `platform-math`).
///
/// Against the host's `f64` run ([`compare_accuracy`]): the accuracy of the `f32` chain on the
/// firmware scenario, measured (docs/embedded.md) at 8.3e-6 sites in wall position and 5.2e-6 of
/// `E0` in energy with `libm`'s `sinf`/`cosf` (the firmware under QEMU, bit-identical to the host's
/// `libm` run), 6.4e-6 and 4.4e-6 with the platform's (test `accuracy.rs`); the bounds leave a
/// margin of about 3.5.
impl Tolerated for f32 {
    const TOLERANCE: Tolerance =
        Tolerance { position: 16.0 * 16.0 * F32_EPSILON, energy: 16.0 * F32_EPSILON };
    const ACCURACY: Tolerance = Tolerance { position: 3e-5, energy: 2e-5 };
}

/// `f32::EPSILON` as an `f64`.
const F32_EPSILON: f64 = f32::EPSILON as f64;

/// The largest deviations found, and how the two runs compare.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Agreement {
    /// Samples compared.
    pub samples: usize,
    /// Largest `|x_firmware - x_host|` over every wall of every sample.
    pub position: f64,
    /// Largest energy difference over every sample and the summary, divided by `|E0|`.
    pub energy: f64,
    /// Every number equal to the last bit.
    pub identical: bool,
}

impl fmt::Display for Agreement {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} samples, largest differences: wall position {:.3e} sites, energy {:.3e} of E0{}",
            self.samples,
            self.position,
            self.energy,
            if self.identical { " (every number bit-identical)" } else { "" }
        )
    }
}

/// Why the firmware's output does not match the host.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CompareError {
    #[error("line {line}: {error}: `{text}`")]
    /// A line of the firmware's output that cannot be read.
    Parse {
        /// The line (from 1).
        line: usize,
        /// What is wrong.
        error: ParseError,
        /// The line.
        text: String,
    },
    /// The firmware printed something that is not a record: an error report or a panic.
    #[error("line {line}: the firmware reported `{text}`")]
    Firmware {
        /// The line (from 1).
        line: usize,
        /// The line.
        text: String,
    },
    #[error("the firmware's output has no `rotor-chain kink run:` header line")]
    /// No header line.
    NoHeader,
    #[error("the firmware's output ends without a `done` line (it stopped after {samples} samples)")]
    /// The output ends before the summary.
    Unfinished {
        /// Samples read.
        samples: usize,
    },
    #[error("the firmware ran {firmware}, the host compares {host}")]
    /// The firmware ran another chain or scenario.
    DifferentRun {
        /// The firmware's header.
        firmware: String,
        /// The host's header.
        host: String,
    },
    #[error("no field `energy_bits=0x...` with 16 hex digits")]
    /// The summary has no final energy.
    NoFinalEnergy,
    #[error("the host run failed: {0}")]
    /// The host run failed.
    Host(#[from] DynamicsError),
    #[error("the firmware printed {firmware} samples, the host computed {host}")]
    /// Different numbers of samples.
    SampleCount {
        /// Samples from the firmware.
        firmware: usize,
        /// Samples from the host.
        host: usize,
    },
    #[error(
        "sample {index} (step {step}): {what}: firmware {firmware}, host {host}, difference {difference:.3e} > {tolerance:.1e}"
    )]
    /// A number differs beyond the tolerance.
    Mismatch {
        /// The sample.
        index: usize,
        /// Its Verlet step.
        step: u64,
        /// The quantity.
        what: &'static str,
        /// The firmware's value.
        firmware: f64,
        /// The host's value.
        host: f64,
        /// Their difference.
        difference: f64,
        /// The tolerance.
        tolerance: f64,
    },
    #[error("sample {index} (step {step}): {what} differ: firmware {firmware}, host {host}")]
    /// The samples differ in structure (wall count, charges).
    Structure {
        /// The sample.
        index: usize,
        /// Its Verlet step.
        step: u64,
        /// What differs.
        what: &'static str,
        /// The firmware's.
        firmware: String,
        /// The host's.
        host: String,
    },
}

/// The host's run of `scenario`: its samples and summary.
pub fn host_run<T: Real, M: ChainGeometry<T>, const N: usize>(
    model: &M,
    scenario: &Scenario,
) -> Result<(Vec<Sample<T>>, Summary<T>), DynamicsError> {
    let mut samples = Vec::new();
    let summary = run::<T, M, _, N>(model, scenario, |s| samples.push(*s))?;
    Ok((samples, summary))
}

/// The firmware's output `text`, read as a run of `scenario` on `N` rotors in float type `T`.
fn read_run<'a, T: Tolerated, const N: usize>(
    text: &'a str,
    scenario: &Scenario,
) -> Result<Output<'a, T>, CompareError> {
    let firmware = read::<T>(text)?;
    let expected = Header { n: N, float: T::NAME, scenario: *scenario };
    if firmware.header != expected {
        return Err(CompareError::DifferentRun {
            firmware: firmware.header.to_string(),
            host: expected.to_string(),
        });
    }
    Ok(firmware)
}

/// The firmware's output `text` against the host's run of [`Scenario::FIRMWARE`] on `model`, in
/// float type `T`, within `T`'s [`Tolerance`].
pub fn compare<T: Tolerated, M: ChainGeometry<T>, const N: usize>(
    model: &M,
    text: &str,
) -> Result<Agreement, CompareError> {
    let scenario = Scenario::FIRMWARE;
    let firmware = read_run::<T, N>(text, &scenario)?;
    let (samples, summary) = host_run::<T, M, N>(model, &scenario)?;
    check::<T>(&firmware.samples, &firmware.summary, &samples, &summary, &T::TOLERANCE)
}

/// The firmware's output `text`, computed in `T`, against the host's `f64` run of
/// [`Scenario::FIRMWARE`] on `reference` (the same chain in `f64`), within `T`'s
/// [`Tolerated::ACCURACY`]: wall counts and charges must be equal, positions and energies close.
pub fn compare_accuracy<T: Tolerated, M: ChainGeometry<f64>, const N: usize>(
    reference: &M,
    text: &str,
) -> Result<Agreement, CompareError> {
    let scenario = Scenario::FIRMWARE;
    let firmware = read_run::<T, N>(text, &scenario)?;
    let (samples, summary) = host_run::<f64, M, N>(reference, &scenario)?;
    let widened: Vec<Sample<f64>> = firmware.samples.iter().map(Sample::widen).collect();
    check::<f64>(&widened, &firmware.summary.widen(), &samples, &summary, &T::ACCURACY)
}

/// The `energy_bits=0x...` field of `verlet-cost`'s or `verlet-bare`'s output (the energy after the
/// kink run's steps, widened to `f64`) against the host's final energy of the same run, within
/// `T`'s energy tolerance relative to the initial energy. Returns that relative difference.
pub fn compare_final_energy<T: Tolerated>(text: &str, summary: &Summary<T>) -> Result<f64, CompareError> {
    let bits = text
        .split_whitespace()
        .find_map(|field| field.strip_prefix("energy_bits=0x"))
        .ok_or(CompareError::NoFinalEnergy)?;
    let firmware =
        u64::from_str_radix(bits, 16).map(f64::from_bits).map_err(|_| CompareError::NoFinalEnergy)?;
    let (host, scale) =
        (summary.energy_final.widen(), summary.energy_initial.widen().abs().max(f64::MIN_POSITIVE));
    let difference = (firmware - host).abs() / scale;
    if difference <= T::TOLERANCE.energy {
        Ok(difference)
    } else {
        Err(CompareError::Mismatch {
            index: 0,
            step: summary.steps,
            what: "final energy",
            firmware,
            host,
            difference,
            tolerance: T::TOLERANCE.energy,
        })
    }
}

/// The records of the firmware's output.
struct Output<'a, T> {
    header: Header<'a>,
    samples: Vec<Sample<T>>,
    summary: Summary<T>,
}

fn read<T: Real>(text: &str) -> Result<Output<'_, T>, CompareError> {
    let (mut header, mut samples, mut summary) = (None, Vec::new(), None);
    for (number, line) in text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty()) {
        let line_no = number + 1;
        match Record::<T>::parse(line) {
            Ok(Record::Header(h)) => header = Some(h),
            Ok(Record::Sample(s)) => samples.push(s),
            Ok(Record::Done(s)) => summary = Some(s),
            Ok(Record::Other(text)) => {
                return Err(CompareError::Firmware { line: line_no, text: text.into() });
            }
            Err(error) => return Err(CompareError::Parse { line: line_no, error, text: line.into() }),
        }
    }
    let header = header.ok_or(CompareError::NoHeader)?;
    let summary = summary.ok_or(CompareError::Unfinished { samples: samples.len() })?;
    Ok(Output { header, samples, summary })
}

/// Sample by sample: the same steps, times and walls (count and charges), and every number
/// within `tolerance`.
pub fn check<T: Real>(
    firmware: &[Sample<T>],
    firmware_summary: &Summary<T>,
    host: &[Sample<T>],
    host_summary: &Summary<T>,
    tolerance: &Tolerance,
) -> Result<Agreement, CompareError> {
    if firmware.len() != host.len() {
        return Err(CompareError::SampleCount { firmware: firmware.len(), host: host.len() });
    }
    let scale = host.first().map_or(1.0, |s| s.energy().widen().abs()).max(f64::MIN_POSITIVE);
    let mut agreement = Agreement { samples: host.len(), identical: true, ..Agreement::default() };
    for (index, (f, h)) in firmware.iter().zip(host).enumerate() {
        let at = At { index, step: h.step };
        if (f.step, f.time) != (h.step, h.time) {
            let (f, h) = (format!("{} at {}", f.step, f.time), format!("{} at {}", h.step, h.time));
            return Err(at.structure("step and time", f, h));
        }
        if f.wall_count != h.wall_count {
            return Err(at.structure("wall counts", f.wall_count.to_string(), h.wall_count.to_string()));
        }
        for (wf, wh) in f.walls().iter().zip(h.walls()) {
            if wf.charge != wh.charge {
                return Err(at.structure("wall charges", wf.charge.name().into(), wh.charge.name().into()));
            }
            let d = at.deviation(
                "wall position",
                wf.position,
                wh.position,
                1.0,
                tolerance.position,
                &mut agreement,
            )?;
            agreement.position = agreement.position.max(d);
        }
        for (what, a, b) in
            [("kinetic energy", f.kinetic, h.kinetic), ("potential energy", f.potential, h.potential)]
        {
            let d = at.deviation(what, a, b, scale, tolerance.energy, &mut agreement)?;
            agreement.energy = agreement.energy.max(d);
        }
    }
    let (f, h) = (firmware_summary, host_summary);
    let at = At { index: host.len(), step: h.steps };
    if f.steps != h.steps {
        return Err(at.structure("step counts of the summary", f.steps.to_string(), h.steps.to_string()));
    }
    for (what, a, b) in [
        ("initial energy", f.energy_initial, h.energy_initial),
        ("final energy", f.energy_final, h.energy_final),
        ("largest energy error", f.max_energy_error, h.max_energy_error),
    ] {
        let d = at.deviation(what, a, b, scale, tolerance.energy, &mut agreement)?;
        agreement.energy = agreement.energy.max(d);
    }
    Ok(agreement)
}

/// Where in the output a comparison is made: the sample's index (the summary counts as the sample
/// after the last) and step.
#[derive(Clone, Copy)]
struct At {
    index: usize,
    step: u64,
}

impl At {
    fn structure(self, what: &'static str, firmware: String, host: String) -> CompareError {
        CompareError::Structure { index: self.index, step: self.step, what, firmware, host }
    }

    /// `|firmware - host| / scale`, or a mismatch if that is above `tolerance` (or NaN); clears
    /// `identical` unless the two are the same to the last bit.
    fn deviation<T: Real>(
        self,
        what: &'static str,
        firmware: T,
        host: T,
        scale: f64,
        tolerance: f64,
        agreement: &mut Agreement,
    ) -> Result<f64, CompareError> {
        let (firmware, host) = (firmware.widen(), host.widen());
        agreement.identical &= firmware.to_bits() == host.to_bits();
        let difference = (firmware - host).abs() / scale;
        if difference <= tolerance {
            Ok(difference)
        } else {
            Err(CompareError::Mismatch {
                index: self.index,
                step: self.step,
                what,
                firmware,
                host,
                difference,
                tolerance,
            })
        }
    }
}
