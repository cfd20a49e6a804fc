//! The antikink's adiabatic path across a window of centres and the free equilibria on it: the
//! landscape of [`super::landscape::scan`] (paper Sec. V; issue 34).
//!
//! Newton's method from the symmetric reflected kink at each centring ([`super::antikink`]) finds
//! the equilibrium there when there is one; next to a stiff impurity the symmetric guess itself is
//! far from any antikink of that centre (at `5k`, n = 40, `theta_bar = 0.4` to 0.6 its core
//! splits into a kink-antikink pair on the impurity). Here the path is walked instead: one point
//! with its centre held ([`super::path::at_centre`]) every [`PATH_STEP`] from the centre farthest
//! from every impurity in the window outward to both edges, each warm-started from its
//! neighbour, so the antikink is carried continuously onto the impurity. A step that finds no
//! point of the same branch is halved down to [`MIN_STEP`] (`path::next_point`, the descent's
//! step); below that the path has ended (a pair nucleates, or a fold) and the walk stops on that
//! side.
//!
//! Every sign change of `dE/dc` between neighbouring points brackets a free equilibrium: closed
//! by regula falsi (Illinois, as in the descent, to [`super::path::PATH_RESOLUTION`]) and
//! polished by free Newton, it is classified by the Sturm count of its tangent stiffness, so a
//! saddle across the path is a saddle even where the path has a minimum. Why a step of 1/8 site:
//! as for the descent, at least two path points in every well, so no pair of zeros falls between
//! two samples.

use alloc::vec::Vec;

use super::antikink::{Antikink, AntikinkOptions};
use super::error::StaticsError;
use super::kink::reflected_kink;
use super::path::{MIN_STEP, PATH_STEP, PathPoint, at_centre, next_point, refine};
use crate::model::ChainModel;

/// The path across a window and its free equilibria.
#[derive(Clone, Debug, PartialEq)]
pub struct PathScan {
    /// The stretches of path walked, each in order of centre and the stretches in order: every
    /// multiple of [`PATH_STEP`] the walks reached, and the halved steps they needed. Between two
    /// stretches the path has ended (no antikink with its centre held one [`MIN_STEP`] further:
    /// a pair nucleates at a soft impurity, or a fold).
    pub segments: Vec<Vec<PathPoint>>,
    /// The free equilibria on the stretches (zeros of `dE/dc`), in order of centre, polished and
    /// classified.
    pub equilibria: Vec<Antikink>,
}

impl PathScan {
    /// The path point held exactly at `centre`, if a walk reached it.
    pub fn at(&self, centre: f64) -> Option<&PathPoint> {
        self.segments.iter().flatten().find(|p| p.centre == centre)
    }

    /// The path point nearest `centre` (ties: the lower centre).
    pub fn nearest(&self, centre: f64) -> Option<&PathPoint> {
        self.segments.iter().flatten().fold(None, |best: Option<&PathPoint>, p| match best {
            Some(b) if (b.centre - centre).abs() <= (p.centre - centre).abs() => Some(b),
            _ => Some(p),
        })
    }

    /// Whether `centre` lies on a stretch walked.
    pub fn covers(&self, centre: f64) -> bool {
        self.segments.iter().any(|s| {
            s.first().is_some_and(|a| a.centre <= centre) && s.last().is_some_and(|b| centre <= b.centre)
        })
    }
}

/// Walks from `start` toward `edge` along the path, appending the points (module doc). Returns
/// where the path ended if it did not reach `edge`.
fn walk<M: ChainModel + ?Sized>(
    model: &M,
    start: &PathPoint,
    edge: f64,
    options: &AntikinkOptions,
    points: &mut Vec<PathPoint>,
) -> Result<Option<f64>, StaticsError> {
    let dir = if edge >= start.centre { 1.0 } else { -1.0 };
    let mut p = start.clone();
    // Each target is the next multiple of PATH_STEP; each point found moves at least MIN_STEP / 2
    // toward it (`next_point` halves down to MIN_STEP), so a target takes at most 128 points; the
    // bound below is looser.
    let targets = libm::floor((edge - start.centre).abs() / PATH_STEP) as usize;
    for m in 1..=targets {
        let target = start.centre + dir * m as f64 * PATH_STEP;
        for _ in 0..7 * (PATH_STEP / MIN_STEP) as usize {
            if p.centre == target {
                break;
            }
            match next_point(model, &p, target, options)? {
                Some(q) => {
                    points.push(q.clone());
                    p = q;
                }
                None => return Ok(Some(p.centre)),
            }
        }
        if p.centre != target {
            return Ok(Some(p.centre));
        }
    }
    Ok(None)
}

/// The path point at `start` (a multiple of [`PATH_STEP`]) from the reflected kink there, ends
/// held; `None` where Newton's method finds none there or the antikink is lost.
fn origin<M: ChainModel + ?Sized>(
    model: &M,
    start: f64,
    options: &AntikinkOptions,
) -> Result<Option<PathPoint>, StaticsError> {
    let mut guess = reflected_kink(model, start)?;
    let tb = model.theta_bar();
    let len = guess.len();
    (guess[0], guess[len - 1]) = (-tb, tb);
    match at_centre(model, &guess, start, options) {
        Ok(p) => Ok(Some(p)),
        Err(StaticsError::NoConvergence { .. } | StaticsError::DefectLost { .. }) => Ok(None),
        Err(e) => Err(e),
    }
}

/// The path from `from` toward `to`, in order of centre (`from` included); empty if no path point
/// is at `from`.
fn stretch<M: ChainModel + ?Sized>(
    model: &M,
    from: f64,
    to: f64,
    options: &AntikinkOptions,
) -> Result<Vec<PathPoint>, StaticsError> {
    let Some(start) = origin(model, from, options)? else {
        return Ok(Vec::new());
    };
    let mut points = Vec::new();
    walk(model, &start, to, options, &mut points)?;
    points.insert(0, start);
    if to < from {
        points.reverse();
    }
    Ok(points)
}

/// The path on `[lo, hi]` (inside `[1, n - 2]`; its ends rounded inward to multiples of
/// [`PATH_STEP`]): walked from the multiple farthest from every spring in `impurities` (ties: the
/// one nearer the middle of the window) to both edges; where a walk ends short of an edge, walked
/// again from that edge back toward it. Then its free equilibria (module doc).
///
/// # Errors
/// A window outside `[1, n - 2]` or narrower than [`PATH_STEP`] ([`StaticsError::InvalidValue`]);
/// the errors of [`reflected_kink`] and [`at_centre`] other than a lost antikink or Newton's
/// method not converging (the path has ended there), of the refinement and of Newton's method at
/// an equilibrium.
pub fn scan_path<M: ChainModel + ?Sized>(
    model: &M,
    lo: f64,
    hi: f64,
    impurities: &[usize],
    options: &AntikinkOptions,
) -> Result<PathScan, StaticsError> {
    let n = model.rotor_count() as f64;
    let (first, last) = (libm::ceil(lo / PATH_STEP) as i64, libm::floor(hi / PATH_STEP) as i64);
    if !(lo >= 1.0 && hi <= n - 2.0 && first <= last) {
        return Err(StaticsError::InvalidValue {
            what: "the window of the antikink's path scan (its lower end)",
            value: lo,
            expected: "lo <= hi inside [1, n - 2] (between the held end rotors), at least PATH_STEP apart",
        });
    }
    let (lo, hi) = (first as f64 * PATH_STEP, last as f64 * PATH_STEP);
    let middle = 0.5 * (lo + hi);
    let clearance =
        |c: f64| impurities.iter().map(|&p| (c - (p as f64 + 0.5)).abs()).fold(f64::INFINITY, f64::min);
    let start = (first..=last).map(|m| m as f64 * PATH_STEP).fold(lo, |b, c| {
        if clearance(b) > clearance(c)
            || (clearance(b) == clearance(c) && (b - middle).abs() <= (c - middle).abs())
        {
            b
        } else {
            c
        }
    });
    let mut left = stretch(model, start, lo, options)?;
    let mut right = stretch(model, start, hi, options)?;
    right.drain(..right.len().min(1));
    left.append(&mut right);
    let mut segments = Vec::new();
    let (reached_lo, reached_hi) =
        (left.first().map_or(start, |p| p.centre), left.last().map_or(start, |p| p.centre));
    if reached_lo > lo {
        segments.push(stretch(model, lo, reached_lo, options)?);
    }
    segments.push(left);
    if reached_hi < hi {
        segments.push(stretch(model, hi, reached_hi, options)?);
    }
    // Where a walk from an edge met the middle stretch, the two are one path: keep both (the
    // meeting point twice is harmless: no zero of the slope between equal points).
    segments.retain(|s| !s.is_empty());
    let mut equilibria = Vec::new();
    for segment in &segments {
        for w in segment.windows(2) {
            let (a, b) = (&w[0], &w[1]);
            let zero = a.slope == 0.0 || (a.slope < 0.0) != (b.slope < 0.0);
            if !zero || b.slope == 0.0 {
                continue;
            }
            let bottom =
                if a.slope == 0.0 { a.clone() } else { refine(model, a.clone(), b.clone(), options)? };
            equilibria.push(super::antikink::polished_on_path(model, bottom, options)?);
        }
    }
    equilibria.sort_by(|a, b| a.centre.total_cmp(&b.centre));
    Ok(PathScan { segments, equilibria })
}
