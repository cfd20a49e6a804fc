//! Following every domain wall of a scattering run from output to output, with where it came
//! from: the incoming defect, a free end, or the inside of the chain (pair creation at the
//! impurity, or a defect breaking up).
//!
//! Interior walls alternate in charge along the chain, move by a fraction of a site between
//! outputs, and appear and vanish in kink-antikink pairs (or one at a time through a free end).
//! At each output every wall is matched to a wall of the same charge seen before, nearest pairs
//! first, within `max_jump` sites. A wall that finds no match is new. A wall that is no longer
//! seen becomes a *ghost* for `grace` time units: two walls that overlap for an output or two
//! (an end-born kink crossing the antikink's core) reappear as the same walls, and only a wall
//! that stays unseen for `grace` has vanished.

use alloc::vec::Vec;

use crate::dynamics::track::Snapshot;
use crate::statics::walls::Charge;

/// Where a wall came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    /// Present at the launch: the incoming defect.
    Incoming,
    /// Appeared within the end zone of a free end.
    End,
    /// Appeared elsewhere: a pair created at the impurity or by the defect breaking up.
    Inside,
}

/// A wall followed through the run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Followed {
    /// Its latest position, in rotor indices.
    pub position: f64,
    /// Kink or antikink.
    pub charge: Charge,
    /// Where it came from.
    pub origin: Origin,
    /// When it first appeared.
    pub born: f64,
    /// When it last appeared: `born`, or when it reappeared after vanishing for less than the
    /// grace time (the two walls of a pair process that re-forms).
    pub appeared: f64,
    /// When it was last seen.
    pub seen: f64,
}

/// A wall that stayed unseen for the grace time, and where it was last.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vanished {
    /// The wall, as last seen.
    pub wall: Followed,
    /// Whether a wall from a free end vanished within `max_jump` sites and the grace time of
    /// it: the two annihilated.
    pub with_end_wall: bool,
    /// Whether it vanished within the end zone with no wall of the other charge vanishing near
    /// it: it left the chain through the end.
    pub through_end: bool,
}

/// The walls of a run, with their origins.
#[derive(Clone, Debug)]
pub struct Follower {
    /// The walls followed now.
    pub walls: Vec<Followed>,
    ghosts: Vec<Followed>,
    /// Recently vanished walls, kept to pair annihilations.
    vanished: Vec<Followed>,
    /// Buffers [`Follower::update`] reuses from output to output: it runs every few steps of a
    /// scattering run, and fresh vectors each time cost ~6 % of a phase diagram's wall time
    /// (docs/benchmarks.md, sixth round).
    scratch: Scratch,
    last_rotor: f64,
    end_zone: f64,
    max_jump: f64,
    grace: f64,
    started: bool,
}

/// The working vectors of one [`Follower::update`], kept between calls (contents meaningless
/// between them).
#[derive(Clone, Debug, Default)]
struct Scratch {
    current: Vec<(f64, Charge)>,
    previous: Vec<Followed>,
    pairs: Vec<(usize, usize, f64)>,
    matched_current: Vec<Option<usize>>,
    matched_previous: Vec<bool>,
    walls: Vec<Followed>,
    ghosts: Vec<Followed>,
    expired: Vec<Followed>,
}

impl Follower {
    /// `n` rotors; new walls within `end_zone` sites of rotor 0 or `n - 1` are end-born.
    pub fn new(n: usize, end_zone: f64, max_jump: f64, grace: f64) -> Self {
        Self {
            walls: Vec::new(),
            ghosts: Vec::new(),
            vanished: Vec::new(),
            scratch: Scratch::default(),
            last_rotor: n.saturating_sub(1) as f64,
            end_zone,
            max_jump,
            grace,
            started: false,
        }
    }

    /// The walls unseen for less than the grace time, as last seen: each may reappear, or turn
    /// out to have left through an end or been annihilated.
    pub fn ghosts(&self) -> &[Followed] {
        &self.ghosts
    }

    /// Matches the interior walls of `s` to the walls followed so far; returns the walls that
    /// vanished (stayed unseen for the grace time) at this output.
    pub fn update(&mut self, s: &Snapshot) -> Vec<Vanished> {
        let time = s.time;
        let Scratch { current, previous, pairs, matched_current, matched_previous, walls, ghosts, expired } =
            &mut self.scratch;
        current.clear();
        current.extend(
            s.walls.iter().zip(&s.at_boundary).filter(|(_, b)| !**b).map(|(w, _)| (w.position, w.charge)),
        );
        if !self.started {
            // Whatever is there at launch is the incoming defect.
            self.started = true;
            self.walls.clear();
            self.walls.extend(current.iter().map(|&(position, charge)| Followed {
                position,
                charge,
                origin: Origin::Incoming,
                born: time,
                appeared: time,
                seen: time,
            }));
            return Vec::new();
        }
        // Candidates: followed walls first, then ghosts, each (current, previous, distance).
        previous.clear();
        previous.extend(self.walls.iter().chain(&self.ghosts).copied());
        pairs.clear();
        for (c, &(x, q)) in current.iter().enumerate() {
            for (p, w) in previous.iter().enumerate() {
                let d = (w.position - x).abs();
                if w.charge == q && d <= self.max_jump {
                    pairs.push((c, p, d));
                }
            }
        }
        // Nearest first; a live wall before a ghost at the same distance.
        pairs.sort_by(|a, b| a.2.total_cmp(&b.2).then(a.1.cmp(&b.1)));
        matched_current.clear();
        matched_current.resize(current.len(), None);
        matched_previous.clear();
        matched_previous.resize(previous.len(), false);
        for &(c, p, _) in pairs.iter() {
            if matched_current[c].is_none() && !matched_previous[p] {
                matched_current[c] = Some(p);
                matched_previous[p] = true;
            }
        }
        walls.clear();
        let live = self.walls.len();
        for (c, &(position, charge)) in current.iter().enumerate() {
            let wall = match matched_current[c] {
                Some(p) if p < live => Followed { position, seen: time, ..previous[p] },
                Some(p) => Followed { position, seen: time, appeared: time, ..previous[p] },
                None => {
                    let at_end = position <= self.end_zone || position >= self.last_rotor - self.end_zone;
                    let origin = if at_end { Origin::End } else { Origin::Inside };
                    Followed { position, charge, origin, born: time, appeared: time, seen: time }
                }
            };
            walls.push(wall);
        }
        ghosts.clear();
        expired.clear();
        for (&w, &matched) in previous.iter().zip(matched_previous.iter()) {
            if matched {
                continue;
            }
            if time - w.seen < self.grace {
                ghosts.push(w);
            } else {
                expired.push(w);
            }
        }
        core::mem::swap(&mut self.walls, walls);
        core::mem::swap(&mut self.ghosts, ghosts);
        // A wall that vanished near a wall from an end within the grace time was annihilated by it.
        self.vanished.retain(|w| time - w.seen <= 2.0 * self.grace);
        self.vanished.extend(expired.iter().copied());
        let vanished = &self.vanished;
        let (jump, grace, zone, last) = (self.max_jump, self.grace, self.end_zone, self.last_rotor);
        expired
            .iter()
            .map(|&wall| {
                let partner = |o: &&Followed| {
                    o.charge != wall.charge
                        && (o.position - wall.position).abs() <= jump
                        && (o.seen - wall.seen).abs() <= grace
                };
                let at_end = wall.position <= zone || wall.position >= last - zone;
                Vanished {
                    wall,
                    with_end_wall: vanished.iter().filter(partner).any(|o| o.origin == Origin::End),
                    through_end: at_end && !vanished.iter().any(|o| partner(&o)),
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::statics::walls::Wall;

    fn snapshot(time: f64, walls: &[(f64, Charge)]) -> Snapshot {
        Snapshot {
            time,
            walls: walls.iter().map(|&(position, charge)| Wall { position, charge }).collect(),
            at_boundary: alloc::vec![false; walls.len()],
        }
    }

    #[test]
    fn an_end_wall_that_annihilates_the_incoming_one_is_paired_with_it() {
        use Charge::{Antikink as A, Kink as K};
        let mut f = Follower::new(60, 4.0, 3.0, 0.05);
        f.update(&snapshot(0.0, &[(44.0, A)]));
        f.update(&snapshot(0.01, &[(1.0, K), (43.0, A)]));
        assert_eq!(f.walls[0].origin, Origin::End);
        assert_eq!(f.walls[1].origin, Origin::Incoming);
        // They approach each other a site per output.
        let mut time = 0.01;
        for k in 1..=20 {
            time += 0.01;
            f.update(&snapshot(time, &[(1.0 + k as f64, K), (43.0 - k as f64, A)]));
        }
        // Overlapping for one output: ghosts, and the same walls when they reappear.
        assert!(f.update(&snapshot(time + 0.01, &[])).is_empty());
        f.update(&snapshot(time + 0.02, &[(21.5, K), (22.0, A)]));
        assert_eq!(f.walls.iter().map(|w| w.origin).collect::<Vec<_>>(), [Origin::End, Origin::Incoming]);
        let mut gone = Vec::new();
        for k in 3..12 {
            gone.extend(f.update(&snapshot(time + 0.01 * k as f64, &[])));
        }
        assert_eq!(gone.len(), 2);
        let incoming = gone.iter().find(|v| v.wall.origin == Origin::Incoming).unwrap();
        assert!(incoming.with_end_wall);
    }

    #[test]
    fn a_pair_born_inside_is_inside() {
        use Charge::{Antikink as A, Kink as K};
        let mut f = Follower::new(60, 4.0, 3.0, 0.05);
        f.update(&snapshot(0.0, &[(33.0, K)]));
        f.update(&snapshot(0.01, &[(31.0, K), (31.6, A), (32.2, K)]));
        let origins: Vec<Origin> = f.walls.iter().map(|w| w.origin).collect();
        // The incoming kink is the one nearest to where it was.
        assert_eq!(origins, [Origin::Inside, Origin::Inside, Origin::Incoming]);
    }
}
