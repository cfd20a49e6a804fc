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

/// The equilibrium angle of Figs. `fig:mode-config`, `fig:longbar` and Sec. VII-B.
const THETA_BAR: f64 = 0.58;

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

/// `"0.8936 (r/a)√(k/M)"`, `"0 (rounding)"` within the resolution `floor` of zero, or for a
/// signed frequency below `-floor` (an unstable direction, `omega^2 < 0`,
/// [`signed_frequency`](rotor_chain::statics::modes::signed_frequency)) `"0.8936i (r/a)√(k/M), unstable"`
/// (all in `1/t`).
fn frequency_label(omega: f64, floor: f64, unit: f64) -> String {
    if omega.abs() <= floor {
        "0 (rounding)".to_owned()
    } else if omega < 0.0 {
        format!("{}i (r/a)√(k/M), unstable", format_number(-omega / unit))
    } else {
        format!("{} (r/a)√(k/M)", format_number(omega / unit))
    }
}
