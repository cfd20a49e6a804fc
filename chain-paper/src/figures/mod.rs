//! One function per figure of the paper, each taking the chain's parameters and a [`Quality`],
//! returning a [`crate::Figure`] (data and summary rows). Grouped by the paper's sections.

use rotor_chain::RuntimeChain;
use rotor_chain::dynamics::DynamicsError;
use rotor_chain::statics::StaticsError;
use rotor_chain::statics::continuum::{ContinuumChain, ContinuumError};
use rotor_chain::statics::linkage::LinkageError;
use rotor_chain::{BranchError, ParameterError};

use crate::drawing::DrawingError;
use crate::model::{Figure, Quality};

pub mod dynamics;
pub mod resolution;
pub mod statics_a;
pub mod statics_b;

/// Everything a figure is computed from: the chain (`n`, `r`, `k`, `mass`; Appendix B) and, per
/// family of figures, the angles, speeds, impurities and ranges the paper chose. The default is the
/// paper's everywhere, so `figure(&Params::default(), Quality::Full)` reproduces the paper; change
/// any field to recompute a figure for another chain:
///
/// ```
/// use chain_paper::Quality;
/// use chain_paper::figures::{Params, statics_a};
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// // Fig. akconfigpn for a 40-rotor chain of shorter rotors at another angle.
/// let mut params = Params { n: 40, r: 0.7, ..Params::default() };
/// params.barrier.theta_bar = 0.5;
/// let figure = statics_a::akconfigpn(&params, Quality::Quick)?;
/// assert!(figure.caption.contains("n = 40, r/a = 0.7, θ̄ = 0.5"));
/// # Ok(())
/// # }
/// ```
///
/// Units are the paper's: `a = 1`, so lengths are in lattice spacings, stiffness in `M/t^2`.
#[derive(Clone, Debug, PartialEq)]
pub struct Params {
    /// Rotors.
    pub n: usize,
    /// Rotor length, in `a`.
    pub r: f64,
    /// Spring stiffness, in `M / t^2`.
    pub k: f64,
    /// Tip mass `M`.
    pub mass: f64,
    /// The kink and antikink pictures and cobweb plots (Sec. II).
    pub cobweb: statics_a::Cobweb,
    /// The antikink's energy and Peierls-Nabarro barrier (Secs. III, V).
    pub barrier: statics_a::Barrier,
    /// The localised modes (Sec. IV).
    pub modes: statics_b::Modes,
    /// The long middle spring (Sec. VII-A).
    pub long_bar: statics_b::LongBar,
    /// The linkage limit (Sec. VII-B).
    pub linkage: statics_b::Linkage,
    /// Moving kinks and antikinks in a perfect chain (Sec. V).
    pub propagation: dynamics::Propagation,
    /// Scattering on a stiffness impurity and the phase diagrams (Sec. VI).
    pub scattering: dynamics::Scattering,
}

impl Default for Params {
    /// The paper's chain (Appendix B: `n = 60`, `r/a = 0.8`, `k = 1e4 M/t^2`, `M = 1`) and the
    /// paper's choices for every figure.
    fn default() -> Self {
        Self {
            n: 60,
            r: 0.8,
            k: 1.0e4,
            mass: 1.0,
            cobweb: statics_a::Cobweb::default(),
            barrier: statics_a::Barrier::default(),
            modes: statics_b::Modes::default(),
            long_bar: statics_b::LongBar::default(),
            linkage: statics_b::Linkage::default(),
            propagation: dynamics::Propagation::default(),
            scattering: dynamics::Scattering::default(),
        }
    }
}

/// A figure that could not be computed: its label, the parameters of the point that failed
/// (e.g. `θ̄ = 0.3`, or `v0 = 4`, `k_i/k = 0.8`; empty when the whole figure failed) and the cause.
#[derive(Debug, thiserror::Error)]
#[error("{label}{}: {cause}", at_text(.at))]
pub struct FigureError {
    /// The figure's LaTeX label (`fig:...`).
    pub label: &'static str,
    /// The parameters of the point that failed, as `(name, value)`.
    pub at: Vec<(&'static str, f64)>,
    #[source]
    /// Why.
    pub cause: Cause,
}

fn at_text(at: &[(&'static str, f64)]) -> String {
    if at.is_empty() {
        return String::new();
    }
    let pairs: Vec<String> = at.iter().map(|(name, value)| format!("{name} = {value}")).collect();
    format!(" ({})", pairs.join(", "))
}

/// Why a figure failed: an error of the library, or a figure's own check.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Cause {
    #[error(transparent)]
    /// The chain breaks a parameter rule.
    Parameter(#[from] ParameterError),
    #[error("branch solve: {0}")]
    /// The branch solve failed.
    Branch(#[from] BranchError),
    #[error(transparent)]
    /// A static analysis failed.
    Statics(#[from] StaticsError),
    #[error(transparent)]
    /// A continuum closed form does not apply.
    Continuum(#[from] ContinuumError),
    #[error("linkage limit: {0}")]
    /// The linkage-limit analysis failed.
    Linkage(#[from] LinkageError),
    #[error(transparent)]
    /// A dynamics run failed.
    Dynamics(#[from] DynamicsError),
    #[error("chain drawing: {0}")]
    /// A drawing of the chain could not be made.
    Drawing(#[from] DrawingError),
    /// A phase diagram's settings (chain-sweep).
    #[error("phase diagram: {0}")]
    PhaseDiagram(#[from] chain_sweep::scattering::ConfigError),
    /// A grid of chain-sweep.
    #[error(transparent)]
    Grid(#[from] chain_sweep::GridError),
    /// The sweep machinery (thread pool).
    #[error(transparent)]
    Sweep(#[from] chain_sweep::SweepError),
    /// The points of a sweep do not fit its grid.
    #[error(transparent)]
    OutcomeGrid(#[from] crate::outcomes::OutcomeGridError),
    /// A network (chain-network: a cell, a patch, a network model); boxed, as it is large.
    #[error(transparent)]
    Network(Box<chain_network::NetworkError>),
    /// A network's cell (chain-network's ready cells); boxed, as it is large.
    #[error(transparent)]
    Cell(Box<chain_network::CellError>),
    /// A fit or a figure needs more resolved points than the computation gave.
    #[error("{what}: {found} resolved, at least {needed} needed")]
    TooFewPoints {
        /// The fit or figure.
        what: &'static str,
        /// Resolved points.
        found: usize,
        /// Points needed.
        needed: usize,
    },
    /// A mode the figure shows was not found among the lowest modes.
    #[error("no {kind} mode of the {defect} among the lowest {searched} modes")]
    NoSuchMode {
        /// Kink or antikink.
        defect: &'static str,
        /// The mode's kind.
        kind: &'static str,
        /// Modes searched.
        searched: usize,
    },
    /// A figure function returned a figure with another label (a bug in the figure list).
    #[error("the figure function returned a figure labelled `{returned}`")]
    WrongLabel {
        /// The label it returned.
        returned: &'static str,
    },
}

impl From<chain_network::NetworkError> for Cause {
    fn from(e: chain_network::NetworkError) -> Self {
        Cause::Network(Box::new(e))
    }
}

impl From<chain_network::CellError> for Cause {
    fn from(e: chain_network::CellError) -> Self {
        Cause::Cell(Box::new(e))
    }
}

impl FigureError {
    /// `cause` while computing figure `label`.
    pub fn new(label: &'static str, cause: impl Into<Cause>) -> Self {
        Self { label, at: Vec::new(), cause: cause.into() }
    }

    /// Maps any error of the library to a `FigureError` of `label`: `.map_err(FigureError::on(LABEL))`.
    pub fn on<E: Into<Cause>>(label: &'static str) -> impl Fn(E) -> FigureError {
        move |e| FigureError::new(label, e)
    }

    /// The same error at the point `name = value` of the figure (added in order).
    pub fn at(mut self, name: &'static str, value: f64) -> Self {
        self.at.push((name, value));
        self
    }
}

/// A figure function.
pub type FigureFn = fn(&Params, Quality) -> Result<Figure, FigureError>;

/// Every figure: `(label, function)`, statics first, then dynamics.
pub fn all() -> Vec<(&'static str, FigureFn)> {
    let mut all = statics_a::figures();
    all.extend(statics_b::figures());
    all.extend(dynamics::figures());
    all
}

/// `count` evenly spaced values from `from` to `to`, both included (`[from]` for a count of 1,
/// nothing for 0). The one grid of every figure.
pub fn grid(from: f64, to: f64, count: usize) -> Vec<f64> {
    match count {
        0 => Vec::new(),
        1 => vec![from],
        _ => {
            let last = (count - 1) as f64;
            // `to` exactly at the end, not `from + (count - 1) * step` with its rounding.
            (0..count)
                .map(|j| if j + 1 == count { to } else { from + (to - from) * j as f64 / last })
                .collect()
        }
    }
}

/// The paper's chain with `n` rotors at `theta_bar` (`a = 1`).
pub fn chain(p: &Params, n: usize, theta_bar: f64) -> Result<RuntimeChain, ParameterError> {
    RuntimeChain::builder(n, p.r, p.k, theta_bar).mass(p.mass).build()
}

/// The continuum theory of the same chain.
pub fn continuum(p: &Params, theta_bar: f64) -> Result<ContinuumChain, ParameterError> {
    ContinuumChain::new(1.0, p.r, theta_bar, p.k, p.mass)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_holds_both_ends_for_every_count() {
        assert_eq!(grid(0.0, 1.0, 0), Vec::<f64>::new());
        assert_eq!(grid(0.5, 1.0, 1), vec![0.5]);
        assert_eq!(grid(0.5, 1.0, 2), vec![0.5, 1.0]);
        let g = grid(0.05, 0.65, 25);
        assert_eq!((g.len(), g[0], g[24]), (25, 0.05, 0.65));
        assert!((g[1] - 0.075).abs() < 1e-15);
        assert!(g.windows(2).all(|w| w[1] > w[0]));
    }

    #[test]
    fn errors_name_the_figure_and_the_point() {
        let e =
            FigureError::new("fig:x", Cause::TooFewPoints { what: "fit", found: 1, needed: 2 }).at("θ̄", 0.3);
        assert_eq!(e.to_string(), "fig:x (θ̄ = 0.3): fit: 1 resolved, at least 2 needed");
        let e = FigureError::new("fig:y", chain(&Params::default(), 1, 0.5).unwrap_err());
        assert!(e.to_string().starts_with("fig:y: "), "{e}");
    }
}
