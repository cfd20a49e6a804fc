//! The rotor chain in symbols: one spring's energy and everything derived from it.
//!
//! Geometry (paper Sec. II and Appendix A; `docs/theory.md`): pivot `i` sits at `(i a, 0)` and the
//! tip of rotor `i` at `(i a + r_i sin theta_i, (-1)^i r_i cos theta_i)`, angles being measured
//! alternately from `+y` and `-y`. Spring `p` joins tips `p` and `p + 1`, so its squared length is
//!
//! `l_p^2 = (a + r_{p+1} sin theta_{p+1} - r_p sin theta_p)^2 + (r_p cos theta_p + r_{p+1} cos theta_{p+1})^2`,
//!
//! which for equal rotor lengths is the paper's Eq. (`eq:instantlength`). The spring stores
//! `law(l, l0, k)`; the harmonic law `k (l - l0)^2 / 2` is the default.
//!
//! From that one expression the engine derives, for spring `p` and its two rotors (paper
//! Appendix D, Guest's tangent stiffness, written in the angles; the gradient and the Hessian block
//! in the paper's form, `t^ d(l^2 / 2)/dtheta` and stress matrix plus material part, which take
//! fewer operations than the chain rule's order, see [`SpringTerms::derive`]):
//! - the gradient `dE/dtheta` and Hessian block `d2E/dtheta dtheta`;
//! - tension `t = dlaw/dl`, axial stiffness `g = dt/dl`, tension coefficient `t^ = t / l`, and
//!   modified axial stiffness `g^ = g - t^`;
//! - the material part `g^ (dl/dtheta)(dl/dtheta)^T` and the stress matrix
//!   `t^ d2(l^2 / 2)/dtheta dtheta`, whose sum is the Hessian block;
//! - the compatibility-matrix row `dl / d(r theta)`.

use std::collections::HashMap;

use crate::diff::diff;
use crate::graph::{Graph, Id, Node};

/// A spring law: the stored energy as an expression in the symbols `l` (length), `l0` (rest
/// length) and `k` (stiffness).
#[derive(Clone, Copy, Debug)]
pub struct SpringLaw {
    pub energy: Id,
    pub l: Id,
    pub l0: Id,
    pub k: Id,
}

/// Names of the law's own symbols in the graph (kept apart from every user name).
pub const LAW_L: &str = "law::l";
pub const LAW_L0: &str = "law::l0";
pub const LAW_K: &str = "law::k";

impl SpringLaw {
    /// The law's symbols `(l, l0, k)`, for building a custom law.
    pub fn symbols(g: &mut Graph) -> (Id, Id, Id) {
        (g.symbol(LAW_L), g.symbol(LAW_L0), g.symbol(LAW_K))
    }

    /// A law from an energy expression built on [`SpringLaw::symbols`].
    pub fn custom(g: &mut Graph, energy: Id) -> Self {
        let (l, l0, k) = Self::symbols(g);
        Self { energy, l, l0, k }
    }

    /// The harmonic law `k (l - l0)^2 / 2` (paper Eq. `eq:discretelagrangian`), written as
    /// `(k (l - l0)) (l - l0) / 2`: its first product is the tension `t = k (l - l0)`, which the
    /// gradient needs anyway, so energy and gradient share it (the same two roundings as
    /// `k ((l - l0)^2)`).
    pub fn harmonic(g: &mut Graph) -> Self {
        let (l, l0, k) = Self::symbols(g);
        let stretch = g.sub(l, l0);
        let tension = g.mul(k, stretch);
        let twice = g.mul(tension, stretch);
        let half = g.constant(0.5);
        let energy = g.mul(half, twice);
        Self { energy, l, l0, k }
    }

    /// The paper's quartic approximation `k (l^2 - l0^2)^2 / (8 l0^2)` (Eq. `eq:discretepotential`).
    pub fn quartic(g: &mut Graph) -> Self {
        let (l, l0, k) = Self::symbols(g);
        let l2 = g.powi(l, 2);
        let l02 = g.powi(l0, 2);
        let d = g.sub(l2, l02);
        let d2 = g.powi(d, 2);
        let eight = g.constant(8.0);
        let den = g.mul(eight, l02);
        let kd = g.div(k, den);
        let energy = g.mul(kd, d2);
        Self { energy, l, l0, k }
    }
}

/// The parameters of one spring and its two rotors, each a constant or a symbol.
#[derive(Clone, Copy, Debug)]
pub struct SpringParams {
    /// Lattice spacing `a`.
    pub a: Id,
    /// Length of the left rotor `r_p`.
    pub r1: Id,
    /// Length of the right rotor `r_{p+1}`.
    pub r2: Id,
    /// Stiffness `k_p`.
    pub k: Id,
    /// Rest length `l0_p`.
    pub l0: Id,
}

/// Every quantity of one spring, as nodes of the graph. Pairs are `(left rotor, right rotor)`
/// and blocks are `[11, 12, 22]` of the symmetric 2x2 block on rotors `(p, p + 1)`.
#[derive(Clone, Copy, Debug)]
pub struct SpringTerms {
    /// `[sin theta_p, cos theta_p, sin theta_{p+1}, cos theta_{p+1}]`.
    pub trig: [Id; 4],
    pub length: Id,
    pub energy: Id,
    pub tension: Id,
    pub gradient: [Id; 2],
    pub hessian: [Id; 3],
    pub material: [Id; 3],
    pub stress: [Id; 3],
    /// `dl / d(r theta)` for the two rotors: the compatibility-matrix row of the spring.
    pub compatibility: [Id; 2],
}

impl SpringTerms {
    /// Derives every term of the spring joining the rotors whose angles are the symbols
    /// `theta1` and `theta2`.
    pub fn derive(g: &mut Graph, law: &SpringLaw, p: &SpringParams, theta1: Id, theta2: Id) -> Self {
        let (s1, c1) = (g.sin(theta1), g.cos(theta1));
        let (s2, c2) = (g.sin(theta2), g.cos(theta2));
        // l^2 = (a + r2 s2 - r1 s1)^2 + (r1 c1 + r2 c2)^2
        let r2s2 = g.mul(p.r2, s2);
        let r1s1 = g.mul(p.r1, s1);
        let dx = g.add(p.a, r2s2);
        let dx = g.sub(dx, r1s1);
        let r1c1 = g.mul(p.r1, c1);
        let r2c2 = g.mul(p.r2, c2);
        let dy = g.add(r1c1, r2c2);
        let dx2 = g.powi(dx, 2);
        let dy2 = g.powi(dy, 2);
        let q = g.add(dx2, dy2);
        let length = g.sqrt(q);

        let LawAtLength { energy, tension, t_hat, g_hat } = LawAtLength::derive(g, law, p.k, p.l0, length, q);
        let half = g.constant(0.5);
        let half_q = g.mul(half, q);
        let dq1 = diff(g, half_q, theta1);
        let dq2 = diff(g, half_q, theta2);
        let g1 = g.mul(t_hat, dq1);
        let g2 = g.mul(t_hat, dq2);

        let stress = [(dq1, theta1), (dq1, theta2), (dq2, theta2)].map(|(dq, theta)| {
            let d = diff(g, dq, theta);
            g.mul(t_hat, d)
        });
        let per_q = g.div(g_hat, q);
        let hessian =
            [(dq1, dq1, stress[0]), (dq1, dq2, stress[1]), (dq2, dq2, stress[2])].map(|(a, b, s)| {
                let ab = g.mul(a, b);
                let m = g.mul(per_q, ab);
                g.add(m, s)
            });

        // Guest's material part in the paper's own terms, `g^ dl_i dl_j`.
        let dl1 = diff(g, length, theta1);
        let dl2 = diff(g, length, theta2);
        let material = [(dl1, dl1), (dl1, dl2), (dl2, dl2)].map(|(a, b)| {
            let ab = g.mul(a, b);
            g.mul(g_hat, ab)
        });
        let compatibility = [g.div(dl1, p.r1), g.div(dl2, p.r2)];

        Self {
            trig: [s1, c1, s2, c2],
            length,
            energy,
            tension,
            gradient: [g1, g2],
            hessian,
            material,
            stress,
            compatibility,
        }
    }
}

/// A law evaluated at a spring's length `l = sqrt(q)` with the spring's own `k` and `l0`: the
/// energy, the tension `t = dlaw/dl`, the tension coefficient `t^ = t / l` and the modified axial
/// stiffness `g^ = g - t^` (paper Appendix D), from which every spring or bond (the chain's
/// [`SpringTerms`], a network's [`BondTerms`](crate::bond::BondTerms)) writes its force and
/// stiffness in the paper's form.
#[derive(Clone, Copy, Debug)]
pub struct LawAtLength {
    pub energy: Id,
    pub tension: Id,
    pub t_hat: Id,
    pub g_hat: Id,
}

impl LawAtLength {
    /// `law` with stiffness `k` and rest length `l0` at the length `length = sqrt(q)`.
    pub fn derive(g: &mut Graph, law: &SpringLaw, k: Id, l0: Id, length: Id, q: Id) -> Self {
        // The law with this spring's k and l0, still a function of the symbol l.
        let fixed = HashMap::from([(law.l0, l0), (law.k, k)]);
        let law_l = g.substitute(law.energy, &fixed);
        let tension_l = diff(g, law_l, law.l);
        let axial_l = diff(g, tension_l, law.l);
        // At the spring's length: `l = sqrt(q)`, and a power `l^n` (n >= 2) of the law is
        // `q^(n/2)`, times `l` for odd `n`, which `q >= 0` allows (the graph itself keeps
        // `sqrt(x)^2`, NaN for `x < 0`): fewer roundings and no power of a square root. The
        // quartic law is then a function of `q` alone in its energy and force. Like the paper's
        // form of the force below, this is a choice of formula made here, where `q >= 0` is
        // known; the graph's own rewrites stay exact (the same IEEE result for every input).
        let mut at_length = HashMap::from([(law.l, length)]);
        for id in g.reachable(&[law_l, tension_l, axial_l], &|_| false) {
            if let Node::Powi(x, n) = g.node(id)
                && x == law.l
            {
                let power = length_power(g, n, length, q);
                at_length.insert(id, power);
            }
        }
        let energy = g.substitute(law_l, &at_length);
        let tension = g.substitute(tension_l, &at_length);
        let axial = g.substitute(axial_l, &at_length);

        // The force and the tangent stiffness as the paper writes them (Appendix D), with the
        // tension coefficient `t^ = t / l`, the modified axial stiffness `g^ = g - t^` and
        // `q = l^2`:
        // - force, Eq. `eq:prestress1`: `dE/dtheta_i = t^ d(q/2)/dtheta_i`;
        // - stiffness, Eqs. `eq:prestress6`-`eq:prestress8`: the stress matrix
        //   `t^ d2(q/2)/dtheta_i dtheta_j` plus the material part `g^ dl_i dl_j`, written as
        //   `(g^ / q) d(q/2)/dtheta_i d(q/2)/dtheta_j` (as `dl_i = d(q/2)/dtheta_i / l`).
        // The same functions as the chain rule through `l = sqrt(q)` gives, in fewer operations:
        // `t^` is one division shared by both gradients (each rounds three times, not four as
        // `law'(l) (1 / l) d(q/2)/dtheta_i`), and the Hessian divides twice (`t^`, `g^ / q`), as
        // often as its chain-rule form. The harmonic kernels: energy + gradient 29 -> 25
        // operations, with the Hessian 73 -> 57 (quartic 35 -> 31 and 92 -> 69; 27 and 65 with
        // `l^2 = q` and `t^` without its factor `l`, above and below, and then no square root
        // in the quartic energy + gradient); timings in docs/benchmarks.md, ninth and eleventh
        // rounds. Every derivative in it (`law'`, `law''`, those of `q`) is the engine's.
        // Where the tension has the factor `l` (the quartic law's `k l (l^2 - l0^2) / (2 l0^2)`,
        // or `k l^2 = k q` of a law `k l^3 / 3`), `t^` is the rest of it: no division, and `t^`
        // stays finite at `l = 0`, as the force `t^ d(q/2)/dtheta` does.
        let t_hat = without_length(g, tension, length, q).unwrap_or_else(|| g.div(tension, length));
        let g_hat = g.sub(axial, t_hat);
        Self { energy, tension, t_hat, g_hat }
    }
}

/// `l^n` at the spring's length `l = sqrt(q)`: `q^(n/2)` for even `n`, `q^((n-1)/2) l` for odd
/// `n >= 3`, and `l^n` itself for `n = 1` and negative odd `n`.
fn length_power(g: &mut Graph, n: i32, length: Id, q: Id) -> Id {
    match n {
        _ if n % 2 == 0 => g.powi(q, n / 2),
        _ if n >= 3 => {
            let even = g.powi(q, (n - 1) / 2);
            g.mul(even, length)
        }
        _ => g.powi(length, n),
    }
}

/// `e / l` where `e` is a product (possibly negated, or a quotient) with a factor `l = length`,
/// written as `l` itself or within `q = l^2` or a power of `q` ([`length_power`]'s forms): `e`
/// with one factor `l` left out, `None` where none is found. The same function as `e / l` where
/// `l` is finite and not zero, with a division's rounding less; where `l` is zero or infinite,
/// `e / l` is NaN and the product without `l` is its limit.
fn without_length(g: &mut Graph, e: Id, length: Id, q: Id) -> Option<Id> {
    if e == length {
        return Some(g.one());
    }
    if e == q {
        return Some(length);
    }
    match g.node(e) {
        Node::Mul(a, b) => {
            if let Some(rest) = without_length(g, a, length, q) {
                Some(g.mul(rest, b))
            } else {
                let rest = without_length(g, b, length, q)?;
                Some(g.mul(a, rest))
            }
        }
        Node::Div(a, b) => {
            let rest = without_length(g, a, length, q)?;
            Some(g.div(rest, b))
        }
        Node::Neg(a) => {
            let rest = without_length(g, a, length, q)?;
            Some(g.neg(rest))
        }
        Node::Powi(x, m) if x == q && m >= 2 => Some(length_power(g, 2 * m - 1, length, q)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setup(law: fn(&mut Graph) -> SpringLaw) -> (Graph, SpringTerms, [Id; 2]) {
        let mut g = Graph::new();
        let law = law(&mut g);
        let params = SpringParams {
            a: g.constant(1.0),
            r1: g.constant(0.8),
            r2: g.constant(0.7),
            k: g.constant(3.0),
            l0: g.constant(1.5),
        };
        let t1 = g.symbol("theta1");
        let t2 = g.symbol("theta2");
        let terms = SpringTerms::derive(&mut g, &law, &params, t1, t2);
        (g, terms, [t1, t2])
    }

    fn at(x1: f64, x2: f64) -> impl Fn(&str) -> f64 {
        move |name| if name == "theta1" { x1 } else { x2 }
    }

    /// Length from the tip coordinates directly (an independent statement of the geometry).
    fn tip_distance(x1: f64, x2: f64) -> f64 {
        let tip1 = (0.8 * x1.sin(), 0.8 * x1.cos());
        let tip2 = (1.0 + 0.7 * x2.sin(), -0.7 * x2.cos());
        ((tip2.0 - tip1.0).powi(2) + (tip2.1 - tip1.1).powi(2)).sqrt()
    }

    #[test]
    fn length_is_the_distance_between_the_tips() {
        let (g, t, _) = setup(SpringLaw::harmonic);
        for (x1, x2) in [(0.3, -0.2), (1.1, 0.9), (-0.7, 2.0)] {
            let l = g.eval(t.length, &at(x1, x2));
            assert!((l - tip_distance(x1, x2)).abs() < 1e-14);
            let e = g.eval(t.energy, &at(x1, x2));
            assert!((e - 1.5 * (tip_distance(x1, x2) - 1.5).powi(2)).abs() < 1e-12);
        }
    }

    /// The quartic law is a polynomial in `q = l^2`: at the spring's length its energy and force
    /// take no square root, and `t^ = t / l` no division (`setup`'s `k` and `l0` are numbers, so
    /// the law's `k / (8 l0^2)` is one too). The harmonic law keeps both: its `t = k (l - l0)`
    /// has no factor `l` to cancel. A law whose tension has the factor `l` inside `l^2` (`k l^3 /
    /// 3`) needs the square root for its energy, but no division either.
    #[test]
    fn a_tension_with_the_factor_l_is_not_divided_by_the_length() {
        type Is = fn(&Node) -> bool;
        let count = |g: &Graph, t: &SpringTerms, what: Is| {
            let roots = [t.energy, t.gradient[0], t.gradient[1]];
            g.reachable(&roots, &|_| false).into_iter().filter(|&id| what(&g.node(id))).count()
        };
        let is_sqrt: Is = |n| matches!(n, Node::Sqrt(_));
        let is_div: Is = |n| matches!(n, Node::Div(..));
        let (g, t, _) = setup(SpringLaw::quartic);
        assert_eq!(
            (count(&g, &t, is_sqrt), count(&g, &t, is_div)),
            (0, 0),
            "quartic: square roots, divisions"
        );
        let (g, t, _) = setup(SpringLaw::harmonic);
        assert_eq!(
            (count(&g, &t, is_sqrt), count(&g, &t, is_div)),
            (1, 1),
            "harmonic: square roots, divisions"
        );
        // A factor `l` inside `q`: the tension `k l^2` of `k l^3 / 3` is `k q`, and `t^ = k l`.
        let (g, t, _) = setup(cubic);
        assert_eq!((count(&g, &t, is_sqrt), count(&g, &t, is_div)), (1, 0), "cubic: square roots, divisions");
    }

    /// `k l^3 / 3`: its tension `k l^2` has the factor `l` only through `l^2 = q`.
    fn cubic(g: &mut Graph) -> SpringLaw {
        let (l, _, k) = SpringLaw::symbols(g);
        let cube = g.powi(l, 3);
        let third = g.constant(1.0 / 3.0);
        let scaled = g.mul(third, k);
        let energy = g.mul(scaled, cube);
        SpringLaw::custom(g, energy)
    }

    /// A law unlike both built-in ones: `k (exp(l - l0) - 1 - (l - l0)) + l^3 / 3`.
    fn exponential(g: &mut Graph) -> SpringLaw {
        let (l, l0, k) = SpringLaw::symbols(g);
        let stretch = g.sub(l, l0);
        let e = g.exp(stretch);
        let one = g.one();
        let e1 = g.sub(e, one);
        let e2 = g.sub(e1, stretch);
        let soft = g.mul(k, e2);
        let cube = g.powi(l, 3);
        let third = g.constant(1.0 / 3.0);
        let hard = g.mul(third, cube);
        let energy = g.add(soft, hard);
        SpringLaw::custom(g, energy)
    }

    /// The gradient and Hessian in the paper's form (`t^ d(q/2)`, stress plus material) are those
    /// the chain rule gives straight from the energy; the material part in the paper's own terms
    /// (`g^ dl dl`) adds to the stress matrix to the same Hessian.
    #[test]
    fn the_papers_force_and_stiffness_are_the_energys_derivatives() {
        for law in [SpringLaw::harmonic, SpringLaw::quartic, exponential, cubic] {
            let (mut g, t, [t1, t2]) = setup(law);
            let d1 = diff(&mut g, t.energy, t1);
            let d2 = diff(&mut g, t.energy, t2);
            let chain_rule = [d1, d2];
            let d11 = diff(&mut g, d1, t1);
            let d12 = diff(&mut g, d1, t2);
            let d22 = diff(&mut g, d2, t2);
            let second = [d11, d12, d22];
            for (x1, x2) in [(0.3, -0.2), (1.1, 0.9), (-0.7, 2.0), (2.6, -1.4)] {
                let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()));
                for (i, &direct) in chain_rule.iter().enumerate() {
                    let ours = g.eval(t.gradient[i], &at(x1, x2));
                    let direct = g.eval(direct, &at(x1, x2));
                    assert!(close(ours, direct), "gradient {i} at ({x1}, {x2}): {ours} vs {direct}");
                }
                for (b, &direct) in second.iter().enumerate() {
                    let h = g.eval(t.hessian[b], &at(x1, x2));
                    let direct = g.eval(direct, &at(x1, x2));
                    let m = g.eval(t.material[b], &at(x1, x2));
                    let s = g.eval(t.stress[b], &at(x1, x2));
                    assert!(close(h, direct), "block {b} at ({x1}, {x2}): {h} vs {direct}");
                    assert!(close(m + s, direct), "block {b} at ({x1}, {x2}): {m} + {s} vs {direct}");
                }
            }
        }
    }

    /// Gradient and every Hessian entry against central differences of each law's energy, written
    /// in `f64` from the tip distance (independent of the engine), for the built-in laws and a
    /// custom one.
    #[test]
    fn gradient_and_hessian_match_finite_differences_of_the_tip_distance() {
        // k = 3, l0 = 1.5 as in `setup`.
        type Law = (fn(&mut Graph) -> SpringLaw, fn(f64) -> f64);
        let laws: [Law; 4] = [
            (SpringLaw::harmonic, |l| 1.5 * (l - 1.5).powi(2)),
            (SpringLaw::quartic, |l| 3.0 * (l * l - 2.25).powi(2) / (8.0 * 2.25)),
            (exponential, |l| 3.0 * ((l - 1.5).exp() - 1.0 - (l - 1.5)) + l.powi(3) / 3.0),
            (cubic, |l| 3.0 * l.powi(3) / 3.0),
        ];
        for (law, energy_of_length) in laws {
            let (g, t, _) = setup(law);
            let energy = |x1: f64, x2: f64| energy_of_length(tip_distance(x1, x2));
            for (x1, x2) in [(0.3, -0.2), (1.1, 0.9), (-0.7, 2.0)] {
                let h = 1e-5;
                let fd = [
                    (energy(x1 + h, x2) - energy(x1 - h, x2)) / (2.0 * h),
                    (energy(x1, x2 + h) - energy(x1, x2 - h)) / (2.0 * h),
                ];
                for (i, fd) in fd.into_iter().enumerate() {
                    let ours = g.eval(t.gradient[i], &at(x1, x2));
                    assert!(
                        (ours - fd).abs() < 1e-8 * (1.0 + fd.abs()),
                        "gradient {i} at ({x1}, {x2}): {ours} vs {fd}"
                    );
                }
                let h = 1e-4;
                let e0 = energy(x1, x2);
                let fd = [
                    (energy(x1 + h, x2) - 2.0 * e0 + energy(x1 - h, x2)) / (h * h),
                    (energy(x1 + h, x2 + h) - energy(x1 + h, x2 - h) - energy(x1 - h, x2 + h)
                        + energy(x1 - h, x2 - h))
                        / (4.0 * h * h),
                    (energy(x1, x2 + h) - 2.0 * e0 + energy(x1, x2 - h)) / (h * h),
                ];
                for (b, fd) in fd.into_iter().enumerate() {
                    let ours = g.eval(t.hessian[b], &at(x1, x2));
                    assert!(
                        (ours - fd).abs() < 1e-5 * (1.0 + fd.abs()),
                        "block {b} at ({x1}, {x2}): {ours} vs {fd}"
                    );
                }
            }
        }
    }
}
