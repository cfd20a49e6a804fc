//! The linkage limit of paper Sec. VII-B and the kink coordinates of Appendix C (`App: AppendixC`).
//!
//! Two sub-chains of `m` rotors each (the paper uses `m = 8`) have rigid bars of length `lbar`
//! for springs, and are joined head to head by one soft impurity spring of rest length `l0` and
//! stiffness `k`. Each sub-chain keeps one degree of freedom, the position of its kink, so the
//! chain has two: `x1`, `x2`.
//!
//! # Orientation and positions
//!
//! The left sub-chain is rotors `0..m` of the full chain (far end `0`, head `m - 1`), the right one
//! rotors `m..2m` (head `m`, far end `2m - 1`). The chain is mirror-symmetric,
//! `l(theta_p, theta_{p+1}) = l(-theta_{p+1}, -theta_p)`, so the right sub-chain read from its far
//! end with negated angles, `phi_j = -theta_{2m-1-j}`, is a left sub-chain. Every sub-chain quantity
//! below is in this **left frame**: angles `phi_0..phi_{m-1}` from the far end to the head, and a
//! kink runs from `+theta_bar` (far-end side) to `-theta_bar` (head side), the zero-energy kink of
//! `docs/theory.md` §4 in both sub-chains. Positions are the paper's (it counts from 1): rotor `j`
//! sits at `j + 1`, the head at `x_head = m`, and the far end's collinear point at `0`.
//!
//! # Kink coordinate (Appendix C), [`kink_coordinate`]
//!
//! `|x|` interpolates the sign change of the angles, `|x| = j + phi_{j-1} / (phi_{j-1} - phi_j)`
//! between rotors `j - 1 > 0 >= j`, so a vertical rotor carries the kink at its own position. When the
//! kink reaches the far end, the end rotor turns until it is collinear with its bar (`x = 0`) and
//! then flips over: the other rotors retrace their angles with the end rotor on the other root of
//! the branch solve. The sign of `x` is that lean, `sign(a cos phi_0 + r sin(phi_0 + phi_1))` (this
//! is `-dl_0/dphi_0`, which vanishes exactly at the collinear point and is positive on the flipper
//! branch); `|x|` is computed with the end rotor put back on the flipper branch, so flipping the end
//! rotor negates `x`. Between the collinear point and the vertical end rotor,
//! `|x| = 1 - phi_0 / phi_c` with `phi_c = -atan2(a + r sin phi_1, r cos phi_1)` the collinear angle
//! (the paper's linear interpolation of the end rotor's angle between `0` and `1`). The paper stops
//! at the head; we continue with the mirror of the end rule, `|x| = m + phi_{m-1} / phi_h` with
//! `phi_h = atan2(a - r sin phi_{m-2}, r cos phi_{m-2})` the head's collinear angle, up to `m + 1`.
//!
//! # Reduced model
//!
//! The head angle follows the continuum kink (Sec. VII-B):
//!
//! ```text
//! sin theta~(x) = sin theta_bar tanh((|x| - x_head) / w)                                   (head_angle)
//! ```
//!
//! even in `x` (the far-end flip), with a cusp at `x = 0`. Positions `x` count sites, so `w` here
//! and below is the width in sites, `w / a` (the paper's `a = 1`): the model is the same for a
//! chain with all lengths scaled. **The printed equation has
//! `r sin theta_bar (|x| - x_head) / a^2 = (|x| - x_head) / (2w)`: a profile twice as wide as
//! Eq. (`eq:kinksolution`)**, whose argument is `(x - x0) / (a^2 / 2 ubar) = (x - x0) / w`. We use
//! `w` (a test shows that the discrete linkage follows `w`, not `2w`, at small `theta_bar`);
//! [`LinkageChain::with_profile_width`] with [`LinkageChain::printed_profile_width`] reproduces the
//! printed equation. Beyond the head (`|x| > x_head`) the formula describes a kink that has left
//! through the head, `theta~ -> +theta_bar`; the paper draws `|x| <= 8`.
//!
//! The impurity spring joins the two heads, `l12 = l(theta~(x1), -theta~(x2))` (rotor `m - 1` at
//! `theta~(x1)`, rotor `m` at `-theta~(x2)`), and
//!
//! ```text
//! V(x1, x2; l0) = k (l12 - l0)^2 / 2                                                       (potential)
//! ```
//!
//! for the harmonic law of the paper. The impurity spring is a two-rotor [`ChainModel`]
//! ([`LinkageChain::with_impurity`]): `V` is its energy at the two head angles and the forces on
//! the kinks are its generated gradient times the head slopes `dtheta~/dx`, so any spring law
//! (a `#[rotor_chain(n = 2, law = ..)]` struct) is the law of the reduced model; nothing is
//! derived by hand here.
//!
//! At `x1 = x2 = 0` both heads sit at `-+theta_bar tanh(x_head / w)`, so `l12 = l_critical` up to
//! `O(exp(-2 x_head / w))`: the impurity is maximally stretched and `V = E_c = k (l0 - l_critical)^2 / 2`.
//!
//! **Kink mass.** `T = sum_j M r^2 thetadot_j^2 / 2` over the `m` rotors of a sub-chain, each on the
//! continuum profile `sin theta_j = sin theta_bar tanh((|x| - (j + 1)) / w)`, is `m(x) xdot^2 / 2` with
//!
//! ```text
//! m(x) = M r^2 sum_j (dtheta_j/dx)^2 = (M r^2 / w^2) sum_j s^2 sech^4(xi_j) / (1 - s^2 tanh^2(xi_j)),
//! xi_j = (|x| - j - 1) / w,  s = sin theta_bar                                              (kink_mass)
//! ```
//!
//! so `p = m(x) xdot` and `H = p1^2/(2 m(x1)) + p2^2/(2 m(x2)) + V(x1, x2; l0)`. Deep in a long
//! sub-chain `m -> 4 M ubar^2 a / (3 w)` (small `theta_bar`), the continuum kink's mass per site
//! squared (the continuum's `4 M ubar^2 / (3 w a)` per length squared, times `a^2`); it falls as the
//! kink leaves the sub-chain. The paper writes `T(p1, p2)` as if the mass were constant:
//! [`KinkMass::Constant`] gives that model.
//!
//! **Dynamics.** `H` is not separable when `m` depends on `x`, so [`LinkageChain::trajectory`] uses
//! the generalised Stormer-Verlet (leapfrog) method for `H(q, p)` (Hairer, Lubich and Wanner,
//! *Geometric Numerical Integration*, Sec. VI.3): symplectic, time-reversible, second order. The
//! implicit half kick is a quadratic in `p` solved exactly, the implicit drift a scalar Newton
//! solve per kink. With a constant mass it is velocity Verlet. The `|x|` of the head formula puts a
//! cusp in `V` and `m` at each far end (`x = 0`; the real linkage is smooth there, the end rotor
//! simply passing its collinear point), and a step across a cusp would feel the jump of the force
//! and lose `O(dt)` energy per crossing. So each step is taken on the half lines the kinks start
//! on (the one-sided formulas continue smoothly past `0`), and a step in which a kink crosses is
//! split where it lands on `0` (regula falsi) and finished on the other side. The energy error then
//! stays `O(dt^2)` and bounded (tested over `10^5` steps with crossings).
//!
//! **Regimes** (Figs. `fig:KLphaseportrait`, `fig:orbit`, `fig:ELdiagram`), for `l0 > lbar`: below
//! `l_critical` one kink (the other at `x2 = 0`) has minima at `+-x_eq` (about `+-8` in the paper)
//! and a maximum `E_c` at `0`; as `l0 -> l_critical` they merge at `0` (supercritical pitchfork).
//! With two kinks and `E < E_c` the accessible region of the `(x1, x2)` plane is a square annulus
//! (never both kinks near the far ends), with `E >= E_c` a disk; above `l_critical` it is a disk and
//! energies below `E_min = k (l0 - l_critical)^2 / 2` are forbidden.

use alloc::vec::Vec;

use chain_geometry::{Key, ParameterError, check_positive, check_rotor_count, spring_length};

use super::continuum::ContinuumChain;
use crate::branch;
use crate::error::BranchError;
use crate::math;
use crate::model::ChainModel;
use crate::runtime::RuntimeChain;

/// A linkage computation that could not be carried out.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LinkageError {
    #[error(transparent)]
    /// The chain's parameters are invalid.
    Parameter(#[from] ParameterError),
    #[error("branch solve: {0}")]
    /// The branch solve failed.
    Branch(#[from] BranchError),
    #[error("{what} must be finite, got {value}")]
    /// A non-finite input.
    NotFinite {
        /// Which input.
        what: &'static str,
        /// The value found.
        value: f64,
    },
    #[error("{what} must be a finite number > 0, got {value}")]
    /// An input that must be positive is not.
    NotPositive {
        /// Which input.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// The sub-chain's angles do not change sign once, from `+` (far end) to `-` (head).
    #[error("not a single kink: rotor {rotor} leans back to theta = {theta} after the sign change")]
    NotAKink {
        /// The rotor that leans back.
        rotor: usize,
        /// Its angle, radians.
        theta: f64,
    },
    /// The head rotor has turned past collinear with its bar: outside the coordinate's range.
    #[error("the head rotor has flipped over its bar (lean {lean} < 0): the kink coordinate ends at m + 1")]
    HeadFlipped {
        /// The head rotor's lean.
        lean: f64,
    },
    /// The regimes of Sec. VII-B are for `l0 > lbar`.
    #[error("l0 = {rest_length} must exceed the bar length lbar = {bar_length} (paper Sec. VII-B)")]
    RestLengthNotAboveBar {
        /// The impurity rest length `l0`.
        rest_length: f64,
        /// The bar length `lbar`.
        bar_length: f64,
    },
    /// The implicit half kick has no real solution: the step is too large for the mass gradient.
    #[error("step {step}: dt = {dt} is too large for the kink mass gradient (half kick has no real root)")]
    StepTooLarge {
        /// The step.
        step: usize,
        /// The time step, in `t`.
        dt: f64,
    },
    /// The implicit drift did not converge.
    #[error("step {step}: the implicit drift did not converge (last correction {residual:e})")]
    StepNotConverged {
        /// The step.
        step: usize,
        /// The residual reached (relative, as the message says).
        residual: f64,
    },
    /// The state left the finite numbers (a kink escaped through a head, where its mass vanishes).
    #[error("step {step}: the state is no longer finite")]
    StateNotFinite {
        /// The step.
        step: usize,
    },
    /// The impurity model must be one spring between two rotors.
    #[error("the impurity model must have 2 rotors (one spring), it has {rotors}")]
    ImpurityNotOneSpring {
        /// Rotors of the impurity model.
        rotors: usize,
    },
    /// The impurity model's geometry differs from the chain's.
    #[error("the impurity model's {what} is {impurity}, the chain's is {chain}: they must be equal")]
    ImpurityGeometry {
        /// What the value is (the name of the input or quantity).
        what: &'static str,
        /// The impurity model's value.
        impurity: f64,
        /// The chain's value.
        chain: f64,
    },
}

/// The effective mass of each kink.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum KinkMass {
    /// `m(x)` from the continuum profile (module doc): the default.
    Profile,
    /// A constant mass, the paper's `T(p1, p2)`.
    Constant(f64),
}

/// A point of the two-kink phase space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhaseState {
    /// Position of the first kink (Appendix C coordinate), in sites.
    pub x1: f64,
    /// Position of the second kink, in sites.
    pub x2: f64,
    /// Momentum conjugate to `x1`: `m(x1) dx1/dt`, in `M a^2 / t` (a length squared: `x` is in sites).
    pub p1: f64,
    /// Momentum conjugate to `x2`.
    pub p2: f64,
}

/// One recorded step of [`LinkageChain::trajectory`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrajectoryPoint {
    /// Time, in `t`.
    pub t: f64,
    /// Position of the first kink, in sites.
    pub x1: f64,
    /// Position of the second kink, in sites.
    pub x2: f64,
    /// Momentum conjugate to `x1`.
    pub p1: f64,
    /// Momentum conjugate to `x2`.
    pub p2: f64,
    /// `H(x1, x2, p1, p2)`.
    pub energy: f64,
}

/// An equilibrium of one kink with the other held at `x2 = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Equilibrium {
    /// Where, in the kink coordinate.
    pub x: f64,
    /// `V(x, 0)`.
    pub energy: f64,
    /// Whether it is a minimum of the reduced potential.
    pub stable: bool,
}

/// The accessible region of the `(x1, x2)` plane at energy `E` (Fig. `fig:ELdiagram`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Region {
    /// `l0 <= l_critical`, `E < E_c`: the kinks take turns leaving the impurity.
    Annulus,
    /// Both kinks may leave the impurity at once.
    Disk,
    /// Below the least energy (`E < 0`, or `E < E_min` for `l0 > l_critical`).
    Forbidden,
}

impl Region {
    /// The region at energy `energy` for impurity rest length `l0 > lbar` (Fig. `fig:ELdiagram`).
    pub fn classify(chain: &ContinuumChain, l0: f64, energy: f64) -> Result<Self, LinkageError> {
        check_above_bar(chain, l0)?;
        if !energy.is_finite() {
            return Err(LinkageError::NotFinite { what: "energy", value: energy });
        }
        let e_c = chain.critical_energy(l0);
        Ok(if energy < 0.0 {
            Region::Forbidden
        } else if l0 <= chain.l_critical() {
            if energy < e_c { Region::Annulus } else { Region::Disk }
        } else if energy < e_c {
            Region::Forbidden
        } else {
            Region::Disk
        })
    }
}

/// The curve `(l0, E_c(l0))` of Fig. `fig:ELdiagram` on the given `l0 > lbar`: the annulus/disk
/// boundary left of `l_critical`, the edge of the forbidden region right of it.
pub fn el_diagram(chain: &ContinuumChain, l0s: &[f64]) -> Result<Vec<[f64; 2]>, LinkageError> {
    l0s.iter().map(|&l0| Ok([check_above_bar(chain, l0)?, chain.critical_energy(l0)])).collect()
}

fn check_above_bar(chain: &ContinuumChain, l0: f64) -> Result<f64, LinkageError> {
    let bar = chain.rest_length();
    if l0.is_finite() && l0 > bar {
        Ok(l0)
    } else {
        Err(LinkageError::RestLengthNotAboveBar { rest_length: l0, bar_length: bar })
    }
}

/// The Appendix C coordinate of the kink in a sub-chain, from its angles in the left frame (far
/// end first, head last; module doc). Positive when the end rotor leans on the flipper branch.
pub fn kink_coordinate(chain: &ContinuumChain, angles: &[f64]) -> Result<f64, LinkageError> {
    let m = check_rotor_count(angles.len())?;
    if let Some(&bad) = angles.iter().find(|t| !t.is_finite()) {
        return Err(LinkageError::NotFinite { what: "sub-chain angle", value: bad });
    }
    let (a, r) = (chain.a(), chain.r());
    let (before_head, head) = (angles[m - 2], angles[m - 1]);
    let head_lean = a * math::cos(head) - r * math::sin(before_head + head);
    if head_lean < 0.0 {
        return Err(LinkageError::HeadFlipped { lean: head_lean });
    }
    let (end, next) = (angles[0], angles[1]);
    let flipped = a * math::cos(end) + r * math::sin(end + next) < 0.0;
    // The end rotor on the flipper branch: itself, or the other root of its bar.
    let end = if flipped {
        branch::previous_angles(0, a, r, r, spring_length(a, r, r, end, next), next)?[0]
    } else {
        end
    };
    let psi = |j: usize| if j == 0 { end } else { angles[j] };
    let boundary = (0..m).find(|&j| psi(j) <= 0.0).unwrap_or(m);
    if let Some(rotor) = (boundary..m).find(|&j| psi(j) > 0.0) {
        return Err(LinkageError::NotAKink { rotor, theta: psi(rotor) });
    }
    let magnitude = if boundary == 0 {
        let collinear = -math::atan2(a + r * math::sin(next), r * math::cos(next));
        (1.0 - end / collinear).clamp(0.0, 1.0)
    } else if boundary == m {
        let collinear = math::atan2(a - r * math::sin(before_head), r * math::cos(before_head));
        m as f64 + (head / collinear).min(1.0)
    } else {
        let (t0, t1) = (psi(boundary - 1), psi(boundary));
        boundary as f64 + t0 / (t0 - t1)
    };
    Ok(if flipped { -magnitude } else { magnitude })
}

/// The reduced two-kink model of Sec. VII-B (module doc).
///
/// The impurity spring is a [`ChainModel`] of two rotors, `M`: its energy, length and gradient
/// (the generated code of a `#[rotor_chain]` struct, or a [`RuntimeChain`]'s kernel) give `V`,
/// `l12` and the forces on the kinks, so a custom spring law is the law of the linkage limit too.
/// [`LinkageChain::new`] uses the harmonic law of Sec. VII-B.
#[derive(Clone, Debug, PartialEq)]
pub struct LinkageChain<M = RuntimeChain> {
    chain: ContinuumChain,
    rotors: usize,
    impurity: M,
    rest_length: f64,
    profile_width: f64,
    kink_mass: KinkMass,
}

impl LinkageChain<RuntimeChain> {
    /// Two sub-chains of `rotors` rotors each and a harmonic impurity spring of rest length `l0`
    /// and the chain's stiffness `k`; profile width `w`, mass [`KinkMass::Profile`].
    pub fn new(chain: ContinuumChain, rotors: usize, l0: f64) -> Result<Self, LinkageError> {
        let l0 = check_positive(Key::RestLength, l0)?;
        let impurity = RuntimeChain::builder(2, chain.r(), chain.k(), chain.theta_bar())
            .lattice_spacing(chain.a())
            .mass(chain.mass())
            .spring_rest_length(0, l0)
            .build()?;
        Self::with_impurity(chain, rotors, impurity)
    }
}

impl<M: ChainModel> LinkageChain<M> {
    /// Two sub-chains of `rotors` rotors each joined by the spring of `impurity`, a chain of two
    /// rotors whose lattice spacing and rotor lengths are the chain's, with any spring law and
    /// the rest length of its spring as `l0`.
    pub fn with_impurity(chain: ContinuumChain, rotors: usize, impurity: M) -> Result<Self, LinkageError> {
        let rotors = check_rotor_count(rotors)?;
        if impurity.rotor_count() != 2 {
            return Err(LinkageError::ImpurityNotOneSpring { rotors: impurity.rotor_count() });
        }
        let geometry = [
            ("lattice spacing", impurity.lattice_spacing(), chain.a()),
            ("first rotor length", impurity.rotor_length(0), chain.r()),
            ("second rotor length", impurity.rotor_length(1), chain.r()),
        ];
        for (what, impurity, chain) in geometry {
            if impurity != chain {
                return Err(LinkageError::ImpurityGeometry { what, impurity, chain });
            }
        }
        let rest_length = check_positive(Key::RestLength, impurity.rest_length(0))?;
        Ok(Self {
            chain,
            rotors,
            impurity,
            rest_length,
            profile_width: chain.width() / chain.a(),
            kink_mass: KinkMass::Profile,
        })
    }

    /// The impurity spring's model.
    pub fn impurity(&self) -> &M {
        &self.impurity
    }

    /// The same model with head profile width `width`, in sites (default: the continuum `w / a`).
    pub fn with_profile_width(&self, width: f64) -> Result<Self, LinkageError>
    where
        M: Clone,
    {
        if !(width.is_finite() && width > 0.0) {
            return Err(LinkageError::NotPositive { what: "profile width", value: width });
        }
        Ok(Self { profile_width: width, ..self.clone() })
    }

    /// The same model with another kink mass.
    pub fn with_kink_mass(&self, kink_mass: KinkMass) -> Result<Self, LinkageError>
    where
        M: Clone,
    {
        if let KinkMass::Constant(m) = kink_mass {
            check_positive(Key::Mass, m)?;
        }
        Ok(Self { kink_mass, ..self.clone() })
    }

    /// The width `a^2 / (r sin theta_bar) = 2w` that the printed Sec. VII-B equation implies, in
    /// sites (`2w / a`), as [`LinkageChain::profile_width`].
    pub fn printed_profile_width(&self) -> f64 {
        2.0 * self.chain.width() / self.chain.a()
    }

    /// The chain parameters.
    pub fn chain(&self) -> &ContinuumChain {
        &self.chain
    }

    /// Rotors per sub-chain, `m`.
    pub fn rotors(&self) -> usize {
        self.rotors
    }

    /// The impurity's rest length `l0`.
    pub fn impurity_rest_length(&self) -> f64 {
        self.rest_length
    }

    /// The head width used for the profile, in sites (the positions `x` are): `w / a` unless
    /// [`LinkageChain::with_profile_width`] set another.
    pub fn profile_width(&self) -> f64 {
        self.profile_width
    }

    /// The head's position `x_head = m`.
    pub fn head_position(&self) -> f64 {
        self.rotors as f64
    }

    /// Angle and `d/dx` of the rotor at position `at` for a kink at `x` (left frame), on `side`:
    /// `|x|` is read as `side * x`, so `side = sign(x)` is the model and a fixed `side = +-1` is
    /// the smooth continuation of one half past `x = 0` (used by the integrator).
    fn rotor_angle(&self, x: f64, at: f64, side: f64) -> (f64, f64) {
        let (theta, slope, _) = wall_angle(self.sin_bar(), (side * x - at) / self.profile_width);
        (theta, side * slope / self.profile_width)
    }

    fn sin_bar(&self) -> f64 {
        math::sin(self.chain.theta_bar())
    }

    /// The head angle `theta~(x)` (Sec. VII-B, module doc), in the left frame.
    pub fn head_angle(&self, x: f64) -> f64 {
        self.rotor_angle(x, self.head_position(), crate::math::sign(x)).0
    }

    /// `dtheta~/dx` (zero at `x = 0`, where the two one-sided slopes are opposite).
    pub fn head_angle_slope(&self, x: f64) -> f64 {
        self.rotor_angle(x, self.head_position(), crate::math::sign(x)).1
    }

    /// The continuum angles of one sub-chain's rotors for a kink at `x`, in the left frame.
    pub fn sub_chain_profile(&self, x: f64) -> Vec<f64> {
        (1..=self.rotors).map(|pos| self.rotor_angle(x, pos as f64, crate::math::sign(x)).0).collect()
    }

    /// All `2m` angles of the chain in the real frame: the left sub-chain as is, the right one
    /// mirrored (`theta_{2m-1-j} = -phi_j`).
    pub fn chain_profile(&self, x1: f64, x2: f64) -> Vec<f64> {
        let mut out = self.sub_chain_profile(x1);
        out.extend(self.sub_chain_profile(x2).into_iter().rev().map(|phi| -phi));
        out
    }

    /// The head angles `(theta~(x1), -theta~(x2))` of the impurity's two rotors and their
    /// derivatives `(dtheta~/dx1, -dtheta~/dx2)`, on the given sides.
    fn heads(&self, x1: f64, x2: f64, sides: [f64; 2]) -> ([f64; 2], [f64; 2]) {
        let (t1, d1) = self.rotor_angle(x1, self.head_position(), sides[0]);
        let (t2, d2) = self.rotor_angle(x2, self.head_position(), sides[1]);
        ([t1, -t2], [d1, -d2])
    }

    /// The impurity spring's length `l12(x1, x2)`, from the impurity model.
    pub fn impurity_length(&self, x1: f64, x2: f64) -> f64 {
        let (angles, _) = self.heads(x1, x2, [crate::math::sign(x1), crate::math::sign(x2)]);
        let mut l = [0.0];
        self.impurity.spring_lengths_into(&angles, &mut l);
        l[0]
    }

    /// `V(x1, x2; l0)`: the impurity model's energy with its rotors at the two heads (for the
    /// harmonic law of [`LinkageChain::new`], `k (l12 - l0)^2 / 2`, Sec. VII-B).
    pub fn potential(&self, x1: f64, x2: f64) -> f64 {
        let (angles, _) = self.heads(x1, x2, [crate::math::sign(x1), crate::math::sign(x2)]);
        self.impurity.energy(&angles)
    }

    /// `[dV/dx1, dV/dx2]`: the impurity model's generated gradient in its two angles times the
    /// head slopes (zero component at `x_i = 0`, the cusp).
    pub fn potential_gradient(&self, x1: f64, x2: f64) -> [f64; 2] {
        self.gradient_on(x1, x2, [crate::math::sign(x1), crate::math::sign(x2)])
    }

    fn gradient_on(&self, x1: f64, x2: f64, sides: [f64; 2]) -> [f64; 2] {
        let (angles, slopes) = self.heads(x1, x2, sides);
        let mut g = [0.0; 2];
        self.impurity.gradient_into(&angles, &mut g);
        [g[0] * slopes[0], g[1] * slopes[1]]
    }

    /// The critical energy `E_c`: the impurity's energy at `l_critical`, with its rotors at
    /// `-theta_bar` and `+theta_bar` (for the harmonic law the paper's `k (l0 - l_critical)^2 / 2`).
    pub fn critical_energy(&self) -> f64 {
        let tb = self.chain.theta_bar();
        self.impurity.energy(&[-tb, tb])
    }

    /// The model's own `V(0, 0)`: `E_c` up to the `tanh` tail `O(exp(-2 x_head / w))`.
    pub fn separatrix_energy(&self) -> f64 {
        self.potential(0.0, 0.0)
    }

    /// The accessible region at energy `energy` (requires `l0 > lbar`), with this model's `E_c`
    /// ([`LinkageChain::critical_energy`]; [`Region::classify`] is the harmonic closed form). The
    /// law's least energy is taken as 0, at `l0`.
    pub fn region(&self, energy: f64) -> Result<Region, LinkageError> {
        check_above_bar(&self.chain, self.rest_length)?;
        if !energy.is_finite() {
            return Err(LinkageError::NotFinite { what: "energy", value: energy });
        }
        let e_c = self.critical_energy();
        Ok(if energy < 0.0 {
            Region::Forbidden
        } else if self.rest_length <= self.chain.l_critical() {
            if energy < e_c { Region::Annulus } else { Region::Disk }
        } else if energy < e_c {
            Region::Forbidden
        } else {
            Region::Disk
        })
    }

    /// The kink mass `m(x)` and `dm/dx` on `side` (see `rotor_angle`).
    fn mass_and_slope(&self, x: f64, side: f64) -> (f64, f64) {
        match self.kink_mass {
            KinkMass::Constant(m) => (m, 0.0),
            KinkMass::Profile => {
                let s = self.sin_bar();
                let w = self.profile_width;
                let (mut sum, mut dsum) = (0.0, 0.0);
                for pos in 1..=self.rotors {
                    let (_, h, dh) = wall_angle(s, (side * x - pos as f64) / w);
                    sum += h * h;
                    dsum += 2.0 * h * dh;
                }
                let scale = self.chain.mass() * self.chain.r() * self.chain.r() / (w * w);
                (scale * sum, side * scale * dsum / w)
            }
        }
    }

    /// The effective kink mass `m(x)` (module doc).
    pub fn kink_mass(&self, x: f64) -> f64 {
        self.mass_and_slope(x, crate::math::sign(x)).0
    }

    /// `dm/dx`.
    pub fn kink_mass_slope(&self, x: f64) -> f64 {
        self.mass_and_slope(x, crate::math::sign(x)).1
    }

    /// `H(x1, x2, p1, p2) = p1^2/(2 m(x1)) + p2^2/(2 m(x2)) + V(x1, x2; l0)`.
    pub fn hamiltonian(&self, s: &PhaseState) -> f64 {
        0.5 * s.p1 * s.p1 / self.kink_mass(s.x1)
            + 0.5 * s.p2 * s.p2 / self.kink_mass(s.x2)
            + self.potential(s.x1, s.x2)
    }

    /// One kink with the other held at `x2 = 0`: `p^2 / (2 m(x)) + V(x, 0)`.
    pub fn one_kink_hamiltonian(&self, x: f64, p: f64) -> f64 {
        0.5 * p * p / self.kink_mass(x) + self.potential(x, 0.0)
    }

    /// `(x, V(x, 0))` on the grid `xs`: the red curve of Fig. `fig:KLphaseportrait`.
    pub fn potential_profile(&self, xs: &[f64]) -> Vec<[f64; 2]> {
        xs.iter().map(|&x| [x, self.potential(x, 0.0)]).collect()
    }

    /// The equilibria of one kink with `x2 = 0`, by `x`. For `l0` between the plateau
    /// `l(theta_bar, -theta~(0))` (kink gone through the head) and `l12(0, 0)`: minima at `+-x_eq`
    /// (`V = 0`) and the maximum `E_c` at `0`. For `l0 >= l12(0, 0)`: one minimum at `0` (the
    /// pitchfork has merged). Below the plateau: only the maximum at `0` (the minima are at infinity).
    pub fn equilibria(&self) -> Vec<Equilibrium> {
        let (a, r) = (self.chain.a(), self.chain.r());
        let lowest = self.head_angle(0.0);
        let length = |t: f64| spring_length(a, r, r, t, -lowest);
        let top = Equilibrium { x: 0.0, energy: self.separatrix_energy(), stable: false };
        let l0 = self.rest_length;
        if l0 >= length(lowest) {
            return alloc::vec![Equilibrium { stable: true, ..top }];
        }
        if l0 <= length(self.chain.theta_bar()) {
            return alloc::vec![top];
        }
        // l(t, phi) falls as t rises on [-theta_bar, theta_bar] (flipper phase): bisection.
        let (mut lo, mut hi) = (lowest, self.chain.theta_bar());
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid == lo || mid == hi {
                break;
            }
            if length(mid) > l0 { lo = mid } else { hi = mid }
        }
        let ratio = (math::sin(0.5 * (lo + hi)) / self.sin_bar()).min(1.0 - f64::EPSILON);
        let x = (self.head_position() + self.profile_width * libm::atanh(ratio)).max(0.0);
        let energy = self.potential(x, 0.0);
        alloc::vec![Equilibrium { x: -x, energy, stable: true }, top, Equilibrium { x, energy, stable: true }]
    }

    /// The level set `H(x, p) = energy` of one kink (`x2 = 0`) on the grid `xs`: one closed polyline
    /// per run of grid points with `V(x, 0) <= energy`, upper branch (`p >= 0`) left to right, then
    /// the lower branch back. A run that reaches the end of the grid is cut there.
    pub fn level_curves(&self, energy: f64, xs: &[f64]) -> Vec<Vec<[f64; 2]>> {
        let mut curves = Vec::new();
        let mut upper: Vec<[f64; 2]> = Vec::new();
        let mut close = |upper: &mut Vec<[f64; 2]>| {
            if !upper.is_empty() {
                let lower = upper.iter().rev().map(|&[x, p]| [x, -p]);
                let curve: Vec<[f64; 2]> = upper.iter().copied().chain(lower).collect();
                curves.push(curve);
                upper.clear();
            }
        };
        for &x in xs {
            let v = self.potential(x, 0.0);
            if v <= energy {
                upper.push([x, math::sqrt(2.0 * self.kink_mass(x) * (energy - v))]);
            } else {
                close(&mut upper);
            }
        }
        close(&mut upper);
        curves
    }

    /// Integrates Hamilton's equations from `start` for `steps` steps of `dt` (module doc),
    /// recording the start and every `stride`-th step.
    pub fn trajectory(
        &self,
        start: PhaseState,
        dt: f64,
        steps: usize,
        stride: usize,
    ) -> Result<Vec<TrajectoryPoint>, LinkageError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(LinkageError::NotPositive { what: "time step", value: dt });
        }
        if stride == 0 {
            return Err(LinkageError::NotPositive { what: "stride", value: 0.0 });
        }
        for (what, value) in [("x1", start.x1), ("x2", start.x2), ("p1", start.p1), ("p2", start.p2)] {
            if !value.is_finite() {
                return Err(LinkageError::NotFinite { what, value });
            }
        }
        let record = |t: f64, s: &PhaseState| TrajectoryPoint {
            t,
            x1: s.x1,
            x2: s.x2,
            p1: s.p1,
            p2: s.p2,
            energy: self.hamiltonian(s),
        };
        let mut out = Vec::with_capacity(steps / stride + 1);
        let mut state = start;
        out.push(record(0.0, &state));
        for step in 1..=steps {
            state = self.advance(state, dt, step)?;
            if step % stride == 0 {
                out.push(record(step as f64 * dt, &state));
            }
        }
        Ok(out)
    }

    /// One step of `h`. Each kink's half line (`x > 0` or `x < 0`) carries a smooth Hamiltonian,
    /// but `|x|` puts a cusp in `V` and `m` at `x = 0`; a Stormer-Verlet step across it would see
    /// the jump of the force and lose `O(h)` energy. So the step is taken on the sides the kinks
    /// start on, and if a kink crosses `0`, split where it does (regula falsi on the sub-step)
    /// and continued on the new side.
    fn advance(&self, s: PhaseState, h: f64, step: usize) -> Result<PhaseState, LinkageError> {
        let side = |x: f64, p: f64| {
            if x != 0.0 {
                crate::math::sign(x)
            } else if p < 0.0 {
                -1.0
            } else {
                1.0
            }
        };
        let mut sides = [side(s.x1, s.p1), side(s.x2, s.p2)];
        let (mut state, mut remaining) = (s, h);
        // Each pass moves at least one kink to its other side; two kinks, a few crossings at most.
        for _ in 0..8 {
            let trial = self.leapfrog(state, remaining, sides, step)?;
            let at = |t: &PhaseState, k: usize| if k == 0 { t.x1 } else { t.x2 };
            // The kink that crosses first (by linear interpolation), if any.
            let first = (0..2)
                .filter(|&k| at(&trial, k) * sides[k] < 0.0)
                .map(|k| (k, at(&state, k) / (at(&state, k) - at(&trial, k))))
                .min_by(|a, b| a.1.total_cmp(&b.1));
            let Some((k, _)) = first else {
                return Ok(trial);
            };
            // The sub-step that lands kink k on 0, by regula falsi: x_k has the sign of sides[k] at
            // 0 and the opposite one at `remaining`.
            let (mut lo, mut hi) = ((0.0, at(&state, k)), (remaining, at(&trial, k)));
            let mut landed = (remaining, trial);
            for _ in 0..30 {
                let tau = (lo.0 * hi.1 - hi.0 * lo.1) / (hi.1 - lo.1);
                landed = (tau, self.leapfrog(state, tau, sides, step)?);
                let x = at(&landed.1, k);
                if x.abs() <= 1e-13 * (1.0 + self.head_position()) || hi.0 - lo.0 <= 1e-15 * h {
                    break;
                }
                if x * sides[k] > 0.0 { lo = (tau, x) } else { hi = (tau, x) }
            }
            let (tau, next) = landed;
            for (j, side) in sides.iter_mut().enumerate() {
                if j == k || at(&next, j) * *side < 0.0 {
                    *side = -*side;
                }
            }
            state = next;
            remaining -= tau;
        }
        Err(LinkageError::StepNotConverged { step, residual: remaining })
    }

    /// One generalised Stormer-Verlet step of `h` on fixed sides: half kick (implicit in `p`),
    /// drift (implicit in `x`), half kick (explicit).
    fn leapfrog(
        &self,
        s: PhaseState,
        h: f64,
        sides: [f64; 2],
        step: usize,
    ) -> Result<PhaseState, LinkageError> {
        let g = self.gradient_on(s.x1, s.x2, sides);
        let half = [
            self.half_kick(s.p1, g[0], s.x1, sides[0], h, step)?,
            self.half_kick(s.p2, g[1], s.x2, sides[1], h, step)?,
        ];
        let x1 = self.drift(s.x1, half[0], sides[0], h, step)?;
        let x2 = self.drift(s.x2, half[1], sides[1], h, step)?;
        let g = self.gradient_on(x1, x2, sides);
        let kick = |p: f64, dv: f64, x: f64, side: f64| {
            let (m, dm) = self.mass_and_slope(x, side);
            p - 0.5 * h * (dv - p * p * dm / (2.0 * m * m))
        };
        let next = PhaseState {
            x1,
            x2,
            p1: kick(half[0], g[0], x1, sides[0]),
            p2: kick(half[1], g[1], x2, sides[1]),
        };
        if [next.x1, next.x2, next.p1, next.p2].iter().all(|v| v.is_finite()) {
            Ok(next)
        } else {
            Err(LinkageError::StateNotFinite { step })
        }
    }

    /// Solves `q = p - (h/2) (dV/dx - q^2 m'/(2 m^2))` for `q`: `c q^2 - q + b = 0` with
    /// `c = h m' / (4 m^2)`, `b = p - h dV/dx / 2`; the root that tends to `b` as `h -> 0`.
    fn half_kick(
        &self,
        p: f64,
        dv: f64,
        x: f64,
        side: f64,
        h: f64,
        step: usize,
    ) -> Result<f64, LinkageError> {
        let (m, dm) = self.mass_and_slope(x, side);
        let c = h * dm / (4.0 * m * m);
        let b = p - 0.5 * h * dv;
        let disc = 1.0 - 4.0 * c * b;
        if disc < 0.0 {
            return Err(LinkageError::StepTooLarge { step, dt: h });
        }
        Ok(2.0 * b / (1.0 + math::sqrt(disc)))
    }

    /// Solves `y = x + (h/2) q (1/m(x) + 1/m(y))` for `y` by Newton's method.
    fn drift(&self, x: f64, q: f64, side: f64, h: f64, step: usize) -> Result<f64, LinkageError> {
        let v0 = 1.0 / self.mass_and_slope(x, side).0;
        let mut y = x + h * q * v0;
        let mut correction = f64::INFINITY;
        for _ in 0..50 {
            let (m, dm) = self.mass_and_slope(y, side);
            let g = y - x - 0.5 * h * q * (v0 + 1.0 / m);
            let dg = 1.0 + 0.5 * h * q * dm / (m * m);
            correction = g / dg;
            y -= correction;
            if correction.abs() <= 4.0 * f64::EPSILON * (1.0 + y.abs()) {
                return Ok(y);
            }
        }
        Err(LinkageError::StepNotConverged { step, residual: correction })
    }
}

/// `theta = asin(s tanh xi)` with `dtheta/dxi` and `d2theta/dxi2`.
fn wall_angle(s: f64, xi: f64) -> (f64, f64, f64) {
    let t = libm::tanh(xi);
    let c = libm::cosh(xi);
    let sech2 = 1.0 / (c * c);
    let q = 1.0 - s * s * t * t;
    let root = math::sqrt(q);
    let h = s * sech2 / root;
    let dh = s * t * sech2 * (s * s * sech2 - 2.0 * q) / (q * root);
    (libm::asin(s * t), h, dh)
}
