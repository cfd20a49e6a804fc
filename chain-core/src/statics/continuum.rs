//! Closed forms of the continuum theory (paper Sec. III, IV, V and the Peierls-Nabarro appendix
//! `app:AppendixPN`) and the exact linear phonons of the uniform chain.
//!
//! Every function cites the equation it implements. Conventions are those of `docs/theory.md`:
//! the field is `u = r sin theta`, `ubar = r sin theta_bar`, and the zero-energy **kink** runs from
//! `+theta_bar` on the left to `-theta_bar` on the right (walls are chosen with [`Charge`], shared
//! with the discrete analysis of [`super::walls`]). Energies are absolute (in units of `k a^2` when
//! `k = a = 1`), frequencies in `1/t` with `t` the unit of time in which `k` and `M` are given.
//!
//! # Continuum energy and its normalisation
//!
//! Eq. (`eq:continuouspotential`) gives the energy of *one spring* in the continuum limit,
//! `a V[theta] = (2k / lbar^2) (a^2/2 u' + ubar^2 - u^2)^2`. Summing over springs, one per lattice
//! spacing, turns into `(1/a) int dx`, so the potential energy of a configuration is
//!
//! ```text
//! V = int dx (2k / (a lbar^2)) (a^2/2 u' + ubar^2 - u^2)^2          (potential_density)
//! ```
//!
//! (the potential terms of Eq. `eq:continuouslagrangian`, with the boundary term kept). On the
//! antikink `u = +ubar tanh(x/w)` the bracket is `2 ubar^2 sech^2(x/w)`; with `int sech^4 = 4w/3`
//! this gives Eq. (`eq:akenergy`), `V = 16 k ubar^3 a / (3 lbar^2)`. A test integrates the density
//! numerically.
//!
//! # The Peierls-Nabarro barrier: derivation and the printed formula
//!
//! The appendix sums the discretised density over sites, `V_PN(X) = sum_n f(n, X)` with
//! `f(n, X) = A sech^4((n a - X)/w)`, `A = 8 k ubar^4 / lbar^2` (Eq. `eq:PNoneterm2`). Poisson
//! summation (Eq. `eq:PNpoisson`) with `t = (n a - X)/w` and the transform
//! `int sech^4(t) e^{-i s t} dt = pi s (s^2 + 4) / (6 sinh(pi s / 2))` ([`sech4_fourier_transform`])
//! gives, exactly,
//!
//! ```text
//! V_PN(X) = A (w/a) [ 4/3 + 2 sum_{m >= 1} F(2 pi m w / a) cos(2 pi m X / a) ]    (pn_potential)
//! ```
//!
//! The first harmonic is a sinusoid of amplitude `2 A (w/a) F(2 pi w/a)`, largest when the centre
//! sits on a site (`X = 0`) and smallest half-way (`X = a/2`). Using `ubar = a^2/(2w)` and
//! `lbar^2 / a^2 = 1 + 4 (r/a)^2 cos^2 theta_bar = 1 + 4 (r/a)^2 - (a/w)^2`:
//!
//! ```text
//! amplitude         = (4 pi^2 / 3) k a^2 (pi^2 + (a/w)^2) / ((1 + 4 (r/a)^2 - (a/w)^2) sinh(pi^2 w / a))
//! barrier (max-min) = 2 * amplitude                                                   (pn_barrier)
//! ```
//!
//! **The printed Eq. (`eq:PNB2`) is the amplitude, not the barrier.** Its `r` dependence and its
//! `lbar` (hidden in `1 + 4 (r/a)^2 - (a/w)^2 = lbar^2/a^2`) are right, and it is `V_PNB / (k a^2)`
//! although printed as `V_PNB`. But the paper defines the barrier as the height of the sinusoid and
//! measures it as the energy difference between the saddle and the minimum (Sec. V, `0.60` at
//! `theta_bar = 0.58`), which is twice the amplitude: the commented-out line of Eq. (`eq:PNB2`),
//! `int 16 k ubar^4/lbar^2 sech^4 e^{-2 pi i n'} dn'`, is `2 f_hat(1)`, the coefficient of the cosine.
//! [`ContinuumChain::pn_barrier`] is our derivation (max - min of the first harmonic),
//! [`ContinuumChain::pn_barrier_as_printed`] the paper's formula times `k a^2`; the ratio is exactly
//! 2, which leaves the paper's conclusion (theory and lattice differ by at least an order of
//! magnitude) intact; measured, the continuum barrier lies 30 to 120 times *above* the lattice one.
//! Both decay as `exp(-pi^2 w / a)`: the slope of `ln V_PNB` against `w/a` tends to
//! [`PN_ASYMPTOTIC_LOG_SLOPE`] `= -pi^2` (the paper's fit to the lattice gives `-10.6`).
//!
//! # Linear phonons of the uniform chain
//!
//! All springs at rest, so the Hessian is the material part alone (`docs/theory.md` §7):
//! `H = k C^T C` with `C` the `(n-1) x n` bidiagonal matrix of `dl_p/dtheta`, constant along the
//! uniform chain: `alpha = dl/dtheta_p`, `beta = dl/dtheta_{p+1}`. From
//! `l^2 = (a + r sin theta_{p+1} - r sin theta_p)^2 + (r cos theta_p + r cos theta_{p+1})^2` at
//! `theta_p = theta_{p+1} = theta_bar` (`dx = a`, `dy = 2 r cos theta_bar`):
//!
//! ```text
//! alpha = -r cos theta_bar (a + 2 r sin theta_bar) / lbar
//! beta  =  r cos theta_bar (a - 2 r sin theta_bar) / lbar
//! lambda(q) = k |alpha + beta e^{iq}|^2 = k (alpha^2 + beta^2 + 2 alpha beta cos q)
//! omega(q)  = sqrt(lambda(q) / (M r^2))
//! ```
//!
//! `alpha beta < 0`, so the band runs from `k (alpha + beta)^2` at `q = 0` to `k (alpha - beta)^2` at
//! `q = pi`. For a free chain of `n` rotors the nonzero eigenvalues of `C^T C` are those of the
//! `(n-1) x (n-1)` tridiagonal Toeplitz matrix `C C^T` (diagonal `alpha^2 + beta^2`, off-diagonal
//! `alpha beta`), so the spectrum is exactly
//! `{0} u {k (alpha^2 + beta^2 + 2 alpha beta cos(j pi/n)), j = 1..n-1}`.
//! The cobweb slope is `F'(theta_bar) = -alpha/beta` (`docs/theory.md` §6).
//!
//! The continuum gap `4 ubar sqrt(k/M) / lbar` ([`ContinuumChain::continuum_phonon_gap`]) is the
//! lattice band bottom `sqrt(k/(M r^2)) |alpha + beta| = 4 ubar cos(theta_bar) sqrt(k/M) / lbar`
//! without the `cos theta_bar`, which the continuum theory drops with the `u^2/r^2` of the kinetic
//! term (Eq. `eq:continuouskinetic`).

use alloc::vec::Vec;
use core::f64::consts::PI;

use chain_geometry::{Key, ParameterError, check_flipper_phase, check_positive, check_rotor_count};

use super::cobweb::slope_closed_form;
use super::walls::Charge;
use crate::math;

/// The large-width slope of `ln V_PNB` against `w/a` (Eq. `eq:PNB2`): `-pi^2`.
pub const PN_ASYMPTOTIC_LOG_SLOPE: f64 = -PI * PI;

/// A continuum closed form asked for something it does not describe.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ContinuumError {
    /// The Lorentz factor of Eq. (`eq:kinksolution`) needs `|v| < c`.
    #[error("a wall moving at v = {speed} is not described: the speed must satisfy |v| < c = {sound_speed}")]
    NotSubsonic {
        /// The wall speed given, in `a / t`.
        speed: f64,
        /// The continuum sound speed `c`, in `a / t`.
        sound_speed: f64,
    },
}

/// The parameters of the continuum theory: lattice spacing `a`, rotor length `r`, equilibrium angle
/// `theta_bar`, spring stiffness `k` and tip mass `M`. Built only through [`ContinuumChain::new`],
/// so every value is finite and positive and `theta_bar` lies in the flipper phase.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContinuumChain {
    a: f64,
    r: f64,
    theta_bar: f64,
    k: f64,
    mass: f64,
}

impl ContinuumChain {
    /// Checks every parameter (chain-geometry's rules: positive lengths, stiffness and mass;
    /// `theta_bar` in the flipper phase `0 < theta_bar < pi/2`, `2 r sin theta_bar < a`).
    pub fn new(a: f64, r: f64, theta_bar: f64, k: f64, mass: f64) -> Result<Self, ParameterError> {
        let a = check_positive(Key::LatticeSpacing, a)?;
        let r = check_positive(Key::RotorLength, r)?;
        let k = check_positive(Key::Stiffness, k)?;
        let mass = check_positive(Key::Mass, mass)?;
        let theta_bar = check_flipper_phase(a, r, theta_bar)?;
        Ok(Self { a, r, theta_bar, k, mass })
    }

    /// Lattice spacing `a`.
    pub fn a(&self) -> f64 {
        self.a
    }

    /// Rotor length `r`.
    pub fn r(&self) -> f64 {
        self.r
    }

    /// Equilibrium angle `theta_bar`.
    pub fn theta_bar(&self) -> f64 {
        self.theta_bar
    }

    /// Spring stiffness `k`.
    pub fn k(&self) -> f64 {
        self.k
    }

    /// Tip mass `M`.
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// `ubar = r sin theta_bar`, the tip's `x`-offset in the uniform states (Sec. III).
    pub fn u_bar(&self) -> f64 {
        self.r * math::sin(self.theta_bar)
    }

    /// `lbar = sqrt(a^2 + 4 r^2 cos^2 theta_bar)`, the rest length (after Eq. `eq:instantlength`).
    pub fn rest_length(&self) -> f64 {
        chain_geometry::rest_length(self.a, self.r, self.theta_bar)
    }

    /// Wall width `w = a^2 / (2 ubar) = a^2 / (2 r sin theta_bar)` (Eq. `eq:kinksolution`, and
    /// Eq. `eq:PNstaticsolution`). In the flipper phase `w > a`.
    pub fn width(&self) -> f64 {
        self.a * self.a / (2.0 * self.u_bar())
    }

    /// Speed of sound `c = (a^2 / lbar) sqrt(k / M)` (after Eq. `eq:kinksolution`).
    pub fn sound_speed(&self) -> f64 {
        self.a * self.a / self.rest_length() * math::sqrt(self.k / self.mass)
    }

    /// The static wall `u(x) = -+ ubar tanh((x - x0)/w)` of Eq. (`eq:kinksolution`) with `v = 0`:
    /// `-` for the kink, `+` for the antikink. (NaN in, NaN out.)
    pub fn field(&self, charge: Charge, x: f64, x0: f64) -> f64 {
        sign(charge) * self.u_bar() * libm::tanh((x - x0) / self.width())
    }

    /// The rotor angle of the static wall, `theta(x) = asin(u(x) / r)`; `|u| <= ubar < r`, so it is
    /// always defined. Rotor `i` of a discrete chain sits at `x = i a`.
    pub fn angle(&self, charge: Charge, x: f64, x0: f64) -> f64 {
        libm::asin(self.field(charge, x, x0) / self.r)
    }

    /// The wall moving at speed `v` (Eq. `eq:kinksolution`):
    /// `u = -+ ubar tanh((x - x0 - v t) / (w sqrt(1 - v^2/c^2)))`, Lorentz-contracted.
    pub fn moving_field(
        &self,
        charge: Charge,
        x: f64,
        t: f64,
        x0: f64,
        v: f64,
    ) -> Result<f64, ContinuumError> {
        let gamma_inv = self.inverse_lorentz_factor(v)?;
        Ok(sign(charge) * self.u_bar() * libm::tanh((x - x0 - v * t) / (self.width() * gamma_inv)))
    }

    /// The rotor angle `asin(u / r)` of [`moving_field`](Self::moving_field).
    pub fn moving_angle(
        &self,
        charge: Charge,
        x: f64,
        t: f64,
        x0: f64,
        v: f64,
    ) -> Result<f64, ContinuumError> {
        Ok(libm::asin(self.moving_field(charge, x, t, x0, v)? / self.r))
    }

    /// The static wall's angles at the rotors `i = 0..n` of a chain (at `x = i a`), centre `x0`;
    /// `n` checked as a chain's rotor count (as [`finite_chain_spectrum`](Self::finite_chain_spectrum)
    /// does), so that no request allocates past [`chain_geometry::MAX_ROTORS`].
    pub fn angle_profile(&self, charge: Charge, n: usize, x0: f64) -> Result<Vec<f64>, ParameterError> {
        let n = check_rotor_count(n)?;
        Ok((0..n).map(|i| self.angle(charge, i as f64 * self.a, x0)).collect())
    }

    /// `sqrt(1 - v^2 / c^2)`, or an error unless `|v| < c`.
    fn inverse_lorentz_factor(&self, v: f64) -> Result<f64, ContinuumError> {
        let c = self.sound_speed();
        if v.is_finite() && v.abs() < c {
            Ok(math::sqrt(1.0 - (v / c) * (v / c)))
        } else {
            Err(ContinuumError::NotSubsonic { speed: v, sound_speed: c })
        }
    }

    /// The potential energy per unit length, `(2k / (a lbar^2)) (a^2/2 u' + ubar^2 - u^2)^2`
    /// (Eq. `eq:continuouspotential` divided by `a`, one spring per lattice spacing).
    pub fn potential_density(&self, u: f64, du_dx: f64) -> f64 {
        let l2 = self.rest_length() * self.rest_length();
        let ub = self.u_bar();
        let bracket = 0.5 * self.a * self.a * du_dx + ub * ub - u * u;
        2.0 * self.k / (self.a * l2) * bracket * bracket
    }

    /// Energy of the static continuum antikink (Eq. `eq:akenergy`):
    /// `V = k a^2 (16/3) (r/a)^3 sin^3 theta_bar / (1 + 4 (r/a)^2 cos^2 theta_bar)` (`0.161 k a^2` at
    /// `theta_bar = 0.58`, `r/a = 0.8`). The kink's is zero.
    pub fn antikink_energy(&self) -> f64 {
        let rho = self.r / self.a;
        let (s, c) = math::sin_cos(self.theta_bar);
        self.k * self.a * self.a * (16.0 / 3.0) * math::powi(rho * s, 3) / (1.0 + 4.0 * rho * rho * c * c)
    }

    /// Frequency of the translation mode of either wall in the continuum (Eq.
    /// `eq:continuumtheoryfrequency1`): zero.
    pub fn translation_mode_frequency(&self) -> f64 {
        0.0
    }

    /// Frequency of the shape mode (Eq. `eq:continuumtheoryfrequency2`):
    /// `omega_s = (r/a) sqrt(12 k / M) sin theta_bar / sqrt(1 + 4 (r/a)^2 cos^2 theta_bar)`,
    /// i.e. `sqrt(3)/2` of [`continuum_phonon_gap`](Self::continuum_phonon_gap) (the phi^4 result).
    pub fn shape_mode_frequency(&self) -> f64 {
        let rho = self.r / self.a;
        let (s, c) = math::sin_cos(self.theta_bar);
        rho * math::sqrt(12.0 * self.k / self.mass) * s / math::sqrt(1.0 + 4.0 * rho * rho * c * c)
    }

    /// The bottom of the phonon band of Eq. (`eq:smallosci`) about `u = ubar`:
    /// `omega_0 = 4 ubar sqrt(k / M) / lbar`.
    pub fn continuum_phonon_gap(&self) -> f64 {
        4.0 * self.u_bar() * math::sqrt(self.k / self.mass) / self.rest_length()
    }

    /// `V_PN(X)`: the discretised continuum energy of the antikink centred at `x` (Eqs.
    /// `eq:PNsum`, `eq:PNoneterm2`), summed exactly by its Poisson series (module doc). Periodic in
    /// `x` with period `a`; maximal at `x = 0` (mod `a`).
    pub fn pn_potential(&self, x: f64) -> f64 {
        let y = self.width() / self.a;
        let ub = self.u_bar();
        let l2 = self.rest_length() * self.rest_length();
        let amplitude = 8.0 * self.k * ub * ub * ub * ub / l2 * y;
        let mut sum = 4.0 / 3.0;
        // w > a in the flipper phase, so each harmonic is at least e^{-pi^2} smaller than the last.
        for m in 1..=64 {
            let term = sech4_fourier_transform(2.0 * PI * f64::from(m) * y);
            if term < 1e-18 {
                break;
            }
            sum += 2.0 * term * math::cos(2.0 * PI * f64::from(m) * x / self.a);
        }
        amplitude * sum
    }

    /// The Peierls-Nabarro barrier of the antikink, our derivation (module doc): the peak-to-peak
    /// height of the first Poisson harmonic,
    /// `V_PNB = (8 pi^2 / 3) k a^2 (pi^2 + (a/w)^2) / ((lbar/a)^2 sinh(pi^2 w / a))`.
    /// Twice [`pn_barrier_as_printed`](Self::pn_barrier_as_printed).
    pub fn pn_barrier(&self) -> f64 {
        2.0 * self.pn_barrier_as_printed()
    }

    /// Eq. (`eq:PNB2`) as printed, times `k a^2`:
    /// `(4 pi^2 / 3) k a^2 (pi^2 + (a/w)^2) / ((1 + 4 (r/a)^2 - (a/w)^2) sinh(pi^2 w / a))`, the
    /// amplitude of the first harmonic (half the barrier).
    pub fn pn_barrier_as_printed(&self) -> f64 {
        let inv = self.a / self.width();
        let rho = self.r / self.a;
        let denominator = (1.0 + 4.0 * rho * rho - inv * inv) * libm::sinh(PI * PI / inv);
        self.k * self.a * self.a * 4.0 * PI * PI * (PI * PI + inv * inv) / (3.0 * denominator)
    }

    /// `d ln V_PNB / d(w/a)` at fixed `r/a` (varying `theta_bar`):
    /// `-2 y^-3/(pi^2 + y^-2) - 2 y^-3/(1 + 4 (r/a)^2 - y^-2) - pi^2 coth(pi^2 y)` with `y = w/a`.
    /// Tends to [`PN_ASYMPTOTIC_LOG_SLOPE`] `= -pi^2` as `w/a` grows.
    pub fn pn_log_slope(&self) -> f64 {
        let y = self.width() / self.a;
        let rho = self.r / self.a;
        let y3 = y * y * y;
        -2.0 / (y3 * (PI * PI + 1.0 / (y * y)))
            - 2.0 / (y3 * (1.0 + 4.0 * rho * rho - 1.0 / (y * y)))
            - PI * PI / libm::tanh(PI * PI * y)
    }

    /// `l_critical = sqrt((2 r sin theta_bar + a)^2 + (2 r cos theta_bar)^2)` (Sec. VII-B): the
    /// length of a spring whose left rotor is at `-theta_bar` and right rotor at `+theta_bar`, the
    /// longest an impurity spring between two uniform sub-chains can be (`2.305 a` in the paper's
    /// chain).
    pub fn l_critical(&self) -> f64 {
        let (s, c) = math::sin_cos(self.theta_bar);
        let dx = 2.0 * self.r * s + self.a;
        let dy = 2.0 * self.r * c;
        math::sqrt(dx * dx + dy * dy)
    }

    /// `E_c(l0) = k (l0 - l_critical)^2 / 2` (Sec. VII-B): the separatrix energy for
    /// `l0 < l_critical` and the least energy `E_min` for `l0 > l_critical`.
    pub fn critical_energy(&self, l0: f64) -> f64 {
        let d = l0 - self.l_critical();
        0.5 * self.k * d * d
    }

    /// `(alpha, beta) = (dl/dtheta_p, dl/dtheta_{p+1})` in the uniform state (module doc). The
    /// compatibility matrix of `docs/theory.md` §7 (per tip displacement) is `(alpha, beta) / r`.
    pub fn spring_length_derivatives(&self) -> (f64, f64) {
        let (s, c) = math::sin_cos(self.theta_bar);
        let l = self.rest_length();
        let alpha = -self.r * c * (self.a + 2.0 * self.r * s) / l;
        let beta = self.r * c * (self.a - 2.0 * self.r * s) / l;
        (alpha, beta)
    }

    /// `lambda(q) = k (alpha^2 + beta^2 + 2 alpha beta cos q)`: the eigenvalue of the Hessian (in
    /// the angles) of the Bloch wave `theta_p = e^{i q p}` of the infinite uniform chain.
    pub fn phonon_stiffness(&self, q: f64) -> f64 {
        let (alpha, beta) = self.spring_length_derivatives();
        self.k * (alpha * alpha + beta * beta + 2.0 * alpha * beta * math::cos(q))
    }

    /// `omega(q) = sqrt(lambda(q) / (M r^2))`, the exact linear dispersion of the uniform chain.
    pub fn phonon_frequency(&self, q: f64) -> f64 {
        self.frequency_of(self.phonon_stiffness(q))
    }

    /// The band edges `[omega(0), omega(pi)]`: `4 r sin theta_bar cos theta_bar sqrt(k/M) / lbar`
    /// and `2 a cos theta_bar sqrt(k/M) / lbar`.
    pub fn phonon_band_edges(&self) -> [f64; 2] {
        [self.phonon_frequency(0.0), self.phonon_frequency(PI)]
    }

    /// The exact Hessian spectrum of the uniform free chain of `n` rotors, ascending:
    /// `{0} u {k (alpha^2 + beta^2 + 2 alpha beta cos(j pi / n)), j = 1..n-1}` (module doc).
    pub fn finite_chain_spectrum(&self, n: usize) -> Result<Vec<f64>, ParameterError> {
        let n = check_rotor_count(n)?;
        let mut out = Vec::with_capacity(n);
        out.push(0.0);
        out.extend((1..n).map(|j| self.phonon_stiffness(j as f64 * PI / n as f64)));
        out.sort_by(f64::total_cmp);
        Ok(out)
    }

    /// The mode frequencies `sqrt(lambda / (M r^2))` of
    /// [`finite_chain_spectrum`](Self::finite_chain_spectrum).
    pub fn finite_chain_frequencies(&self, n: usize) -> Result<Vec<f64>, ParameterError> {
        Ok(self.finite_chain_spectrum(n)?.into_iter().map(|l| self.frequency_of(l)).collect())
    }

    fn frequency_of(&self, stiffness: f64) -> f64 {
        math::sqrt(stiffness.max(0.0) / (self.mass * self.r * self.r))
    }

    /// The cobweb slope `F'(theta_bar) = (a + 2 r sin theta_bar)/(a - 2 r sin theta_bar) = -alpha/beta`
    /// (`docs/theory.md` §6).
    pub fn cobweb_slope(&self) -> f64 {
        slope_closed_form(self.a, self.r, self.theta_bar)
    }

    /// The decay length `a / ln F'(theta_bar)` of deformations of the uniform state (Sec. II);
    /// tends to `w / 2` as `theta_bar -> 0`, the decay of the continuum wall's tails.
    pub fn decay_length(&self) -> f64 {
        self.a / math::ln(self.cobweb_slope())
    }
}

/// `int sech^4(t) e^{-i s t} dt = pi s (s^2 + 4) / (6 sinh(pi s / 2))` (even in `s`, `4/3` at `s = 0`,
/// zero once `sinh` overflows).
pub fn sech4_fourier_transform(s: f64) -> f64 {
    let x = 0.5 * PI * s.abs();
    // x / sinh x, with its limit at 0.
    let ratio = if x < 1e-4 { 1.0 - x * x / 6.0 } else { x / libm::sinh(x) };
    (s * s + 4.0) / 3.0 * ratio
}

fn sign(charge: Charge) -> f64 {
    match charge {
        Charge::Kink => -1.0,
        Charge::Antikink => 1.0,
    }
}
