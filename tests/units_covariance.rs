//! Units: every public analysis is covariant under a change of units (docs/theory.md §3: lengths
//! in the unit of `a`, `k` in `M / t^2`, energies absolute in `k` times length squared, times in
//! `t`).
//!
//! A chain is run once as given and again with its lengths scaled by `L` (`a`, `r`, every rest
//! length and rotor-length override), its stiffnesses by `K` (`k` and every per-spring `k`) or its
//! tip mass by `m`, alone and all at once. Dimensional analysis then fixes every output of the
//! second run from the first: angles, positions in sites, mode shapes in tip displacements and
//! scattering outcomes do not change; lengths scale as `L`, tensions as `K L`, energies, forces
//! `dV/dtheta` and stiffnesses in the angles as `K L^2`, moments of inertia as `m L^2`, times as
//! `T = sqrt(m / K)`, frequencies and angular velocities as `1 / T`, speeds (`v0`, tip speeds,
//! the continuum sound speed) as `L / T`. Every expected value below is the unscaled run's output
//! times its factor; nothing is compared with a number the code printed.
//!
//! The audit that added this file found two analyses that broke the law under `L`, both by
//! comparing a wall width in the length unit with positions in sites: the mode kinds and the
//! linkage model's head profile. Both are fixed and checked here.

use rotor_chain::dynamics::integrate::{Sponge, State};
use rotor_chain::dynamics::launch::{Direction, launch};
use rotor_chain::dynamics::run::{Method, RunOptions, propagate};
use rotor_chain::dynamics::scatter::{ScatterSetup, paper_time_unit, scatter};
use rotor_chain::prelude::*;
use rotor_chain::statics::antikink::{AntikinkOptions, antikink_relaxed, peierls_nabarro};
use rotor_chain::statics::cobweb::fixed_points;
use rotor_chain::statics::continuum::ContinuumChain;
use rotor_chain::statics::counting::{maxwell_calladine, tensional_modes};
use rotor_chain::statics::impurity::{critical_length, two_kink_configuration};
use rotor_chain::statics::kink::{kink, reflected_kink};
use rotor_chain::statics::linkage::{LinkageChain, PhaseState, kink_coordinate};
use rotor_chain::statics::modes::{ModeOptions, modes};
use rotor_chain::statics::walls::{Charge, domain_walls};
use rotor_chain::{Law, batch};

/// Relative tolerance of results computed in closed form or by a fixed sequence of operations
/// (evaluations, branch solves, Verlet runs): rounding, amplified by cancellation.
const EXACT: f64 = 1e-10;
/// Relative tolerance of results of Newton's method (its default stops at `|dV/dtheta| <= 1e-11
/// ||K||`, docs/statics.md §12).
const NEWTON: f64 = 1e-9;

/// One change of units: lengths times `l`, stiffnesses times `k`, the tip mass times `m`.
#[derive(Clone, Copy, Debug)]
struct Units {
    l: f64,
    k: f64,
    m: f64,
}

impl Units {
    /// No change: the unscaled run.
    const NONE: Units = Units { l: 1.0, k: 1.0, m: 1.0 };

    /// Each scaling alone, and all three at once.
    const ALL: [Units; 4] = [
        Units { l: 2.3, k: 1.0, m: 1.0 },
        Units { l: 1.0, k: 7.1, m: 1.0 },
        Units { l: 1.0, k: 1.0, m: 0.37 },
        Units { l: 0.6, k: 43.0, m: 3.1 },
    ];

    fn length(self) -> f64 {
        self.l
    }
    fn tension(self) -> f64 {
        self.k * self.l
    }
    /// Energies, `dV/dtheta` and stiffnesses in the angles.
    fn energy(self) -> f64 {
        self.k * self.l * self.l
    }
    fn inertia(self) -> f64 {
        self.m * self.l * self.l
    }
    fn time(self) -> f64 {
        (self.m / self.k).sqrt()
    }
    /// Frequencies, rates and angular velocities.
    fn rate(self) -> f64 {
        1.0 / self.time()
    }
    fn speed(self) -> f64 {
        self.l / self.time()
    }
}

/// A chain with overrides of every kind that carries a unit.
#[derive(Clone, Copy, Debug)]
struct Params {
    n: usize,
    a: f64,
    r: f64,
    k: f64,
    mass: f64,
    theta_bar: f64,
    law: Law,
    /// Spring `.0` gets stiffness `.1 * k` (a stiffness impurity).
    soft: (usize, f64),
    /// Spring `.0` gets rest length `.1 * lbar`.
    long: (usize, f64),
    /// Rotor `.0` gets length `.1 * r`.
    rotor: Option<(usize, f64)>,
}

impl Params {
    /// `lbar = sqrt(a^2 + 4 r^2 cos^2 theta_bar)` (docs/theory.md §2), to give the override.
    fn lbar(&self) -> f64 {
        (self.a * self.a + 4.0 * (self.r * self.theta_bar.cos()).powi(2)).sqrt()
    }

    fn chain(&self, u: Units) -> RuntimeChain {
        let mut b = RuntimeChain::builder(self.n, self.r * u.l, self.k * u.k, self.theta_bar)
            .lattice_spacing(self.a * u.l)
            .mass(self.mass * u.m)
            .law(self.law)
            .spring_constant(self.soft.0, self.soft.1 * self.k * u.k)
            .spring_rest_length(self.long.0, self.long.1 * self.lbar() * u.l);
        if let Some((i, f)) = self.rotor {
            b = b.rotor(i, f * self.r * u.l);
        }
        b.build().unwrap()
    }
}

const SETS: [Params; 3] = [
    Params {
        n: 48,
        a: 1.7,
        r: 0.8 * 1.7,
        k: 3.3e3,
        mass: 2.5,
        theta_bar: 0.5,
        law: Law::Harmonic,
        soft: (8, 0.3),
        long: (38, 1.02),
        rotor: None,
    },
    Params {
        n: 40,
        a: 1.7,
        r: 1.2,
        k: 3.3e3,
        mass: 2.5,
        theta_bar: 0.6,
        law: Law::Quartic,
        soft: (6, 2.2),
        long: (31, 0.97),
        rotor: Some((34, 0.9)),
    },
    Params {
        n: 60,
        a: 0.9,
        r: 0.72,
        k: 1.0e4,
        mass: 1.0,
        theta_bar: 0.55,
        law: Law::Harmonic,
        soft: (44, 0.5),
        long: (12, 1.01),
        rotor: None,
    },
];

/// Asserts `got = factor * unscaled` entry by entry, within `tol` of the largest expected entry
/// (which must not be zero: a comparison of zeros would check nothing).
#[track_caller]
fn assert_scaled(what: &str, got: &[f64], unscaled: &[f64], factor: f64, tol: f64) {
    assert_eq!(got.len(), unscaled.len(), "{what}: lengths");
    let size = unscaled.iter().fold(0.0f64, |s, x| s.max((factor * x).abs()));
    assert!(size > 0.0 && size.is_finite(), "{what}: nothing to compare ({unscaled:?})");
    let error = got.iter().zip(unscaled).fold(0.0f64, |e, (g, x)| e.max((g - factor * x).abs()));
    assert!(error <= tol * size, "{what}: off by {:.2e} of {size:.3e}", error / size);
}

#[track_caller]
fn assert_scaled1(what: &str, got: f64, unscaled: f64, factor: f64, tol: f64) {
    assert_scaled(what, &[got], &[unscaled], factor, tol);
}

/// `v` with its sign chosen to agree with `reference` (eigenvectors are defined up to sign).
fn aligned(v: &[f64], reference: &[f64]) -> Vec<f64> {
    let dot: f64 = v.iter().zip(reference).map(|(a, b)| a * b).sum();
    v.iter().map(|x| if dot < 0.0 { -x } else { *x }).collect()
}

/// A configuration that stretches every spring differently: a kink of the unscaled chain plus a
/// smooth disturbance (angles are dimensionless, so both chains take the same one).
fn disturbed(chain: &RuntimeChain) -> Vec<f64> {
    let n = chain.rotor_count();
    let mut theta = kink(chain, 0.4 * n as f64 + 0.3).unwrap();
    for (i, t) in theta.iter_mut().enumerate() {
        *t += 0.07 * (0.9 * i as f64).sin();
    }
    theta
}

/// The slice outputs of a chain at `theta`, named by [`Outputs::NAMES`], scaling by
/// [`Outputs::factors`].
struct Outputs([Vec<f64>; 9]);

impl Outputs {
    /// Energy (with the fused energy + gradient), gradient, stiffness bands, material part,
    /// stress matrix, spring lengths, tensions, compatibility bands, moments of inertia.
    fn of(chain: &RuntimeChain, theta: &[f64]) -> Self {
        let n = chain.rotor_count();
        // A matrix's values in the chain's layout: the two bands one after the other.
        let band = |len: usize, f: &dyn Fn(&mut [f64])| {
            let mut values = vec![0.0; len];
            f(&mut values);
            values
        };
        let mut g = vec![0.0; n];
        let fused = chain.energy_and_gradient_into(theta, &mut g);
        let (mut g3, mut k3) = (vec![0.0; n], vec![0.0; 2 * n - 1]);
        let fused3 = chain.energy_gradient_stiffness_into(theta, &mut g3, &mut k3);
        let mut energy = vec![chain.energy(theta), fused, fused3];
        energy.extend(g3);
        let mut stiffness = band(2 * n - 1, &|k| chain.tangent_stiffness_into(theta, k));
        stiffness.extend(k3);
        let mut lengths = vec![0.0; n - 1];
        chain.spring_lengths_into(theta, &mut lengths);
        lengths.extend((0..n - 1).map(|p| chain.rest_length(p)));
        lengths.extend((0..n).map(|i| chain.rotor_length(i)));
        lengths.push(chain.lattice_spacing());
        let mut tensions = vec![0.0; n - 1];
        chain.tensions_into(theta, &mut tensions);
        Outputs([
            energy,
            g,
            stiffness,
            band(2 * n - 1, &|k| chain.material_stiffness_into(theta, k)),
            band(2 * n - 1, &|k| chain.stress_matrix_into(theta, k)),
            lengths,
            tensions,
            band(2 * (n - 1), &|c| chain.compatibility_into(theta, c)),
            (0..n).map(|i| chain.inertia(i)).collect(),
        ])
    }

    const NAMES: [&str; 9] = [
        "energies (energy, fused, fused + stiffness; fused gradient)",
        "gradient",
        "tangent stiffness",
        "material part",
        "stress matrix",
        "spring lengths, rest lengths, rotor lengths, a",
        "tensions",
        "compatibility matrix",
        "moments of inertia",
    ];

    fn factors(u: Units) -> [f64; 9] {
        let e = u.energy();
        [e, e, e, e, e, u.length(), u.tension(), 1.0, u.inertia()]
    }
}

#[test]
fn evaluations_scale_as_energy_tension_length_and_inertia() {
    for p in SETS {
        let chain = p.chain(Units::NONE);
        let theta = disturbed(&chain);
        let base = Outputs::of(&chain, &theta);
        let n = p.n;
        // Ten configurations back to back through the batch API.
        let thetas: Vec<f64> = (0..10).flat_map(|c| theta.iter().map(move |t| t + 0.01 * c as f64)).collect();
        let batch_of = |chain: &RuntimeChain| {
            let (mut e, mut g) = (vec![0.0; 10], vec![0.0; 10 * n]);
            batch::energies_and_gradients(chain, &thetas, &mut e, &mut g).unwrap();
            e.extend(g);
            e
        };
        let batch_base = batch_of(&chain);
        for u in Units::ALL {
            let scaled = p.chain(u);
            let what = |name: &str| format!("{name}, {p:?}, {u:?}");
            let got = Outputs::of(&scaled, &theta);
            for ((name, factor), (got, base)) in
                Outputs::NAMES.iter().zip(Outputs::factors(u)).zip(got.0.iter().zip(&base.0))
            {
                assert_scaled(&what(name), got, base, factor, EXACT);
            }
            assert_scaled(&what("batch"), &batch_of(&scaled), &batch_base, u.energy(), EXACT);
            let k: Vec<f64> = (0..n - 1).map(|q| chain.spring_constant(q)).collect();
            let k_scaled: Vec<f64> = (0..n - 1).map(|q| scaled.spring_constant(q)).collect();
            assert_scaled(&what("stiffnesses"), &k_scaled, &k, u.k, EXACT);
            assert_eq!(scaled.theta_bar(), chain.theta_bar());
            // The branch solve of Appendix A: angles in, angles out.
            for q in [3, p.soft.0, p.long.0, n - 2] {
                let (next, prev) =
                    (scaled.next_angles(q, 0.3).unwrap(), scaled.previous_angles(q, -0.2).unwrap());
                assert_scaled(&what("next_angles"), &next, &chain.next_angles(q, 0.3).unwrap(), 1.0, EXACT);
                assert_scaled(
                    &what("previous_angles"),
                    &prev,
                    &chain.previous_angles(q, -0.2).unwrap(),
                    1.0,
                    EXACT,
                );
            }
            // The uniform state given by its rest length: the same angle.
            let by_length = |u: Units| {
                RuntimeChain::builder(n, p.r * u.l, p.k * u.k, 0.0)
                    .lattice_spacing(p.a * u.l)
                    .rest_length(1.01 * p.lbar() * u.l)
                    .build()
                    .unwrap()
                    .theta_bar()
            };
            assert_scaled1(&what("theta_bar from lbar"), by_length(u), by_length(Units::NONE), 1.0, EXACT);
        }
    }
}

/// A macro chain whose every parameter is a field, so that one declaration takes any units:
/// unrolled (`n <= 16`) and looped.
#[rotor_chain(n = 12, a = a, r = r, theta_bar = 0.52, k = k, mass = mass, spring(5, k = k_imp),
              spring(8, l0 = l0), rotor(3, r = r3))]
struct Unrolled {
    a: f64,
    r: f64,
    k: f64,
    mass: f64,
    k_imp: f64,
    l0: f64,
    r3: f64,
}

#[rotor_chain(n = 24, a = a, r = r, theta_bar = 0.52, k = k, mass = mass, spring(5, k = k_imp),
              spring(8, l0 = l0), rotor(3, r = r3), law = k * (l * l - l0 * l0).powi(2) / (8.0 * l0 * l0))]
struct Looped {
    a: f64,
    r: f64,
    k: f64,
    mass: f64,
    k_imp: f64,
    l0: f64,
    r3: f64,
}

macro_rules! check_macro_chain {
    ($Chain:ident) => {{
        let make = |u: Units| {
            let (a, r) = (1.7 * u.l, 1.3 * u.l);
            let c = $Chain {
                a,
                r,
                k: 3.3e3 * u.k,
                mass: 2.5 * u.m,
                k_imp: 900.0 * u.k,
                l0: 2.4 * u.l,
                r3: 1.1 * u.l,
            };
            c.check().unwrap();
            c
        };
        let chain = make(Units::NONE);
        let theta: [f64; $Chain::N] =
            core::array::from_fn(|i| 0.52 * (0.3 * i as f64).cos() + 0.05 * i as f64);
        let name = stringify!($Chain);
        for u in Units::ALL {
            let scaled = make(u);
            let what = |s: &str| format!("{name} {s}, {u:?}");
            let e = u.energy();
            assert_scaled1(&what("energy"), scaled.energy(&theta), chain.energy(&theta), e, EXACT);
            assert_scaled(&what("gradient"), &scaled.gradient(&theta), &chain.gradient(&theta), e, EXACT);
            let (h, h0) = (scaled.hessian(&theta), chain.hessian(&theta));
            assert_scaled(&what("hessian"), h.as_slice(), h0.as_slice(), e, EXACT);
            let mut lengths = [0.0; $Chain::N - 1];
            let mut base = [0.0; $Chain::N - 1];
            SpringNetwork::spring_lengths_into(&scaled, &theta, &mut lengths);
            SpringNetwork::spring_lengths_into(&chain, &theta, &mut base);
            assert_scaled(&what("spring lengths"), &lengths, &base, u.length(), EXACT);
            SpringNetwork::tensions_into(&scaled, &theta, &mut lengths);
            SpringNetwork::tensions_into(&chain, &theta, &mut base);
            assert_scaled(&what("tensions"), &lengths, &base, u.tension(), EXACT);
            let inertia: Vec<f64> = (0..$Chain::N).map(|i| Potential::inertia(&scaled, i)).collect();
            let inertia0: Vec<f64> = (0..$Chain::N).map(|i| Potential::inertia(&chain, i)).collect();
            assert_scaled(&what("inertia"), &inertia, &inertia0, u.inertia(), EXACT);
            assert_scaled(
                &what("kink"),
                &kink(&scaled, 6.3).unwrap(),
                &kink(&chain, 6.3).unwrap(),
                1.0,
                EXACT,
            );
        }
    }};
}

#[test]
fn macro_chains_with_parameters_in_fields_scale_alike() {
    check_macro_chain!(Unrolled);
    check_macro_chain!(Looped);
}

#[test]
fn kinks_cobweb_counting_and_the_length_impurity_are_dimensionless() {
    for p in SETS {
        let chain = p.chain(Units::NONE);
        let theta = disturbed(&chain);
        let centre = 0.6 * p.n as f64 + 0.25;
        let counting = maxwell_calladine(&chain, &theta, None).unwrap();
        let tensional = tensional_modes(&chain, &theta, 2).unwrap();
        let fixed = fixed_points(&chain, 4).unwrap();
        // A spring-length impurity between two uniform sub-chains (paper Sec. VII-A).
        let impure = |u: Units| {
            RuntimeChain::builder(p.n, p.r * u.l, p.k * u.k, p.theta_bar)
                .lattice_spacing(p.a * u.l)
                .mass(p.mass * u.m)
                .spring(p.n / 2, None, Some(1.1 * (p.a * p.a + 4.0 * p.r * p.r).sqrt() * u.l))
                .build()
                .unwrap()
        };
        let two_kinks = two_kink_configuration(&impure(Units::NONE), p.n / 2).unwrap();
        let l_critical = critical_length(&chain, p.n / 2).unwrap();
        for u in Units::ALL {
            let scaled = p.chain(u);
            let what = |s: &str| format!("{s}, {p:?}, {u:?}");
            assert_scaled(
                &what("kink"),
                &kink(&scaled, centre).unwrap(),
                &kink(&chain, centre).unwrap(),
                1.0,
                EXACT,
            );
            let reflected = reflected_kink(&scaled, centre).unwrap();
            assert_scaled(
                &what("reflected kink"),
                &reflected,
                &reflected_kink(&chain, centre).unwrap(),
                1.0,
                EXACT,
            );
            let (walls, walls0) =
                (domain_walls(&reflected), domain_walls(&reflected_kink(&chain, centre).unwrap()));
            let charges =
                |w: &[rotor_chain::statics::walls::Wall]| w.iter().map(|w| w.charge).collect::<Vec<_>>();
            assert_eq!(charges(&walls), charges(&walls0), "{}", what("walls"));
            let positions =
                |w: &[rotor_chain::statics::walls::Wall]| w.iter().map(|w| w.position).collect::<Vec<_>>();
            assert_scaled(&what("wall positions"), &positions(&walls), &positions(&walls0), 1.0, EXACT);
            for (f, f0) in fixed_points(&scaled, 4).unwrap().iter().zip(&fixed) {
                assert_scaled(
                    &what("fixed point"),
                    &[f.theta, f.slope, f.decay_length],
                    &[f0.theta, f0.slope, f0.decay_length],
                    1.0,
                    EXACT,
                );
                assert_eq!(f.stability, f0.stability, "{}", what("stability"));
            }
            let c = maxwell_calladine(&scaled, &theta, None).unwrap();
            assert_eq!((c.rank, c.index()), (counting.rank, counting.index()), "{}", what("rank"));
            assert_scaled(
                &what("singular values"),
                &c.singular_values,
                &counting.singular_values,
                1.0,
                EXACT,
            );
            assert_scaled1(&what("rank tolerance"), c.tolerance, counting.tolerance, 1.0, EXACT);
            for (z, z0) in c.zero_modes.iter().zip(&counting.zero_modes) {
                assert_scaled(&what("zero mode"), &aligned(z, z0), z0, 1.0, 1e-8);
            }
            for (t, t0) in tensional_modes(&scaled, &theta, 2).unwrap().iter().zip(&tensional) {
                assert_scaled1(&what("tensional eigenvalue"), t.eigenvalue, t0.eigenvalue, 1.0, EXACT);
                assert_scaled(
                    &what("tensional mode"),
                    &aligned(&t.tensions, &t0.tensions),
                    &t0.tensions,
                    1.0,
                    1e-8,
                );
            }
            let two = two_kink_configuration(&impure(u), p.n / 2).unwrap();
            assert_scaled(&what("two-kink state"), &two, &two_kinks, 1.0, EXACT);
            assert_scaled1(
                &what("l_critical"),
                critical_length(&scaled, p.n / 2).unwrap(),
                l_critical,
                u.length(),
                EXACT,
            );
        }
    }
}

#[test]
fn mode_frequencies_scale_as_one_over_time_and_shapes_as_tip_displacements() {
    for p in SETS {
        let chain = p.chain(Units::NONE);
        let configurations = [kink(&chain, 0.5 * p.n as f64 - 0.5).unwrap(), vec![p.theta_bar; p.n]];
        let options = ModeOptions { count: Some(6), ..ModeOptions::default() };
        for theta in &configurations {
            let base = modes(&chain, theta, &options).unwrap();
            for u in Units::ALL {
                let found = modes(&p.chain(u), theta, &options).unwrap();
                let what = |s: &str| format!("mode {s}, {p:?}, {u:?}");
                let pick = |m: &[rotor_chain::statics::modes::Mode],
                            f: fn(&rotor_chain::statics::modes::Mode) -> f64| {
                    m.iter().map(f).collect::<Vec<f64>>()
                };
                // The zero mode's omega^2 is rounding (eps ||K|| / I): compared from mode 1 on.
                assert_scaled(
                    &what("omega^2"),
                    &pick(&found[1..], |m| m.omega_squared),
                    &pick(&base[1..], |m| m.omega_squared),
                    u.rate().powi(2),
                    EXACT,
                );
                assert_scaled(
                    &what("frequency"),
                    &pick(&found[1..], |m| m.frequency),
                    &pick(&base[1..], |m| m.frequency),
                    u.rate(),
                    EXACT,
                );
                assert_scaled(
                    &what("position"),
                    &pick(&found, |m| m.position),
                    &pick(&base, |m| m.position),
                    1.0,
                    1e-8,
                );
                assert_scaled(
                    &what("participation"),
                    &pick(&found, |m| m.participation),
                    &pick(&base, |m| m.participation),
                    1.0,
                    1e-8,
                );
                // sum_i I_i v_i^2 = 1 with I = M r^2: v scales as 1 / (L sqrt(m)).
                for (m, m0) in found.iter().zip(&base).skip(1) {
                    assert_scaled(
                        &what("shape"),
                        &aligned(&m.shape, &m0.shape),
                        &m0.shape,
                        1.0 / u.inertia().sqrt(),
                        1e-8,
                    );
                }
                // The kinds compare wall widths with positions, both in sites.
                let kinds: Vec<_> = found.iter().map(|m| m.kind).collect();
                assert_eq!(kinds, base.iter().map(|m| m.kind).collect::<Vec<_>>(), "{}", what("kinds"));
            }
        }
    }
}

#[test]
fn peierls_nabarro_barrier_and_antikinks_scale_as_energy() {
    let options = AntikinkOptions::default();
    for p in SETS {
        let chain = p.chain(Units::NONE);
        let pn = peierls_nabarro(&chain, &options).unwrap();
        assert!(pn.resolved && pn.barrier > 0.0, "{p:?}: {pn:?}");
        let start = 0.5 * p.n as f64 + 0.3;
        let relaxed = antikink_relaxed(&chain, start, &options).unwrap();
        for u in Units::ALL {
            let scaled = p.chain(u);
            let what = |s: &str| format!("{s}, {p:?}, {u:?}");
            let got = peierls_nabarro(&scaled, &options).unwrap();
            assert!(got.resolved, "{}", what("resolved"));
            assert_scaled1(&what("barrier"), got.barrier, pn.barrier, u.energy(), NEWTON);
            for (a, a0) in [
                (got.minimum().unwrap(), pn.minimum().unwrap()),
                (got.saddle().unwrap(), pn.saddle().unwrap()),
            ] {
                assert_scaled1(&what("energy"), a.energy, a0.energy, u.energy(), NEWTON);
                assert_scaled(&what("angles"), &a.theta, &a0.theta, 1.0, NEWTON);
                assert_scaled1(&what("centre"), a.centre, a0.centre, 1.0, NEWTON);
                let class = |a: &rotor_chain::statics::antikink::Antikink| {
                    (a.classification.index, a.classification.nullity)
                };
                assert_eq!(class(a), class(a0), "{}", what("classification"));
                assert_scaled1(
                    &what("zero tolerance"),
                    a.classification.tolerance,
                    a0.classification.tolerance,
                    u.energy(),
                    NEWTON,
                );
            }
            let r = antikink_relaxed(&scaled, start, &options).unwrap();
            assert_scaled1(&what("relaxed energy"), r.energy, relaxed.energy, u.energy(), NEWTON);
            assert_scaled(&what("relaxed angles"), &r.theta, &relaxed.theta, 1.0, NEWTON);
            assert_eq!(r.relax_steps, relaxed.relax_steps, "{}", what("relaxation steps"));
        }
    }
}

#[test]
fn continuum_closed_forms_carry_their_documented_units() {
    for p in SETS {
        let c0 = ContinuumChain::new(p.a, p.r, p.theta_bar, p.k, p.mass).unwrap();
        for u in Units::ALL {
            let c = ContinuumChain::new(p.a * u.l, p.r * u.l, p.theta_bar, p.k * u.k, p.mass * u.m).unwrap();
            let what = |s: &str| format!("continuum {s}, {p:?}, {u:?}");
            let (e, l, w) = (u.energy(), u.length(), u.rate());
            let cases: [(&str, f64, f64, f64); 16] = [
                ("antikink energy", c.antikink_energy(), c0.antikink_energy(), e),
                ("width", c.width(), c0.width(), l),
                ("rest length", c.rest_length(), c0.rest_length(), l),
                ("sound speed", c.sound_speed(), c0.sound_speed(), u.speed()),
                ("shape mode", c.shape_mode_frequency(), c0.shape_mode_frequency(), w),
                ("phonon gap", c.continuum_phonon_gap(), c0.continuum_phonon_gap(), w),
                ("band bottom", c.phonon_band_edges()[0], c0.phonon_band_edges()[0], w),
                ("band top", c.phonon_band_edges()[1], c0.phonon_band_edges()[1], w),
                ("PN barrier", c.pn_barrier(), c0.pn_barrier(), e),
                ("PN barrier as printed", c.pn_barrier_as_printed(), c0.pn_barrier_as_printed(), e),
                ("PN potential", c.pn_potential(0.3 * c.a()), c0.pn_potential(0.3 * c0.a()), e),
                ("ln PN slope", c.pn_log_slope(), c0.pn_log_slope(), 1.0),
                ("l_critical", c.l_critical(), c0.l_critical(), l),
                (
                    "critical energy",
                    c.critical_energy(1.3 * c.l_critical()),
                    c0.critical_energy(1.3 * c0.l_critical()),
                    e,
                ),
                ("cobweb slope", c.cobweb_slope(), c0.cobweb_slope(), 1.0),
                ("decay length", c.decay_length(), c0.decay_length(), l),
            ];
            for (name, got, base, factor) in cases {
                assert_scaled1(&what(name), got, base, factor, EXACT);
            }
            let profile = |c: &ContinuumChain| c.angle_profile(Charge::Antikink, 30, 14.3 * c.a()).unwrap();
            assert_scaled(&what("angle profile"), &profile(&c), &profile(&c0), 1.0, EXACT);
            let spectrum = |c: &ContinuumChain| c.finite_chain_frequencies(30).unwrap();
            assert_scaled(&what("finite chain"), &spectrum(&c), &spectrum(&c0), w, EXACT);
            let moving = |c: &ContinuumChain, t: f64, v: f64| {
                c.moving_angle(Charge::Kink, 5.0 * c.a(), t, 3.0 * c.a(), v).unwrap()
            };
            let v0 = 0.4 * c0.sound_speed();
            assert_scaled1(
                &what("moving wall"),
                moving(&c, 0.01 * u.time(), v0 * u.speed()),
                moving(&c0, 0.01, v0),
                1.0,
                EXACT,
            );
        }
    }
}

#[test]
fn linkage_limit_scales_with_lengths_stiffness_and_mass() {
    // Positions are in sites: unchanged under L; the kink mass M r^2 sum (dtheta/dx)^2 is an
    // inertia (m L^2), the momenta m(x) xdot scale as m L^2 / T.
    let base = ContinuumChain::new(1.3, 1.04, 0.58, 3.3e3, 2.5).unwrap();
    let l0 = 2.15 * 1.3;
    let link0 = LinkageChain::new(base, 8, l0).unwrap();
    let momentum = |u: Units| u.inertia() * u.rate();
    let start = |u: Units| PhaseState { x1: 7.2, x2: 1.1, p1: 0.5 * momentum(u), p2: -0.2 * momentum(u) };
    let path0 = link0.trajectory(start(Units::NONE), 4e-4, 400, 100).unwrap();
    let sub_chain = link0.sub_chain_profile(5.4);
    for u in Units::ALL {
        let c = ContinuumChain::new(1.3 * u.l, 1.04 * u.l, 0.58, 3.3e3 * u.k, 2.5 * u.m).unwrap();
        let link = LinkageChain::new(c, 8, l0 * u.l).unwrap();
        let what = |s: &str| format!("linkage {s}, {u:?}");
        assert_scaled1(&what("V"), link.potential(3.0, 1.0), link0.potential(3.0, 1.0), u.energy(), EXACT);
        assert_scaled1(&what("E_c"), link.critical_energy(), link0.critical_energy(), u.energy(), EXACT);
        assert_scaled1(&what("kink mass"), link.kink_mass(5.0), link0.kink_mass(5.0), u.inertia(), EXACT);
        assert_scaled(&what("profile"), &link.sub_chain_profile(5.4), &sub_chain, 1.0, EXACT);
        let eq: Vec<f64> = link.equilibria().iter().map(|e| e.x).collect();
        let eq0: Vec<f64> = link0.equilibria().iter().map(|e| e.x).collect();
        assert_scaled(&what("equilibria"), &eq, &eq0, 1.0, EXACT);
        // The same path at equal scaled times.
        let path = link.trajectory(start(u), 4e-4 * u.time(), 400, 100).unwrap();
        for (q, q0) in path.iter().zip(&path0) {
            assert_scaled(&what("path"), &[q.t, q.x1, q.x2], &[q0.t / u.rate(), q0.x1, q0.x2], 1.0, EXACT);
            assert_scaled(&what("momenta"), &[q.p1, q.p2], &[q0.p1, q0.p2], momentum(u), EXACT);
            assert_scaled1(&what("energy"), q.energy, q0.energy, u.energy(), EXACT);
        }
    }
    // The Appendix C coordinate of given angles is a length-free statement.
    for u in Units::ALL {
        let c = ContinuumChain::new(1.3 * u.l, 1.04 * u.l, 0.58, 3.3e3 * u.k, 2.5 * u.m).unwrap();
        let x = kink_coordinate(&c, &sub_chain).unwrap();
        assert_scaled1(
            &format!("kink coordinate, {u:?}"),
            x,
            kink_coordinate(&base, &sub_chain).unwrap(),
            1.0,
            EXACT,
        );
    }
}

/// `RunOptions` with every time scaled by `t` and every rate by `1 / t`.
fn run_options(t_max: f64, t: f64, method: Method) -> RunOptions {
    RunOptions {
        t_max: t_max * t,
        output_interval: 0.01 * t,
        method,
        damping: 0.4 / t,
        absorbing_ends: Some(Sponge { width: 6, strength: 30.0 / t }),
        ..RunOptions::default()
    }
}

#[test]
fn launched_defects_move_alike_at_equal_scaled_times() {
    for p in [SETS[0], SETS[2]] {
        let chain = p.chain(Units::NONE);
        // A speed amplitude of a fifth of the continuum sound speed, in the chain's own units.
        let v0 = 0.2 * ContinuumChain::new(p.a, p.r, p.theta_bar, p.k, p.mass).unwrap().sound_speed();
        let start = 0.6 * p.n as f64;
        for charge in [Charge::Kink, Charge::Antikink] {
            let l0 = launch(&chain, charge, start, v0, Direction::Left).unwrap();
            let verlet0 =
                propagate(&chain, l0.state.clone(), &run_options(0.3, 1.0, Method::Verlet), &mut |_| false)
                    .unwrap();
            let dop0 =
                propagate(&chain, l0.state.clone(), &run_options(0.05, 1.0, Method::dop853()), &mut |_| {
                    false
                })
                .unwrap();
            for u in Units::ALL {
                let scaled = p.chain(u);
                let what = |s: &str| format!("{charge:?} {s}, {p:?}, {u:?}");
                let l = launch(&scaled, charge, start, v0 * u.speed(), Direction::Left).unwrap();
                assert_scaled(&what("launch angles"), &l.state.theta, &l0.state.theta, 1.0, NEWTON);
                assert_scaled(&what("launch velocities"), &l.state.omega, &l0.state.omega, u.rate(), NEWTON);
                assert_scaled(&what("launch vector"), &l.mode, &l0.mode, 1.0, NEWTON);
                assert_scaled1(&what("launch position"), l.position, l0.position, 1.0, NEWTON);
                let kinetic = |c: &RuntimeChain, s: &State| {
                    (0..c.rotor_count()).map(|i| 0.5 * c.inertia(i) * s.omega[i] * s.omega[i]).sum::<f64>()
                };
                assert_scaled1(
                    &what("launch energy"),
                    kinetic(&scaled, &l.state),
                    kinetic(&chain, &l0.state),
                    u.energy(),
                    NEWTON,
                );

                let run = propagate(
                    &scaled,
                    l.state.clone(),
                    &run_options(0.3, u.time(), Method::Verlet),
                    &mut |_| false,
                )
                .unwrap();
                assert_eq!(run.report.steps, verlet0.report.steps, "{}", what("Verlet steps"));
                assert_scaled(
                    &what("Verlet angles"),
                    &run.final_state.theta,
                    &verlet0.final_state.theta,
                    1.0,
                    NEWTON,
                );
                assert_scaled(
                    &what("Verlet velocities"),
                    &run.final_state.omega,
                    &verlet0.final_state.omega,
                    u.rate(),
                    NEWTON,
                );
                assert_scaled1(
                    &what("Verlet time"),
                    run.final_state.time,
                    verlet0.final_state.time,
                    u.time(),
                    EXACT,
                );
                let series = |r: &rotor_chain::dynamics::run::Run| {
                    r.kinetic.iter().map(|&(_, e)| e).collect::<Vec<_>>()
                };
                assert_scaled(&what("kinetic energy"), &series(&run), &series(&verlet0), u.energy(), NEWTON);
                let report = [
                    run.report.energy_initial,
                    run.report.energy_final,
                    run.report.max_energy_rise.max(run.report.max_energy_error),
                ];
                let report0 = [
                    verlet0.report.energy_initial,
                    verlet0.report.energy_final,
                    verlet0.report.max_energy_rise.max(verlet0.report.max_energy_error),
                ];
                assert_scaled(&what("energy report"), &report, &report0, u.energy(), NEWTON);
                let walls = |r: &rotor_chain::dynamics::run::Run| {
                    r.tracker
                        .snapshots
                        .iter()
                        .flat_map(|s| s.walls.iter().map(|w| w.position))
                        .collect::<Vec<_>>()
                };
                assert_scaled(&what("wall positions"), &walls(&run), &walls(&verlet0), 1.0, NEWTON);

                // DOP853's atol is absolute (radians and radians per t), so its steps differ:
                // agreement to its tolerances.
                let dop = propagate(
                    &scaled,
                    l.state.clone(),
                    &run_options(0.05, u.time(), Method::dop853()),
                    &mut |_| false,
                )
                .unwrap();
                assert_scaled(
                    &what("DOP853 angles"),
                    &dop.final_state.theta,
                    &dop0.final_state.theta,
                    1.0,
                    1e-8,
                );
                assert_scaled(
                    &what("DOP853 velocities"),
                    &dop.final_state.omega,
                    &dop0.final_state.omega,
                    u.rate(),
                    1e-7,
                );
            }
        }
    }
}

#[test]
fn scattering_outcomes_are_invariant_in_scaled_units() {
    // The paper's chain of Sec. VI (a = 1, k = 1e4, M = 1) and its five named points, unscaled;
    // then in other units, with v0 in length per t (Appendix B) and every time of the setup
    // (`ScatterSetup`: times in t, distances in sites) scaled.
    let points = [
        (Charge::Kink, 4.0, 0.10),
        (Charge::Kink, 9.6, 0.01),
        (Charge::Antikink, 4.0, 0.80),
        (Charge::Antikink, 4.0, 0.70),
        (Charge::Antikink, 4.8, 0.20),
    ];
    let setup = |charge, v0: f64, u: Units| {
        let mut s = ScatterSetup::from_the_right(charge, v0 * u.speed(), 29);
        let t = u.time();
        for time in [
            &mut s.persistence,
            &mut s.trap_time,
            &mut s.entry_window,
            &mut s.pair_age,
            &mut s.break_time,
            &mut s.grace,
            &mut s.confirm,
            &mut s.watch,
            &mut s.run.t_max,
            &mut s.run.output_interval,
        ] {
            *time *= t;
        }
        s
    };
    let chain = |ki: f64, u: Units| {
        RuntimeChain::builder(60, 0.8 * u.l, 1e4 * u.k, 0.28)
            .lattice_spacing(u.l)
            .mass(u.m)
            .spring_constant(29, ki * 1e4 * u.k)
            .build()
            .unwrap()
    };
    for (charge, v0, ki) in points {
        let base = scatter(&chain(ki, Units::NONE), &setup(charge, v0, Units::NONE)).unwrap();
        for u in Units::ALL {
            let got = scatter(&chain(ki, u), &setup(charge, v0, u)).unwrap();
            let what = format!("{charge:?} v0 = {v0} k_i/k = {ki}, {u:?}");
            assert_eq!((got.outcome, got.confirmed), (base.outcome, base.confirmed), "{what}");
            // Decided at the same output, up to rounding in the output times.
            let (t, t0) = (got.decided_at / u.time(), base.decided_at);
            assert!((t - t0).abs() <= 0.0101, "{what}: decided at {t} (scaled) against {t0}");
            // The library's own carrying-over of the paper's setup (what Python's scatter and the
            // phase diagrams use) scales the same times and gives the same result.
            let own = ScatterSetup::from_the_right(charge, v0 * u.speed(), 29)
                .in_time_unit(paper_time_unit(1e4 * u.k, u.m));
            let times = |s: &ScatterSetup| {
                [
                    s.persistence,
                    s.trap_time,
                    s.entry_window,
                    s.pair_age,
                    s.break_time,
                    s.grace,
                    s.confirm,
                    s.watch,
                    s.run.t_max,
                    s.run.output_interval,
                ]
            };
            let by_hand = setup(charge, v0, u);
            assert_scaled(&format!("{what}: setup times"), &times(&own), &times(&by_hand), 1.0, EXACT);
            let carried = scatter(&chain(ki, u), &own).unwrap();
            assert_eq!((carried.outcome, carried.confirmed), (base.outcome, base.confirmed), "{what}");
            let t = carried.decided_at / u.time();
            assert!((t - t0).abs() <= 0.0101, "{what}: in_time_unit decided at {t} (scaled) against {t0}");
        }
    }
}
