//! The `#[rotor_chain]` attribute macro.
//!
//! A thin entry over a pipeline of named phases, one file each:
//! `attr` parses the attribute into a typed `attr::Spec` that keeps every span,
//! `valid` checks it against the chain's rules (all errors at once, each at its key),
//! `law` turns a custom spring law into the symbolic graph,
//! `model` builds the chain's energy in `chain-symbolic` and derives everything from it,
//! `expand` emits the code, and `fallback` emits the bare struct plus the errors when the
//! model is invalid. See `docs/macro.md` for the keys.
#![deny(missing_docs)]

mod attr;
mod ctxt;
mod expand;
mod fallback;
#[cfg(test)]
mod fuzz;
mod law;
mod model;
mod valid;

use proc_macro::TokenStream;

/// Declares a topological rotor chain on a struct and generates its energy, gradient, tangent
/// stiffness (material part + stress matrix), spring lengths, tensions, compatibility matrix, a
/// run-time parameter check and an `impl ChainModel` (which adds the branch solve of paper
/// Appendix A). Use it through the facade, `rotor_chain::prelude::*`.
///
/// Conventions are those of the paper (Sec. II, Appendix A; `rotor_chain::guide::theory`):
/// rotors $i = 0, \dots, n-1$ with pivots at $(i a, 0)$, angle $\theta_i$ from the vertical,
/// spring $p$ joining the tips of rotors $p$ and $p + 1$, harmonic energy
/// $V = \sum_p \tfrac12 k_p (l_p - l_{0,p})^2$ unless `law` says otherwise. Units are the paper's
/// (Appendix B): lengths in the lattice spacing $a$, masses in $M$, time in an arbitrary unit
/// $t$, stiffness in $M/t^2$, angles in radians.
///
/// Every numeric value is either a float literal (folded into the generated code and checked at
/// compile time) or the name of an `f64` field of the struct (read as `self.field` at run time
/// and checked by the generated `check()`). Every invalid model is a compile error at its key, all
/// errors at once. The whole guide, with every generated item and every error message, is
/// `rotor_chain::guide::macros`.
///
/// # Keys
///
/// | key | meaning | units | default |
/// |---|---|---|---|
/// | `n` | number of rotors, an integer literal $2 \le n \le 10^8$ | — | required |
/// | `a` | lattice spacing (pivot distance) | length | `1.0` |
/// | `r` | rotor length of every rotor | length | required |
/// | `theta_bar` | angle $\bar\theta$ of the uniform states $\pm\bar\theta$, in the flipper phase $0 < \bar\theta < \pi/2$, $2 r \sin\bar\theta < a$ | rad | this or `rest_length` required |
/// | `rest_length` | the uniform state given by its rest length $\bar l$, with $a < \bar l < \sqrt{a^2+4r^2}$ | length | — |
/// | `k` | stiffness of every spring | $M/t^2$ | required |
/// | `mass` | tip mass $M$ | mass | `1.0` |
/// | `spring(p, k = .., l0 = ..)` | override spring $p$'s stiffness and/or rest length | as `k`; length | — |
/// | `rotor(i, r = ..)` | override rotor $i$'s length | length | — |
/// | `law` | the spring energy as an expression in `l`, `l0`, `k` | energy | $\tfrac12 k (l - l_0)^2$ |
/// | `unroll` | chains with $n \le$ `unroll` get straight-line code, longer ones a loop over a per-spring kernel | — | `128` |
///
/// The default rest length of every spring is $\bar l = \sqrt{a^2 + 4 r^2 \cos^2\bar\theta}$
/// (paper Eq. `eq:instantlength` at $\theta_p = \theta_{p+1} = \bar\theta$), or `rest_length` when
/// given; rotor overrides do not change it.
///
/// ## `n`, `r`, `theta_bar`, `k`: the required keys
///
/// ```
/// use rotor_chain::prelude::*;
///
/// #[rotor_chain(n = 60, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
/// pub struct Chain;
///
/// let theta = [0.58f64; Chain::N];          // the uniform state +theta_bar
/// assert_eq!(Chain::N, 60);
/// assert_eq!(Chain::SPRINGS, 59);
/// assert!(Chain.energy(&theta).abs() < 1e-9); // every spring at rest
/// ```
///
/// ## `a` and `mass`
///
/// ```
/// use rotor_chain::prelude::*;
///
/// #[rotor_chain(n = 8, a = 2.0, r = 1.6, theta_bar = 0.58, k = 1.0e4, mass = 3.0)]
/// pub struct Scaled;
///
/// assert_eq!(Scaled.lattice_spacing(), 2.0);
/// assert_eq!(Scaled.mass(), 3.0);
/// assert!((Scaled.inertia(0) - 3.0 * 1.6 * 1.6).abs() < 1e-12); // M r^2
/// ```
///
/// ## `rest_length` instead of `theta_bar`
///
/// ```
/// use rotor_chain::prelude::*;
///
/// #[rotor_chain(n = 8, r = 0.8, rest_length = 1.7, k = 1.0e4)]
/// pub struct ByLength;
///
/// // lbar = sqrt(a^2 + 4 r^2 cos^2 theta_bar)  =>  cos theta_bar = sqrt(lbar^2 - a^2) / (2 r)
/// let expected = ((1.7f64 * 1.7 - 1.0).sqrt() / 1.6).acos();
/// assert!((ByLength.theta_bar() - expected).abs() < 1e-12);
/// ```
///
/// ## `spring(p, k = .., l0 = ..)` and fields
///
/// A value may name an `f64` field: here the impurity's stiffness is chosen at run time.
///
/// ```
/// use rotor_chain::prelude::*;
///
/// #[rotor_chain(n = 60, r = 0.8, theta_bar = 0.28, k = 1.0e4,
///               spring(29, k = k_imp),    // read from the field at run time
///               spring(7, l0 = 2.30))]    // a literal: checked at compile time
/// pub struct Impurity { pub k_imp: f64 }
///
/// let chain = Impurity { k_imp: 1.0e3 };
/// chain.check()?;                          // the field obeys the rules too
/// assert_eq!(chain.stiffness(29), 1.0e3);
/// assert_eq!(chain.rest_length(7), 2.30);
/// assert!(Impurity { k_imp: -1.0 }.check().is_err());
/// # Ok::<(), rotor_chain::ParameterError>(())
/// ```
///
/// ## `rotor(i, r = ..)`
///
/// ```
/// use rotor_chain::prelude::*;
///
/// #[rotor_chain(n = 16, r = 0.8, theta_bar = 0.58, k = 1.0e4, rotor(12, r = 0.7))]
/// pub struct Defective;
///
/// assert_eq!(Defective.rotor_length(12), 0.7);
/// assert_eq!(Defective.rotor_length(11), 0.8);
/// // Springs 11 and 12 keep the default rest length, so they are stretched in the uniform state.
/// let tensions = Defective.tensions(&[0.58; 16]);
/// assert!(tensions[11] != 0.0 && tensions[10].abs() < 1e-9);
/// ```
///
/// ## `law`
///
/// Differentiated by the same symbolic engine as the chain: `+ - * /`, unary `-`, parentheses,
/// literals, the symbols `l`, `l0`, `k`, and `.powi(n)`, `.sqrt()`, `.sin()`, `.cos()`, `.exp()`,
/// `.ln()`.
///
/// ```
/// use rotor_chain::prelude::*;
///
/// /// The paper's quartic approximation, Eq. (eq:discretepotential).
/// #[rotor_chain(n = 6, r = 0.8, theta_bar = 0.58, k = 1.0e4,
///               law = k / (8.0 * l0 * l0) * (l * l - l0 * l0).powi(2))]
/// pub struct Quartic;
///
/// let rest = [0.58f64; 6];
/// assert!(Quartic.energy(&rest).abs() < 1e-9);
/// // Near rest the quartic law has the harmonic curvature k: compare with the harmonic chain.
/// #[rotor_chain(n = 6, r = 0.8, theta_bar = 0.58, k = 1.0e4)]
/// pub struct Harmonic;
/// let (hq, hh) = (Quartic.hessian(&rest), Harmonic.hessian(&rest));
/// assert!((hq[(2, 3)] - hh[(2, 3)]).abs() < 1e-9 * hh[(2, 3)].abs());
/// ```
///
/// ## `unroll`
///
/// Both strategies come from the same symbolic derivation and agree to rounding.
///
/// ```
/// use rotor_chain::prelude::*;
///
/// #[rotor_chain(n = 40, r = 0.8, theta_bar = 0.58, k = 1.0e4)]              // unrolled
/// pub struct Unrolled;
/// #[rotor_chain(n = 40, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 0)]  // looped
/// pub struct Looped;
///
/// let theta: Vec<f64> = (0..40).map(|i| 0.58 * (0.3 * i as f64).cos()).collect();
/// let theta: [f64; 40] = theta.try_into().unwrap();
/// let (gu, gl) = (Unrolled.gradient(&theta), Looped.gradient(&theta));
/// assert!(gu.iter().zip(&gl).all(|(u, l)| (u - l).abs() <= 1e-9 * (1.0 + u.abs())));
/// ```
///
/// ## Compile errors
///
/// An invalid model does not compile; the message points at the key:
///
/// ```compile_fail
/// use rotor_chain::prelude::*;
///
/// // theta_bar = 0.7 with r = 0.8 is past the flipper phase (2 r sin(0.7) = 1.03 > a = 1).
/// #[rotor_chain(n = 60, r = 0.8, theta_bar = 0.7, k = 1.0e4)]
/// pub struct Wobbler;
/// ```
#[proc_macro_attribute]
pub fn rotor_chain(attr: TokenStream, item: TokenStream) -> TokenStream {
    expand::expand(attr.into(), item.into()).into()
}
