//! Every field of every public options struct of chain-network is validated (issue 37):
//! [`WindingOptions`], [`Strip`], [`BistableChain`] and [`CoupledChains`], each destructured
//! without `..` (a new field does not compile until it is listed here), each field given its
//! invalid values, which
//! must fail [`Validate::validate`] with the [`InvalidOption`] naming that struct, that field and
//! that value, while the valid value they replace passes. Then the entry points refuse them the
//! same way.

use chain_core::validate::{InvalidOption, Validate};
use chain_network::NetworkError;
use chain_network::cell::ready;
use chain_network::motion::MotionError;
use chain_network::motion::transition::BistableChain;
use chain_network::motion::wall::CoupledChains;
use chain_network::strip::{DEFAULT_Q, MAX_STRIP_DOF, Strip, compatibility, strip_modes};
use chain_network::winding::{WindingOptions, winding};

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;
const TINY: f64 = 5e-324;
const POSITIVE: &[f64] = &[NAN, INF, -INF, -1.0, -TINY, 0.0];

/// The `InvalidOption` an error carries.
trait Invalid {
    fn invalid(&self) -> Option<InvalidOption>;
}

impl Invalid for NetworkError {
    fn invalid(&self) -> Option<InvalidOption> {
        match self {
            NetworkError::InvalidOption(o) => Some(*o),
            _ => None,
        }
    }
}

impl Invalid for MotionError {
    fn invalid(&self) -> Option<InvalidOption> {
        match self {
            MotionError::InvalidOption(o) => Some(*o),
            _ => None,
        }
    }
}

fn assert_names<E: Invalid + std::fmt::Display>(error: &E, options: &str, field: &str, value: f64) {
    let o = error.invalid().unwrap_or_else(|| panic!("not an invalid option: {error}"));
    assert_eq!((o.options, o.field), (options, field), "{error}");
    assert!(o.value.to_bits() == value.to_bits() || (o.value.is_nan() && value.is_nan()), "{value}: {error}");
    assert!(error.to_string().contains(&format!("{options}.{field} = ")), "{error}");
}

/// `make(valid)` validates, and `make(v)` for each `v` of `bad` fails naming `options.field = v`.
fn values<S: Validate>(options: &str, field: &str, valid: f64, bad: &[f64], make: impl Fn(f64) -> S)
where
    S::Error: Invalid + std::fmt::Display + std::fmt::Debug,
{
    if let Err(e) = make(valid).validate() {
        panic!("{options}.{field} = {valid} is valid, got {e}");
    }
    for &v in bad {
        match make(v).validate() {
            Ok(()) => panic!("{options}.{field} = {v} passed"),
            Err(e) => assert_names(&e, options, field, v),
        }
    }
}

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
    values("Strip", "along", along as f64, &[2.0, usize::MAX as f64], |v| Strip {
        along: v as usize,
        ..base
    });
    let too_many = (MAX_STRIP_DOF + 1) as f64;
    values("Strip", "cells", cells as f64, &[0.0, too_many], |v| Strip { cells: v as usize, ..base });
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
    values(o, "sites", sites as f64, &[0.0, 7.0], |v| BistableChain { sites: v as usize, ..base });
    values(o, "coupling", coupling, POSITIVE, |v| BistableChain { coupling: v, ..base });
    values(o, "on_site", on_site, POSITIVE, |v| BistableChain { on_site: v, ..base });
    // Positive and below well / 2 = 0.1.
    let bad_barrier = &[NAN, INF, -1.0, 0.0, 0.1, 1.0];
    values(o, "barrier", barrier, bad_barrier, |v| BistableChain { barrier: v, ..base });
    values(o, "well", well, POSITIVE, |v| BistableChain { well: v, ..base });
    values(o, "damping", damping, POSITIVE, |v| BistableChain { damping: v, ..base });
    // Positive, and after fit_from (15).
    values(o, "duration", duration, POSITIVE, |v| BistableChain { duration: v, ..base });
    values(o, "fit_from", 15.0, &[NAN, INF, -TINY, 70.0, 71.0], |v| BistableChain {
        fit_from: v,
        duration: 70.0,
        ..base
    });
    values(o, "samples", samples as f64, &[0.0, 1.0], |v| BistableChain { samples: v as usize, ..base });
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
    values(o, "chains", chains as f64, &[0.0, 1.0], |v| CoupledChains { chains: v as usize, ..base });
    values(o, "cells", cells as f64, &[0.0, 7.0], |v| CoupledChains { cells: v as usize, ..base });
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
    values(o, "frames", frames as f64, &[0.0, 1.0], |v| CoupledChains { frames: v as usize, ..base });
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
}
