//! The comparison itself: it accepts the host's own output, read back through the text format,
//! as bit-identical, and rejects every kind of disagreement with the numbers that show it.

use embedded_check::report::Header;
use embedded_check::{Chain16, Chain16F32, Sample, Scenario, Summary};
use embedded_host::{CompareError, Tolerated, compare, compare_accuracy, host_run};

/// The host run printed as the firmware prints it, after `edit` has changed the records.
fn output(edit: impl FnOnce(&mut Header<'static>, &mut Vec<Sample<f64>>, &mut Summary<f64>)) -> String {
    let (mut samples, mut summary) = host_run::<f64, _, 16>(&Chain16, &Scenario::FIRMWARE).unwrap();
    let mut header = Header { n: 16, float: "f64", scenario: Scenario::FIRMWARE };
    edit(&mut header, &mut samples, &mut summary);
    let mut text = format!("{header}\n");
    samples.iter().for_each(|s| text += &format!("{s}\n"));
    text + &format!("{summary}\n")
}

fn check(text: &str) -> Result<embedded_host::Agreement, CompareError> {
    compare::<f64, _, 16>(&Chain16, text)
}

#[test]
fn the_hosts_own_output_is_bit_identical() {
    let agreement = check(&output(|_, _, _| {})).unwrap();
    assert!(agreement.identical);
    assert_eq!((agreement.samples, agreement.position, agreement.energy), (17, 0.0, 0.0));
}

#[test]
fn differences_within_the_tolerance_pass_but_are_not_identical() {
    let tolerance = f64::TOLERANCE;
    let agreement = check(&output(|_, samples, _| {
        samples[5].walls[0].position += 0.5 * tolerance.position;
        samples[9].kinetic *= 1.0 + 0.5 * tolerance.energy;
    }))
    .unwrap();
    assert!(!agreement.identical);
    assert!(agreement.position > 0.4 * tolerance.position && agreement.position <= tolerance.position);
    assert!(agreement.energy > 0.0 && agreement.energy <= tolerance.energy);
}

#[test]
fn a_wall_beyond_the_tolerance_is_a_mismatch_naming_the_sample() {
    let error = check(&output(|_, samples, _| samples[7].walls[0].position += 1e-9)).unwrap_err();
    match error {
        CompareError::Mismatch { index, what, difference, .. } => {
            assert_eq!((index, what), (7, "wall position"));
            assert!((difference - 1e-9).abs() < 1e-12, "{difference}");
        }
        other => panic!("{other}"),
    }
}

#[test]
fn energies_and_the_summary_are_checked_too() {
    let error = check(&output(|_, samples, _| samples[2].potential += 1e-9)).unwrap_err();
    assert!(matches!(error, CompareError::Mismatch { index: 2, what: "potential energy", .. }), "{error}");
    let error = check(&output(|_, _, summary| summary.max_energy_error *= 2.0)).unwrap_err();
    assert!(matches!(error, CompareError::Mismatch { what: "largest energy error", .. }), "{error}");
}

#[test]
fn structural_differences_are_reported() {
    let error = check(&output(|_, samples, _| {
        samples.pop();
    }))
    .unwrap_err();
    assert!(matches!(error, CompareError::SampleCount { firmware: 16, host: 17 }), "{error}");

    let error = check(&output(|_, samples, _| samples[4].wall_count = 2)).unwrap_err();
    assert!(matches!(error, CompareError::Structure { what: "wall counts", .. }), "{error}");

    let error = check(&output(|header, _, _| header.scenario.v0 = 2.5)).unwrap_err();
    assert!(error.to_string().contains("v0=2.5e0"), "{error}");

    let error = check(&output(|header, _, _| header.float = "f32")).unwrap_err();
    assert!(matches!(error, CompareError::DifferentRun { .. }), "{error}");
}

#[test]
fn a_firmware_that_failed_or_stopped_early_is_reported() {
    let text = output(|_, _, _| {});
    let cut: String = text.lines().take(6).map(|l| format!("{l}\n")).collect();
    assert!(matches!(check(&cut), Err(CompareError::Unfinished { samples: 5 })));

    let failed = cut + "error: omega[3] = NaN is not finite after step 17\n";
    let error = check(&failed).unwrap_err();
    assert_eq!(
        error.to_string(),
        "line 7: the firmware reported `error: omega[3] = NaN is not finite after step 17`"
    );

    assert!(matches!(check(""), Err(CompareError::NoHeader)));
    let garbled = text.replacen("kinetic=", "kinetic=x", 1);
    assert!(matches!(check(&garbled), Err(CompareError::Parse { line: 2, .. })));
}

#[test]
fn the_final_energy_of_the_cost_firmware_is_checked() {
    let (_, summary) = host_run::<f64, _, 16>(&Chain16, &Scenario::FIRMWARE).unwrap();
    let line =
        |e: f64| format!("verlet-bare peak_stack_bytes=3008 final energy_bits={:#018x}\n", e.to_bits());
    assert_eq!(embedded_host::compare_final_energy(&line(summary.energy_final), &summary).unwrap(), 0.0);
    let off = summary.energy_final * (1.0 + 1e-9);
    let error = embedded_host::compare_final_energy(&line(off), &summary).unwrap_err();
    assert!(matches!(error, CompareError::Mismatch { what: "final energy", .. }), "{error}");
    assert!(matches!(
        embedded_host::compare_final_energy("verlet-bare\n", &summary),
        Err(CompareError::NoFinalEnergy)
    ));
}

/// The host's `f32` run printed as the `f32` firmware prints it, after `edit`.
fn output_f32(edit: impl FnOnce(&mut Vec<Sample<f32>>)) -> String {
    let (mut samples, summary) = host_run::<f32, _, 16>(&Chain16F32, &Scenario::FIRMWARE).unwrap();
    edit(&mut samples);
    let mut text = format!("{}\n", Header { n: 16, float: "f32", scenario: Scenario::FIRMWARE });
    samples.iter().for_each(|s| text += &format!("{s}\n"));
    text + &format!("{summary}\n")
}

#[test]
fn an_f32_run_is_checked_against_f32_and_its_accuracy_against_f64() {
    // Unchanged: bit-identical to the host's f32 run, and within f32's accuracy of the f64 run.
    let text = output_f32(|_| {});
    assert!(compare::<f32, _, 16>(&Chain16F32, &text).unwrap().identical);
    let accuracy = compare_accuracy::<f32, _, 16>(&Chain16, &text).unwrap();
    assert!(!accuracy.identical && accuracy.position < f32::ACCURACY.position, "{accuracy}");
    // A wall moved by twice the documented accuracy fails both checks, naming the sample.
    let moved = output_f32(|samples| samples[11].walls[0].position += 2.0 * f32::ACCURACY.position as f32);
    let error = compare::<f32, _, 16>(&Chain16F32, &moved).unwrap_err();
    assert!(matches!(error, CompareError::Mismatch { index: 11, what: "wall position", .. }), "{error}");
    let error = compare_accuracy::<f32, _, 16>(&Chain16, &moved).unwrap_err();
    assert!(matches!(error, CompareError::Mismatch { index: 11, what: "wall position", .. }), "{error}");
    // An energy off by twice the accuracy fails the accuracy check.
    let heavier = output_f32(|samples| samples[4].kinetic *= 1.0 + 2.0 * f32::ACCURACY.energy as f32);
    let error = compare_accuracy::<f32, _, 16>(&Chain16, &heavier).unwrap_err();
    assert!(matches!(error, CompareError::Mismatch { index: 4, .. }), "{error}");
    // An f64 output is not an f32 run.
    let error = compare_accuracy::<f32, _, 16>(&Chain16, &output(|_, _, _| {})).unwrap_err();
    assert!(matches!(error, CompareError::DifferentRun { .. }), "{error}");
}
