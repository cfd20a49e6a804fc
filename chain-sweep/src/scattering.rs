//! The scattering phase diagram (paper Sec. VI, Fig. `fig:phasediagram`): a kink or antikink
//! launched at speed `v0` towards an impurity spring of stiffness `k_i`, and what became of it.
//! [`PhaseDiagram::compute_point`] is the one implementation of a point: the `phase-diagram` tool
//! and the paper reproduction (`chain-paper`) both call it.
//!
//! **Energy budget.** Every point is a run held to the dynamics' energy budget
//! ([`scatter_within_budget`]: a Verlet run above [`PhaseDiagram::energy_tolerance`] is computed
//! again with DOP853, a point that still breaks it fails with the numbers); this module keeps the
//! grid's side: the chain and the experiment of each point, its record and its file columns.
//!
//! **Unresolved points.** A point whose outcome is not the impurity's alone keeps its outcome
//! and carries the reason in [`PointRecord::unresolved`] (columns `unresolved`,
//! `unresolved_outcome`, `t_unresolved`): a wall born at a free end reached the impurity before
//! the decision ([`Unresolved::EndWallFirst`], read from every run), or, with
//! [`PhaseDiagram::cross_check`], Verlet and DOP853 decided differently
//! ([`Unresolved::IntegratorsDisagree`], [`cross_checked`]). The cross-check is an option, not the
//! default: it runs every point with DOP853 as well, which costs several times a Verlet point
//! (docs/dynamics.md §6 gives the measured cost and how often each reason occurs).

use std::fmt;
use std::num::NonZeroUsize;
use std::str::FromStr;

use rotor_chain::dynamics::DynamicsError;
pub use rotor_chain::dynamics::launch::Direction;
use rotor_chain::dynamics::run::{ABSORBING_ENDS, RunOptions};
pub use rotor_chain::dynamics::scatter::Unresolved;
pub use rotor_chain::dynamics::scatter::budget::{BudgetError, DEFAULT_ENERGY_TOLERANCE, VerletBreach};
use rotor_chain::dynamics::scatter::{
    CrossChecked, EnergyBudget, ScatterSetup, cross_checked, paper_time_unit, scatter_within_budget,
};
use rotor_chain::geometry::{MAX_ROTORS, Short};
pub use rotor_chain::integrate::Method;
use rotor_chain::integrate::{IntegrateError, Schedule, VerletOptions};
use rotor_chain::statics::walls::Charge;
use rotor_chain::validate::{Fields, InvalidOption, OptionError, Validate};
use rotor_chain::{ParameterError, RuntimeChain};

use crate::record::{ParseError, Record, expect_fields, format_f64, parse_field};

/// What the impurity did to the incident defect, and what happened to it later: the dynamics'
/// own types, with their names (`transmitted`, ...) as the `outcome` and `later` columns.
pub use rotor_chain::dynamics::scatter::{LaterEvent, Outcome, UnknownOutcome};

/// A name that none of a setting's values has (`"kinks"` for a [`Defect`]), with the names it
/// could have been: the error of the settings' `FromStr`, whose names are their `name()`s, so the
/// command line, the results file and Python spell them alike.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{what} must be one of {}, got '{got}'", names.iter().map(|n| format!("'{n}'")).collect::<Vec<_>>().join(", "))]
pub struct UnknownName {
    /// The setting (`defect`, `ends`, `integrator`).
    pub what: &'static str,
    /// The name given.
    pub got: String,
    /// Every name it may have.
    pub names: Vec<&'static str>,
}

/// The value of `all` whose `name` is `s`.
fn by_name<T: Copy>(
    what: &'static str,
    s: &str,
    all: &[T],
    name: fn(T) -> &'static str,
) -> Result<T, UnknownName> {
    all.iter().copied().find(|&t| name(t) == s).ok_or_else(|| UnknownName {
        what,
        got: s.to_owned(),
        names: all.iter().map(|&t| name(t)).collect(),
    })
}

/// The defect launched at the impurity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Defect {
    /// The zero-energy domain wall (`+theta_bar` on the left, `-theta_bar` on the right).
    Kink,
    /// The domain wall that stretches springs (`-theta_bar` on the left, `+theta_bar` on the right).
    Antikink,
}

impl Defect {
    /// Every defect, in the order of the docs.
    pub const ALL: [Defect; 2] = [Defect::Kink, Defect::Antikink];

    /// The name used on the command line and in the results file: its charge's, `kink` or
    /// `antikink`.
    pub fn name(self) -> &'static str {
        self.charge().name()
    }

    /// The wall charge of this defect.
    pub fn charge(self) -> Charge {
        match self {
            Defect::Kink => Charge::Kink,
            Defect::Antikink => Charge::Antikink,
        }
    }
}

impl fmt::Display for Defect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The chain's ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ends {
    /// Free ends, as in the paper (the default).
    Free,
    /// A damping sponge on the last rotors at each end
    /// ([`ABSORBING_ENDS`]): nothing comes back from
    /// the ends, as in an infinite chain.
    Absorbing,
}

impl Ends {
    /// Both kinds of ends, the default first.
    pub const ALL: [Ends; 2] = [Ends::Free, Ends::Absorbing];

    /// The name used on the command line and in the results file.
    pub fn name(self) -> &'static str {
        match self {
            Ends::Free => "free",
            Ends::Absorbing => "absorbing",
        }
    }
}

/// Every integrator a point may start with (the names of [`Method`]: `verlet`, `dop853` at its
/// default tolerances), the default first.
pub const METHODS: [Method; 2] = [Method::Verlet, Method::dop853()];

/// The integrator named `s` (`verlet` or `dop853`), with the names it could have been.
pub fn method_by_name(s: &str) -> Result<Method, UnknownName> {
    by_name("integrator", s, &METHODS, |m| m.name())
}

impl FromStr for Defect {
    type Err = UnknownName;
    /// The defect of [`Defect::name`]: `kink` or `antikink`.
    fn from_str(s: &str) -> Result<Self, UnknownName> {
        by_name("defect", s, &Self::ALL, Self::name)
    }
}

impl FromStr for Ends {
    type Err = UnknownName;
    /// The ends of [`Ends::name`]: `free` or `absorbing`.
    fn from_str(s: &str) -> Result<Self, UnknownName> {
        by_name("ends", s, &Self::ALL, Self::name)
    }
}

/// A phase-diagram configuration that cannot be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ConfigError {
    #[error("invalid chain: {0}")]
    /// The chain breaks a parameter rule.
    Chain(#[from] ParameterError),
    #[error(transparent)]
    /// A field of [`PhaseDiagram`] outside its range ([`Validate`]).
    InvalidOption(#[from] InvalidOption),
    #[error("invalid {name}: {} must be {rule}", Short(*value))]
    /// An argument out of its range (`k_i/k`).
    Value {
        /// The setting.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The rule it breaks.
        rule: &'static str,
    },
    #[error(
        "t_max = {} needs {outputs:e} outputs of the run every {}, more than its budget of \
         {budget}: shorten t_max",
        Short(*t_max), Short(*output_interval)
    )]
    /// `t_max` asks every point's run for more output times than a run allows
    /// ([`RunOptions::max_outputs`]): refused with the settings, not at every point.
    OutputBudget {
        /// The end of each run.
        t_max: f64,
        /// The run's output interval (`t`).
        output_interval: f64,
        /// The outputs it would need.
        outputs: f64,
        /// The most outputs a run allows.
        budget: usize,
    },
    #[error(
        "dt = {} needs {steps:e} Verlet steps to reach t_max = {}, more than a run's budget of {budget}: \
         lengthen dt or leave it to the default",
        Short(*dt), Short(*t_max)
    )]
    /// The Verlet step `dt` is so short that no run could reach `t_max` within the run's step
    /// budget ([`RunOptions::max_steps`]): refused with the settings, before any point.
    StepBudget {
        /// The step asked for.
        dt: f64,
        /// The end of each run.
        t_max: f64,
        /// The steps a run would need.
        steps: f64,
        /// The most steps a run allows.
        budget: u64,
    },
    #[error("a chain of {n} rotors cannot hold the experiment ({}): {source}", experiment_rule(*n, *shortest))]
    /// The experiment of [`PhaseDiagram::setup`] does not fit on the chain (too short for the
    /// defect's start 15.5 sites right of the middle spring: `n >= 38` for the paper's).
    Experiment {
        /// Rotors.
        n: usize,
        /// The fewest rotors that hold this experiment ([`PhaseDiagram::shortest_chain`]);
        /// `None`: no chain of up to [`MAX_ROTORS_SEARCHED`] rotors.
        shortest: Option<NonZeroUsize>,
        /// What the setup breaks (boxed: it is the largest error of the dynamics, and this enum
        /// travels inside the figures' and the sweep's errors).
        source: Box<DynamicsError>,
    },
}

/// The rule an experiment that does not fit a chain of `n` rotors breaks, in words.
fn experiment_rule(n: usize, shortest: Option<NonZeroUsize>) -> String {
    match shortest {
        Some(m) if m.get() > n => format!("this experiment needs n >= {m}"),
        Some(_) => "this impurity, start and direction do not fit this chain".to_owned(),
        None => format!("no chain of up to {MAX_ROTORS_SEARCHED} rotors holds this experiment"),
    }
}

/// How far [`PhaseDiagram::shortest_chain`] looks: a chain longer than the phase diagrams use.
pub const MAX_ROTORS_SEARCHED: usize = 100_000;

/// The version of the scattering physics and outcome rules in every run label: a results file
/// written by other rules is refused on resume instead of mixing two rules' labels in one
/// diagram. Raised whenever a rule changes a label: v3, a wall unseen for less than the grace
/// time counts where it was last seen (a split no longer hangs on the output a wall leaves at).
/// Since v3 the rules' windows and the output interval are in the chain's time unit
/// ([`paper_time_unit`]`(k, mass)`, 1 for the paper's `k = 1e4`, `M = 1`); for other chains the
/// label names it (`time_unit=`), so a file such a chain wrote before is refused too. v4: a
/// point whose decision came after a wall from a free end reached the impurity is marked
/// unresolved ([`PointRecord::unresolved`]).
pub const PHYSICS: &str = "scatter-v4";

/// One phase diagram: the chain, the defect, and how each point is computed. Build with
/// [`PhaseDiagram::new`], then change the public fields as needed.
#[derive(Clone, Debug, PartialEq)]
pub struct PhaseDiagram {
    /// Rotors `n`, rotor length `r` (lattice spacing `a = 1`), stiffness `k`, angle
    /// `theta_bar`, tip mass `M` (default 1). `n` between 2 and [`MAX_ROTORS`] (the chain
    /// builder's rule); whether the experiment fits the chain is [`PhaseDiagram::check`]'s.
    pub n: usize,
    /// Rotor length `r`, in units of `a`.
    pub r: f64,
    /// Spring stiffness `k`, in `M / t^2`.
    pub k: f64,
    /// Equilibrium angle, radians.
    pub theta_bar: f64,
    /// Tip mass `M`.
    pub mass: f64,
    /// The incoming defect.
    pub defect: Defect,
    /// Free (the paper's) or absorbing ends.
    pub ends: Ends,
    /// The integrator every point starts with.
    pub integrator: Method,
    /// Verlet's step; `None`: a tenth of its stability limit.
    pub dt: Option<f64>,
    /// A point whose relative energy error exceeds this is recomputed (see the module doc).
    pub energy_tolerance: f64,
    /// Recompute a point over the tolerance with DOP853 (default); `false`: record it as failed.
    pub recompute: bool,
    /// The end of every run, in the time unit `t`, as given (not scaled with the chain's time
    /// unit). Default 20 (the paper's runs; `20 * paper_time_unit(k, mass)` is the same span
    /// for another chain).
    pub t_max: f64,
    /// The impurity spring `p` (its centre at `p + 1/2`); `None`: the middle one, `(n - 1) / 2`,
    /// the paper's.
    pub impurity_spring: Option<usize>,
    /// The impurity spring's rest length `l0`, in units of `a` (a rest-length impurity, with or
    /// without a stiffness one); `None`: the chain's `lbar`, the paper's.
    pub impurity_rest_length: Option<f64>,
    /// Which way the defect is launched. Default [`Direction::Left`], the paper's: from the right
    /// of the impurity towards rotor 0.
    pub direction: Direction,
    /// Where the defect starts (rotor index, fractional allowed); `None`: 15 sites from the
    /// impurity's centre on the side it comes from, the paper's.
    pub start: Option<f64>,
    /// Damping rate `gamma >= 0` of every rotor, in `1 / t` as given (like `t_max`, not scaled
    /// with the chain's time unit). Default 0: the paper's undamped runs.
    pub damping: f64,
    /// Run every point with Verlet and with DOP853 ([`cross_checked`]) and mark it unresolved
    /// where they decide differently. Default `false`: DOP853 costs several times a Verlet run
    /// (docs/dynamics.md §6), and the integrators agree on all but a corner of the paper's plane;
    /// the end-wall check is made either way.
    pub cross_check: bool,
}

impl Validate for PhaseDiagram {
    type Error = ConfigError;

    /// Every field in its range, on its own: `r`, `k`, `theta_bar`, `mass`,
    /// `energy_tolerance` and `t_max` positive and finite, the integrator's tolerances
    /// (`rtol >= 0`, `atol > 0`), `dt > 0`, `impurity_rest_length > 0`, `start` and `damping`
    /// finite (`damping >= 0`), `n` between 2 and [`MAX_ROTORS`]. The chain's own rules (the
    /// flipper phase, the impurity's rest length against the chain) and the experiment's fit are
    /// [`PhaseDiagram::check`]'s, which names the shortest chain that holds the experiment
    /// ([`ConfigError::Experiment`]).
    fn validate(&self) -> Result<(), ConfigError> {
        // No `..`: a field added here does not compile until it is checked.
        let Self {
            n,
            r,
            k,
            theta_bar,
            mass,
            defect: _,
            ends: _,
            integrator,
            dt,
            energy_tolerance,
            recompute: _,
            t_max,
            impurity_spring: _,
            impurity_rest_length,
            direction: _,
            start,
            damping,
            cross_check: _,
        } = *self;
        // `impurity_spring` is any index: whether the chain has it is the experiment's check.
        let fields = Fields("PhaseDiagram");
        let rule = "between 2 and MAX_ROTORS = 100000000 (the chain builder's rule)";
        fields.count_in("n", n as u64, 2, MAX_ROTORS as u64, rule)?;
        for (name, value) in [
            ("r", r),
            ("k", k),
            ("theta_bar", theta_bar),
            ("mass", mass),
            ("energy_tolerance", energy_tolerance),
            ("t_max", t_max),
        ] {
            fields.positive(name, value)?;
        }
        if let Method::Dop853 { rtol, atol } = integrator {
            fields.non_negative("integrator.rtol", rtol)?;
            fields.positive("integrator.atol", atol)?;
        }
        if let Some(dt) = dt {
            fields.positive("dt", dt)?;
        }
        if let Some(l0) = impurity_rest_length {
            fields.positive("impurity_rest_length", l0)?;
        }
        if let Some(start) = start {
            fields.finite("start", start)?;
        }
        fields.non_negative("damping", damping)?;
        Ok(())
    }
}

impl PhaseDiagram {
    /// The paper's chain of Sec. VI with these parameters, checked: free ends, Verlet, the
    /// default energy tolerance, `t_max = 20`.
    pub fn new(n: usize, r: f64, k: f64, theta_bar: f64, defect: Defect) -> Result<Self, ConfigError> {
        RuntimeChain::builder(n, r, k, theta_bar).build()?;
        Ok(Self {
            n,
            r,
            k,
            theta_bar,
            mass: 1.0,
            defect,
            ends: Ends::Free,
            integrator: Method::Verlet,
            dt: None,
            energy_tolerance: DEFAULT_ENERGY_TOLERANCE,
            recompute: true,
            t_max: RunOptions::default().t_max,
            impurity_spring: None,
            impurity_rest_length: None,
            direction: Direction::Left,
            start: None,
            damping: 0.0,
            cross_check: false,
        })
    }

    /// The impurity spring: [`PhaseDiagram::impurity_spring`], or the middle one, `(n - 1) / 2`
    /// (0 for a chain without springs, which [`PhaseDiagram::check`] refuses).
    pub fn impurity(&self) -> usize {
        self.impurity_spring.unwrap_or(self.n.saturating_sub(1) / 2)
    }

    /// Where the defect starts: [`PhaseDiagram::start`], or 15 sites from the impurity's centre
    /// on the side it is launched from.
    pub fn start_site(&self) -> f64 {
        let centre = self.impurity() as f64 + 0.5;
        self.start.unwrap_or(match self.direction {
            Direction::Left => centre + 15.0,
            Direction::Right => centre - 15.0,
        })
    }

    /// The fewest rotors on which this experiment fits (the same impurity, start and direction
    /// rules as [`ScatterSetup::check`]); `None` if no chain of up to [`MAX_ROTORS_SEARCHED`]
    /// rotors holds it (an impurity or a start far out).
    pub fn shortest_chain(&self) -> Option<usize> {
        (2..=MAX_ROTORS_SEARCHED)
            .find(|&n| Self { n, ..self.clone() }.setup(1.0, self.integrator).check(n).is_ok())
    }

    /// Checks the settings before any point: every field ([`Validate::validate`]), the run's
    /// output and step budgets, the experiment's fit on the chain and the chain itself.
    pub fn check(&self) -> Result<(), ConfigError> {
        self.validate()?;
        // The output budget every point's run would meet (the run's own check, at its start).
        let run = self.setup(1.0, self.integrator).run;
        if let Err(IntegrateError::OutputBudget { outputs, budget }) =
            Schedule::covering(0.0, self.t_max, run.output_interval, run.max_outputs)
        {
            return Err(ConfigError::OutputBudget {
                t_max: self.t_max,
                output_interval: run.output_interval,
                outputs,
                budget,
            });
        }
        // The step budget every Verlet run would meet (the run's own check, at its start): a
        // step too short to reach t_max is refused here, not found at every point (each of which
        // would then be recomputed with DOP853).
        if let (Method::Verlet, Some(dt), Ok(schedule)) = (
            self.integrator,
            self.dt,
            Schedule::covering(0.0, self.t_max, run.output_interval, run.max_outputs),
        ) {
            let verlet = VerletOptions { max_steps: run.max_steps, ..VerletOptions::new(dt) };
            if let Err(IntegrateError::StepBudget { steps, budget, .. }) = verlet.steps_per_output(&schedule)
            {
                return Err(ConfigError::StepBudget { dt, t_max: self.t_max, steps, budget });
            }
        }
        // The experiment itself (the defect starts 15.5 sites right of the middle spring, more
        // than `edge_margin` from the end): refused here, not at every point of the grid.
        self.setup(1.0, self.integrator).check(self.n).map_err(|source| ConfigError::Experiment {
            n: self.n,
            shortest: self.shortest_chain().and_then(NonZeroUsize::new),
            source: Box::new(source),
        })?;
        // The impurity's rest length must admit the chain (the builder's own check, once here).
        self.builder(1.0).build().map(|_| ()).map_err(ConfigError::Chain)
    }

    /// Checks an impurity stiffness ratio: `k_i = ki_ratio * k` must be a positive, finite
    /// spring stiffness.
    pub fn check_ki(&self, ki_ratio: f64) -> Result<(), ConfigError> {
        let ki = ki_ratio * self.k;
        if ki_ratio > 0.0 && ki > 0.0 && ki.is_finite() {
            Ok(())
        } else {
            Err(ConfigError::Value {
                name: "k_i/k",
                value: ki_ratio,
                rule: "> 0, with k_i = k_i/k * k finite",
            })
        }
    }

    /// The run label stored in a results file: a file of another chain, defect, method or
    /// version of the outcome rules ([`PHYSICS`]) is refused on resume.
    pub fn run_label(&self) -> String {
        let dt = self.dt.map_or("stable".to_owned(), |dt| format!("{dt:?}"));
        format!(
            "defect={} n={} r={:?} k={:?} theta_bar={:?}{}{} ends={} integrator={} dt={dt} energy_tolerance={:?} \
             recompute={} t_max={:?} physics={PHYSICS}",
            self.defect.name(),
            self.n,
            self.r,
            self.k,
            self.theta_bar,
            if self.mass == 1.0 { String::new() } else { format!(" mass={:?}", self.mass) },
            if self.time_unit() == 1.0 {
                String::new()
            } else {
                format!(" time_unit={:?}", self.time_unit())
            },
            self.ends.name(),
            self.integrator.name(),
            self.energy_tolerance,
            self.recompute,
            self.t_max
        ) + &self.experiment_label()
    }

    /// The settings of the experiment that differ from the paper's, for the run label (empty for
    /// the paper's, so the files written before these settings existed still resume).
    fn experiment_label(&self) -> String {
        let mut label = String::new();
        if let Some(p) = self.impurity_spring {
            label += &format!(" impurity={p}");
        }
        if let Some(l0) = self.impurity_rest_length {
            label += &format!(" impurity_rest_length={l0:?}");
        }
        if self.direction == Direction::Right {
            label += " direction=right";
        }
        if let Some(start) = self.start {
            label += &format!(" start={start:?}");
        }
        if self.damping != 0.0 {
            label += &format!(" damping={:?}", self.damping);
        }
        if self.cross_check {
            label += " cross_check=true";
        }
        label
    }

    /// The chain with the impurity `k_i = ki_ratio * k` (and the impurity's rest length, if
    /// any) on the [impurity spring](PhaseDiagram::impurity).
    pub fn chain(&self, ki_ratio: f64) -> Result<RuntimeChain, PointError> {
        self.check_ki(ki_ratio)?;
        Ok(self.builder(ki_ratio).build()?)
    }

    fn builder(&self, ki_ratio: f64) -> rotor_chain::ChainBuilder {
        RuntimeChain::builder(self.n, self.r, self.k, self.theta_bar).mass(self.mass).spring(
            self.impurity(),
            Some(ki_ratio * self.k),
            self.impurity_rest_length,
        )
    }

    /// The chain's time unit relative to the paper's, [`paper_time_unit`]`(k, mass)`.
    pub fn time_unit(&self) -> f64 {
        paper_time_unit(self.k, self.mass)
    }

    /// The paper's experiment (Sec. VI) for this point: by default the defect 15 sites to the
    /// right of the middle spring, moving left (else this diagram's impurity, start and
    /// direction), with this diagram's ends, `t_max` and damping; the rules' windows, the output
    /// interval and the absorbing ends in the chain's [time unit](PhaseDiagram::time_unit), so
    /// that chains with the same `sqrt(M / k)`-scaled motion get the same outcomes.
    pub fn setup(&self, v0: f64, integrator: Method) -> ScatterSetup {
        let mut setup = ScatterSetup::from_the_right(self.defect.charge(), v0, self.impurity());
        setup.start = self.start_site();
        setup.direction = self.direction;
        if self.ends == Ends::Absorbing {
            setup.run.absorbing_ends = Some(ABSORBING_ENDS);
        }
        let mut setup = setup.in_time_unit(self.time_unit());
        setup.run.t_max = self.t_max;
        setup.run.damping = self.damping;
        setup.run.dt = self.dt;
        setup.run.method = integrator;
        setup
    }

    /// One point of the diagram (module doc): the run held to its energy budget, cross-checked
    /// with DOP853 if [`PhaseDiagram::cross_check`], and the record, with the reason if the
    /// point is unresolved (the outcome then is the kept run's: Verlet's when cross-checked).
    pub fn compute_point(&self, ki_ratio: f64, v0: f64) -> Result<PointRecord, PointError> {
        self.validate()?;
        let model = self.chain(ki_ratio)?;
        let budget = EnergyBudget { tolerance: self.energy_tolerance, recompute: self.recompute };
        let setup = self.setup(v0, self.integrator);
        let (kept, unresolved) = if self.cross_check {
            match cross_checked(&model, &setup, &budget)? {
                CrossChecked::Resolved(kept) => (*kept, None),
                CrossChecked::Unresolved { reason, verlet, .. } => (*verlet, Some(reason)),
            }
        } else {
            let kept = scatter_within_budget(&model, &setup, &budget)?;
            let unresolved = kept.scattering.unresolved();
            (kept, unresolved)
        };
        let result = &kept.scattering;
        let last = result.run.tracker.snapshots.last().ok_or(BudgetError::NothingRecorded)?;
        let (kinks_final, antikinks_final) = last.counts();
        Ok(PointRecord {
            outcome: result.outcome,
            t_decided: result.decided_at,
            confirmed: result.confirmed,
            later: result.later,
            kinks_final,
            antikinks_final,
            energy_error: kept.energy_error,
            integrator: if kept.recomputed { Recomputed::Dop853 } else { Recomputed::No(kept.integrator) },
            unresolved,
        })
    }
}

/// Why a phase-diagram point has no record. Its `Display` is the text of the results file's
/// `error` column.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PointError {
    /// The impurity stiffness ratio is outside its range ([`PhaseDiagram::check_ki`]).
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// The chain with the impurity breaks a parameter rule.
    #[error(transparent)]
    Chain(#[from] ParameterError),
    /// The run did not meet its energy budget or could not be read
    /// ([`scatter_within_budget`]).
    #[error(transparent)]
    Scatter(#[from] BudgetError),
}

impl OptionError for ConfigError {
    fn invalid_option(&self) -> Option<InvalidOption> {
        match self {
            Self::InvalidOption(o) => Some(*o),
            _ => None,
        }
    }
}

impl OptionError for PointError {
    fn invalid_option(&self) -> Option<InvalidOption> {
        match self {
            Self::Config(e) => e.invalid_option(),
            Self::Scatter(e) => e.invalid_option(),
            _ => None,
        }
    }
}

/// Which integrator produced a record.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Recomputed {
    /// The configured integrator, within the energy tolerance.
    No(Method),
    /// DOP853, after the Verlet run broke the energy budget.
    Dop853,
}

impl fmt::Display for Recomputed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Recomputed::No(i) => f.write_str(i.name()),
            Recomputed::Dop853 => f.write_str("dop853-recomputed"),
        }
    }
}

impl FromStr for Recomputed {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "verlet" => Ok(Recomputed::No(Method::Verlet)),
            "dop853" => Ok(Recomputed::No(Method::dop853())),
            "dop853-recomputed" => Ok(Recomputed::Dop853),
            other => {
                Err(format!("unknown integrator `{other}`: expected verlet, dop853 or dop853-recomputed"))
            }
        }
    }
}

/// One scattering simulation's result: the columns of a phase-diagram results file.
#[derive(Clone, Debug, PartialEq)]
pub struct PointRecord {
    /// What the impurity did to the defect.
    pub outcome: Outcome,
    /// When the outcome was decided, in the time unit of the dynamics (the run's end if
    /// undecided).
    pub t_decided: f64,
    /// Whether the confirmation window closed before the run ended.
    pub confirmed: bool,
    /// An event after the outcome was settled, and when (columns `later`, `t_later`).
    pub later: Option<(LaterEvent, f64)>,
    /// Kinks and antikinks at the end of the run, boundary walls included.
    pub kinks_final: usize,
    /// Antikinks at the end of the run.
    pub antikinks_final: usize,
    /// The run's largest relative energy error (`Report::relative_energy_error`).
    pub energy_error: f64,
    /// Which integrator produced the record.
    pub integrator: Recomputed,
    /// Why the outcome is not robust, if it is not (module doc): columns `unresolved` (the
    /// reason's [`Unresolved::name`]), `unresolved_outcome` (DOP853's outcome where the
    /// integrators disagree) and `t_unresolved` (DOP853's decision time, or when the end-born
    /// wall reached the impurity); the reason's other half is `outcome` and `t_decided`. Files
    /// written before these columns existed read back with `None`.
    pub unresolved: Option<Unresolved>,
}

impl PointRecord {
    /// [`PointRecord::unresolved`] as its three columns: the reason's name, DOP853's outcome
    /// (where the integrators disagree) and the reason's time (DOP853's decision, or when the
    /// end-born wall reached the impurity). The other half of a reason is the record's own
    /// `outcome` and `t_decided`.
    pub fn unresolved_columns(&self) -> (Option<&'static str>, Option<Outcome>, Option<f64>) {
        match self.unresolved {
            None => (None, None, None),
            Some(reason @ Unresolved::IntegratorsDisagree { dop853, .. }) => {
                (Some(reason.name()), Some(dop853.0), Some(dop853.1))
            }
            Some(reason @ Unresolved::EndWallFirst { arrived, .. }) => {
                (Some(reason.name()), None, Some(arrived))
            }
            // A reason this version does not know how to store (the enum is non-exhaustive).
            Some(reason) => (Some(reason.name()), None, None),
        }
    }

    /// The reason of [`PointRecord::unresolved_columns`] back from its columns, with this
    /// record's `outcome` and `t_decided` as its other half; `Err` names what is wrong.
    pub fn unresolved_of(
        &self,
        (name, outcome, time): (Option<&str>, Option<Outcome>, Option<f64>),
    ) -> Result<Option<Unresolved>, String> {
        let decided = (self.outcome, self.t_decided);
        Ok(match (name, outcome, time) {
            (None, None, None) => None,
            (Some("integrators-disagree"), Some(other), Some(t)) => {
                Some(Unresolved::IntegratorsDisagree { verlet: decided, dop853: (other, t) })
            }
            (Some("end-wall-first"), None, Some(arrived)) => {
                Some(Unresolved::EndWallFirst { arrived, decided })
            }
            _ => {
                return Err(format!(
                    "unresolved {name:?} with outcome {outcome:?} and time {time:?}: expected nothing, \
                     integrators-disagree with DOP853's outcome and time, or end-wall-first with a time"
                ));
            }
        })
    }
}

impl Record for PointRecord {
    fn header() -> &'static [&'static str] {
        &[
            "outcome",
            "t_decided",
            "confirmed",
            "later",
            "t_later",
            "kinks_final",
            "antikinks_final",
            "energy_error",
            "integrator",
            "unresolved",
            "unresolved_outcome",
            "t_unresolved",
        ]
    }

    /// The three `unresolved` columns came with physics v4: files without them still read.
    fn optional_columns() -> usize {
        3
    }

    fn to_fields(&self) -> Vec<String> {
        let mut fields = vec![
            self.outcome.name().to_owned(),
            format_f64(self.t_decided),
            self.confirmed.to_string(),
            self.later.map_or(String::new(), |(e, _)| e.name().to_owned()),
            self.later.map_or(String::new(), |(_, t)| format_f64(t)),
            self.kinks_final.to_string(),
            self.antikinks_final.to_string(),
            format_f64(self.energy_error),
            self.integrator.to_string(),
        ];
        let (reason, other, time) = self.unresolved_columns();
        fields.extend([
            reason.unwrap_or_default().to_owned(),
            other.map_or(String::new(), |o| o.name().to_owned()),
            time.map_or(String::new(), format_f64),
        ]);
        fields
    }

    fn from_fields(fields: &[&str]) -> Result<Self, ParseError> {
        let header = Self::header();
        // The file's own columns: all of them, or those before the optional ones.
        if fields.len() != header.len() - Self::optional_columns() {
            expect_fields(fields, header.len())?;
        }
        let later = match (fields[3], fields[4]) {
            ("", "") => None,
            _ => Some((parse_field(fields, 3, header[3])?, parse_field(fields, 4, header[4])?)),
        };
        let mut record = Self {
            outcome: parse_field(fields, 0, header[0])?,
            t_decided: parse_field(fields, 1, header[1])?,
            confirmed: parse_field(fields, 2, header[2])?,
            later,
            kinks_final: parse_field(fields, 5, header[5])?,
            antikinks_final: parse_field(fields, 6, header[6])?,
            energy_error: parse_field(fields, 7, header[7])?,
            integrator: parse_field(fields, 8, header[8])?,
            unresolved: None,
        };
        // The optional columns, empty when the file has none.
        let optional = |k: usize| fields.get(k).copied().filter(|f| !f.is_empty());
        let other = optional(10).map(|_| parse_field(fields, 10, header[10])).transpose()?;
        let time = optional(11).map(|_| parse_field(fields, 11, header[11])).transpose()?;
        record.unresolved = record.unresolved_of((optional(9), other, time)).map_err(|reason| {
            ParseError::Field { column: header[9].to_owned(), value: fields[9].to_owned(), reason }
        })?;
        Ok(record)
    }
}

/// A stand-in for the physics, for testing the sweep machinery only: a record that depends on
/// nothing but `(ki_ratio, v0)`, with every outcome appearing across a grid. It is not physics.
#[doc(hidden)]
pub fn fake_point(ki_ratio: f64, v0: f64) -> PointRecord {
    let cell = (ki_ratio * 10.0).floor() + v0.floor();
    let outcome = Outcome::ALL[cell.rem_euclid(Outcome::ALL.len() as f64) as usize];
    let (kinks_final, antikinks_final) = if outcome == Outcome::Split { (2, 1) } else { (1, 0) };
    PointRecord {
        outcome,
        t_decided: 10.0 + ki_ratio + v0,
        confirmed: true,
        later: (outcome == Outcome::Trapped).then_some((LaterEvent::Annihilated, 12.0 + v0)),
        kinks_final,
        antikinks_final,
        energy_error: 1e-9 * (1.0 + ki_ratio * v0),
        integrator: Recomputed::No(Method::Verlet),
        unresolved: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_setting_parses_back_from_its_name_and_an_unknown_name_lists_them() {
        for d in Defect::ALL {
            assert_eq!(d.name().parse::<Defect>(), Ok(d));
        }
        for e in Ends::ALL {
            assert_eq!(e.name().parse::<Ends>(), Ok(e));
        }
        for i in METHODS {
            assert_eq!(method_by_name(i.name()), Ok(i));
        }
        // The names, as the docs and the command line's --help list them.
        let names = |all: &[&str]| all.join(" ");
        assert_eq!(names(&Defect::ALL.map(Defect::name)), "kink antikink");
        assert_eq!(names(&Ends::ALL.map(Ends::name)), "free absorbing");
        assert_eq!(names(&METHODS.map(|m| m.name())), "verlet dop853");
        let e = "Kink".parse::<Defect>().unwrap_err();
        assert_eq!(e.to_string(), "defect must be one of 'kink', 'antikink', got 'Kink'");
        assert_eq!(method_by_name("rk4").unwrap_err().names, ["verlet", "dop853"]);
        assert_eq!("".parse::<Ends>().unwrap_err().what, "ends");
    }

    #[test]
    fn check_refuses_a_t_max_past_the_runs_output_budget_with_its_numbers() {
        let mut d = PhaseDiagram::new(60, 0.8, 1.0e4, 0.28, Defect::Antikink).unwrap();
        d.t_max = 1.0e9;
        // 1e9 / 0.01 = 1e11 outputs against the run's budget of 1 000 000.
        match d.check() {
            Err(ConfigError::OutputBudget { t_max, output_interval, outputs, budget }) => {
                assert_eq!((t_max, output_interval, budget), (1.0e9, 0.01, 1_000_000));
                assert!((outputs / 1.0e11 - 1.0).abs() < 1e-9, "{outputs}");
            }
            other => panic!("{other:?}"),
        }
        d.t_max = 20.0;
        assert!(d.check().is_ok());
    }

    /// The shortest chains: every length that passes `check` runs a point of either defect, and
    /// every shorter one is refused by `check`, with the setup's reason, before any point runs.
    /// The experiment off the paper's: an impurity at spring 20 that is stiff (k_i/k = 2) and
    /// short (l0 = 1.75 against lbar = 1.834), the kink launched rightwards from site 5.0,
    /// damped. The point equals the same run set up by hand on the library, and the settings are
    /// in the run label (and none of them for the paper's experiment, whose label is unchanged).
    #[test]
    fn every_setting_of_the_experiment_reaches_the_run_and_the_label() {
        let paper = PhaseDiagram::new(60, 0.8, 1.0e4, 0.28, Defect::Kink).unwrap();
        assert_eq!(
            paper.run_label(),
            format!(
                "defect=kink n=60 r=0.8 k=10000.0 theta_bar=0.28 ends=free integrator=verlet dt=stable \
                 energy_tolerance={DEFAULT_ENERGY_TOLERANCE:?} recompute=true t_max=20.0 physics={PHYSICS}"
            )
        );
        let mut d = paper.clone();
        (d.impurity_spring, d.impurity_rest_length, d.start) = (Some(20), Some(1.75), Some(5.0));
        (d.direction, d.damping, d.t_max) = (Direction::Right, 0.5, 6.0);
        d.check().unwrap();
        assert!(
            d.run_label().ends_with(
                "physics=scatter-v4 impurity=20 impurity_rest_length=1.75 direction=right start=5.0 damping=0.5"
            ),
            "{}",
            d.run_label()
        );
        let record = d.compute_point(2.0, 1.5).unwrap();

        let model =
            RuntimeChain::builder(60, 0.8, 1.0e4, 0.28).spring(20, Some(2.0e4), Some(1.75)).build().unwrap();
        let mut setup = ScatterSetup::from_the_right(Charge::Kink, 1.5, 20);
        (setup.start, setup.direction) = (5.0, Direction::Right);
        (setup.run.t_max, setup.run.damping) = (6.0, 0.5);
        let budget = EnergyBudget { tolerance: DEFAULT_ENERGY_TOLERANCE, recompute: true };
        let by_hand = scatter_within_budget(&model, &setup, &budget).unwrap();
        assert_eq!(
            (record.outcome, record.t_decided.to_bits(), record.energy_error.to_bits()),
            (
                by_hand.scattering.outcome,
                by_hand.scattering.decided_at.to_bits(),
                by_hand.energy_error.to_bits()
            )
        );
        // Damping changes the run (the same point undamped decides otherwise or later).
        let undamped = PhaseDiagram { damping: 0.0, ..d.clone() }.compute_point(2.0, 1.5).unwrap();
        assert_ne!(
            (undamped.outcome, undamped.t_decided.to_bits()),
            (record.outcome, record.t_decided.to_bits())
        );

        // Settings out of range, and experiments that do not fit, name their rule.
        let refused = |d: PhaseDiagram| d.check().unwrap_err().to_string();
        assert!(
            refused(PhaseDiagram { damping: -1.0, ..d.clone() })
                .contains("PhaseDiagram.damping = -1 is invalid")
        );
        assert!(
            refused(PhaseDiagram { start: Some(f64::NAN), ..d.clone() })
                .contains("PhaseDiagram.start = NaN is invalid")
        );
        let text = refused(PhaseDiagram { impurity_rest_length: Some(-0.0), ..d.clone() });
        assert!(
            text.contains(
                "PhaseDiagram.impurity_rest_length = -0 is invalid: it must be positive and finite"
            ),
            "{text}"
        );
        // Spring 50, launched leftwards from 65.5: the start needs n - 4 > 65.5, so n >= 70.
        let text = refused(PhaseDiagram { impurity_spring: Some(50), ..paper.clone() });
        assert!(
            text.starts_with(
                "a chain of 60 rotors cannot hold the experiment (this experiment needs n >= 70)"
            ),
            "{text}"
        );
        let text = refused(PhaseDiagram { n: 37, ..paper.clone() });
        assert!(text.contains("(this experiment needs n >= 38)"), "{text}");
    }

    #[test]
    fn check_refuses_exactly_the_chains_too_short_for_the_experiment() {
        let mut shortest = None;
        for n in 0..=45 {
            for defect in [Defect::Kink, Defect::Antikink] {
                // `n` set after `new`, as a caller may: `check` must catch what `new` did not see.
                let mut d = PhaseDiagram::new(60, 0.8, 1.0e4, 0.28, defect).unwrap();
                (d.n, d.t_max) = (n, 2.0);
                match d.check() {
                    Ok(()) => {
                        let point = d.compute_point(0.5, 2.0);
                        assert!(point.is_ok(), "n = {n}, {defect:?}: {point:?}");
                        shortest.get_or_insert(n);
                    }
                    Err(ConfigError::Experiment { n: m, shortest: needs, source }) => {
                        assert_eq!(needs.map(NonZeroUsize::get), Some(38), "n = {n}");
                        assert_eq!(m, n);
                        assert!(shortest.is_none(), "n = {n} refused after a shorter chain passed");
                        assert!(d.compute_point(0.5, 2.0).is_err(), "n = {n} refused, yet its point ran");
                        assert!(source.to_string().contains("start"), "n = {n}: {source}");
                    }
                    // Below two rotors there is no chain: `validate`'s rule on `n`, before the
                    // experiment is looked at.
                    Err(ConfigError::InvalidOption(o)) if n < 2 => {
                        assert_eq!((o.options, o.field, o.value), ("PhaseDiagram", "n", n as f64));
                        assert!(d.compute_point(0.5, 2.0).is_err(), "n = {n} refused, yet its point ran");
                    }
                    Err(other) => panic!("n = {n}: {other}"),
                }
            }
        }
        assert!(shortest.is_some_and(|n| n <= 40), "{shortest:?}");
    }

    /// A chain with other `k` and `M` moves as the paper's in its time unit `sqrt(1e4 M / k)`:
    /// at `v0` divided by that unit (and `t_max` times it) every point has the paper's outcome,
    /// decided at the same scaled time (an audit found (antikink, 0.8, 4.0) transmitted for the
    /// paper's chain and reflected at k = 4e4, v0 = 8 while the rules' windows stayed in t). The
    /// label names the unit when it is not 1, so a results file of the old rules is refused.
    #[test]
    fn a_chain_in_other_units_has_the_papers_outcomes() {
        let points = [
            (Defect::Antikink, 0.8, 4.0),
            (Defect::Antikink, 0.7, 4.0),
            (Defect::Antikink, 0.2, 4.8),
            (Defect::Kink, 0.01, 9.6),
        ];
        let paper = PhaseDiagram::new(60, 0.8, 1.0e4, 0.28, Defect::Antikink).unwrap();
        assert!(!paper.run_label().contains("time_unit"), "{}", paper.run_label());
        for (k, mass, unit) in [(4.0e4, 1.0, 0.5), (1.0e4, 0.25, 0.5), (1.0e6, 4.0, 0.2)] {
            for ends in [Ends::Free, Ends::Absorbing] {
                for (defect, ki, v0) in points {
                    let base = PhaseDiagram { defect, ends, ..paper.clone() };
                    let other = PhaseDiagram { k, mass, t_max: 20.0 * unit, ..base.clone() };
                    assert_eq!(other.time_unit(), unit);
                    let (want, got) =
                        (base.compute_point(ki, v0).unwrap(), other.compute_point(ki, v0 / unit).unwrap());
                    let what = format!("{defect:?} at ({ki}, {v0}), {ends:?}, k = {k}, M = {mass}");
                    assert_eq!((got.outcome, got.confirmed), (want.outcome, want.confirmed), "{what}");
                    let t = got.t_decided / unit;
                    assert!(
                        (t - want.t_decided).abs() <= 0.0101,
                        "{what}: decided at {t} against {}",
                        want.t_decided
                    );
                }
            }
            let other = PhaseDiagram { k, mass, ..paper.clone() };
            assert!(other.run_label().contains(&format!(" time_unit={unit:?} ")), "{}", other.run_label());
        }
    }

    #[test]
    fn outcome_names_round_trip() {
        for outcome in Outcome::ALL {
            assert_eq!(outcome.name().parse::<Outcome>(), Ok(outcome));
        }
        assert_eq!("bounced".parse::<Outcome>(), Err(UnknownOutcome("bounced".to_owned())));
    }

    #[test]
    fn records_round_trip_through_fields() {
        let record = PointRecord {
            outcome: Outcome::Trapped,
            t_decided: 1.0 / 3.0,
            confirmed: true,
            later: Some((LaterEvent::Annihilated, 4.25)),
            kinks_final: 2,
            antikinks_final: 1,
            energy_error: 2.5e-13,
            integrator: Recomputed::Dop853,
            unresolved: None,
        };
        let fields = record.to_fields();
        let fields: Vec<&str> = fields.iter().map(String::as_str).collect();
        assert_eq!(
            fields,
            [
                "trapped",
                "0.3333333333333333",
                "true",
                "annihilated",
                "4.25",
                "2",
                "1",
                "2.5e-13",
                "dop853-recomputed",
                "",
                "",
                ""
            ]
        );
        assert_eq!(PointRecord::from_fields(&fields), Ok(record.clone()));
        let quiet = PointRecord { later: None, integrator: Recomputed::No(Method::Verlet), ..record };
        let fields = quiet.to_fields();
        let fields: Vec<&str> = fields.iter().map(String::as_str).collect();
        assert_eq!(PointRecord::from_fields(&fields), Ok(quiet));
        let err =
            PointRecord::from_fields(&["split", "x", "true", "", "", "2", "1", "0", "verlet"]).unwrap_err();
        assert!(err.to_string().contains("column `t_decided`"), "{err}");
        assert!(PointRecord::from_fields(&["split"]).is_err());
    }

    /// An unresolved point keeps its reason through the file's columns, with both halves of it
    /// (the record's outcome and decision time, and the columns' own); the fields of a file
    /// written before the columns existed read as resolved; a reason without its numbers is an
    /// error naming the column.
    #[test]
    fn unresolved_records_round_trip_and_records_without_the_columns_still_read() {
        let base = PointRecord {
            outcome: Outcome::PairCreation,
            t_decided: 11.1,
            confirmed: true,
            later: None,
            kinks_final: 2,
            antikinks_final: 3,
            energy_error: 1.5e-3,
            integrator: Recomputed::No(Method::Verlet),
            unresolved: None,
        };
        let disagree = PointRecord {
            unresolved: Some(Unresolved::IntegratorsDisagree {
                verlet: (Outcome::PairCreation, 11.1),
                dop853: (Outcome::Trapped, 8.2),
            }),
            ..base.clone()
        };
        let end_wall = PointRecord {
            unresolved: Some(Unresolved::EndWallFirst {
                arrived: 5.25,
                decided: (Outcome::PairCreation, 11.1),
            }),
            ..base.clone()
        };
        for (record, tail) in [
            (&disagree, ["integrators-disagree", "trapped", "8.2"]),
            (&end_wall, ["end-wall-first", "", "5.25"]),
            (&base, ["", "", ""]),
        ] {
            let fields = record.to_fields();
            let fields: Vec<&str> = fields.iter().map(String::as_str).collect();
            assert_eq!(fields[9..], tail);
            assert_eq!(PointRecord::from_fields(&fields).as_ref(), Ok(record));
            // The nine columns of a file written before physics v4: resolved.
            assert_eq!(PointRecord::from_fields(&fields[..9]), Ok(base.clone()));
        }
        let mut fields: Vec<String> = disagree.to_fields();
        fields[11].clear();
        let fields: Vec<&str> = fields.iter().map(String::as_str).collect();
        let err = PointRecord::from_fields(&fields).unwrap_err();
        assert!(err.to_string().starts_with("column `unresolved`"), "{err}");
        let mut fields: Vec<&str> = base.to_fields().iter().map(|_| "").collect();
        fields.truncate(10);
        assert!(matches!(PointRecord::from_fields(&fields), Err(ParseError::FieldCount { .. })));
    }

    #[test]
    fn fake_points_are_deterministic_and_cover_every_outcome() {
        assert_eq!(fake_point(0.3, 4.5), fake_point(0.3, 4.5));
        let seen: Vec<Outcome> = (0..Outcome::ALL.len()).map(|k| fake_point(0.0, k as f64).outcome).collect();
        assert_eq!(seen, Outcome::ALL);
    }
}
