//! The energy budget of a scattering run: the policy by which one point of a phase diagram
//! (paper Sec. VI, Fig. `fig:phasediagram`) earns its label.
//!
//! Every run reports its largest relative energy error ([`Budgeted::energy_error`]). A run above
//! [`EnergyBudget::tolerance`] (or one stopped by an integration error, such as the integrator's
//! own energy limit) is computed again with DOP853 at its default tolerances; if that run is still
//! above the tolerance, or fails, the point fails with the numbers ([`BudgetError`]). A run whose
//! rotors spun through `|theta| = pi` (the walls cannot be read from signs any more) fails too.
//! No point gets a label it did not earn. The sweeps (`chain-sweep`), the paper's diagrams and
//! Python all go through [`scatter_within_budget`].

use alloc::boxed::Box;
use alloc::format;
use alloc::string::String;
use core::fmt;

use chain_geometry::Short;

use super::{ScatterSetup, Scattering, scatter};
use crate::dynamics::DynamicsError;
use crate::integrate::Method;
use crate::model::ChainModel;
use crate::validate::{Fields, InvalidOption, Validate};

/// The default energy tolerance: 5e-3 of the run's initial energy.
///
/// Why: velocity Verlet conserves a modified energy, and the energy it reports oscillates about
/// it by up to `(omega dt)^2 / 4` of the energy in the fastest phonons, 1 % at the default step.
/// A collision that radiates a tenth of the energy into phonons therefore shows ~1e-3 without any
/// error in the walls' motion: over both 40 x 40 diagrams the largest is 1.75e-3, and the labels
/// agree with DOP853 (energy error ~1e-9) at 99.5-100 % of the points (docs/dynamics.md §6).
/// A step past the stability limit exceeds it within a few steps.
pub const DEFAULT_ENERGY_TOLERANCE: f64 = 5e-3;

/// How a scattering run is held to its energy (the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnergyBudget {
    /// A run whose largest relative energy error exceeds this is recomputed or fails. Default
    /// [`DEFAULT_ENERGY_TOLERANCE`].
    pub tolerance: f64,
    /// Recompute a Verlet run over the tolerance with DOP853 (default `true`); `false`: fail.
    pub recompute: bool,
}

impl Default for EnergyBudget {
    fn default() -> Self {
        Self { tolerance: DEFAULT_ENERGY_TOLERANCE, recompute: true }
    }
}

impl Validate for EnergyBudget {
    type Error = BudgetError;

    /// `tolerance` positive and finite (`recompute` is a choice).
    fn validate(&self) -> Result<(), BudgetError> {
        let Self { tolerance, recompute: _ } = *self;
        Ok(Fields("EnergyBudget").positive("tolerance", tolerance)?)
    }
}

/// A scattering run that met its energy budget.
#[derive(Clone, Debug, PartialEq)]
pub struct Budgeted {
    /// The run and its outcome.
    pub scattering: Scattering,
    /// Its largest relative energy error (`Report::relative_energy_error`).
    pub energy_error: f64,
    /// The integrator of the run kept.
    pub integrator: Method,
    /// Whether it is DOP853's recomputation of a Verlet run that broke the budget.
    pub recomputed: bool,
}

/// Why a scattering run did not meet its energy budget, or could not be read.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BudgetError {
    /// A field of the [`EnergyBudget`] outside its range.
    #[error(transparent)]
    InvalidOption(#[from] InvalidOption),
    /// The setup does not describe an experiment on this chain ([`ScatterSetup::check`]):
    /// refused before any run, so no integrator is tried, nor recomputed.
    #[error("the setup: {0}")]
    Setup(DynamicsError),
    /// The run of `integrator` failed: the launch, or the integration (for example its own
    /// 10 % energy limit, or a state that is not finite).
    #[error("{integrator}: {source}")]
    Run {
        /// The integrator that ran.
        integrator: Method,
        #[source]
        /// Its error.
        source: DynamicsError,
    },
    /// The run's largest relative energy error is above the tolerance.
    #[error("energy error {error:.3e} above the tolerance {tolerance:.1e} ({integrator})")]
    EnergyBudget {
        /// The run's largest relative energy error.
        error: f64,
        /// The tolerance.
        tolerance: f64,
        /// The integrator that ran.
        integrator: Method,
    },
    /// The Verlet run broke the budget (or failed), and its DOP853 recomputation did not succeed
    /// either: `dop853` is a [`BudgetError::Run`] or a [`BudgetError::EnergyBudget`].
    #[error("{}", recomputed_message(verlet, dop853))]
    Recomputed {
        /// Why the Verlet run was not kept.
        verlet: VerletBreach,
        /// How the DOP853 recomputation failed.
        dop853: Box<BudgetError>,
    },
    /// The tracker's charge check failed: rotors spun through `|theta| = pi`, so the walls cannot
    /// be read from the signs of the angles. `time` is the first output where it failed.
    #[error(
        "the rotors spun through |theta| = pi at t = {time} ({outputs} outputs): walls cannot be read from signs", time = Short(*time)
    )]
    SpunThroughPi {
        /// The first output where it failed, in `t`.
        time: f64,
        /// Outputs recorded until then.
        outputs: usize,
    },
    /// The run ended before its first output.
    #[error("the run recorded nothing")]
    NothingRecorded,
}

/// Why the Verlet run of a point was recomputed with DOP853.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum VerletBreach {
    /// Its largest relative energy error, above the tolerance.
    EnergyError {
        /// The run's largest relative energy error.
        error: f64,
    },
    /// It stopped with an error.
    Failed {
        /// Its error.
        source: DynamicsError,
    },
}

impl fmt::Display for VerletBreach {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            VerletBreach::EnergyError { error } => write!(f, "energy error {error:.3e}"),
            VerletBreach::Failed { source } => write!(f, "verlet: {source}"),
        }
    }
}

/// The text of [`BudgetError::Recomputed`]: `verlet: <why>; energy error ... (dop853)` when
/// DOP853 broke the budget too, `<why>; dop853: <error>` when it failed.
fn recomputed_message(verlet: &VerletBreach, dop853: &BudgetError) -> String {
    match dop853 {
        BudgetError::EnergyBudget { .. } => format!("verlet: {verlet}; {dop853}"),
        _ => format!("{verlet}; {dop853}"),
    }
}

/// [`scatter`] held to `budget` (the module doc): the run of `setup.run.method`, recomputed with
/// DOP853 if it was a Verlet run over the tolerance (and `budget.recompute`), checked for rotors
/// that spun through `pi`.
///
/// # Errors
/// A [`BudgetError`] that says which run failed and with what numbers.
pub fn scatter_within_budget<M: ChainModel + ?Sized>(
    model: &M,
    setup: &ScatterSetup,
    budget: &EnergyBudget,
) -> Result<Budgeted, BudgetError> {
    budget.validate()?;
    setup.check(model.rotor_count()).map_err(BudgetError::Setup)?;
    let first = setup.run.method;
    let run = |method: Method| -> Result<Scattering, BudgetError> {
        let mut setup = *setup;
        setup.run.method = method;
        scatter(model, &setup).map_err(|source| BudgetError::Run { integrator: method, source })
    };
    let error_of = |s: &Scattering| s.run.report.relative_energy_error();
    let over = |s: Scattering, integrator: Method| {
        let error = error_of(&s);
        if error <= budget.tolerance {
            Ok(s)
        } else {
            Err(BudgetError::EnergyBudget { error, tolerance: budget.tolerance, integrator })
        }
    };
    let (scattering, integrator, recomputed) = match run(first) {
        Ok(s) if error_of(&s) <= budget.tolerance => (s, first, false),
        attempt if budget.recompute && first == Method::Verlet => {
            let verlet = match attempt {
                Ok(s) => VerletBreach::EnergyError { error: error_of(&s) },
                Err(BudgetError::Run { source, .. }) => VerletBreach::Failed { source },
                Err(other) => return Err(other),
            };
            let dop853 = Method::dop853();
            match run(dop853).and_then(|s| over(s, dop853)) {
                Ok(s) => (s, dop853, true),
                Err(e) => return Err(BudgetError::Recomputed { verlet, dop853: Box::new(e) }),
            }
        }
        Ok(s) => {
            let error = error_of(&s);
            return Err(BudgetError::EnergyBudget { error, tolerance: budget.tolerance, integrator: first });
        }
        Err(e) => return Err(e),
    };
    if let Some(&time) = scattering.run.tracker.violations.first() {
        return Err(BudgetError::SpunThroughPi { time, outputs: scattering.run.tracker.violations.len() });
    }
    if scattering.run.tracker.snapshots.is_empty() {
        return Err(BudgetError::NothingRecorded);
    }
    let energy_error = error_of(&scattering);
    Ok(Budgeted { scattering, energy_error, integrator, recomputed })
}

/// Why a point's label would change with the integrator ([`cross_checked`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Unresolved {
    /// Verlet and DOP853, each within the energy budget, decided different outcomes.
    IntegratorsDisagree {
        /// Verlet's outcome and when it was decided.
        verlet: (super::Outcome, f64),
        /// DOP853's outcome and when it was decided.
        dop853: (super::Outcome, f64),
    },
    /// A wall born at a free end reached the impurity's range (`reach`) at `arrived`, at or
    /// before the outcome was decided: the label mixes what the impurity did with what the
    /// finite chain's ends sent back ([`super::Scattering::unresolved`]).
    EndWallFirst {
        /// When the end-born wall came within `reach` of the impurity.
        arrived: f64,
        /// The run's outcome and when it was decided.
        decided: (super::Outcome, f64),
    },
}

impl Unresolved {
    /// Lower-case name of the reason, for files and tables: `integrators-disagree`,
    /// `end-wall-first`.
    pub fn name(&self) -> &'static str {
        match self {
            Unresolved::IntegratorsDisagree { .. } => "integrators-disagree",
            Unresolved::EndWallFirst { .. } => "end-wall-first",
        }
    }
}

impl fmt::Display for Unresolved {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Unresolved::IntegratorsDisagree { verlet, dop853 } => write!(
                f,
                "the integrators disagree: verlet {:?} at t = {}, dop853 {:?} at t = {}",
                verlet.0, verlet.1, dop853.0, dop853.1
            ),
            Unresolved::EndWallFirst { arrived, decided } => write!(
                f,
                "a wall from a free end reached the impurity at t = {arrived}, before the decision ({} at t = {})",
                decided.0, decided.1
            ),
        }
    }
}

/// A point labelled only if a second integrator would give it the same label.
#[derive(Clone, Debug, PartialEq)]
pub enum CrossChecked {
    /// Both integrators decided this outcome; the run kept is Verlet's (or its recomputation).
    Resolved(Box<Budgeted>),
    /// The outcome is not robust: no label, the reason instead, and both runs.
    Unresolved {
        /// Why.
        reason: Unresolved,
        /// The Verlet run (within budget, or its DOP853 recomputation).
        verlet: Box<Budgeted>,
        /// The DOP853 run.
        dop853: Box<Budgeted>,
    },
}

/// [`scatter_within_budget`] with Verlet and again with DOP853 (default tolerances): the point is
/// [`CrossChecked::Resolved`] when both decide the same outcome and no wall from a free end
/// reached the impurity before the decision, else [`CrossChecked::Unresolved`] with the reason
/// ([`Unresolved::IntegratorsDisagree`] with both outcomes and decision times first, then
/// Verlet's [`Unresolved::EndWallFirst`]). 6.2 times the cost of a Verlet run on the paper's
/// phase diagrams (docs/dynamics.md §6);
/// the phase diagrams' honest label where a collision is chaotic (docs/dynamics.md §6: at
/// `k_i/k ~ 0.01`, `v0 ~ 1` a pair nucleates at the impurity before the antikink arrives, and the
/// integrators' rounding decides what it becomes).
///
/// # Errors
/// The [`BudgetError`] of either run.
pub fn cross_checked<M: ChainModel + ?Sized>(
    model: &M,
    setup: &ScatterSetup,
    budget: &EnergyBudget,
) -> Result<CrossChecked, BudgetError> {
    let with = |method: Method| {
        let mut setup = *setup;
        setup.run.method = method;
        scatter_within_budget(model, &setup, budget)
    };
    let verlet = with(Method::Verlet)?;
    let dop853 = with(Method::dop853())?;
    let (a, b) = (&verlet.scattering, &dop853.scattering);
    let reason = if a.outcome == b.outcome {
        a.unresolved()
    } else {
        Some(Unresolved::IntegratorsDisagree {
            verlet: (a.outcome, a.decided_at),
            dop853: (b.outcome, b.decided_at),
        })
    };
    Ok(match reason {
        None => CrossChecked::Resolved(Box::new(verlet)),
        Some(reason) => {
            CrossChecked::Unresolved { reason, verlet: Box::new(verlet), dop853: Box::new(dop853) }
        }
    })
}
