//! Scattering of a kink or an antikink on a stiffness impurity (paper Sec. VI, Figs.
//! `fig:scheme-scattering`, `fig:k-scatter`, `fig:ak-scatter`, `fig:phasediagram`).
//!
//! The impurity is spring `p` (the model carries its stiffness `k_i`); its centre is at
//! `x_imp = p + 1/2`. A defect launched from one side ([`super::launch`]) is tracked
//! ([`super::track`]) and the run stops as soon as the outcome is decided.
//!
//! **Identity.** Walls are followed from output to output by continuity (nearest wall of the same
//! charge within `max_jump` sites). A wall that appears within `edge_margin + 1` rotors of a free
//! end was born there: phonons radiated by the launch reach the free ends at the speed of sound and can
//! push an end along its zero-energy mechanism, so a kink walks in from the end. Such walls, and
//! every wall within `edge_margin` of an end, are ignored; only the incoming wall and walls born
//! elsewhere (at the impurity) decide the outcome.
//!
//! **Rules.** With `reach` the impurity's range (default 4 sites):
//! - **transmitted**: one wall, of the incoming charge, farther than `reach` on the far side;
//! - **reflected**: after having come within `reach`, one wall of the incoming charge farther than
//!   `reach` back on the incoming side;
//! - **split** (the kink's outcome II): a kink on each side beyond `reach` and an antikink within
//!   `reach` of the impurity;
//! - **trapped**: a single wall of the incoming charge within `reach` for three times the time it
//!   would take to cross the impurity's range (`2 reach`) at its launch speed (measured over the
//!   first 0.1 time units; at least `trap_time`), or at the end of the run. The clock restarts
//!   whenever the pattern is broken by more than one wall or by a wall leaving the range.
//!
//! A pattern must hold for `persistence` (default 0.3 time units) before it decides the outcome,
//! so transient wall pairs made by phonon radiation do not count (trapping has its own, longer
//! clock and decides as soon as it runs out). A run that ends undecided says
//! so ([`Outcome::Undecided`]).

use super::DynamicsError;
use super::launch::{Direction, launch};
use super::run::{Run, RunOptions, propagate};
use super::track::Snapshot;
use crate::model::ChainModel;
use crate::statics::walls::Charge;

/// The outcome of one scattering event.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Outcome {
    Transmitted,
    Reflected,
    Trapped,
    /// A kink split into a reflected kink, a trapped antikink and a transmitted kink.
    Split,
    /// Nothing decided before `t_max`.
    Undecided,
}

impl Outcome {
    /// Every outcome, in the order of the paper's regimes, undecided last.
    pub const ALL: [Outcome; 5] =
        [Outcome::Transmitted, Outcome::Reflected, Outcome::Trapped, Outcome::Split, Outcome::Undecided];

    /// Lower-case name, for files and tables.
    pub fn name(self) -> &'static str {
        match self {
            Outcome::Transmitted => "transmitted",
            Outcome::Reflected => "reflected",
            Outcome::Trapped => "trapped",
            Outcome::Split => "split",
            Outcome::Undecided => "undecided",
        }
    }
}

impl core::fmt::Display for Outcome {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not one of [`Outcome::ALL`]'s.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown outcome `{0}`: expected transmitted, reflected, trapped, split or undecided")]
pub struct UnknownOutcome(pub alloc::string::String);

impl core::str::FromStr for Outcome {
    type Err = UnknownOutcome;

    fn from_str(name: &str) -> Result<Self, UnknownOutcome> {
        Outcome::ALL.into_iter().find(|o| o.name() == name).ok_or_else(|| UnknownOutcome(name.into()))
    }
}

/// One scattering experiment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScatterSetup {
    pub charge: Charge,
    /// Launch speed amplitude (Appendix B).
    pub v0: f64,
    /// The impurity spring `p`.
    pub impurity: usize,
    /// Where the defect starts (rotor index, fractional allowed).
    pub start: f64,
    pub direction: Direction,
    /// The impurity's range, in sites. Default 4.
    pub reach: f64,
    /// Walls this close to a free end are ignored. Default 3.
    pub edge_margin: f64,
    /// How long a pattern must hold to decide. Default 0.3.
    pub persistence: f64,
    /// The shortest time a wall must stay at the impurity to count as trapped (the rule scales it
    /// with the measured incoming speed). Default 0.5.
    pub trap_time: f64,
    /// The farthest a wall may move between two outputs and still be the same wall. Default 3.
    pub max_jump: f64,
    pub run: RunOptions,
}

impl ScatterSetup {
    /// The paper's experiment (Sec. VI): the defect starts 15 sites from the impurity on the
    /// right and moves left.
    pub fn from_the_right(charge: Charge, v0: f64, impurity: usize) -> Self {
        Self {
            charge,
            v0,
            impurity,
            start: impurity as f64 + 0.5 + 15.0,
            direction: Direction::Left,
            reach: 4.0,
            edge_margin: 3.0,
            persistence: 0.3,
            trap_time: 0.5,
            max_jump: 3.0,
            run: RunOptions::default(),
        }
    }
}

/// The result of [`scatter`].
#[derive(Clone, Debug, PartialEq)]
pub struct Scattering {
    pub outcome: Outcome,
    /// When the outcome was decided (the run's end time if undecided).
    pub decided_at: f64,
    pub run: Run,
}

/// A wall followed through the run.
#[derive(Clone, Copy, Debug)]
struct Followed {
    position: f64,
    charge: Charge,
    /// Born within `edge_margin` of a free end: ignored by the rules.
    from_end: bool,
}

/// Matches the interior walls of a snapshot to the walls followed so far (nearest of the same
/// charge within `max_jump`); unmatched walls are new, born at an end or inside.
fn follow(
    previous: &[Followed],
    s: &Snapshot,
    n: usize,
    edge_margin: f64,
    max_jump: f64,
) -> alloc::vec::Vec<Followed> {
    let mut taken = alloc::vec![false; previous.len()];
    let last = (n - 1) as f64;
    s.walls
        .iter()
        .zip(&s.at_boundary)
        .filter(|(_, b)| !**b)
        .map(|(w, _)| {
            let best = previous
                .iter()
                .enumerate()
                .filter(|(k, f)| {
                    !taken[*k] && f.charge == w.charge && (f.position - w.position).abs() <= max_jump
                })
                .min_by(|a, b| {
                    (a.1.position - w.position).abs().total_cmp(&(b.1.position - w.position).abs())
                });
            match best {
                Some((k, f)) => {
                    taken[k] = true;
                    Followed { position: w.position, charge: w.charge, from_end: f.from_end }
                }
                None => {
                    let at_end = w.position <= edge_margin + 1.0 || w.position >= last - edge_margin - 1.0;
                    Followed { position: w.position, charge: w.charge, from_end: at_end }
                }
            }
        })
        .collect()
}

/// What the followed walls say, before persistence.
fn classify(
    walls: &[Followed],
    time: f64,
    setup: &ScatterSetup,
    n: usize,
    visited: bool,
    near_since: &mut Option<f64>,
    trap_time: f64,
) -> Outcome {
    let x_imp = setup.impurity as f64 + 0.5;
    let incoming_side = if setup.start > x_imp { 1.0 } else { -1.0 };
    let inside = |x: f64| x > setup.edge_margin && x < (n - 1) as f64 - setup.edge_margin;
    let walls: alloc::vec::Vec<(f64, Charge)> = walls
        .iter()
        .filter(|w| !w.from_end && inside(w.position))
        .map(|w| (w.position - x_imp, w.charge))
        .collect();
    let near = |d: f64| d.abs() <= setup.reach;
    let beyond_in = |d: f64| d * incoming_side > setup.reach;
    let beyond_out = |d: f64| -d * incoming_side > setup.reach;
    let q = setup.charge;
    if q == Charge::Kink && walls.len() == 3 {
        let kinks_out = walls.iter().filter(|(d, c)| *c == Charge::Kink && beyond_out(*d)).count();
        let kinks_in = walls.iter().filter(|(d, c)| *c == Charge::Kink && beyond_in(*d)).count();
        let trapped = walls.iter().filter(|(d, c)| *c == Charge::Antikink && near(*d)).count();
        if (kinks_out, kinks_in, trapped) == (1, 1, 1) {
            return Outcome::Split;
        }
    }
    if let [(d, c)] = walls[..] {
        if c != q {
            return Outcome::Undecided;
        }
        if near(d) {
            let since = *near_since.get_or_insert(time);
            if time - since >= trap_time {
                return Outcome::Trapped;
            }
            return Outcome::Undecided;
        }
        *near_since = None;
        if beyond_out(d) {
            return Outcome::Transmitted;
        }
        if beyond_in(d) && visited {
            return Outcome::Reflected;
        }
    } else {
        *near_since = None;
    }
    Outcome::Undecided
}

/// Launches the defect of `setup` towards the impurity and runs until the outcome is decided.
pub fn scatter<M: ChainModel + ?Sized>(model: &M, setup: &ScatterSetup) -> Result<Scattering, DynamicsError> {
    let n = model.rotor_count();
    let launched = launch(model, setup.charge, setup.start, setup.v0, setup.direction)?;
    let x_imp = setup.impurity as f64 + 0.5;
    let mut visited = false;
    let mut near_since = None;
    let mut candidate: Option<(Outcome, f64)> = None;
    let mut decided: Option<(Outcome, f64)> = None;
    let mut followed: alloc::vec::Vec<Followed> = alloc::vec::Vec::new();
    let mut first = true;
    let mut speed: Option<f64> = None;
    let mut launch_at = setup.start;
    let mut stop = |s: &Snapshot| -> bool {
        followed = follow(&followed, s, n, setup.edge_margin, setup.max_jump);
        if first {
            // Whatever is there at launch is the incoming defect, wherever it is.
            followed.iter_mut().for_each(|w| w.from_end = false);
            first = false;
        }
        if followed.iter().any(|w| !w.from_end && (w.position - x_imp).abs() <= setup.reach) {
            visited = true;
        }
        // The incoming speed, measured over the first output intervals.
        if speed.is_none()
            && let Some(w) = followed.iter().find(|w| !w.from_end && w.charge == setup.charge)
        {
            if s.time == 0.0 {
                launch_at = w.position;
            } else if s.time >= 0.1 {
                speed = Some((w.position - launch_at).abs() / s.time);
            }
        }
        let trap_time = match speed {
            Some(v) if v > 0.0 => (3.0 * 2.0 * setup.reach / v).max(setup.trap_time),
            _ => f64::INFINITY,
        };
        let now = classify(&followed, s.time, setup, n, visited, &mut near_since, trap_time);
        match (now, candidate) {
            (Outcome::Undecided, _) => candidate = None,
            (o, Some((c, since))) if o == c => {
                if s.time - since >= setup.persistence || o == Outcome::Trapped {
                    decided = Some((o, s.time));
                    return true;
                }
            }
            (o, _) => candidate = Some((o, s.time)),
        }
        false
    };
    let run = propagate(model, launched.state, &setup.run, &mut stop)?;
    let end = run.final_state.time;
    let (outcome, decided_at) = match decided {
        Some(d) => d,
        // At t_max a wall still sitting at the impurity is trapped.
        None if near_since.is_some() => (Outcome::Trapped, end),
        None => (Outcome::Undecided, end),
    };
    Ok(Scattering { outcome, decided_at, run })
}
