//! Figures of the paper's linear modes and bond-length impurity (Secs. IV and VII, see
//! [`super::all`]): the localised modes of the kink and the antikink (`modes`:
//! `fig:mode-config`, `fig:w-th`), the zero, soft and tensional modes of a long middle spring
//! ([`longbar`]: `fig:longbar`), and the linkage limit (`linkage`: the two-kink potential and
//! phase portraits `fig:defectiveKL`, two-kink orbits `fig:orbit`, the `(E, l0)` diagram
//! `fig:ELdiagram`).
//!
//! Frequencies are given in the paper's unit `(r/a) sqrt(k/M)` (Sec. VII-A), energies in
//! `M a^2 / t^2` (with `a = 1`), positions in lattice spacings `a`.

use rotor_chain::RuntimeChain;
use rotor_chain::linalg::SymmetricMatrix;
use rotor_chain::statics::modes::{Mode, ModeKind};

use super::{FigureFn, Params};
use crate::model::format_number;

mod linkage;
mod longbar;
mod modes;

pub use linkage::{defective_kl, el_diagram_figure, orbit};
pub use longbar::longbar;
pub use modes::{mode_config, w_th};

/// This module's figures, in the paper's order.
pub fn figures() -> Vec<(&'static str, FigureFn)> {
    vec![
        ("fig:mode-config", mode_config as FigureFn),
        ("fig:w-th", w_th),
        ("fig:longbar", longbar),
        ("fig:defectiveKL", defective_kl),
        ("fig:orbit", orbit),
        ("fig:ELdiagram", el_diagram_figure),
    ]
}

/// The localised modes of Sec. IV (`fig:mode-config`, `fig:w-th`).
#[derive(Clone, Debug, PartialEq)]
pub struct Modes {
    /// Equilibrium angle (rad) of `fig:mode-config` and of the `omega_t / omega_s` row of
    /// `fig:w-th`: 0.58, the paper's chain.
    pub theta_bar: f64,
    /// `theta_bar` range (rad) of `fig:w-th`: 0.05 to 0.65, the paper's axis.
    pub theta_range: (f64, f64),
    /// The least chain length of `fig:w-th` (the larger of this and `Params::n` is used): 240, so
    /// that the walls at `theta_bar = 0.05` (`w = 12.5 a`) do not feel the ends, which at `n = 60`
    /// lift the antikink's translation frequency to `1e-3`.
    pub w_th_rotors: usize,
}

impl Default for Modes {
    fn default() -> Self {
        Self { theta_bar: 0.58, theta_range: (0.05, 0.65), w_th_rotors: 240 }
    }
}

/// The long middle spring of Sec. VII-A (`fig:longbar`).
#[derive(Clone, Debug, PartialEq)]
pub struct LongBar {
    /// Equilibrium angle (rad): 0.58, the paper's chain.
    pub theta_bar: f64,
    /// Rest length of the middle spring, in `a`: 2.30, the paper's, just below `l_critical`.
    pub rest_length: f64,
}

impl Default for LongBar {
    fn default() -> Self {
        Self { theta_bar: 0.58, rest_length: 2.30 }
    }
}

/// The linkage limit of Sec. VII-B (`fig:defectiveKL`, `fig:orbit`, `fig:ELdiagram`).
#[derive(Clone, Debug, PartialEq)]
pub struct Linkage {
    /// Equilibrium angle (rad): 0.58, the paper's chain.
    pub theta_bar: f64,
    /// Rotors per sub-chain: 8, the paper's Fig. `fig:defect-chain-conf`.
    pub rotors: usize,
    /// Impurity rest lengths (in `a`) below, near (just below) and above `l_critical` (2.3051 for
    /// the paper's chain): 2.15, 2.30 and 2.40, the paper's.
    pub rest_lengths: [f64; 3],
}

impl Default for Linkage {
    fn default() -> Self {
        Self { theta_bar: 0.58, rotors: 8, rest_lengths: [2.15, 2.30, 2.40] }
    }
}

/// The paper's frequency unit `(r/a) sqrt(k/M)` (`a = 1`), in `1/t`.
fn unit(params: &Params) -> f64 {
    params.r * (params.k / params.mass).sqrt()
}

/// The middle spring of an `n`-rotor chain, the impurity of Sec. VII-A.
fn middle_spring(n: usize) -> usize {
    (n - 1) / 2
}

/// `v` scaled so that its largest component is `+1` (sign fixed for reproducible plots).
fn normalised(v: &[f64]) -> Vec<f64> {
    let peak = v.iter().copied().max_by(|a, b| a.abs().total_cmp(&b.abs())).unwrap_or(0.0);
    if peak == 0.0 { v.to_vec() } else { v.iter().map(|x| x / peak).collect() }
}

/// `(i, v_i)` for `i` in `range`.
fn indexed(v: &[f64], range: std::ops::Range<usize>) -> Vec<(f64, f64)> {
    range.filter_map(|i| v.get(i).map(|&x| (i as f64, x))).collect()
}

fn first_of(list: &[Mode], kind: ModeKind) -> Option<&Mode> {
    list.iter().find(|m| m.kind == kind)
}

/// The smallest frequency we count as resolved at `theta`: ten times `sqrt(eps ||K|| / (M r^2))`,
/// the rounding of a double-precision `omega^2` (a margin of 100 in `omega^2`); below it a
/// frequency is zero at machine precision.
fn frequency_resolution(model: &RuntimeChain, theta: &[f64], params: &Params) -> f64 {
    let norm = SymmetricMatrix::tangent_stiffness(model, theta).map_or(f64::NAN, |k| k.inf_norm());
    10.0 * (f64::EPSILON * norm / (params.mass * params.r * params.r)).sqrt()
}

/// `"0.8936 (r/a)√(k/M)"`, or `"0 (rounding)"` below the resolution `floor` (both in `1/t`).
fn frequency_label(omega: f64, floor: f64, unit: f64) -> String {
    if omega <= floor {
        "0 (rounding)".to_owned()
    } else {
        format!("{} (r/a)√(k/M)", format_number(omega / unit))
    }
}
