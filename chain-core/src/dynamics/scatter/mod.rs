//! Scattering of a kink or an antikink on a stiffness impurity (paper Sec. VI, Figs.
//! `fig:scheme-scattering`, `fig:k-scatter`, `fig:ak-scatter`, `fig:phasediagram`).
//!
//! The impurity is spring `p` (the model carries its stiffness `k_i`); its centre is at
//! `x_imp = p + 1/2`. A defect launched from one side ([`super::launch`]) is tracked
//! ([`super::track`]), every wall is followed with its origin (`follow`), and the run stops once
//! the outcome is decided, confirmed, and watched for as long as asked (`rules`).
//!
//! **What an outcome means.** It answers the paper's question: what did the impurity do to the
//! incoming defect? [`Outcome::Transmitted`], [`Outcome::Reflected`], [`Outcome::Trapped`] and,
//! for a kink, [`Outcome::Split`] are the paper's regimes. Free ends add one more: phonons
//! radiated in the collision flip an end of an antikink's domain, and a kink walks in from it
//! (docs/dynamics.md §5). If such a wall annihilates the defect *after* its outcome was settled,
//! the outcome stands and the annihilation is recorded as [`Scattering::later`]; only if it comes
//! before anything was settled is the outcome [`Outcome::Annihilated`]. A defect that breaks up
//! before reaching the impurity is [`Outcome::Disintegrated`], pairs left at the impurity are
//! [`Outcome::PairCreation`], and [`Outcome::Undecided`] means only that the run ended before
//! anything was settled.

pub mod budget;
mod follow;
mod rules;

use super::DynamicsError;
use super::launch::{Direction, launch};
use super::run::{Run, RunOptions, propagate};
use super::track::Snapshot;
use crate::model::ChainModel;
use crate::statics::walls::Charge;
use crate::validate::{Fields, Validate};

pub use budget::{
    BudgetError, Budgeted, CrossChecked, EnergyBudget, Unresolved, cross_checked, scatter_within_budget,
};
pub use follow::{Followed, Follower, Origin, Vanished};

/// What the impurity did to the incoming defect.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Outcome {
    /// One wall, of the incoming charge, moved clear of the impurity on the far side and kept
    /// going.
    Transmitted,
    /// One wall, of the incoming charge, came back from the impurity and kept going.
    Reflected,
    /// One wall, of the incoming charge, stayed at the impurity.
    Trapped,
    /// A kink split into a transmitted kink, an antikink at the impurity and a reflected kink.
    Split,
    /// Before anything was settled, the defect was annihilated by a wall that entered from a
    /// free end.
    Annihilated,
    /// The defect broke up into several walls before reaching the impurity.
    Disintegrated,
    /// Several walls (not a kink's split) left after the collision: pairs made at the impurity.
    PairCreation,
    /// The run ended before anything was settled.
    Undecided,
}

impl Outcome {
    /// Every outcome: the paper's regimes, the others, undecided last.
    pub const ALL: [Outcome; 8] = [
        Outcome::Transmitted,
        Outcome::Reflected,
        Outcome::Trapped,
        Outcome::Split,
        Outcome::Annihilated,
        Outcome::Disintegrated,
        Outcome::PairCreation,
        Outcome::Undecided,
    ];

    /// Lower-case name, for files and tables.
    pub fn name(self) -> &'static str {
        match self {
            Outcome::Transmitted => "transmitted",
            Outcome::Reflected => "reflected",
            Outcome::Trapped => "trapped",
            Outcome::Split => "split",
            Outcome::Annihilated => "annihilated",
            Outcome::Disintegrated => "disintegrated",
            Outcome::PairCreation => "pair-creation",
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
#[error(
    "unknown outcome `{0}`: expected transmitted, reflected, trapped, split, annihilated, disintegrated, \
     pair-creation or undecided"
)]
pub struct UnknownOutcome(pub alloc::string::String);

impl core::str::FromStr for Outcome {
    type Err = UnknownOutcome;

    fn from_str(name: &str) -> Result<Self, UnknownOutcome> {
        Outcome::ALL.into_iter().find(|o| o.name() == name).ok_or_else(|| UnknownOutcome(name.into()))
    }
}

/// Something that happened to the defect after its outcome was settled.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LaterEvent {
    /// A wall that entered from a free end annihilated it.
    Annihilated,
    /// The trapped wall left the impurity.
    Escaped,
}

impl LaterEvent {
    /// Lower-case name, for files and tables.
    pub fn name(self) -> &'static str {
        match self {
            LaterEvent::Annihilated => "annihilated",
            LaterEvent::Escaped => "escaped",
        }
    }
}

impl core::str::FromStr for LaterEvent {
    type Err = UnknownOutcome;

    fn from_str(name: &str) -> Result<Self, UnknownOutcome> {
        [LaterEvent::Annihilated, LaterEvent::Escaped]
            .into_iter()
            .find(|o| o.name() == name)
            .ok_or_else(|| UnknownOutcome(name.into()))
    }
}

/// The paper's time unit carried to a chain of stiffness `k` (in `M / t^2`) and tip mass `mass`:
/// `sqrt(1e4 mass / k)`, so 1 for the paper's `k = 1e4`, `M = 1` (Sec. VI). Times of a chain
/// scale as `sqrt(M / k)` (its equations of motion have no other time), so the paper's windows
/// and output interval, multiplied by this ([`ScatterSetup::in_time_unit`]), give the same
/// outcome for a chain whose `k` and `M` differ from the paper's but whose `sqrt(M / k)`-scaled
/// motion is the same: `v0` in length per `t` scaled by `1 / unit` then finds the same regime.
pub fn paper_time_unit(k: f64, mass: f64) -> f64 {
    crate::math::sqrt(1.0e4 * mass / k)
}

/// One scattering experiment and the numbers of its rules (docs/dynamics.md §5 says why each
/// default was chosen). Times in the unit `t` of Appendix B, distances in sites. The defaults of
/// [`ScatterSetup::from_the_right`] are the paper's, for `k = 1e4 M / t^2`; for another chain,
/// [`ScatterSetup::in_time_unit`] with [`paper_time_unit`] carries them over (Python's
/// `Chain.scatter` and chain-sweep's diagrams do).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScatterSetup {
    /// The incoming defect: kink or antikink.
    pub charge: Charge,
    /// Launch speed amplitude (Appendix B).
    pub v0: f64,
    /// The impurity spring `p`, centred at `p + 0.5`; its range (`reach`) must lie clear of the
    /// end zones (`edge_margin`), so that a transmitted wall has room on the far side.
    pub impurity: usize,
    /// Where the defect starts (rotor index, fractional allowed), farther than `edge_margin`
    /// from either end, and farther than `reach` from the impurity's centre on the side it is
    /// launched from.
    pub start: f64,
    /// Which way it is launched.
    pub direction: Direction,
    /// The impurity's range: a wall within `reach` of its centre is at the impurity. Default 4
    /// (1.8 wall widths at `theta_bar = 0.28`).
    pub reach: f64,
    /// A wall farther than `clear` from the impurity's centre has left it; between `reach` and
    /// `clear` it may still be orbiting in the impurity's basin. Default 8.
    pub clear: f64,
    /// The end zones: a wall born within `edge_margin + 1` of a free end came from it, and a wall
    /// within `edge_margin` of an end has reached it. Default 3.
    pub edge_margin: f64,
    /// How long a transmitted, reflected, split, broken or annihilated pattern must hold to
    /// decide. Default 0.5.
    pub persistence: f64,
    /// How far a transmitted or reflected wall must move on while its pattern holds, and how much
    /// nearer than its start a wall must have come for a turn before the impurity's range to
    /// count as a repulsion from afar. Default 1.
    pub progress: f64,
    /// The shortest time a wall must stay at the impurity to count as trapped. Default 1.
    pub trap_time: f64,
    /// A wall at the impurity counts as trapped after `trap_crossings` times the time it would
    /// need to cross the impurity's range (`2 reach`) at the speed it came in with. Default 2.
    pub trap_crossings: f64,
    /// ...or after [`ScatterSetup::trap_time`] once it has turned round this often at the
    /// impurity: it oscillates in the impurity's well. Default 2. Between 0 (trapped after
    /// `trap_time` without turning) and the run's [`RunOptions::max_outputs`]: a turn is seen at
    /// an output, so no run could count more.
    pub turns: usize,
    /// A turn counts when the wall has come back this far from its farthest point, in sites.
    /// Default 0.3.
    pub turn_band: f64,
    /// Over how long before it reached the impurity the entry speed is measured. Default 0.2.
    pub entry_window: f64,
    /// Walls of the defect closer than this are one group, which counts by its net charge.
    /// Default 2.
    pub cluster_gap: f64,
    /// Walls born inside the chain less than this long ago do not count yet if their charges
    /// add up to 0 and they lie within [`ScatterSetup::pair_extent`]. Default 1.
    pub pair_age: f64,
    /// See [`ScatterSetup::pair_age`]. Default 8 (twice `reach`).
    pub pair_extent: f64,
    /// A defect that has had three walls or more for this long before reaching the impurity has
    /// disintegrated. Default 0.1.
    pub break_time: f64,
    /// A wall unseen for this long has vanished (shorter: two walls overlapping, or a wall
    /// passing through another's core). Default 0.25.
    pub grace: f64,
    /// The farthest a wall may move between two outputs and still be the same wall. Default 3.
    pub max_jump: f64,
    /// After a decision, the run goes on this long; if the pattern breaks meanwhile (other than
    /// by an end-born wall), the decision is withdrawn. Default 1.
    pub confirm: f64,
    /// After the confirmation, the run goes on this long to record a later event. Default 0.
    pub watch: f64,
    /// The run's settings (span, integrator, damping, ends).
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
            clear: 8.0,
            edge_margin: 3.0,
            persistence: 0.5,
            progress: 1.0,
            trap_time: 1.0,
            trap_crossings: 2.0,
            turns: 2,
            turn_band: 0.3,
            entry_window: 0.2,
            cluster_gap: 2.0,
            pair_age: 1.0,
            pair_extent: 8.0,
            break_time: 0.1,
            grace: 0.25,
            max_jump: 3.0,
            confirm: 1.0,
            watch: 0.0,
            run: RunOptions::default(),
        }
    }

    /// This setup with every duration multiplied by `unit` (> 0) and every rate divided by it:
    /// the rules' windows (`persistence`, `trap_time`, `entry_window`, `pair_age`, `break_time`,
    /// `grace`, `confirm`, `watch`) and the run's `t_max`, `output_interval` and `dt`, its
    /// `damping` and the strength of its absorbing ends. Distances (in sites) and counts stay, and
    /// so does `max_jump`, a distance per output whose speeds and interval scale inversely. With
    /// `unit = paper_time_unit(k, M)` the paper's setup is carried to a chain of stiffness `k` and
    /// tip mass `M`; set `t_max` or `dt` of your own afterwards if they are meant as given.
    pub fn in_time_unit(mut self, unit: f64) -> Self {
        for duration in [
            &mut self.persistence,
            &mut self.trap_time,
            &mut self.entry_window,
            &mut self.pair_age,
            &mut self.break_time,
            &mut self.grace,
            &mut self.confirm,
            &mut self.watch,
            &mut self.run.t_max,
            &mut self.run.output_interval,
        ] {
            *duration *= unit;
        }
        if let Some(dt) = &mut self.run.dt {
            *dt *= unit;
        }
        self.run.damping /= unit;
        if let Some(sponge) = &mut self.run.absorbing_ends {
            sponge.strength /= unit;
        }
        self
    }

    /// Whether the setup describes an experiment on a chain of `n` rotors (what [`scatter`]
    /// checks first): every field in its range ([`Validate::validate`]), the impurity one of its
    /// springs, the start on the chain, farther than `edge_margin` from either end (nearer, the
    /// launched wall would count as having reached that end at once), the impurity's range
    /// (`reach`) clear of the end zones, and the start beyond that range on the side the defect
    /// is launched from (otherwise no outcome would mean anything).
    pub fn check(&self, n: usize) -> Result<(), DynamicsError> {
        self.validate()?;
        if self.impurity >= n.saturating_sub(1) {
            return Err(DynamicsError::NoSuchSpring { spring: self.impurity, springs: n.saturating_sub(1) });
        }
        let last = n.saturating_sub(1) as f64;
        if !(self.start > self.edge_margin && self.start < last - self.edge_margin) {
            return Err(DynamicsError::InvalidSetup {
                options: "ScatterSetup",
                name: "start",
                value: self.start,
                rule: "a position on the chain, farther than edge_margin from either end",
            });
        }
        // The outcomes need room: the impurity's range clear of the end zones (a transmitted
        // wall must be able to leave it on the far side), and the defect coming from outside that
        // range, on the side it is launched from.
        let centre = self.impurity as f64 + 0.5;
        if !(centre - self.reach > self.edge_margin && centre + self.reach < last - self.edge_margin) {
            return Err(DynamicsError::InvalidSetup {
                options: "ScatterSetup",
                name: "impurity",
                value: self.impurity as f64,
                rule: "a spring whose range (reach) lies clear of the end zones (edge_margin)",
            });
        }
        let ahead = match self.direction {
            Direction::Left => self.start - centre,
            Direction::Right => centre - self.start,
        };
        // `start` and `reach` are finite here (checked above), so `ahead` is a number.
        if ahead <= self.reach {
            return Err(DynamicsError::InvalidSetup {
                options: "ScatterSetup",
                name: "start",
                value: self.start,
                rule: "farther than reach from the impurity, on the side the defect is launched from",
            });
        }
        Ok(())
    }
}

impl Validate for ScatterSetup {
    type Error = DynamicsError;

    /// Every field in its range, whatever the chain: `v0`, the windows and distances finite and
    /// `>= 0`, `reach`, `max_jump` and `cluster_gap` `> 0`, `clear >= reach`, `start` finite,
    /// the run's settings ([`RunOptions`]'s), `turns` at most `run.max_outputs`. Where the setup
    /// lies on a chain is [`ScatterSetup::check`]'s.
    fn validate(&self) -> Result<(), DynamicsError> {
        // Every field is named here, without `..`: a field added to the setup does not compile
        // until it is given its check below (or said to need none, as the enums).
        let Self {
            charge: _,
            v0,
            impurity: _,
            start,
            direction: _,
            reach,
            clear,
            edge_margin,
            persistence,
            progress,
            trap_time,
            trap_crossings,
            turns,
            turn_band,
            entry_window,
            cluster_gap,
            pair_age,
            pair_extent,
            break_time,
            grace,
            max_jump,
            confirm,
            watch,
            run,
        } = *self;
        // `impurity` is any spring index: whether the chain has the spring is `check`'s.
        let fields = Fields("ScatterSetup");
        fields.non_negative("v0", v0)?;
        fields.finite("start", start)?;
        for (name, value) in [
            ("edge_margin", edge_margin),
            ("persistence", persistence),
            ("progress", progress),
            ("trap_time", trap_time),
            ("trap_crossings", trap_crossings),
            ("turn_band", turn_band),
            ("entry_window", entry_window),
            ("pair_age", pair_age),
            ("pair_extent", pair_extent),
            ("break_time", break_time),
            ("grace", grace),
            ("confirm", confirm),
            ("watch", watch),
        ] {
            fields.non_negative(name, value)?;
        }
        for (name, value) in [("reach", reach), ("max_jump", max_jump), ("cluster_gap", cluster_gap)] {
            fields.positive(name, value)?;
        }
        fields.rule(
            "clear",
            clear,
            clear >= reach && clear.is_finite(),
            "finite and at least reach (a wall leaves the impurity's range before it is clear of it)",
        )?;
        run.validate()?;
        // After the run's own check, whose `max_outputs` bounds it.
        fields.count_in(
            "turns",
            turns as u64,
            0,
            run.max_outputs as u64,
            "between 0 and run.max_outputs (a turn is seen at an output)",
        )?;
        Ok(())
    }
}

/// The result of [`scatter`].
#[derive(Clone, Debug, PartialEq)]
pub struct Scattering {
    /// What the impurity did to the defect.
    pub outcome: Outcome,
    /// When the outcome was decided (the run's end time if undecided).
    pub decided_at: f64,
    /// Whether the confirmation window closed before the run ended.
    pub confirmed: bool,
    /// An event after the outcome was settled, and when.
    pub later: Option<(LaterEvent, f64)>,
    /// When a wall born at a free end first came within [`ScatterSetup::reach`] of the impurity
    /// (`None`: none did while the run was watched). Before [`Scattering::decided_at`], the
    /// outcome mixes what the impurity did with what the ends sent back
    /// ([`Scattering::unresolved`]).
    pub end_wall_at_impurity: Option<f64>,
    /// The run.
    pub run: Run,
}

impl Scattering {
    /// Why this run's outcome is not the impurity's alone, if it is not: a wall born at a free
    /// end reached the impurity's range at or before the decision
    /// ([`Unresolved::EndWallFirst`]). An undecided run has no outcome to doubt (`None`).
    pub fn unresolved(&self) -> Option<Unresolved> {
        let arrived = self.end_wall_at_impurity?;
        (self.outcome != Outcome::Undecided && arrived <= self.decided_at)
            .then_some(Unresolved::EndWallFirst { arrived, decided: (self.outcome, self.decided_at) })
    }
}

/// Launches the defect of `setup` towards the impurity and runs until the outcome is decided,
/// confirmed and watched (`rules`), or until `setup.run.t_max`.
/// # Example
///
/// The paper's antikink at $v_0 = 4.8$, $k_i/k = 0.2$ (Sec. VI) is reflected:
///
/// ```
/// use rotor_chain::RuntimeChain;
/// use rotor_chain::dynamics::scatter::{Outcome, ScatterSetup, scatter};
/// use rotor_chain::statics::walls::Charge;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let k = 1.0e4;
/// let chain = RuntimeChain::builder(60, 0.8, k, 0.28).spring_constant(29, 0.2 * k).build()?;
/// let result = scatter(&chain, &ScatterSetup::from_the_right(Charge::Antikink, 4.8, 29))?;
/// assert_eq!(result.outcome, Outcome::Reflected);
/// # Ok(())
/// # }
/// ```
pub fn scatter<M: ChainModel + ?Sized>(model: &M, setup: &ScatterSetup) -> Result<Scattering, DynamicsError> {
    scatter_with(model, setup, &mut |_| false)
}

/// [`scatter`] with a caller's stop question, asked at every output (`setup.run.output_interval`)
/// after the classifier's: `true` ends the run there, so that a caller can interrupt a long
/// scattering run (Python's `Chain.scatter` stops on Ctrl-C this way). A run stopped before the
/// outcome was decided is [`Outcome::Undecided`] with `decided_at` the stop's time, and one
/// stopped after it but before its confirmation has `confirmed == false`: the result says what
/// was seen, nothing more.
pub fn scatter_with<M: ChainModel + ?Sized>(
    model: &M,
    setup: &ScatterSetup,
    stop: &mut dyn FnMut(&Snapshot) -> bool,
) -> Result<Scattering, DynamicsError> {
    setup.check(model.rotor_count())?;
    let launched = launch(model, setup.charge, setup.start, setup.v0, setup.direction)?;
    let mut classifier = rules::Classifier::new(setup, model.rotor_count());
    let run = propagate(model, launched.state, &setup.run, &mut |s| classifier.observe(s) || stop(s))?;
    let end = run.final_state.time;
    let end_wall_at_impurity = classifier.end_wall_at_impurity;
    Ok(match classifier.verdict {
        Some(v) => Scattering {
            outcome: v.outcome,
            decided_at: v.decided_at,
            confirmed: v.confirmed_at.is_some(),
            later: v.later,
            end_wall_at_impurity,
            run,
        },
        None => Scattering {
            outcome: Outcome::Undecided,
            decided_at: end,
            confirmed: false,
            later: None,
            end_wall_at_impurity,
            run,
        },
    })
}
