//! Every field of every public options struct of chain-network is validated (issue 37):
//! [`WindingOptions`], [`Strip`], [`BistableChain`] and [`CoupledChains`], each destructured
//! without `..` (a new field does not compile until it is listed here), each field given its
//! invalid values, which
//! must fail [`Validate::validate`] with the [`InvalidOption`] naming that struct, that field and
//! that value, while the valid value they replace passes; a count is enumerated at both ends of
//! its documented range (test-support's `options` checks, shared with chain-core's and
//! chain-sweep's tests). Then the entry points refuse them the same way.

use chain_core::dynamics::run::MAX_SPACE_TIME_VALUES;
use chain_core::integrate::MAX_STEP_BUDGET;
use chain_core::validate::Validate;
use chain_network::cell::ready;
use chain_network::motion::transition::BistableChain;
use chain_network::motion::wall::CoupledChains;
use chain_network::patch::MAX_PATCH_BONDS;
use chain_network::strip::{DEFAULT_Q, MAX_STRIP_DOF, Strip, compatibility, strip_modes};
use chain_network::winding::{WindingOptions, winding};
use test_support::options::{assert_names, count_range, rule_states, values};

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;
const TINY: f64 = 5e-324;
const POSITIVE: &[f64] = &[NAN, INF, -INF, -1.0, -TINY, 0.0];

#[test]
fn every_field_of_the_network_options_is_validated() {
    let WindingOptions { transverse } = WindingOptions::default();
    let with = |v: f64| WindingOptions { transverse: vec![transverse[0], v] };
    values("WindingOptions", "transverse", 0.3, &[NAN, INF, -INF], with);
    // An empty list: the value reported is its length.
    let e = WindingOptions { transverse: vec![] }.validate().unwrap_err();
    assert_names(&e, "WindingOptions", "transverse", 0.0);

    let base = Strip { along: 0, cells: 20, q: DEFAULT_Q };
    let Strip { along, cells, q } = base;
    // A lattice direction: 0 or 1 (the cell decides which it has, at the entry point).
    assert!(along <= 1 && (1..=MAX_STRIP_DOF).contains(&cells));
    count_range("Strip", "along", 0, 1, |v| Strip { along: v as usize, ..base });
    values("Strip", "along", 0.0, &[usize::MAX as f64], |v| Strip { along: v as usize, ..base });
    let most = MAX_STRIP_DOF as u64;
    rule_states(count_range("Strip", "cells", 1, most, |v| Strip { cells: v as usize, ..base }), most);
    values("Strip", "q", q, &[NAN, INF, -INF], |v| Strip { q: v, ..base });

    let base = BistableChain::default();
    let BistableChain {
        sites,
        coupling,
        on_site,
        barrier,
        well,
        damping,
        duration,
        samples,
        launch_sites,
        fit_from,
    } = base;
    let o = "BistableChain";
    // Between 8 and the patch rule's bound; the samples' bound below depends on the sites.
    let most = MAX_PATCH_BONDS as u64;
    let o_sites = count_range(o, "sites", 8, most, |v| BistableChain {
        sites: v as usize,
        launch_sites: 1,
        samples: 2,
        ..base
    });
    rule_states(o_sites, most);
    assert!((8..=MAX_PATCH_BONDS).contains(&sites));
    values(o, "coupling", coupling, POSITIVE, |v| BistableChain { coupling: v, ..base });
    values(o, "on_site", on_site, POSITIVE, |v| BistableChain { on_site: v, ..base });
    // Positive and below well / 2 = 0.1.
    let bad_barrier = &[NAN, INF, -1.0, 0.0, 0.1, 1.0];
    values(o, "barrier", barrier, bad_barrier, |v| BistableChain { barrier: v, ..base });
    values(o, "well", well, POSITIVE, |v| BistableChain { well: v, ..base });
    values(o, "damping", damping, POSITIVE, |v| BistableChain { damping: v, ..base });
    // Positive, and after fit_from (15).
    values(o, "duration", duration, POSITIVE, |v| BistableChain { duration: v, ..base });
    // At most MAX_STEP_BUDGET steps of 0.2 / omega_max, omega_max = sqrt(4 k_c + beta b max(a, b - a))
    // (= sqrt(64 + 0.75) at the defaults): the longest duration passes, the next double fails.
    let omega = (4.0 * coupling + on_site * well * barrier.max(well - barrier)).sqrt();
    let longest = MAX_STEP_BUDGET as f64 * 0.2 / omega;
    let longest = if longest * omega / 0.2 > MAX_STEP_BUDGET as f64 { longest.next_down() } else { longest };
    values(o, "duration", longest, &[longest.next_up().next_up(), 1e300], |v| BistableChain {
        duration: v,
        ..base
    });
    values(o, "fit_from", 15.0, &[NAN, INF, -TINY, 70.0, 71.0], |v| BistableChain {
        fit_from: v,
        duration: 70.0,
        ..base
    });
    // Between 2 and the space-time bound over the sites (200 at the defaults).
    let most = (MAX_SPACE_TIME_VALUES / sites) as u64;
    assert!((2..=most).contains(&(samples as u64)));
    count_range(o, "samples", 2, most, |v| BistableChain { samples: v as usize, ..base });
    // At least 1 and below sites / 2 = 100.
    let bad_launch = &[0.0, 100.0, 1e6];
    values(o, "launch_sites", launch_sites as f64, bad_launch, |v| BistableChain {
        launch_sites: v as usize,
        ..base
    });
    let _ = fit_from;

    let base = CoupledChains::default();
    let CoupledChains {
        chains,
        cells,
        spacing,
        rotor_length,
        theta_bar,
        row_spacing,
        coupling,
        speed,
        start,
        stagger,
        damping,
        duration,
        frames,
    } = base;
    let o = "CoupledChains";
    // The patch's cells: chains between 2 and MAX_PATCH_BONDS / 8 (at 8 cells), cells between 8
    // and MAX_PATCH_BONDS / chains (2 frames, which any patch within the bound allows; the wall
    // at 8, inside 8 cells' 16 rotors).
    let most = (MAX_PATCH_BONDS / 8) as u64;
    let o_chains = count_range(o, "chains", 2, most, |v| CoupledChains {
        chains: v as usize,
        cells: 8,
        start: 8.0,
        frames: 2,
        ..base
    });
    rule_states(o_chains, most);
    let most = (MAX_PATCH_BONDS / 2) as u64;
    count_range(o, "cells", 8, most, |v| CoupledChains {
        cells: v as usize,
        chains: 2,
        start: 8.0,
        frames: 2,
        ..base
    });
    let most = (MAX_PATCH_BONDS / chains) as u64;
    count_range(o, "cells", 8, most, |v| CoupledChains { cells: v as usize, start: 8.0, frames: 2, ..base });
    assert!(chains >= 2 && cells >= 8);
    values(o, "spacing", spacing, POSITIVE, |v| CoupledChains { spacing: v, ..base });
    values(o, "rotor_length", rotor_length, POSITIVE, |v| CoupledChains { rotor_length: v, ..base });
    // In (0, pi/2).
    let bad_tilt = &[NAN, INF, -0.3, 0.0, std::f64::consts::FRAC_PI_2, 2.0];
    values(o, "theta_bar", theta_bar, bad_tilt, |v| CoupledChains { theta_bar: v, ..base });
    values(o, "row_spacing", row_spacing, POSITIVE, |v| CoupledChains { row_spacing: v, ..base });
    values(o, "coupling", coupling, POSITIVE, |v| CoupledChains { coupling: v, ..base });
    values(o, "speed", speed, POSITIVE, |v| CoupledChains { speed: v, ..base });
    values(o, "stagger", stagger, &[NAN, INF, -1.0, -TINY], |v| CoupledChains { stagger: v, ..base });
    // Every chain's wall (start +- stagger / 2 = 0.5) in [4, 43] of the 48 rotors.
    let bad_start = &[NAN, INF, -INF, 0.0, 4.4, 42.6, 100.0];
    values(o, "start", start, bad_start, |v| CoupledChains { start: v, ..base });
    values(o, "damping", damping, &[NAN, INF, -1.0, -TINY], |v| CoupledChains { damping: v, ..base });
    values(o, "duration", duration, POSITIVE, |v| CoupledChains { duration: v, ..base });
    // At most MAX_STEP_BUDGET steps of 0.1 / omega_max, omega_max = sqrt(4 (1 + k_c)).
    let omega = (4.0 * (1.0 + coupling)).sqrt();
    let longest = MAX_STEP_BUDGET as f64 * 0.1 / omega;
    let longest = if longest * omega / 0.1 > MAX_STEP_BUDGET as f64 { longest.next_down() } else { longest };
    values(o, "duration", longest, &[longest.next_up().next_up(), 1e300], |v| CoupledChains {
        duration: v,
        ..base
    });
    // Between 2 and the space-time bound over the rotors (6 chains of 48 at the defaults).
    let most = (MAX_SPACE_TIME_VALUES / (2 * cells * chains)) as u64;
    assert!((2..=most).contains(&(frames as u64)));
    count_range(o, "frames", 2, most, |v| CoupledChains { frames: v as usize, ..base });
}

#[test]
fn the_network_entry_points_refuse_an_invalid_struct() {
    let cell = ready::deformed_kagome(0.1, 0.1, 0.1, 0.02).unwrap();
    let e = winding(&cell, &WindingOptions { transverse: vec![0.2, NAN] }).unwrap_err();
    assert_names(&e, "WindingOptions", "transverse", NAN);
    let strip = Strip { along: 0, cells: 20, q: INF };
    assert_names(&compatibility(&cell, &strip).unwrap_err(), "Strip", "q", INF);
    assert_names(&strip_modes(&cell, &strip).unwrap_err(), "Strip", "q", INF);
    let e = BistableChain { coupling: -TINY, ..BistableChain::default() }.run().unwrap_err();
    assert_names(&e, "BistableChain", "coupling", -TINY);
    assert!(e.to_string().contains("BistableChain.coupling = -5e-324 is invalid"), "{e}");
    let e = CoupledChains { speed: 1e300, coupling: -TINY, ..CoupledChains::default() }.run().unwrap_err();
    assert_names(&e, "CoupledChains", "coupling", -TINY);
    // A run too long for any step budget (it looped ~10^300 steps before) and a count past its
    // bound are refused before anything is built.
    let e = BistableChain { duration: 1e300, ..BistableChain::default() }.run().unwrap_err();
    assert_names(&e, "BistableChain", "duration", 1e300);
    let e = CoupledChains { duration: 1e300, ..CoupledChains::default() }.run().unwrap_err();
    assert_names(&e, "CoupledChains", "duration", 1e300);
    let e = CoupledChains { frames: usize::MAX, ..CoupledChains::default() }.run().unwrap_err();
    assert_names(&e, "CoupledChains", "frames", usize::MAX as f64);
}
