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

/// The equilibrium angle of the paper's figures (Secs. II, V).
const THETA_BAR: f64 = 0.58;

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
