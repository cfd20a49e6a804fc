//! Figures of the paper's dynamics (Secs. V and VI, see [`super::all`]): the kinetic energy of a
//! moving kink and antikink (`fig:ketimeplot`), Peierls-Nabarro trapping of a slow antikink
//! (`fig:akpntrapprofile`) (`propagation`, parameters [`Propagation`]), scattering on a stiffness
//! impurity (`fig:k-scatter`, `fig:ak-scatter`, `scattering`) and the scattering phase diagrams
//! (`fig:phasediagram`, `phasediagram`), parameters [`Scattering`].
//!
//! Space-time images show the alternately measured angles `theta_i` (one sign per domain), rows
//! are output times, columns rotors. Scattering runs follow the paper's setup (Sec. VI): the
//! impurity is the middle spring `(n - 1) / 2`, the defect starts 15 sites to its right and moves
//! left (`ScatterSetup::from_the_right` of `rotor_chain::dynamics::scatter`).

use rotor_chain::ParameterError;
use rotor_chain::RuntimeChain;
use rotor_chain::dynamics::track::SpaceTime;

use super::{FigureFn, Params};
use crate::model::Heatmap;

mod phasediagram;
mod propagation;
mod scattering;

pub use phasediagram::phasediagram;
pub(crate) use phasediagram::{label_counts, phase_diagram};
pub use propagation::{akpntrapprofile, ketimeplot};
pub use scattering::{ak_scatter, k_scatter};

/// This module's figures, in the paper's order.
pub fn figures() -> Vec<(&'static str, FigureFn)> {
    vec![
        ("fig:ketimeplot", ketimeplot),
        ("fig:akpntrapprofile", akpntrapprofile),
        ("fig:k-scatter", k_scatter),
        ("fig:ak-scatter", ak_scatter),
        ("fig:phasediagram", phasediagram),
    ]
}

/// Kinks and antikinks moving along a perfect chain, Sec. V (`fig:ketimeplot`,
/// `fig:akpntrapprofile`).
#[derive(Clone, Debug, PartialEq)]
pub struct Propagation {
    /// Equilibrium angle (rad) of `fig:ketimeplot`, and the paper's stated angle of the slow
    /// antikink: 0.58.
    pub theta_bar: f64,
    /// Launch speed (`a/t`) of `fig:ketimeplot`: 2.4, the paper's.
    pub v0: f64,
    /// Equilibrium angle (rad) of the slow antikink of `fig:akpntrapprofile`: 0.575132, where our
    /// Peierls-Nabarro barrier equals the paper's 0.60 (docs/statics.md §3; at 0.58 ours is above
    /// the launch energy and the antikink never leaves its first well).
    pub slow_theta_bar: f64,
    /// Launch speed (`a/t`) of the slow antikink: 1.1, the paper's.
    pub slow_v0: f64,
    /// Where the paper's slow antikink is trapped (rotor index): 35; the damping is bisected for
    /// a stop there.
    pub trap_rotor: f64,
}

impl Default for Propagation {
    fn default() -> Self {
        Self { theta_bar: 0.58, v0: 2.4, slow_theta_bar: 0.575132, slow_v0: 1.1, trap_rotor: 35.0 }
    }
}

/// Scattering on a stiffness impurity on the middle spring, Sec. VI (`fig:k-scatter`,
/// `fig:ak-scatter`, `fig:phasediagram`, and `paper --resolution`).
#[derive(Clone, Debug, PartialEq)]
pub struct Scattering {
    /// Equilibrium angle (rad): 0.28, the paper's Sec. VI.
    pub theta_bar: f64,
    /// The kink runs of `fig:k-scatter`, `(v0, k_i/k)`: the paper's transmitted (4.0, 0.10) and
    /// split (9.6, 0.01).
    pub kink_runs: Vec<(f64, f64)>,
    /// The antikink runs of `fig:ak-scatter`, `(v0, k_i/k)`: the paper's transmitted (4.0, 0.80),
    /// trapped (4.0, 0.70) and reflected (4.8, 0.20).
    pub antikink_runs: Vec<(f64, f64)>,
    /// `k_i/k` range of the speed ratio of `fig:ak-scatter`: 0.7 to 1.3, around the paper's "near
    /// 1", where transmitted antikinks are found at every launch speed below.
    pub slowing_ki: (f64, f64),
    /// Launch speeds (`a/t`) of the speed ratio: 2, 4 and 8, below, at and above the paper's 4.
    pub slowing_v0s: Vec<f64>,
    /// `k_i/k` range of `fig:phasediagram`, log-spaced: 0.01 to 3, so that both the soft
    /// impurities of the kink's split and the stiff ones of the antikink's upper reflection are
    /// resolved.
    pub ki_range: (f64, f64),
    /// `v0` range (`a/t`) of `fig:phasediagram`: 0.5 to 12, the paper's axis.
    pub v0_range: (f64, f64),
    /// Points per axis of `fig:phasediagram` in full (quick: 6): 40, where the four antikink
    /// regimes and their boundaries' slopes are resolved in seconds.
    pub points: usize,
    /// Cross-check every point of `fig:phasediagram` with DOP853 and draw the points where the
    /// integrators disagree as unresolved (chain-sweep's `PhaseDiagram::cross_check`): `true`.
    /// It costs 6.2 times the Verlet points (measured, docs/dynamics.md §6: 3.7 s instead of
    /// 0.6 s for the 40 x 40 antikink diagram in release on 2 cores), affordable at 40 x 40;
    /// `paper --resolution`'s 400 x 400 diagrams are not cross-checked.
    pub cross_check: bool,
    /// `v0` range (`a/t`) of the antikink's stability in a perfect chain: 10 to 25, either side of
    /// the paper's "unstable above 12".
    pub stability_v0: (f64, f64),
    /// The column `k_i/k` and `v0` range of the alternating transmitted / trapped window: 0.75,
    /// 2.5 to 5, around the paper's "k_i/k = 0.75, v0 = 3.6".
    pub window: (f64, (f64, f64)),
    /// `paper --resolution`: the window's `k_i/k` and `v0` ranges at high resolution, 0.6 to 0.9
    /// and 2.5 to 5 (the alternation lies between trapping at 0.6 and transmission at 0.9), and
    /// the points per axis of its two diagrams, 400 (quick: 8).
    pub resolution: ((f64, f64), (f64, f64), usize),
}

impl Default for Scattering {
    fn default() -> Self {
        Self {
            theta_bar: 0.28,
            kink_runs: vec![(4.0, 0.10), (9.6, 0.01)],
            antikink_runs: vec![(4.0, 0.80), (4.0, 0.70), (4.8, 0.20)],
            slowing_ki: (0.7, 1.3),
            slowing_v0s: vec![2.0, 4.0, 8.0],
            ki_range: (0.01, 3.0),
            v0_range: (0.5, 12.0),
            points: 40,
            cross_check: true,
            stability_v0: (10.0, 25.0),
            window: (0.75, (2.5, 5.0)),
            resolution: ((0.6, 0.9), (2.5, 5.0), 400),
        }
    }
}

/// The most rows of a space-time image.
const MAX_IMAGE_ROWS: usize = 400;

/// The chain of `params` at `theta_bar`, with an impurity of stiffness `k_i/k = impurity` on the
/// middle spring.
fn chain(params: &Params, theta_bar: f64, impurity: Option<f64>) -> Result<RuntimeChain, ParameterError> {
    let mut builder = RuntimeChain::builder(params.n, params.r, params.k, theta_bar).mass(params.mass);
    if let Some(ki_ratio) = impurity {
        builder = builder.spring_constant(middle_spring(params), ki_ratio * params.k);
    }
    builder.build()
}

/// The impurity spring of Sec. VI: the middle one.
fn middle_spring(params: &Params) -> usize {
    (params.n - 1) / 2
}

/// `0.97 %`.
fn percent(x: f64) -> String {
    format!("{:.2} %", 100.0 * x)
}

/// The space-time image of `image`, at most [`MAX_IMAGE_ROWS`] rows (every `stride`-th output),
/// coloured on a fixed scale around the domains' `±theta_bar` (a quarter beyond it, so that both
/// domains are strongly coloured even when a few rotors swing far: those take the scale's end
/// colours).
fn space_time_map(title: String, image: &SpaceTime, theta_bar: f64) -> Heatmap {
    let stride = image.times.len().div_ceil(MAX_IMAGE_ROWS).max(1);
    let rows: Vec<usize> = (0..image.times.len()).step_by(stride).collect();
    let n = image.theta.first().map_or(0, Vec::len);
    Heatmap {
        title,
        x_label: "rotor index i".to_owned(),
        y_label: "time t".to_owned(),
        x: (0..n).map(|i| i as f64).collect(),
        y: rows.iter().map(|&r| image.times[r]).collect(),
        values: rows.iter().map(|&r| image.theta[r].clone()).collect(),
        categories: Vec::new(),
        value_label: "θ (rad)".to_owned(),
        log_x: false,
        colour_limit: Some(1.25 * theta_bar),
    }
}
