//! The accuracy of a chain declared with `float = f32` against the same chain in `f64`
//! (docs/embedded.md, "Accuracy of f32"): the same symbolic derivation rendered in both types, so
//! every difference below is single-precision rounding.
//!
//! Each test evaluates the `f64` chain at the `f32` chain's own inputs widened (exactly), so the
//! differences measure the `f32` arithmetic, not a rounding of the inputs. The bounds are the
//! measured worst cases (printed with `--nocapture`) with a margin of about 4, written in units
//! of `f32::EPSILON` (`1.19e-7`) where the quantity is a rounding error.

use embedded_check::Scenario;
use embedded_check::report::Header;
use embedded_check::{
    Chain16, Chain16F32, DomainWalls, Phase, Real, Verlet, kink_into, kink_launch_velocities,
};
use embedded_host::{Tolerated, compare_accuracy, host_run};
use rotor_chain::prelude::*;
use test_support::random::SplitMix;

const EPS: f64 = f32::EPSILON as f64;

/// The shortest spring the random configurations allow, in units of `a`. With `a = 1` and
/// `r = 0.8` two tips can meet (`l = 0`), where the derivatives of `l` carry `1 / l` and every
/// rounding error, in `f64` as in `f32`, is amplified without bound; a chain in use stays far
/// from it (in the uniform states and in a kink every spring is at its rest length, 1.70 a).
const SHORTEST_SPRING: f64 = 0.5;

/// Random `f32` configurations of 16 rotors: half anywhere in `[-pi, pi)`, half near the two
/// uniform states `+-theta_bar` (where a kink lives and the springs are near rest length, the
/// case of cancellation in `l - l0`); those with a spring shorter than [`SHORTEST_SPRING`] are
/// drawn again.
fn configurations(count: usize) -> Vec<[f32; 16]> {
    let mut rng = SplitMix(0x5EED_0F32);
    let mut out = Vec::with_capacity(count);
    for k in 0..100 * count {
        if out.len() == count {
            break;
        }
        let theta: [f32; 16] = core::array::from_fn(|_| {
            let theta = if k % 2 == 0 {
                rng.range(-core::f64::consts::PI, core::f64::consts::PI)
            } else {
                let sign = if rng.range(0.0, 1.0) < 0.5 { -1.0 } else { 1.0 };
                sign * 0.58 + rng.range(-0.05, 0.05)
            };
            theta as f32
        });
        if Chain16.spring_lengths(&widen(&theta)).iter().all(|&l| l >= SHORTEST_SPRING) {
            out.push(theta);
        }
    }
    assert_eq!(out.len(), count, "too few configurations with every spring >= {SHORTEST_SPRING}");
    out
}

fn widen<const N: usize>(theta: &[f32; N]) -> [f64; N] {
    theta.map(f64::from)
}

// The chain's scales: k = 1e4, a = 1, r = 0.8. Energies in units of `k a^2` per spring, forces
// in units of `k a r` (the largest gradient entry of a stretched spring is of that order).
const K: f64 = 1.0e4;
const R: f64 = 0.8;

#[test]
fn energy_and_gradient_agree_with_f64_to_a_few_f32_roundings() {
    let (mut energy, mut gradient) = (0.0f64, 0.0f64);
    for theta in configurations(20_000) {
        let wide = widen(&theta);
        let e32 = f64::from(Chain16F32.energy(&theta));
        let e64 = Chain16.energy(&wide);
        // Relative to the sum of the springs' scales: the energy is a sum of n - 1 terms, each
        // rounded relative to its own size `k l^2 / 2 <= k (a + 2r)^2 / 2`.
        energy = energy.max((e32 - e64).abs() / (15.0 * K));
        let g32 = Chain16F32.gradient(&theta);
        let g64 = Chain16.gradient(&wide);
        for (x, y) in g32.iter().zip(&g64) {
            gradient = gradient.max((f64::from(*x) - y).abs() / (K * R));
        }
    }
    println!(
        "energy: |E32 - E64| <= {energy:.2e} k a^2 per spring ({:.1} f32 eps); gradient: \
         |g32 - g64| <= {gradient:.2e} k a r ({:.1} f32 eps)",
        energy / EPS,
        gradient / EPS
    );
    assert!(energy < 4.0 * EPS, "energy error {energy:.3e} k a^2 per spring");
    assert!(gradient < 16.0 * EPS, "gradient error {gradient:.3e} k a r");
}

#[test]
fn tangent_stiffness_agrees_with_f64() {
    let mut worst = 0.0f64;
    for theta in configurations(5_000) {
        let wide = widen(&theta);
        let h32 = Chain16F32.tangent_stiffness(&theta);
        let h64 = Chain16.tangent_stiffness(&wide);
        // Relative to the entry, or to `k r^2` for an entry smaller than that: an entry carries
        // `1 / l` factors, large where a random configuration compresses a spring.
        for (x, y) in h32.diag.iter().chain(&h32.off).zip(h64.diag.iter().chain(&h64.off)) {
            worst = worst.max((f64::from(*x) - y).abs() / y.abs().max(K * R * R));
        }
    }
    println!(
        "tangent stiffness: |K32 - K64| <= {worst:.2e} of max(|K64|, k r^2) ({:.1} f32 eps)",
        worst / EPS
    );
    assert!(worst < 64.0 * EPS, "tangent stiffness error {worst:.3e} of max(|K64|, k r^2)");
}

#[test]
fn a_kink_built_by_the_f32_branch_solve_matches_the_f64_kink() {
    let (mut angle, mut position, mut energy) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..=60 {
        // Centres over the whole chain, on and between sites (the bisection of the construction).
        let centre = 0.5 + 14.0 * f64::from(k) / 60.0;
        let mut t32 = [0.0f32; 16];
        let mut t64 = [0.0f64; 16];
        kink_into(&Chain16F32, centre as f32, &mut t32).unwrap();
        kink_into(&Chain16, f64::from(centre as f32), &mut t64).unwrap();
        for (x, y) in t32.iter().zip(&t64) {
            angle = angle.max((f64::from(*x) - y).abs());
        }
        let w32: Vec<_> = DomainWalls::of(&t32).collect();
        let w64: Vec<_> = DomainWalls::of(&t64).collect();
        assert_eq!(w32.len(), w64.len(), "centre {centre}: walls {w32:?} against {w64:?}");
        for (a, b) in w32.iter().zip(&w64) {
            assert_eq!(a.charge, b.charge, "centre {centre}");
            position = position.max((f64::from(a.position) - b.position).abs());
        }
        // The f32 kink is a zero-energy state to f32 rounding: its energy evaluated exactly (in
        // f64 at the f32 angles) is what rounding the angles costs, of order k (eps r)^2 per spring.
        energy = energy.max(Chain16.energy(&widen(&t32)) / (15.0 * K * R * R));
    }
    println!(
        "kink: angles within {angle:.2e} rad ({:.1} f32 eps), wall within {position:.2e} sites, \
         f64 energy of the f32 kink <= {energy:.2e} k r^2 per spring",
        angle / EPS
    );
    assert!(angle < 8.0 * EPS, "kink angles differ by {angle:.3e} rad");
    assert!(position < 2e-6, "wall positions differ by {position:.3e} sites");
    assert!(energy < 16.0 * EPS * EPS, "f64 energy of the f32 kink {energy:.3e} k r^2 per spring");
}

/// The chain of the long run: the paper's geometry on 48 rotors, so that a kink launched at
/// `v0 = 1` stays inside the chain for the 1e4 steps.
#[rotor_chain(n = 48, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 1.0)]
struct Chain48;

#[rotor_chain(n = 48, r = 0.8, theta_bar = 0.58, k = 1.0e4, mass = 1.0, float = f32)]
struct Chain48F32;

/// Wall position, energy and the largest `|E - E0|` seen, sampled every 100 steps.
struct Trajectory {
    walls: Vec<f64>,
    energy0: f64,
    max_drift: f64,
    final_energy: f64,
}

fn trajectory<T: Real, M: ChainGeometry<T>>(chain: &M, steps: u32) -> Trajectory {
    const N: usize = 48;
    let (centre, v0, dt) = (8.25, 1.0, 1.953125e-3);
    let mut theta = [T::ZERO; N];
    kink_into(chain, T::of(centre), &mut theta).unwrap();
    let omega = kink_launch_velocities(chain, &theta, T::of(v0)).unwrap();
    let mut stepper = Verlet::new(chain, Phase { time: T::ZERO, theta, omega }, T::of(dt)).unwrap();
    let energy = |s: &Verlet<T, [T; N]>| (s.kinetic_energy(chain) + s.potential_energy(chain)).widen();
    let energy0 = energy(&stepper);
    let (mut walls, mut max_drift) = (Vec::new(), 0.0f64);
    for step in 1..=steps {
        stepper.step(chain).unwrap();
        if step % 100 == 0 {
            let found: Vec<_> = DomainWalls::of(stepper.theta()).collect();
            assert_eq!(found.len(), 1, "step {step}: {} walls in {}", found.len(), T::NAME);
            walls.push(found[0].position.widen());
            max_drift = max_drift.max((energy(&stepper) - energy0).abs());
        }
    }
    Trajectory { walls, energy0, max_drift, final_energy: energy(&stepper) }
}

#[test]
fn a_moving_kink_over_ten_thousand_steps_follows_the_f64_trajectory() {
    let steps = 10_000;
    let t64 = trajectory::<f64, _>(&Chain48, steps);
    let t32 = trajectory::<f32, _>(&Chain48F32, steps);
    let travelled = t64.walls.last().unwrap() - 8.25;
    let position = t32.walls.iter().zip(&t64.walls).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    let drift32 = t32.max_drift / t64.energy0;
    let drift64 = t64.max_drift / t64.energy0;
    let final_difference = (t32.final_energy - t64.final_energy).abs() / t64.energy0;
    println!(
        "1e4 steps (dt = 2^-9, kink travelled {travelled:.2} sites): wall within {position:.2e} sites of \
         f64; |E - E0| <= {drift32:.2e} E0 in f32, {drift64:.2e} E0 in f64; final energies differ \
         by {final_difference:.2e} E0"
    );
    // The kink moves: the comparison is of a travelling kink, not of a resting one.
    assert!(travelled > 10.0, "the kink travelled only {travelled} sites");
    assert!(position < 5e-4, "wall positions differ by {position:.3e} sites");
    // Verlet's own bounded energy oscillation (f64) and what f32 rounding adds to it.
    assert!(drift64 < 1e-5, "f64 energy drift {drift64:.3e} E0");
    assert!(drift32 < 6e-5, "f32 energy drift {drift32:.3e} E0");
    assert!(final_difference < 5e-5, "final energies differ by {final_difference:.3e} E0");
}

#[test]
fn the_firmware_scenario_in_f32_is_within_the_documented_accuracy_of_f64() {
    // The host's own f32 run of the firmware's scenario, in the firmware's format, against the
    // host's f64 run: what `compare-firmware` checks of the f32 firmware, with the same bound.
    let scenario = Scenario::FIRMWARE;
    let (samples, summary) = host_run::<f32, _, 16>(&Chain16F32, &scenario).unwrap();
    let mut text = format!("{}\n", Header { n: 16, float: "f32", scenario });
    for sample in &samples {
        text.push_str(&format!("{sample}\n"));
    }
    text.push_str(&format!("{summary}\n"));
    let agreement = compare_accuracy::<f32, _, 16>(&Chain16, &text).unwrap();
    println!("firmware scenario, f32 against f64: {agreement} (bound {:?})", f32::ACCURACY);
}

/// Every kind of declaration in both types: a user law (with `exp`, `sqrt`, `powi`), a rest length
/// and a stiffness read from fields, a spring override with its own rest length, and a rotor
/// override. The `f32` chain's fields hold the `f64` chain's values rounded to `f32`, so the
/// two chains are the same model up to the rounding of its numbers to `f32`.
#[rotor_chain(n = 12, r = 0.8, rest_length = lbar, k = k_all,
              law = k * l0 * l0 * ((l - l0) / l0).powi(2) * (1.0 + 0.1 * ((l - l0) / l0).exp()) / l.sqrt(),
              spring(4, k = 2.0e4, l0 = 1.65), rotor(7, r = 0.75))]
struct Declared {
    lbar: f64,
    k_all: f64,
}

#[rotor_chain(n = 12, r = 0.8, rest_length = lbar, k = k_all, float = f32,
              law = k * l0 * l0 * ((l - l0) / l0).powi(2) * (1.0 + 0.1 * ((l - l0) / l0).exp()) / l.sqrt(),
              spring(4, k = 2.0e4, l0 = 1.65), rotor(7, r = 0.75))]
struct DeclaredF32 {
    lbar: f32,
    k_all: f32,
}

#[test]
fn other_declarations_agree_with_f64_too() {
    let (lbar, k) = (1.7f32, 1.0e4f32);
    let c32 = DeclaredF32 { lbar, k_all: k };
    let c64 = Declared { lbar: f64::from(lbar), k_all: f64::from(k) };
    c32.check().unwrap();
    c64.check().unwrap();
    // theta_bar is derived in f64 from the f32 chain's values (`r` rounded to f32), so it agrees
    // to an f32 rounding of theta_bar, not bit for bit.
    let theta_bar = (f64::from(c32.theta_bar()) - c64.theta_bar()).abs();
    assert!(theta_bar < 2.0 * EPS, "theta_bar differs by {theta_bar:.3e}");
    let mut rng = SplitMix(0xDEC1_A2ED);
    let (mut energy, mut gradient) = (0.0f64, 0.0f64);
    let mut tried = 0;
    for _ in 0..100_000 {
        if tried == 5_000 {
            break;
        }
        let theta: [f32; 12] = core::array::from_fn(|_| {
            let sign = if rng.range(0.0, 1.0) < 0.5 { -1.0 } else { 1.0 };
            (sign * 0.58 + rng.range(-0.2, 0.2)) as f32
        });
        let wide = widen(&theta);
        if c64.spring_lengths(&wide).iter().any(|&l| l < SHORTEST_SPRING) {
            continue;
        }
        tried += 1;
        energy = energy.max((f64::from(c32.energy(&theta)) - c64.energy(&wide)).abs() / (11.0 * K));
        for (x, y) in c32.gradient(&theta).iter().zip(&c64.gradient(&wide)) {
            gradient = gradient.max((f64::from(*x) - y).abs() / (K * R));
        }
    }
    assert_eq!(tried, 5_000, "too few configurations with every spring >= {SHORTEST_SPRING}");
    // The branch solve of the overridden spring and of an ordinary one, both directions. Near the
    // edge of a map's domain (tangent circles) a root moves as the square root of its inputs, so
    // the f32 roots there carry tens of ulps.
    let mut branch = 0.0f64;
    for p in [3, 4, 6, 7] {
        for k in 0..=40 {
            let t = (0.3 + 0.5 * f64::from(k) / 40.0) as f32;
            let pairs = [
                (c32.next_angles(p, t), ChainGeometry::next_angles(&c64, p, f64::from(t))),
                (c32.previous_angles(p, t), ChainGeometry::previous_angles(&c64, p, f64::from(t))),
            ];
            for pair in pairs {
                match pair {
                    (Ok(x), Ok(y)) => {
                        for (x, y) in x.iter().zip(&y) {
                            branch = branch.max((f64::from(*x) - y).abs());
                        }
                    }
                    // Outside the map's domain in both types (the inverse map past its range).
                    (Err(_), Err(_)) => {}
                    (x, y) => panic!("spring {p}, theta {t}: f32 {x:?}, f64 {y:?}"),
                }
            }
        }
    }
    println!(
        "user law and overrides: energy {:.1} ulps of k a^2 per spring, gradient {:.1} ulps of k a r, \
         branch solve {:.1} ulps (rad)",
        energy / EPS,
        gradient / EPS,
        branch / EPS
    );
    assert!(energy < 4.0 * EPS, "energy error {energy:.3e}");
    assert!(gradient < 16.0 * EPS, "gradient error {gradient:.3e}");
    assert!(branch < 256.0 * EPS, "branch solve error {branch:.3e} rad");
}
