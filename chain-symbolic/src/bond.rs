//! A network's bonds in symbols (issue 36): one bond of each type, joint-joint, joint-rotor and
//! rotor-rotor, with every parameter a symbol, and everything derived from its length.
//!
//! Geometry (the cell format's conventions, `docs/network.md`): a joint's end is its position
//! `(x, y)`; a rotor's end is its tip `pivot + r (cos phi, sin phi)`, `phi` counter-clockwise
//! from `+x`. The bond vector `d` runs from the `from` end to the `to` end, whose cell shift (and,
//! for a rotor, its pivot) enters as the offset `(ox, oy)`:
//!
//! | type | degrees of freedom | `d` | arguments of the rendered kernel |
//! | --- | --- | --- | --- |
//! | joint-joint | `x1, y1, x2, y2` | `((x2 - x1) + ox, (y2 - y1) + oy)` | `x1 y1 x2 y2 ox oy k l0` |
//! | joint-rotor | `x1, y1, phi2` | `((ox + r2 c2) - x1, (oy + r2 s2) - y1)` | `x1 y1 s2 c2 ox oy r2 k l0` |
//! | rotor-rotor | `phi1, phi2` | `((ox + r2 c2) - r1 c1, (oy + r2 s2) - r1 s1)` | `s1 c1 s2 c2 ox oy r1 r2 k l0` |
//!
//! (`s_i, c_i = sin phi_i, cos phi_i`; a joint-joint bond's `(ox, oy)` is the `to` end's shift,
//! a joint-rotor's the rotor's pivot plus shift, a rotor-rotor's the `to` pivot plus shift minus
//! the `from` pivot. A rotor-joint bond is a joint-rotor bond read from its other end.)
//!
//! The bond stores `law(l, l0, k)` at `l = |d|`. As for the chain's spring ([`SpringTerms`]),
//! the gradient and the Hessian block are written in the paper's form (Appendix D), through
//! [`LawAtLength`]: the gradient `t^ d(q/2)/du_i`, the Hessian block the stress matrix
//! `t^ d2(q/2)/du_i du_j` plus the material part `(g^ / q) d(q/2)/du_i d(q/2)/du_j`, with
//! `q = l^2`, the tension coefficient `t^ = t / l` and `g^ = dt/dl - t^`. The compatibility row
//! is `dl / du` per displacement: `dl/dx` for a joint, `dl / d(r phi)` for a rotor, as
//! `chain-network`'s compatibility matrix (whose rotor column is the tip's arc length).
//!
//! A law may take parameters of its own beyond `k` and `l0`: [`polynomial`], the run-time
//! polynomial law in the elongation whose coefficients `c2 .. c6` are symbols, is rendered with
//! them appended to every type's arguments ([`BondKernels::with_parameters`]).
//!
//! [`SpringTerms`]: crate::spring::SpringTerms

use std::fmt::Write;

use crate::diff::diff;
use crate::graph::{Graph, Id, Node};
use crate::lower::lower;
use crate::spring::{LawAtLength, SpringLaw};

/// The three types of bond, by the kinds of their two ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BondKind {
    /// Two joints: four degrees of freedom `x1, y1, x2, y2`.
    JointJoint,
    /// A joint (`from`) and a rotor (`to`): `x1, y1, phi2`.
    JointRotor,
    /// Two rotors: `phi1, phi2`.
    RotorRotor,
}

impl BondKind {
    /// The three types, in the order the kernel files list them.
    pub const ALL: [BondKind; 3] = [BondKind::JointJoint, BondKind::JointRotor, BondKind::RotorRotor];

    /// The name of the type's module in a rendered kernel file.
    pub fn module(self) -> &'static str {
        match self {
            BondKind::JointJoint => "joint_joint",
            BondKind::JointRotor => "joint_rotor",
            BondKind::RotorRotor => "rotor_rotor",
        }
    }

    /// The arguments of the type's rendered kernels, in order.
    pub fn args(self) -> &'static [&'static str] {
        match self {
            BondKind::JointJoint => &["x1", "y1", "x2", "y2", "ox", "oy", "k", "l0"],
            BondKind::JointRotor => &["x1", "y1", "s2", "c2", "ox", "oy", "r2", "k", "l0"],
            BondKind::RotorRotor => &["s1", "c1", "s2", "c2", "ox", "oy", "r1", "r2", "k", "l0"],
        }
    }

    /// The degrees of freedom of the bond, in order (the symbols' names).
    pub fn dofs(self) -> &'static [&'static str] {
        match self {
            BondKind::JointJoint => &["x1", "y1", "x2", "y2"],
            BondKind::JointRotor => &["x1", "y1", "phi2"],
            BondKind::RotorRotor => &["phi1", "phi2"],
        }
    }
}

/// Every quantity of one bond, as nodes of the graph. Blocks are the upper triangle of the
/// symmetric block on the bond's degrees of freedom, row by row (`[00, 01, .., 0n, 11, .., nn]`).
#[derive(Clone, Debug)]
pub struct BondTerms {
    /// The bond's type.
    pub kind: BondKind,
    /// The degrees of freedom (symbols), in [`BondKind::dofs`]' order.
    pub dofs: Vec<Id>,
    /// The rotor ends' `(sin phi, cos phi)` nodes with their argument names (`s1`, `c1`, ...).
    pub trig: Vec<(Id, &'static str)>,
    pub length: Id,
    pub energy: Id,
    pub tension: Id,
    pub gradient: Vec<Id>,
    pub hessian: Vec<Id>,
    pub material: Vec<Id>,
    pub stress: Vec<Id>,
    /// `dl / du` per displacement (`dl/dx`, or `dl / d(r phi)` for a rotor).
    pub compatibility: Vec<Id>,
}

/// A rotor's tip `(ox + r cos phi, oy + r sin phi)` and its `(sin, cos)` nodes.
fn tip(g: &mut Graph, phi: Id, r: Id) -> (Id, Id, Id, Id) {
    let (s, c) = (g.sin(phi), g.cos(phi));
    (g.mul(r, c), g.mul(r, s), s, c)
}

impl BondTerms {
    /// Derives every term of a bond of type `kind` under `law`, every parameter a symbol named
    /// as in [`BondKind::args`].
    pub fn derive(g: &mut Graph, law: &SpringLaw, kind: BondKind) -> Self {
        let dofs: Vec<Id> = kind.dofs().iter().map(|name| g.symbol(name)).collect();
        let (ox, oy, k, l0) = (g.symbol("ox"), g.symbol("oy"), g.symbol("k"), g.symbol("l0"));
        let mut trig = Vec::new();
        let mut rotor_lengths = vec![None; dofs.len()];
        let (dx, dy) = match kind {
            BondKind::JointJoint => {
                let (x1, y1, x2, y2) = (dofs[0], dofs[1], dofs[2], dofs[3]);
                let ex = g.sub(x2, x1);
                let ey = g.sub(y2, y1);
                (g.add(ex, ox), g.add(ey, oy))
            }
            BondKind::JointRotor => {
                let r2 = g.symbol("r2");
                let (rc, rs, s2, c2) = tip(g, dofs[2], r2);
                trig.extend([(s2, "s2"), (c2, "c2")]);
                rotor_lengths[2] = Some(r2);
                let qx = g.add(ox, rc);
                let qy = g.add(oy, rs);
                (g.sub(qx, dofs[0]), g.sub(qy, dofs[1]))
            }
            BondKind::RotorRotor => {
                let (r1, r2) = (g.symbol("r1"), g.symbol("r2"));
                let (rc1, rs1, s1, c1) = tip(g, dofs[0], r1);
                let (rc2, rs2, s2, c2) = tip(g, dofs[1], r2);
                trig.extend([(s1, "s1"), (c1, "c1"), (s2, "s2"), (c2, "c2")]);
                rotor_lengths[0] = Some(r1);
                rotor_lengths[1] = Some(r2);
                let qx = g.add(ox, rc2);
                let qy = g.add(oy, rs2);
                (g.sub(qx, rc1), g.sub(qy, rs1))
            }
        };
        let dx2 = g.powi(dx, 2);
        let dy2 = g.powi(dy, 2);
        let q = g.add(dx2, dy2);
        let length = g.sqrt(q);
        let LawAtLength { energy, tension, t_hat, g_hat } = LawAtLength::derive(g, law, k, l0, length, q);

        // The paper's form (Appendix D), as the chain's spring: `t^ d(q/2)/du_i`, and the stress
        // matrix plus `(g^ / q) d(q/2)/du_i d(q/2)/du_j`.
        let half = g.constant(0.5);
        let half_q = g.mul(half, q);
        let dq: Vec<Id> = dofs.iter().map(|&u| diff(g, half_q, u)).collect();
        let gradient = dq.iter().map(|&d| g.mul(t_hat, d)).collect();
        let pairs: Vec<(usize, usize)> =
            (0..dofs.len()).flat_map(|i| (i..dofs.len()).map(move |j| (i, j))).collect();
        let stress: Vec<Id> = pairs
            .iter()
            .map(|&(i, j)| {
                let d = diff(g, dq[i], dofs[j]);
                g.mul(t_hat, d)
            })
            .collect();
        let per_q = g.div(g_hat, q);
        let hessian = pairs
            .iter()
            .zip(&stress)
            .map(|(&(i, j), &s)| {
                let ab = g.mul(dq[i], dq[j]);
                let m = g.mul(per_q, ab);
                g.add(m, s)
            })
            .collect();
        // Guest's material part in the paper's own terms, `g^ dl_i dl_j`.
        let dl: Vec<Id> = dofs.iter().map(|&u| diff(g, length, u)).collect();
        let material = pairs
            .iter()
            .map(|&(i, j)| {
                let ab = g.mul(dl[i], dl[j]);
                g.mul(g_hat, ab)
            })
            .collect();
        let compatibility = dl
            .iter()
            .zip(&rotor_lengths)
            .map(|(&d, r)| match r {
                Some(r) => g.div(d, *r),
                None => d,
            })
            .collect();
        Self { kind, dofs, trig, length, energy, tension, gradient, hessian, material, stress, compatibility }
    }
}

/// The names of the polynomial law's coefficients `c2 .. c6` as the rendered kernels take them,
/// after [`BondKind::args`]: `p2 .. p6` (`c2` already names a rotor's `cos phi2`).
pub const POLYNOMIAL_COEFFICIENTS: [&str; 5] = ["p2", "p3", "p4", "p5", "p6"];

/// The polynomial law in the elongation `e = l - l0`,
///
/// `E(e) = k (c2 e^2 / 2 + c3 e^3 / 3 + c4 e^4 / 4 + c5 e^5 / 5 + c6 e^6 / 6)`,
///
/// with the coefficients `c2 .. c6` symbols (named as in [`POLYNOMIAL_COEFFICIENTS`]), so one rendered kernel
/// serves every choice at run time: `c2 = 1` alone is the harmonic law `k e^2 / 2`, `c4 > 0` a
/// hardening spring, and `c2 = a b c4`, `c3 = -(a + b) c4` the double well whose tension
/// `k c4 e (e - a) (e - b)` vanishes at `e = 0, a, b` (stable at `0` and `b` for `0 < a < b`:
/// the bistable element of a transition-wave chain). Written in Horner's form,
/// `k e^2 (c2/2 + e (c3/3 + e (c4/4 + e (c5/5 + e c6/6))))`: five multiplications and a
/// rounding error bounded by the sum of the terms' magnitudes; every derivative is the engine's.
pub fn polynomial(g: &mut Graph) -> SpringLaw {
    let (l, l0, k) = SpringLaw::symbols(g);
    let e = g.sub(l, l0);
    let mut horner = None;
    for (j, name) in POLYNOMIAL_COEFFICIENTS.iter().enumerate().rev() {
        let c = g.symbol(name);
        let power = g.constant((j + 2) as f64);
        let term = g.div(c, power);
        horner = Some(match horner {
            None => term,
            Some(inner) => {
                let shifted = g.mul(e, inner);
                g.add(term, shifted)
            }
        });
    }
    let e2 = g.powi(e, 2);
    let ke2 = g.mul(k, e2);
    let energy = g.mul(ke2, horner.expect("five coefficients"));
    SpringLaw::custom(g, energy)
}

/// One function of a rendered bond kernel: the chain kernel's description over the bond's terms.
pub type BondFunction = crate::chain::KernelFunction<BondTerms>;

/// The functions rendered for each bond type (the chain kernel's set, `chain::KERNEL_FUNCTIONS`,
/// over the bond's degrees of freedom).
pub const BOND_FUNCTIONS: [BondFunction; 10] = [
    BondFunction { name: "Energy", doc: "The bond's stored energy.", outputs: |t| vec![t.energy] },
    BondFunction { name: "Length", doc: "The bond's length.", outputs: |t| vec![t.length] },
    BondFunction { name: "Tension", doc: "The bond's tension `dlaw/dl`.", outputs: |t| vec![t.tension] },
    BondFunction {
        name: "Gradient",
        doc: "The gradient in the bond's degrees of freedom.",
        outputs: |t| t.gradient.clone(),
    },
    BondFunction {
        name: "Hessian",
        doc: "The Hessian block, upper triangle row by row.",
        outputs: |t| t.hessian.clone(),
    },
    BondFunction {
        name: "Material",
        doc: "The material part `g^ (dl/du)(dl/du)^T` of the block (paper Eq. `eq:prestress6`).",
        outputs: |t| t.material.clone(),
    },
    BondFunction {
        name: "Stress",
        doc: "The stress-matrix part `t^ d2(l^2/2)/du du` of the block (paper Eq. `eq:prestress7`).",
        outputs: |t| t.stress.clone(),
    },
    BondFunction {
        name: "Compatibility",
        doc: "The compatibility row `dl / du` per displacement (a rotor's: `dl / d(r phi)`).",
        outputs: |t| t.compatibility.clone(),
    },
    BondFunction {
        name: "EnergyGradient",
        doc: "Energy and gradient in one pass: `[E, dE/du..]`.",
        outputs: |t| [[t.energy].as_slice(), &t.gradient].concat(),
    },
    BondFunction {
        name: "EnergyGradientHessian",
        doc: "Energy, gradient and Hessian block in one pass: `[E, dE/du.., block..]`.",
        outputs: |t| [[t.energy].as_slice(), &t.gradient, &t.hessian].concat(),
    },
];

/// A law's bond kernels: each bond type derived in its own graph.
pub struct BondKernels {
    pub bonds: Vec<(Graph, BondTerms)>,
    /// The law's own parameters (symbols), appended to every type's arguments.
    pub parameters: Vec<&'static str>,
}

impl BondKernels {
    /// Derives the three bond types for `law` (built in each fresh graph by the caller's closure).
    pub fn new(law: &dyn Fn(&mut Graph) -> SpringLaw) -> Self {
        Self::with_parameters(law, &[])
    }

    /// As [`BondKernels::new`] for a law with parameters of its own (symbols of the graph other
    /// than the law's `l`, `l0`, `k`), which the rendered kernels take after
    /// [`BondKind::args`], in the order of `parameters`.
    pub fn with_parameters(law: &dyn Fn(&mut Graph) -> SpringLaw, parameters: &[&'static str]) -> Self {
        let bonds = BondKind::ALL
            .iter()
            .map(|&kind| {
                let mut g = Graph::new();
                let law = law(&mut g);
                let terms = BondTerms::derive(&mut g, &law, kind);
                (g, terms)
            })
            .collect();
        Self { bonds, parameters: parameters.to_vec() }
    }

    /// Rust source of the kernels: per bond type a module (`joint_joint`, `joint_rotor`,
    /// `rotor_rotor`) holding, for each of [`BOND_FUNCTIONS`], a unit struct implementing
    /// `BondFn<A, M>`, whose `#[inline(always)] eval<L: Lane>(x: [L; A]) -> [L; M]` is generic
    /// over the lane type and takes [`BondKind::args`] (then the law's parameters), and a unit
    /// struct `Kernels` naming them all (`BondKernels<A, N, N + 1, H, 1 + N + H>`, `N` degrees
    /// of freedom, `H` block entries); after the modules, a unit struct `Law` implementing
    /// `LawKernels` with the three types' `Kernels` (`LawKernels<A1, A2, A3>` with the three
    /// types' argument counts, for a law with parameters): what a network model's drivers are
    /// generic over. The caller puts `Lane`, `BondFn`, `BondKernels` and `LawKernels` in the
    /// file's scope; each module imports them from `super`.
    pub fn render(&self) -> Result<String, String> {
        let mut out = String::new();
        for (g, terms) in &self.bonds {
            let leaf = |id: Id| -> Option<String> {
                if let Some((_, name)) = terms.trig.iter().find(|(t, _)| *t == id) {
                    return Some((*name).to_owned());
                }
                match g.node(id) {
                    Node::Symbol(s) => Some(g.symbol_name(s).to_owned()),
                    _ => None,
                }
            };
            let args: Vec<&str> = terms.kind.args().iter().chain(&self.parameters).copied().collect();
            let a = args.len();
            let _ = writeln!(
                out,
                "/// The {} bond (arguments `{}`).",
                terms.kind.module().replace('_', "-"),
                args.join(" ")
            );
            let _ = writeln!(out, "pub mod {} {{", terms.kind.module());
            let _ = writeln!(out, "use super::{{BondFn, BondKernels, Lane}};\n");
            for f in &BOND_FUNCTIONS {
                let outputs = (f.outputs)(terms);
                let program = lower(g, &outputs, &leaf)?;
                let m = outputs.len();
                let _ = writeln!(out, "/// {}", f.doc);
                let _ = writeln!(out, "pub struct {};\n", f.name);
                let _ = writeln!(out, "impl BondFn<{a}, {m}> for {} {{", f.name);
                let _ = writeln!(out, "#[inline(always)]");
                let _ = writeln!(out, "#[allow(unused_variables, clippy::let_and_return)]");
                let _ = writeln!(out, "fn eval<L: Lane>(x: [L; {a}]) -> [L; {m}] {{");
                let _ = writeln!(out, "let [{}] = x;", args.join(", "));
                out.push_str(&crate::chain::render_lanes(&program));
                let _ = writeln!(out, "}}\n}}\n");
            }
            let n = terms.dofs.len();
            let h = n * (n + 1) / 2;
            let _ = writeln!(out, "/// Every kernel of the bond type, for the model's drivers.");
            let _ = writeln!(out, "pub struct Kernels;\n");
            let _ = writeln!(out, "impl BondKernels<{a}, {n}, {}, {h}, {}> for Kernels {{", n + 1, 1 + n + h);
            for f in &BOND_FUNCTIONS {
                let _ = writeln!(out, "type {0} = {0};", f.name);
            }
            let _ = writeln!(out, "}}\n");
            let _ = writeln!(out, "}}\n");
        }
        let _ = writeln!(out, "/// The law's kernels of every bond type.");
        let _ = writeln!(out, "pub struct Law;\n");
        // A law with parameters of its own names its argument counts; the others take the
        // trait's defaults (8, 9, 10), so their files stay as they were.
        let arities = if self.parameters.is_empty() {
            String::new()
        } else {
            let a: Vec<String> =
                BondKind::ALL.iter().map(|k| (k.args().len() + self.parameters.len()).to_string()).collect();
            format!("<{}>", a.join(", "))
        };
        let _ = writeln!(out, "impl LawKernels{arities} for Law {{");
        for kind in BondKind::ALL {
            let name = format!("{kind:?}");
            let _ = writeln!(out, "type {name} = {}::Kernels;", kind.module());
        }
        let _ = writeln!(out, "}}");
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The parameters of the test bonds (pivots and shifts folded into `(ox, oy)` by hand).
    const R1: f64 = 0.8;
    const R2: f64 = 0.7;
    const K: f64 = 3.0;
    const L0: f64 = 1.1;
    const OFFSET: (f64, f64) = (1.3, -0.4);
    /// The polynomial law's coefficients `c2 .. c6` in the tests: every power present, signs mixed.
    const C: [f64; 5] = [0.9, -1.7, 2.3, -0.6, 0.45];

    fn law_of(energy: fn(f64) -> f64) -> impl Fn(f64) -> f64 {
        energy
    }

    /// The bond's endpoints written in `f64` from the cell format's conventions, independently of
    /// the engine: `u` are the degrees of freedom.
    fn ends(kind: BondKind, u: &[f64]) -> ([f64; 2], [f64; 2]) {
        let (ox, oy) = OFFSET;
        match kind {
            BondKind::JointJoint => ([u[0], u[1]], [u[2] + ox, u[3] + oy]),
            BondKind::JointRotor => ([u[0], u[1]], [ox + R2 * u[2].cos(), oy + R2 * u[2].sin()]),
            BondKind::RotorRotor => {
                ([R1 * u[0].cos(), R1 * u[0].sin()], [ox + R2 * u[1].cos(), oy + R2 * u[1].sin()])
            }
        }
    }

    fn distance(kind: BondKind, u: &[f64]) -> f64 {
        let (p, q) = ends(kind, u);
        (q[0] - p[0]).hypot(q[1] - p[1])
    }

    fn value_of<'a>(kind: BondKind, u: &'a [f64]) -> impl Fn(&str) -> f64 + 'a {
        move |name| {
            if let Some(i) = kind.dofs().iter().position(|d| *d == name) {
                return u[i];
            }
            match name {
                "ox" => OFFSET.0,
                "oy" => OFFSET.1,
                "r1" => R1,
                "r2" => R2,
                "k" => K,
                "l0" => L0,
                "p2" => C[0],
                "p3" => C[1],
                "p4" => C[2],
                "p5" => C[3],
                "p6" => C[4],
                other => panic!("a symbol the bond does not take: {other}"),
            }
        }
    }

    fn points(kind: BondKind) -> Vec<Vec<f64>> {
        let all = [[0.3, -0.2, 1.1, 0.9], [1.1, 0.9, -0.7, 2.0], [-0.7, 2.0, 0.4, -1.3]];
        all.iter().map(|p| p[..kind.dofs().len()].to_vec()).collect()
    }

    /// Central differences of `f` at `u` along degrees of freedom `i` (and `j`).
    fn fd1(f: &dyn Fn(&[f64]) -> f64, u: &[f64], i: usize, h: f64) -> f64 {
        let at = |s: f64| {
            let mut v = u.to_vec();
            v[i] += s;
            f(&v)
        };
        (at(h) - at(-h)) / (2.0 * h)
    }

    fn fd2(f: &dyn Fn(&[f64]) -> f64, u: &[f64], i: usize, j: usize, h: f64) -> f64 {
        let at = |si: f64, sj: f64| {
            let mut v = u.to_vec();
            v[i] += si;
            v[j] += sj;
            f(&v)
        };
        (at(h, h) - at(h, -h) - at(-h, h) + at(-h, -h)) / (4.0 * h * h)
    }

    type Law = (fn(&mut Graph) -> SpringLaw, fn(f64) -> f64);

    /// `k (exp(l - l0) - 1 - (l - l0))`: a custom law unlike both built-in ones.
    fn exponential(g: &mut Graph) -> SpringLaw {
        let (l, l0, k) = SpringLaw::symbols(g);
        let stretch = g.sub(l, l0);
        let e = g.exp(stretch);
        let one = g.one();
        let e1 = g.sub(e, one);
        let e2 = g.sub(e1, stretch);
        let energy = g.mul(k, e2);
        SpringLaw::custom(g, energy)
    }

    const LAWS: [Law; 4] = [
        (SpringLaw::harmonic, |l| 0.5 * K * (l - L0).powi(2)),
        (SpringLaw::quartic, |l| K * (l * l - L0 * L0).powi(2) / (8.0 * L0 * L0)),
        (exponential, |l| K * ((l - L0).exp() - 1.0 - (l - L0))),
        // The sum of powers as written in the law's definition, not the engine's Horner form.
        (polynomial, |l| {
            K * (0..5).map(|j| C[j] * (l - L0).powi(j as i32 + 2) / (j + 2) as f64).sum::<f64>()
        }),
    ];

    /// Length, energy, gradient, Hessian block and compatibility row of every bond type and law
    /// against the endpoints' distance written in `f64` (central differences); material part
    /// plus stress matrix is the Hessian.
    #[test]
    fn every_bond_type_matches_finite_differences_of_its_endpoints_distance() {
        for (law, energy_of_length) in LAWS {
            let energy_of_length = law_of(energy_of_length);
            for kind in BondKind::ALL {
                let mut g = Graph::new();
                let law = law(&mut g);
                let t = BondTerms::derive(&mut g, &law, kind);
                let n = kind.dofs().len();
                let energy = |u: &[f64]| energy_of_length(distance(kind, u));
                let length = |u: &[f64]| distance(kind, u);
                for u in points(kind) {
                    let v = value_of(kind, &u);
                    let close = |a: f64, b: f64, tol: f64| (a - b).abs() <= tol * (1.0 + b.abs());
                    assert!(close(g.eval(t.length, &v), length(&u), 1e-14), "{kind:?} length");
                    assert!(close(g.eval(t.energy, &v), energy(&u), 1e-13), "{kind:?} energy");
                    let mut pair = 0;
                    for i in 0..n {
                        let grad = g.eval(t.gradient[i], &v);
                        assert!(close(grad, fd1(&energy, &u, i, 1e-6), 1e-8), "{kind:?} gradient {i}");
                        // A rotor's column is the tip's arc length: `dl / (r dphi)`.
                        let r = match (kind, i) {
                            (BondKind::JointRotor, 2) | (BondKind::RotorRotor, 1) => R2,
                            (BondKind::RotorRotor, 0) => R1,
                            _ => 1.0,
                        };
                        let row = g.eval(t.compatibility[i], &v);
                        assert!(
                            close(row, fd1(&length, &u, i, 1e-6) / r, 1e-8),
                            "{kind:?} compatibility {i}"
                        );
                        for j in i..n {
                            let h = g.eval(t.hessian[pair], &v);
                            let m = g.eval(t.material[pair], &v);
                            let s = g.eval(t.stress[pair], &v);
                            assert!(
                                close(h, fd2(&energy, &u, i, j, 1e-4), 1e-5),
                                "{kind:?} block ({i}, {j})"
                            );
                            assert!(close(m + s, h, 1e-12), "{kind:?} material + stress ({i}, {j})");
                            pair += 1;
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn kernels_render_every_type_and_function_naming_only_their_arguments() {
        let src = BondKernels::new(&SpringLaw::harmonic).render().unwrap();
        for kind in BondKind::ALL {
            assert!(src.contains(&format!("pub mod {} {{", kind.module())));
            assert!(src.contains(&format!("let [{}] = x;", kind.args().join(", "))));
        }
        assert_eq!(src.matches("impl BondFn<").count(), 3 * BOND_FUNCTIONS.len());
        let code: String = src.lines().filter(|l| !l.starts_with("///")).collect();
        assert!(!code.contains("sin(") && !code.contains("phi"), "angles enter only through s and c");
    }

    #[test]
    fn the_polynomial_law_takes_its_coefficients_after_the_bond_arguments() {
        let src = BondKernels::with_parameters(&polynomial, &POLYNOMIAL_COEFFICIENTS).render().unwrap();
        for kind in BondKind::ALL {
            let args: Vec<&str> = kind.args().iter().chain(&POLYNOMIAL_COEFFICIENTS).copied().collect();
            assert!(src.contains(&format!("let [{}] = x;", args.join(", "))), "{kind:?}");
        }
    }
}
