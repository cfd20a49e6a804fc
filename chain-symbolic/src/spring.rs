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
//! Appendix D, Guest's tangent stiffness, written in the angles):
//! - the gradient `dE/dtheta` and Hessian block `d2E/dtheta dtheta`;
//! - tension `t = dlaw/dl`, axial stiffness `g = dt/dl`, tension coefficient `t^ = t / l`, and
//!   modified axial stiffness `g^ = g - t^`;
//! - the material part `g^ (dl/dtheta)(dl/dtheta)^T` and the stress matrix
//!   `t^ d2(l^2 / 2)/dtheta dtheta`, whose sum is the Hessian block;
//! - the compatibility-matrix row `dl / d(r theta)`.

use std::collections::HashMap;

use crate::diff::diff;
use crate::graph::{Graph, Id};

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

    /// The harmonic law `k (l - l0)^2 / 2` (paper Eq. `eq:discretelagrangian`).
    pub fn harmonic(g: &mut Graph) -> Self {
        let (l, l0, k) = Self::symbols(g);
        let stretch = g.sub(l, l0);
        let sq = g.powi(stretch, 2);
        let half = g.constant(0.5);
        let hk = g.mul(half, k);
        let energy = g.mul(hk, sq);
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

        // The law with this spring's k and l0, still a function of the symbol l.
        let fixed = HashMap::from([(law.l0, p.l0), (law.k, p.k)]);
        let law_l = g.substitute(law.energy, &fixed);
        let tension_l = diff(g, law_l, law.l);
        let axial_l = diff(g, tension_l, law.l);
        let at_length = HashMap::from([(law.l, length)]);
        let energy = g.substitute(law_l, &at_length);
        let tension = g.substitute(tension_l, &at_length);
        let axial = g.substitute(axial_l, &at_length);

        let g1 = diff(g, energy, theta1);
        let g2 = diff(g, energy, theta2);
        let h11 = diff(g, g1, theta1);
        let h12 = diff(g, g1, theta2);
        let h22 = diff(g, g2, theta2);

        // Guest's split (paper Eq. `eq:prestress8`), in the angles.
        let t_hat = g.div(tension, length);
        let g_hat = g.sub(axial, t_hat);
        let dl1 = diff(g, length, theta1);
        let dl2 = diff(g, length, theta2);
        let m11 = {
            let sq = g.powi(dl1, 2);
            g.mul(g_hat, sq)
        };
        let m12 = {
            let pr = g.mul(dl1, dl2);
            g.mul(g_hat, pr)
        };
        let m22 = {
            let sq = g.powi(dl2, 2);
            g.mul(g_hat, sq)
        };
        let half = g.constant(0.5);
        let half_q = g.mul(half, q);
        let dq1 = diff(g, half_q, theta1);
        let dq2 = diff(g, half_q, theta2);
        let s11 = {
            let d = diff(g, dq1, theta1);
            g.mul(t_hat, d)
        };
        let s12 = {
            let d = diff(g, dq1, theta2);
            g.mul(t_hat, d)
        };
        let s22 = {
            let d = diff(g, dq2, theta2);
            g.mul(t_hat, d)
        };
        let compatibility = [g.div(dl1, p.r1), g.div(dl2, p.r2)];

        Self {
            trig: [s1, c1, s2, c2],
            length,
            energy,
            tension,
            gradient: [g1, g2],
            hessian: [h11, h12, h22],
            material: [m11, m12, m22],
            stress: [s11, s12, s22],
            compatibility,
        }
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

    #[test]
    fn material_plus_stress_is_the_hessian() {
        for law in [SpringLaw::harmonic, SpringLaw::quartic] {
            let (g, t, _) = setup(law);
            for (x1, x2) in [(0.3, -0.2), (1.1, 0.9), (-0.7, 2.0)] {
                for b in 0..3 {
                    let h = g.eval(t.hessian[b], &at(x1, x2));
                    let m = g.eval(t.material[b], &at(x1, x2));
                    let s = g.eval(t.stress[b], &at(x1, x2));
                    assert!((h - (m + s)).abs() <= 1e-12 * (1.0 + h.abs()), "block {b}: {h} vs {m} + {s}");
                }
            }
        }
    }

    #[test]
    fn gradient_and_hessian_match_finite_differences_of_the_tip_distance() {
        let (g, t, _) = setup(SpringLaw::harmonic);
        let energy = |x1: f64, x2: f64| 1.5 * (tip_distance(x1, x2) - 1.5).powi(2);
        let h = 1e-5;
        for (x1, x2) in [(0.3, -0.2), (1.1, 0.9)] {
            let g1 = g.eval(t.gradient[0], &at(x1, x2));
            let g2 = g.eval(t.gradient[1], &at(x1, x2));
            let fd1 = (energy(x1 + h, x2) - energy(x1 - h, x2)) / (2.0 * h);
            let fd2 = (energy(x1, x2 + h) - energy(x1, x2 - h)) / (2.0 * h);
            assert!((g1 - fd1).abs() < 1e-8 && (g2 - fd2).abs() < 1e-8);
            let h12 = g.eval(t.hessian[1], &at(x1, x2));
            let fd12 = (energy(x1 + h, x2 + h) - energy(x1 + h, x2 - h) - energy(x1 - h, x2 + h)
                + energy(x1 - h, x2 - h))
                / (4.0 * h * h);
            assert!((h12 - fd12).abs() < 1e-5, "{h12} vs {fd12}");
        }
    }
}
