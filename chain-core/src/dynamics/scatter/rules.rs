//! The outcome rules of a scattering run (docs/dynamics.md §5 states them with their numbers).
//!
//! At each output the followed walls ([`super::follow`]) are reduced to the *defect's walls*:
//! the incoming wall and the walls born inside the chain that have lived at least
//! [`ScatterSetup::pair_age`] (a pair that a phonon burst makes and unmakes within that time is
//! no product of the scattering). Walls born at a free end are not the defect's; when one of them
//! annihilates a wall of the defect, that is recorded. The defect's walls form a *pattern*;
//! an outcome is decided when its pattern has held for its stated time, and confirmed when it
//! still holds [`ScatterSetup::confirm`] later. Events after the confirmation (an end-born wall
//! annihilating a trapped antikink, a trapped wall escaping) are recorded as a later event and
//! never change the outcome.

use alloc::vec::Vec;

use super::follow::{Followed, Follower, Origin};
use super::{LaterEvent, Outcome, ScatterSetup};
use crate::dynamics::track::Snapshot;
use crate::statics::walls::Charge;

/// What the defect's walls show at one output.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Pattern {
    /// One wall of the incoming charge, not yet at the impurity.
    Approaching,
    /// One wall within `reach` of the impurity.
    Near,
    /// One wall between `reach` and `clear` of the impurity, after it met the impurity: in the
    /// impurity's basin, on a wide orbit or on its way out.
    Around,
    /// One wall beyond `clear` on the far side; its distance from the impurity.
    Beyond { distance: f64, at_end: bool },
    /// One wall back beyond `clear` on the incoming side after a visit.
    Back { distance: f64, at_end: bool },
    /// A kink beyond `reach` on each side and an antikink within `reach` (the kink's split).
    Split,
    /// More than one wall before any reached the impurity: the defect broke up by itself.
    Breaking,
    /// More than one wall after the visit, other than a split: pairs made at the impurity.
    Pairs,
    /// No wall of the defect left, one having been annihilated by a wall from a free end.
    Annihilated,
    /// Anything else (a lone wall of the other charge, no wall without an annihilation).
    Unclear,
}

impl Pattern {
    /// The outcome this pattern points to, if any.
    fn outcome(self) -> Option<Outcome> {
        match self {
            Pattern::Near => Some(Outcome::Trapped),
            Pattern::Beyond { .. } => Some(Outcome::Transmitted),
            Pattern::Back { .. } => Some(Outcome::Reflected),
            Pattern::Split => Some(Outcome::Split),
            Pattern::Breaking => Some(Outcome::Disintegrated),
            Pattern::Pairs => Some(Outcome::PairCreation),
            Pattern::Annihilated => Some(Outcome::Annihilated),
            Pattern::Around | Pattern::Approaching | Pattern::Unclear => None,
        }
    }
}

/// The classifier's verdict so far.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Verdict {
    pub outcome: Outcome,
    pub decided_at: f64,
    /// When the confirmation window closed (`None`: still open, or nothing decided).
    pub confirmed_at: Option<f64>,
    pub later: Option<(LaterEvent, f64)>,
}

/// Reads the snapshots of a scattering run and decides its outcome.
pub(super) struct Classifier {
    setup: ScatterSetup,
    x_imp: f64,
    /// +1 if the defect comes from the right of the impurity, -1 from the left.
    side: f64,
    last_rotor: f64,
    follower: Follower,
    /// Whether the defect has met the impurity: been within `reach`, or turned back on its way.
    visited: bool,
    /// When the single wall entered the impurity's range (the trap clock), how fast it came
    /// in, and how often it has turned round since.
    entered: Option<f64>,
    entry_speed: Option<f64>,
    turns: usize,
    /// The direction of the wall's motion (+1 away from rotor 0) and its farthest point that way.
    heading: f64,
    extreme: f64,
    /// Recent `(t, x)` of the single wall while outside the impurity's range, for its entry speed.
    approach: Vec<(f64, f64)>,
    /// A pattern being timed: its outcome, since when, and the wall's distance then.
    candidate: Option<(Outcome, f64, f64)>,
    /// When a wall of the defect was annihilated by a wall from a free end.
    lost_to_end: Option<f64>,
    /// When a wall of the defect last left the chain through a free end.
    exited: Option<f64>,
    /// The walls of the defect that left through a free end: they count as being at that end.
    departed: Vec<(f64, Charge)>,
    /// Since when the defect, not yet at the impurity, has had three walls or more.
    breaking: Option<f64>,
    /// When a wall born at a free end first came within `reach` of the impurity: from then on
    /// the run shows what the finite chain's ends sent back as well as what the impurity did.
    pub end_wall_at_impurity: Option<f64>,
    pub verdict: Option<Verdict>,
}

impl Classifier {
    pub fn new(setup: &ScatterSetup, n: usize) -> Self {
        let x_imp = setup.impurity as f64 + 0.5;
        Self {
            setup: *setup,
            x_imp,
            side: if setup.start > x_imp { 1.0 } else { -1.0 },
            last_rotor: n.saturating_sub(1) as f64,
            follower: Follower::new(n, setup.edge_margin + 1.0, setup.max_jump, setup.grace),
            visited: false,
            entered: None,
            entry_speed: None,
            turns: 0,
            heading: if setup.start > x_imp { -1.0 } else { 1.0 },
            extreme: setup.start,
            approach: Vec::new(),
            candidate: None,
            lost_to_end: None,
            exited: None,
            departed: Vec::new(),
            breaking: None,
            end_wall_at_impurity: None,
            verdict: None,
        }
    }

    /// Whether `x` lies within `edge_margin` of a free end.
    fn at_end(&self, x: f64) -> bool {
        x <= self.setup.edge_margin || x >= self.last_rotor - self.setup.edge_margin
    }

    /// The defect's walls at `time`, reduced to their net charges: the walls not born at an end
    /// (those that left through an end counted at that end, those unseen for less than the grace
    /// time where they were last seen), grouped where they lie within
    /// [`ScatterSetup::cluster_gap`] of each other, each group
    /// `(signed distance from the impurity, charge)` at its mean position, groups of net charge
    /// 0 (a bound kink-antikink pair) left out. The *young* walls, born inside the chain or
    /// reappeared after vanishing less than [`ScatterSetup::pair_age`] ago, are left out
    /// altogether when their charges add up to 0 and they lie within
    /// [`ScatterSetup::pair_extent`]: pairs that the stretched impurity or a phonon burst makes
    /// and unmakes, not yet products of the scattering.
    fn defect(&self, time: f64) -> Vec<(f64, Charge)> {
        let s = &self.setup;
        let charge = |q: Charge| if q == Charge::Kink { 1 } else { -1 };
        let young = |w: &&Followed| self.young(w, time);
        // A ghost counts where it was last seen until its fate is known: a wall leaving through an
        // end, or hidden for an output or two in another's core, would otherwise break the
        // pattern for the grace time and restart its clock (a split decided or not by one
        // output, whichever integrator got there first).
        let live_and_ghosts = self.follower.walls.iter().chain(self.follower.ghosts());
        let defect = live_and_ghosts.filter(|w| w.origin != Origin::End);
        let (mut low, mut high, mut net) = (f64::INFINITY, f64::NEG_INFINITY, 0);
        for w in defect.clone().filter(young) {
            low = low.min(w.position);
            high = high.max(w.position);
            net += charge(w.charge);
        }
        let drop_young = net == 0 && high - low <= s.pair_extent;
        let mut walls: Vec<(f64, Charge)> =
            defect.filter(|w| !(drop_young && young(w))).map(|w| (w.position, w.charge)).collect();
        walls.extend(self.departed.iter().copied());
        walls.sort_by(|a, b| a.0.total_cmp(&b.0));
        // (sum of positions, count, net charge)
        let mut groups: Vec<(f64, usize, i32)> = Vec::new();
        let mut last = f64::NEG_INFINITY;
        for (x, q) in walls {
            match groups.last_mut() {
                Some(g) if x - last <= s.cluster_gap => {
                    g.0 += x;
                    g.1 += 1;
                    g.2 += charge(q);
                }
                _ => groups.push((x, 1, charge(q))),
            }
            last = x;
        }
        groups
            .iter()
            .filter(|g| g.2 != 0)
            .map(|g| {
                let x = g.0 / g.1 as f64;
                ((x - self.x_imp) * self.side, if g.2 > 0 { Charge::Kink } else { Charge::Antikink })
            })
            .collect()
    }

    /// Whether a wall is *young* at `time`: born inside the chain, or reappeared after vanishing,
    /// less than [`ScatterSetup::pair_age`] ago.
    fn young(&self, w: &Followed, time: f64) -> bool {
        time - w.appeared < self.setup.pair_age && (w.origin == Origin::Inside || w.appeared > w.born)
    }

    /// The pattern of the defect's walls at `time`, and the position of its single wall if it
    /// has one.
    fn pattern(&mut self, time: f64) -> (Pattern, Option<f64>) {
        let walls = self.defect(time);
        let s = &self.setup;
        let near = |d: f64| d.abs() <= s.reach;
        if walls.iter().any(|&(d, _)| near(d)) {
            self.visited = true;
        }
        let pattern = match walls[..] {
            [] if self.lost_to_end.is_some() => Pattern::Annihilated,
            [] => Pattern::Unclear,
            [(d, q)] if q == s.charge => {
                let x = self.x_imp + d * self.side;
                if near(d) {
                    Pattern::Near
                } else if d.abs() <= s.clear && self.visited {
                    Pattern::Around
                } else if d < 0.0 {
                    Pattern::Beyond { distance: -d, at_end: self.at_end(x) }
                } else if self.visited {
                    Pattern::Back { distance: d, at_end: self.at_end(x) }
                } else {
                    Pattern::Approaching
                }
            }
            [_] => Pattern::Unclear,
            _ if s.charge == Charge::Kink && walls.len() == 3 => {
                let count = |q: Charge, f: &dyn Fn(f64) -> bool| {
                    walls.iter().filter(|&&(d, c)| c == q && f(d)).count()
                };
                let split = count(Charge::Kink, &|d| d < -s.reach) == 1
                    && count(Charge::Kink, &|d| d > s.reach) == 1
                    && count(Charge::Antikink, &near) == 1;
                if split { Pattern::Split } else { Pattern::Pairs }
            }
            _ if self.visited => Pattern::Pairs,
            _ => Pattern::Breaking,
        };
        let single = match walls[..] {
            [(d, _)] => Some(self.x_imp + d * self.side),
            _ => None,
        };
        (pattern, single)
    }

    /// The time a wall must stay at the impurity to count as trapped: once it has turned round
    /// [`ScatterSetup::turns`] times there (it oscillates in the impurity's well),
    /// [`ScatterSetup::trap_time`]; otherwise `trap_crossings` times the time it would need to
    /// cross the impurity's range at the speed it came in with, if that is longer.
    fn trap_time(&self) -> f64 {
        let s = &self.setup;
        if self.turns >= s.turns {
            return s.trap_time;
        }
        match self.entry_speed {
            Some(v) if v > 0.0 => (s.trap_crossings * 2.0 * s.reach / v).max(s.trap_time),
            _ => f64::INFINITY,
        }
    }

    /// Follows the trap clock, the entry speed and the turns of the single wall.
    fn track_single(&mut self, pattern: Pattern, single: Option<f64>, time: f64) {
        let Some(x) = single else {
            self.entered = None;
            return;
        };
        // Turning points, with a hysteresis of `turn_band` sites.
        if (x - self.extreme) * self.heading > 0.0 {
            self.extreme = x;
        } else if (self.extreme - x) * self.heading >= self.setup.turn_band {
            // How far the wall went towards the impurity before this turn (negative if it never
            // did: a defect launched at rest that drifts away has met nothing).
            let advanced = (self.extreme - self.setup.start) * self.heading;
            self.heading = -self.heading;
            self.extreme = x;
            self.turns += 1;
            // Turned back before reaching the impurity's range, after coming `progress` sites
            // nearer: repelled by it (a stiff spring repels a slow antikink from farther than
            // `reach`).
            if pattern == Pattern::Approaching && self.heading == self.side && advanced >= self.setup.progress
            {
                self.visited = true;
            }
        }
        if pattern == Pattern::Around && self.entered.is_some() {
            return;
        }
        if pattern == Pattern::Near {
            if self.entered.is_none() {
                self.entered = Some(time);
                self.turns = 0;
                self.entry_speed = self
                    .approach
                    .first()
                    .and_then(|&(t0, x0)| (time > t0).then(|| (x - x0).abs() / (time - t0)));
            }
            self.approach.clear();
            return;
        }
        self.entered = None;
        self.approach.push((time, x));
        let window = self.setup.entry_window;
        if let Some(k) = self.approach.iter().position(|(t, _)| time - t <= window) {
            self.approach.drain(..k.saturating_sub(1));
        }
    }

    /// Reads one snapshot; `true` once the outcome is confirmed and the later watch is over.
    pub fn observe(&mut self, snapshot: &Snapshot) -> bool {
        let time = snapshot.time;
        for v in self.follower.update(snapshot) {
            if v.wall.origin != Origin::End && v.with_end_wall && self.lost_to_end.is_none() {
                self.lost_to_end = Some(v.wall.seen);
            }
            if v.wall.origin != Origin::End && v.through_end {
                self.exited = Some(v.wall.seen);
                let end = if v.wall.position < 0.5 * self.last_rotor { 0.0 } else { self.last_rotor };
                self.departed.push((end, v.wall.charge));
            }
        }
        if self.end_wall_at_impurity.is_none() {
            let (x_imp, reach) = (self.x_imp, self.setup.reach);
            let arrived = self
                .follower
                .walls
                .iter()
                .any(|w| w.origin == Origin::End && (w.position - x_imp).abs() <= reach);
            if arrived {
                self.end_wall_at_impurity = Some(time);
            }
        }
        let (pattern, single) = self.pattern(time);
        self.track_single(pattern, single, time);
        // Breaking up on its way: three walls or more (a pair emitted), of any age, from before
        // the impurity on, for `break_time`. Final: what the impurity does to the pieces is
        // another question.
        let walls = self.follower.walls.iter().filter(|w| w.origin != Origin::End).count();
        if self.verdict.is_none() && (!self.visited || self.breaking.is_some()) && walls >= 3 {
            let since = *self.breaking.get_or_insert(time);
            if time - since >= self.setup.break_time {
                let confirmed_at = Some(time);
                self.verdict = Some(Verdict {
                    outcome: Outcome::Disintegrated,
                    decided_at: time,
                    confirmed_at,
                    later: None,
                });
                return self.setup.watch <= 0.0;
            }
        } else {
            self.breaking = None;
        }
        match self.verdict {
            None => self.decide(pattern, time),
            Some(v) => self.confirm(v, pattern, time),
        }
    }

    /// Before a decision: time the current pattern.
    fn decide(&mut self, pattern: Pattern, time: f64) -> bool {
        let s = self.setup;
        // On a wide orbit the trap clock keeps running.
        let orbiting = pattern == Pattern::Around && self.entered.is_some();
        let Some(outcome) = pattern.outcome().or(orbiting.then_some(Outcome::Trapped)) else {
            self.candidate = None;
            return false;
        };
        let distance = match pattern {
            Pattern::Beyond { distance, .. } | Pattern::Back { distance, .. } => distance,
            _ => 0.0,
        };
        let (since, from) = match self.candidate {
            Some((o, since, from)) if o == outcome => (since, from),
            _ => {
                self.candidate = Some((outcome, time, distance));
                (time, distance)
            }
        };
        let held = time - since;
        let settled = match pattern {
            Pattern::Near | Pattern::Around => self.entered.is_some_and(|t| time - t >= self.trap_time()),
            // Moved clear and keeps going: held, and moved on by `progress` sites (or reached an
            // end); a wall that stays beyond the range without moving decides after 4 times as
            // long.
            Pattern::Beyond { distance, at_end } | Pattern::Back { distance, at_end } => {
                at_end
                    || (held >= s.persistence
                        && (distance - from >= s.progress || held >= 4.0 * s.persistence))
            }
            _ => held >= s.persistence,
        };
        if settled {
            let arrived =
                matches!(pattern, Pattern::Beyond { at_end: true, .. } | Pattern::Back { at_end: true, .. });
            let confirmed_at = (arrived || s.confirm <= 0.0).then_some(time);
            self.verdict = Some(Verdict { outcome, decided_at: time, confirmed_at, later: None });
            return confirmed_at.is_some() && s.watch <= 0.0;
        }
        false
    }

    /// After a decision: confirm it, then watch for later events.
    fn confirm(&mut self, mut v: Verdict, pattern: Pattern, time: f64) -> bool {
        let s = self.setup;
        let now = pattern.outcome();
        // What may happen to a decided outcome without unsettling it: the defect annihilated by a
        // wall from a free end, a transmitted or reflected wall gone through an end.
        let annihilated = self.lost_to_end.is_some_and(|t| t >= v.decided_at - s.grace);
        let gone = matches!(pattern, Pattern::Unclear | Pattern::Annihilated);
        // A wall unseen for less than the grace time may yet reappear, or turn out to have left
        // through an end or been annihilated: wait before judging. The defect's own ghosts
        // already hold their place in the pattern (`defect`); this also waits on an end-born
        // wall's (without it, 42 antikink points of the 40 x 40 diagram withdraw a decision and
        // decide the same label later).
        let pending = !self.follower.ghosts().is_empty();
        // A trapped wall on a wide orbit in the impurity's basin is still trapped.
        let orbiting = v.outcome == Outcome::Trapped && pattern == Pattern::Around;
        let holds = now == Some(v.outcome)
            || orbiting
            || gone
            || annihilated
            || pending
            || v.outcome == Outcome::Disintegrated;
        if v.later.is_none() && annihilated && v.outcome != Outcome::Annihilated {
            v.later = Some((LaterEvent::Annihilated, self.lost_to_end.unwrap_or(time)));
        }
        // A transmitted or reflected wall that has reached the end it was heading for, or a
        // product of the scattering that has left through an end, has shown all there is to
        // show: confirmed.
        let exited = self.exited.is_some_and(|t| t >= v.decided_at - s.grace);
        let arrived = exited
            || (matches!(pattern, Pattern::Beyond { at_end: true, .. } | Pattern::Back { at_end: true, .. })
                && now == Some(v.outcome));
        match v.confirmed_at {
            None if arrived => v.confirmed_at = Some(time),
            None if !holds => {
                // Unsettled within the confirmation window: decide afresh.
                self.verdict = None;
                self.candidate = None;
                return self.decide(pattern, time);
            }
            None if time - v.decided_at >= s.confirm => v.confirmed_at = Some(time),
            Some(_) if !holds && v.later.is_none() && v.outcome == Outcome::Trapped => {
                v.later = Some((LaterEvent::Escaped, time));
            }
            _ => {}
        }
        self.verdict = Some(v);
        v.confirmed_at.is_some_and(|t| time - t >= s.watch)
    }
}
