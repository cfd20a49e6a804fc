//! The antikink's energy landscape on a chain that is not uniform (paper Sec. V, VI): which
//! centrings are equilibria near a place, of which Morse index, and how strongly each impurity
//! pins or repels the antikink.
//!
//! On a uniform chain the antikink's equilibria alternate between rotor and spring centrings,
//! minimum and saddle, a Peierls-Nabarro barrier apart. An impurity spring (a stiffness or rest
//! length other than the chain's) adds a potential of its own, as wide as the antikink: a stiffer
//! spring repels it, a softer one pins it. Where that potential's force beats the
//! Peierls-Nabarro force no centring is an equilibrium: Newton's method from the symmetric guess
//! slides away (n = 40, `theta_bar = 0.4`, the middle spring at `2k`: every centring from 15 to 24
//! except the impurity's own, a saddle of index 1), and next to a stiffer spring (`5k`) the
//! symmetric guess splits into a kink-antikink pair. [`scan`] therefore walks the adiabatic path
//! across [`LANDSCAPE_REACH`] sites either side ([`super::path_scan`]) and reports every centring
//! as the path point there (the energy with the centre held) and every free equilibrium of the path
//! with its Morse index, where it lies, on or between the centrings. [`ImpurityEnergy`] is the
//! antikink's energy centred on an impurity spring (or at the end of the path before it, where
//! the path does not reach it) minus its energy at the spring centring farthest from the ends and
//! every impurity.
//!
//! [`default_centre`] places an antikink where nothing disturbs it: the rotor farthest from both
//! ends and from every impurity.

use alloc::vec::Vec;

use super::antikink::{Antikink, AntikinkOptions, Ends, on_path, solve_centring};
use super::error::StaticsError;
use super::path_scan::{PathScan, scan_path};
use crate::model::ChainModel;

/// How far (in sites, either side) [`scan`] looks from the requested place. Why 8: an antikink
/// at `theta_bar >= 0.3` is at most 3 sites wide (`a^2 / (2 r sin theta_bar)`), and an impurity's
/// force decays over that width, so 8 sites reaches past it to the first Peierls-Nabarro minima
/// (at 5 - 10 sites from a spring at `2k`, n = 40, `theta_bar = 0.4`) at the cost of about 130
/// points of the path and a regula falsi per equilibrium.
pub const LANDSCAPE_REACH: f64 = 8.0;

/// A free equilibrium of the path this close to a centring (sites) is that centring's
/// equilibrium: far above the path's resolution (`1e-9`), far below any shift an impurity causes
/// that the landscape reports (`> 1e-3` in every case measured).
pub const ON_CENTRING: f64 = 1e-6;

/// One impurity spring's pinning or repulsion energy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImpurityEnergy {
    /// The impurity spring `p` (between rotors `p` and `p + 1`).
    pub spring: usize,
    /// `V(antikink centred on the spring) - V(antikink at the reference centring)`: negative, the
    /// impurity pins the antikink (a soft or long spring); positive, it repels it.
    pub energy: f64,
    /// The reference centring: the spring centring farthest from the ends and every impurity.
    pub reference: f64,
    /// The centre the energy is taken at: the spring's centring `p + 1/2`, or, where no antikink
    /// with one wall is centred there (next to a stiff spring, `5k` at `theta_bar = 0.4`: the path
    /// ends where a kink-antikink pair nucleates on the way), the point of the path nearest it.
    pub centre: f64,
}

/// The springs whose stiffness or rest length differs from the chain's (the value most springs
/// share), ascending.
pub fn impurity_springs<M: ChainModel + ?Sized>(model: &M) -> Vec<usize> {
    let m = model.spring_count();
    let key = |p: usize| (model.spring_constant(p).to_bits(), model.rest_length(p).to_bits());
    let mut keys: Vec<(u64, u64)> = (0..m).map(key).collect();
    keys.sort_unstable();
    // The most common (stiffness, rest length): the chain's own.
    let (mut best, mut best_count, mut i) = (None, 0, 0);
    while i < keys.len() {
        let j = i + keys[i..].iter().take_while(|k| **k == keys[i]).count();
        if j - i > best_count {
            (best, best_count) = (Some(keys[i]), j - i);
        }
        i = j;
    }
    (0..m).filter(|&p| Some(key(p)) != best).collect()
}

/// The centring (rotor centrings if `offset` is 0, spring centrings if 0.5) farthest from both
/// ends and from every impurity spring's centre `p + 1/2`; ties go to the one nearer the middle,
/// then to the left.
fn farthest_centring(n: usize, impurities: &[usize], offset: f64) -> f64 {
    let last = (n - 1) as f64;
    let clearance =
        |c: f64| impurities.iter().map(|&p| (c - (p as f64 + 0.5)).abs()).fold(c.min(last - c), f64::min);
    let middle = last / 2.0;
    (0..n)
        .map(|i| i as f64 + offset)
        .filter(|&c| c <= last)
        .fold(None::<f64>, |best, c| match best {
            Some(b)
                if clearance(b) > clearance(c)
                    || (clearance(b) == clearance(c) && (b - middle).abs() <= (c - middle).abs()) =>
            {
                Some(b)
            }
            _ => Some(c),
        })
        .unwrap_or(middle)
}

/// Where an antikink is placed when no centre is given (Python's `Chain.antikink()`): the rotor
/// farthest from both ends and from every impurity spring ([`impurity_springs`]); on a uniform
/// chain the middle rotor `(n - 1) / 2` rounded down.
pub fn default_centre<M: ChainModel + ?Sized>(model: &M) -> f64 {
    farthest_centring(model.rotor_count(), &impurity_springs(model), 0.0)
}

/// The landscape within [`LANDSCAPE_REACH`] of `place` (kept in `[1, n - 2]`) and the energies
/// of the impurity springs in it ([`ImpurityEnergy`]).
///
/// With `impurities` (the springs of [`impurity_springs`]), from the adiabatic path
/// ([`super::path_scan`]): every centring (integer and half-integer) as the path point there, its
/// centre held (`held = 1`), and every free equilibrium of the path (a zero of `dE/dc`, polished
/// and classified: `held = 0`), in order of centre. An equilibrium within [`ON_CENTRING`] of a
/// centring takes that centring's place (`requested` the centring); the others keep the centre
/// they were found at as `requested`. A centring where the path has ended (between its stretches,
/// [`PathScan::segments`]: next to a soft impurity a pair nucleates on the way) is solved from its
/// symmetric guess, as every centring is without impurities (a uniform chain whose middle pair is
/// not resolved) and with [`Ends::Free`] (the path needs held ends).
///
/// # Errors
/// Those of [`super::path_scan::scan_path`], and of Newton's method at a centring or at the
/// reference centring.
pub fn scan<M: ChainModel + ?Sized>(
    model: &M,
    place: f64,
    impurities: &[usize],
    options: &AntikinkOptions,
) -> Result<(Vec<Antikink>, Vec<ImpurityEnergy>), StaticsError> {
    scan_with_path(model, place, impurities, options).map(|(landscape, energies, _)| (landscape, energies))
}

/// What [`scan_with_path`] returns: the landscape, the impurities' energies and the path walked.
pub(crate) type Scanned = (Vec<Antikink>, Vec<ImpurityEnergy>, Option<PathScan>);

/// [`scan`] and the path it walked (on a chain with impurities).
pub(crate) fn scan_with_path<M: ChainModel + ?Sized>(
    model: &M,
    place: f64,
    impurities: &[usize],
    options: &AntikinkOptions,
) -> Result<Scanned, StaticsError> {
    let n = model.rotor_count();
    let last = n as f64 - 2.0;
    let (lo, hi) = ((place - LANDSCAPE_REACH).max(1.0), (place + LANDSCAPE_REACH).min(last));
    // The path holds the end rotors (with free ends their near-null edge modes make it singular).
    let path = if impurities.is_empty() || options.ends != Ends::Held {
        None
    } else {
        Some(scan_path(model, lo, hi, impurities, options)?)
    };
    let landscape = match &path {
        Some(path) => on_the_path(model, lo, hi, path, options)?,
        None => centrings(model, lo, hi, options)?,
    };
    let mut energies = Vec::new();
    let near: Vec<usize> = impurities
        .iter()
        .copied()
        .filter(|&p| ((p as f64 + 0.5) - place).abs() <= LANDSCAPE_REACH && p >= 1 && p + 2 < n)
        .collect();
    if !near.is_empty() {
        let reference = farthest_centring(n, impurities, 0.5);
        let far = solve_centring(model, reference, options)?.energy;
        for p in near {
            let centring = p as f64 + 0.5;
            let nearest = path.as_ref().and_then(|path| path.nearest(centring));
            let (centre, on) = match landscape.iter().find(|a| a.requested == centring) {
                Some(a) => (centring, a.energy),
                None => match (solve_centring(model, centring, options), nearest) {
                    (Ok(a), _) if !a.moved() => (centring, a.energy),
                    (Ok(_) | Err(StaticsError::DefectLost { .. }), Some(q)) => (q.centre, q.energy),
                    (Err(e), _) => return Err(e),
                    (Ok(a), None) => (a.centre, a.energy),
                },
            };
            energies.push(ImpurityEnergy { spring: p, energy: on - far, reference, centre });
        }
    }
    Ok((landscape, energies, path))
}

/// The landscape on `[lo, hi]` from the walked `path` (see [`scan`]).
fn on_the_path<M: ChainModel + ?Sized>(
    model: &M,
    lo: f64,
    hi: f64,
    path: &PathScan,
    options: &AntikinkOptions,
) -> Result<Vec<Antikink>, StaticsError> {
    let mut landscape = Vec::new();
    let on_equilibrium = |c: f64| path.equilibria.iter().any(|e| (e.centre - c).abs() <= ON_CENTRING);
    for twice in libm::ceil(2.0 * lo) as i64..=libm::floor(2.0 * hi) as i64 {
        let c = twice as f64 / 2.0;
        if on_equilibrium(c) {
            continue;
        }
        match path.at(c) {
            Some(point) => landscape.push(on_path(model, point.clone(), options)?),
            // Where the path has ended (a pair nucleates on the way), the symmetric guess.
            None if !path.covers(c) => match solve_centring(model, c, options) {
                Ok(a) => landscape.push(a),
                Err(StaticsError::DefectLost { .. }) => {}
                Err(e) => return Err(e),
            },
            None => {}
        }
    }
    // Where a stretch of the path ends inside the window (the path ends there: a pair nucleates
    // one step further), its last point.
    for segment in &path.segments {
        for end in [segment.first(), segment.last()].into_iter().flatten() {
            let centring = 2.0 * end.centre == libm::round(2.0 * end.centre);
            if !centring && end.centre > lo && end.centre < hi && !on_equilibrium(end.centre) {
                landscape.push(on_path(model, end.clone(), options)?);
            }
        }
    }
    for e in &path.equilibria {
        let mut e = e.clone();
        let nearest = libm::round(2.0 * e.centre) / 2.0;
        if (e.centre - nearest).abs() <= ON_CENTRING {
            e.requested = nearest;
        }
        landscape.push(e);
    }
    landscape.sort_by(|a, b| a.requested.total_cmp(&b.requested));
    Ok(landscape)
}

/// Every centring in `[lo, hi]` solved at fixed centring from its symmetric guess (a centring
/// whose antikink is lost at an end is left out): the landscape of a uniform chain whose two
/// middle centrings are not a resolved minimum and saddle (a wide antikink held by the ends).
fn centrings<M: ChainModel + ?Sized>(
    model: &M,
    lo: f64,
    hi: f64,
    options: &AntikinkOptions,
) -> Result<Vec<Antikink>, StaticsError> {
    let mut landscape = Vec::new();
    for twice in libm::ceil(2.0 * lo) as i64..=libm::floor(2.0 * hi) as i64 {
        match solve_centring(model, twice as f64 / 2.0, options) {
            Ok(a) => landscape.push(a),
            Err(StaticsError::DefectLost { .. }) => {}
            Err(e) => return Err(e),
        }
    }
    Ok(landscape)
}
