//! Figures of Secs. II-V (see [`super::all`]): the kink and antikink configurations and cobweb
//! plots (`cobweb`: `fig:kcobweb`, `fig:akcobweb`, `fig:aktheta`), and the antikink's energy and
//! Peierls-Nabarro barrier (`barrier`: `fig:akenergy`, `fig:akconfigpn`, `fig:logvpn-theta`,
//! `fig:logvpn-size`).
//!
//! Units are those of the paper (Appendix B): `a = 1`, so `k a^2` is `params.k`. Energies in the
//! summary rows are absolute (`M a^2 / t^2`, as the paper prints them); energies on the axes are in
//! `k a^2`. The antikink is always the equilibrium with its end rotors held at `-+theta_bar`
//! (`docs/statics.md` §3, "Boundary treatment").

use rotor_chain::statics::StaticsError;
use rotor_chain::statics::antikink::{AntikinkOptions, PeierlsNabarro, peierls_nabarro};

use super::{FigureFn, Params, chain};
use crate::model::{Quantity, Series, Style};

mod barrier;
mod cobweb;

pub use barrier::{akconfigpn, akenergy, logvpn_size, logvpn_theta};
pub use cobweb::{akcobweb, aktheta, kcobweb};

/// This module's figures, in the paper's order.
pub fn figures() -> Vec<(&'static str, FigureFn)> {
    vec![
        ("fig:kcobweb", kcobweb as FigureFn),
        ("fig:akcobweb", akcobweb),
        ("fig:aktheta", aktheta),
        ("fig:akenergy", akenergy),
        ("fig:akconfigpn", akconfigpn),
        ("fig:logvpn-theta", logvpn_theta),
        ("fig:logvpn-size", logvpn_size),
    ]
}

/// The kink and antikink pictures and cobweb plots of Sec. II (`fig:kcobweb`, `fig:akcobweb`,
/// `fig:aktheta`).
#[derive(Clone, Debug, PartialEq)]
pub struct Cobweb {
    /// Rotors of the chain drawn: 16, the paper's "rotors 8 and 9" and "8th spring" at the core.
    pub rotors: usize,
    /// Equilibrium angle `theta_bar` (rad): 0.58, the paper's chain (Sec. II).
    pub theta_bar: f64,
}

impl Default for Cobweb {
    fn default() -> Self {
        Self { rotors: 16, theta_bar: 0.58 }
    }
}

/// The antikink's energy and Peierls-Nabarro barrier of Secs. III and V (`fig:akenergy`,
/// `fig:akconfigpn`, `fig:logvpn-theta`, `fig:logvpn-size`), on chains of `Params::n` rotors.
#[derive(Clone, Debug, PartialEq)]
pub struct Barrier {
    /// Equilibrium angle (rad) of the two equilibria of `fig:akconfigpn` and the energy row of
    /// `fig:akenergy`: 0.58, the paper's Sec. V.
    pub theta_bar: f64,
    /// `theta_bar` range (rad) of `fig:akenergy`: 0.05 to 0.65, the paper's axis.
    pub energy_range: (f64, f64),
    /// `theta_bar` range (rad) of `fig:logvpn-theta`: 0.35 to 0.65, where the barrier is resolved
    /// at `n = 60` (below 0.35 it sinks under the rounding of the two energies).
    pub width_range: (f64, f64),
    /// Equilibrium angle (rad) of the finite-size study `fig:logvpn-size`: 0.40, the paper's.
    pub size_theta_bar: f64,
    /// Chain lengths of `fig:logvpn-size`, first and last (every length between): 16 to 36, where
    /// the correction at 0.40 stays above rounding; `Params::n` is the reference.
    pub sizes: (usize, usize),
}

impl Default for Barrier {
    fn default() -> Self {
        Self {
            theta_bar: 0.58,
            energy_range: (0.05, 0.65),
            width_range: (0.35, 0.65),
            size_theta_bar: 0.40,
            sizes: (16, 36),
        }
    }
}

/// The minimum and saddle of the antikink in the middle of `n` rotors, ends held.
fn pn(p: &Params, n: usize, theta_bar: f64) -> Result<PeierlsNabarro, StaticsError> {
    peierls_nabarro(&chain(p, n, theta_bar)?, &AntikinkOptions::default())
}

/// `k a^2` with `a = 1`.
fn ka2(p: &Params) -> f64 {
    p.k
}

/// `(i, theta_i)`.
fn profile(theta: &[f64]) -> Vec<(f64, f64)> {
    theta.iter().enumerate().map(|(i, &t)| (i as f64, t)).collect()
}

/// Horizontal lines at `+-theta_bar` across `n` rotors.
fn uniform_levels(n: usize, theta_bar: f64) -> [Series; 2] {
    let end = (n - 1) as f64;
    [
        Series::new(Quantity::Reference, "±θ̄", vec![(0.0, theta_bar), (end, theta_bar)], Style::Dashed),
        Series::new(Quantity::Reference, "", vec![(0.0, -theta_bar), (end, -theta_bar)], Style::Dashed),
    ]
}
