//! A whole chain in symbols, and the per-spring kernel.
//!
//! Two emission strategies come from the one derivation of [`SpringTerms`]:
//! - [`ChainOutputs::unrolled`] instantiates the spring derivation for every spring with that
//!   spring's own parameters (constants folded, struct fields as symbols) in one graph, so the
//!   sine and cosine of each angle are shared by the two springs that use them, and assembles the
//!   chain's energy, gradient and banded matrices (paper Eq. `eq:prestress8`: `K = sum_p K_p`).
//! - [`Kernel`] derives one spring with every parameter symbolic and renders one function per
//!   quantity; the macro calls it in a loop for large chains, and `chain-core`'s runtime-sized
//!   chain calls the same rendered source.

use std::fmt::Write;

use crate::graph::{Graph, Id, Node};
use crate::lower::{Expr, Operand, Program, lower, render_const};
use crate::spring::{SpringLaw, SpringParams, SpringTerms};

/// The parameters of spring `p` (a constant or a symbol each) for [`ChainOutputs::unrolled`].
pub type SpringSpec = SpringParams;

/// Every output of an unrolled chain of `n` rotors, as graph nodes.
///
/// Banded matrices are given as `diag` (length `n`) and `off` (length `n - 1`, entry `(p, p + 1)`).
#[derive(Clone, Debug)]
pub struct ChainOutputs {
    pub n: usize,
    /// `(sin theta_i, cos theta_i)` of every rotor: the leaves the emitter computes with one
    /// `sin_cos` call per angle.
    pub trig: Vec<(Id, Id)>,
    pub energy: Id,
    /// The partial sums `sum_{q <= p} E_q` of the springs' energies (the last is `energy`): a
    /// fused method stores them as it goes, so each spring's terms die with its rotors.
    pub energy_partial: Vec<Id>,
    pub gradient: Vec<Id>,
    pub hessian_diag: Vec<Id>,
    pub hessian_off: Vec<Id>,
    pub material_diag: Vec<Id>,
    pub material_off: Vec<Id>,
    pub stress_diag: Vec<Id>,
    pub stress_off: Vec<Id>,
    pub lengths: Vec<Id>,
    pub tensions: Vec<Id>,
    /// Compatibility matrix `C[p][p] = dl_p / d(r_p theta_p)`.
    pub compatibility_left: Vec<Id>,
    /// Compatibility matrix `C[p][p+1] = dl_p / d(r_{p+1} theta_{p+1})`.
    pub compatibility_right: Vec<Id>,
}

impl ChainOutputs {
    /// Derives every spring of the chain. `springs[p]` holds spring `p`'s parameters and
    /// `angle(i)` is the symbol of rotor `i`'s angle.
    pub fn unrolled(
        g: &mut Graph,
        law: &SpringLaw,
        springs: &[SpringSpec],
        angle: &dyn Fn(&mut Graph, usize) -> Id,
    ) -> Self {
        let n = springs.len() + 1;
        let thetas: Vec<Id> = (0..n).map(|i| angle(g, i)).collect();
        let terms: Vec<SpringTerms> = springs
            .iter()
            .enumerate()
            .map(|(p, spec)| SpringTerms::derive(g, law, spec, thetas[p], thetas[p + 1]))
            .collect();
        let trig = thetas.iter().map(|&t| (g.sin(t), g.cos(t))).collect();

        let mut energy = g.zero();
        let mut energy_partial = Vec::with_capacity(terms.len());
        for t in &terms {
            energy = g.add(energy, t.energy);
            energy_partial.push(energy);
        }
        // Rotor i collects the right end of spring i - 1 and the left end of spring i.
        let assemble = |g: &mut Graph, pair: &dyn Fn(&SpringTerms) -> (Id, Id)| -> Vec<Id> {
            (0..n)
                .map(|i| {
                    let left = if i > 0 { pair(&terms[i - 1]).1 } else { g.zero() };
                    let right = if i + 1 < n { pair(&terms[i]).0 } else { g.zero() };
                    g.add(left, right)
                })
                .collect()
        };
        let gradient = assemble(g, &|t| (t.gradient[0], t.gradient[1]));
        let hessian_diag = assemble(g, &|t| (t.hessian[0], t.hessian[2]));
        let material_diag = assemble(g, &|t| (t.material[0], t.material[2]));
        let stress_diag = assemble(g, &|t| (t.stress[0], t.stress[2]));
        Self {
            n,
            trig,
            energy,
            energy_partial,
            gradient,
            hessian_diag,
            hessian_off: terms.iter().map(|t| t.hessian[1]).collect(),
            material_diag,
            material_off: terms.iter().map(|t| t.material[1]).collect(),
            stress_diag,
            stress_off: terms.iter().map(|t| t.stress[1]).collect(),
            lengths: terms.iter().map(|t| t.length).collect(),
            tensions: terms.iter().map(|t| t.tension).collect(),
            compatibility_left: terms.iter().map(|t| t.compatibility[0]).collect(),
            compatibility_right: terms.iter().map(|t| t.compatibility[1]).collect(),
        }
    }

    /// The leaf names of an unrolled chain: `s[iusize]` / `c[iusize]` for the sine and cosine of rotor
    /// `i` (the emitter fills two arrays `s` and `c` with one `sin_cos_into` call), and every
    /// symbol by its own name (struct fields are named by the Rust expression that reads them,
    /// e.g. `self.k_imp`).
    pub fn leaf_namer<'a>(&'a self, g: &'a Graph) -> impl Fn(Id) -> Option<String> + 'a {
        let trig: std::collections::HashMap<Id, String> = self
            .trig
            .iter()
            .enumerate()
            .flat_map(|(i, &(s, c))| [(s, format!("s[{i}usize]")), (c, format!("c[{i}usize]"))])
            .collect();
        move |id| match g.node(id) {
            Node::Symbol(s) => Some(g.symbol_name(s).to_owned()),
            _ => trig.get(&id).cloned(),
        }
    }
}

/// The per-spring kernel: one spring derived with every parameter symbolic.
///
/// Its functions take `x = [s1, c1, s2, c2, a, r1, r2, k, l0]`: the sine and cosine of the two
/// rotors' angles (so that a loop computes each angle's `sin_cos` once and hands it to both of
/// its springs), the lattice spacing, the two rotor lengths, and the spring's stiffness and rest
/// length.
pub struct Kernel {
    pub graph: Graph,
    pub terms: SpringTerms,
}

/// The kernel's argument, element by element.
pub const KERNEL_ARGS: [&str; 9] = ["s1", "c1", "s2", "c2", "a", "r1", "r2", "k", "l0"];

/// One rendered kernel: the type implementing the kernel trait (`SpringFn<M>` for the chain's
/// spring over [`SpringTerms`], `BondFn<A, M>` for a network's bond over `bond::BondTerms`), its
/// documentation, and its `M` outputs.
pub struct KernelFunction<Terms = SpringTerms> {
    pub name: &'static str,
    pub doc: &'static str,
    pub outputs: fn(&Terms) -> Vec<Id>,
}

/// The kernels. The fused ones share every subexpression of their outputs (one square root per
/// spring for energy, gradient and Hessian block together).
pub const KERNEL_FUNCTIONS: [KernelFunction; 10] = [
    KernelFunction { name: "Energy", doc: "The spring's stored energy.", outputs: |t| vec![t.energy] },
    KernelFunction { name: "Length", doc: "The spring's length.", outputs: |t| vec![t.length] },
    KernelFunction { name: "Tension", doc: "The spring's tension `dlaw/dl`.", outputs: |t| vec![t.tension] },
    KernelFunction { name: "Gradient", doc: "`[dE/dtheta1, dE/dtheta2]`.", outputs: |t| t.gradient.to_vec() },
    KernelFunction {
        name: "Hessian",
        doc: "The Hessian block `[11, 12, 22]` in the two angles.",
        outputs: |t| t.hessian.to_vec(),
    },
    KernelFunction {
        name: "Material",
        doc: "The material part `g^ (dl/dtheta)(dl/dtheta)^T` of the block (paper Eq. `eq:prestress6`).",
        outputs: |t| t.material.to_vec(),
    },
    KernelFunction {
        name: "Stress",
        doc: "The stress-matrix part `t^ d2(l^2/2)/dtheta dtheta` of the block (paper Eq. `eq:prestress7`).",
        outputs: |t| t.stress.to_vec(),
    },
    KernelFunction {
        name: "Compatibility",
        doc: "The compatibility-matrix row `[dl/d(r1 theta1), dl/d(r2 theta2)]`.",
        outputs: |t| t.compatibility.to_vec(),
    },
    KernelFunction {
        name: "EnergyGradient",
        doc: "Energy and gradient in one pass: `[E, dE/dtheta1, dE/dtheta2]`.",
        outputs: |t| vec![t.energy, t.gradient[0], t.gradient[1]],
    },
    KernelFunction {
        name: "EnergyGradientHessian",
        doc: "Energy, gradient and Hessian block in one pass: `[E, dE/dtheta1, dE/dtheta2, 11, 12, 22]`.",
        outputs: |t| [[t.energy].as_slice(), &t.gradient, &t.hessian].concat(),
    },
];

impl Kernel {
    /// Derives the kernel for `law` (built in a fresh graph by the caller's closure).
    pub fn new(law: &dyn Fn(&mut Graph) -> SpringLaw) -> Self {
        let mut g = Graph::new();
        let law = law(&mut g);
        let params = SpringParams {
            a: g.symbol("a"),
            r1: g.symbol("r1"),
            r2: g.symbol("r2"),
            k: g.symbol("k"),
            l0: g.symbol("l0"),
        };
        let t1 = g.symbol("theta1");
        let t2 = g.symbol("theta2");
        let terms = SpringTerms::derive(&mut g, &law, &params, t1, t2);
        Self { graph: g, terms }
    }

    /// Rust source of the kernels: for each of [`KERNEL_FUNCTIONS`] a unit struct implementing
    /// `SpringFn<M>`, whose `eval<L: Lane>(x: [L; 9]) -> [L; M]` is generic over the lane type
    /// (`f64`, or the vector types of `chain_core::simd`). The caller puts `Lane` and `SpringFn`
    /// in scope. `eval` is `#[inline(always)]`, so it is compiled into each driver at each lane
    /// width, and constant arguments fold at the call site.
    pub fn render(&self) -> Result<String, String> {
        let g = &self.graph;
        let [s1, c1, s2, c2] = self.terms.trig;
        let leaf = |id: Id| -> Option<String> {
            let trig = [(s1, "s1"), (c1, "c1"), (s2, "s2"), (c2, "c2")];
            if let Some((_, name)) = trig.iter().find(|(t, _)| *t == id) {
                return Some((*name).to_owned());
            }
            match g.node(id) {
                Node::Symbol(s) => Some(g.symbol_name(s).to_owned()),
                _ => None,
            }
        };
        let destructure = format!("let [{}] = x;", KERNEL_ARGS.join(", "));
        let mut out = String::new();
        for f in &KERNEL_FUNCTIONS {
            let outputs = (f.outputs)(&self.terms);
            let program = lower(g, &outputs, &leaf)?;
            let m = outputs.len();
            let _ = writeln!(out, "/// {}", f.doc);
            let _ = writeln!(out, "pub struct {};\n", f.name);
            let _ = writeln!(out, "impl SpringFn<{m}> for {} {{", f.name);
            let _ = writeln!(out, "#[inline(always)]");
            let _ = writeln!(out, "#[allow(unused_variables, clippy::let_and_return)]");
            let _ = writeln!(out, "fn eval<L: Lane>(x: [L; 9]) -> [L; {m}] {{");
            let _ = writeln!(out, "{destructure}");
            out.push_str(&render_lanes(&program));
            let _ = writeln!(out, "}}\n}}\n");
        }
        Ok(out)
    }
}

/// The steps and the output array of `program` over a lane type `L`.
///
/// Why not `Program::render`: that prints `f64` source (constants as `f64` literals, functions as
/// free `math` calls) for the unrolled code; here constants are `L::splat(..)` and functions are
/// `Lane` methods. Integer powers are written as `Program::render` writes them (products for
/// small exponents), so a kernel computes exactly what the unrolled code computes.
pub(crate) fn render_lanes(program: &Program) -> String {
    let op = |o: &Operand| match o {
        Operand::Temp(i) => format!("t{i}"),
        Operand::Leaf(name) => name.clone(),
        Operand::Const(c) if c.is_finite() => format!("L::splat({c:?}f64)"),
        Operand::Const(c) => format!("L::splat({})", render_const(*c)),
    };
    let mut out = String::new();
    for (i, step) in program.steps.iter().enumerate() {
        let rhs = match step {
            Expr::Add(a, b) => format!("{} + {}", op(a), op(b)),
            Expr::Sub(a, b) => format!("{} - {}", op(a), op(b)),
            Expr::Mul(a, b) => format!("{} * {}", op(a), op(b)),
            Expr::Div(a, b) => format!("{} / {}", op(a), op(b)),
            Expr::Neg(a) => format!("-{}", op(a)),
            Expr::Powi(a, n) => {
                let x = op(a);
                match n {
                    2 => format!("{x} * {x}"),
                    3 => format!("{x} * {x} * {x}"),
                    4 => format!("({x} * {x}) * ({x} * {x})"),
                    -1 => format!("L::splat(1.0) / {x}"),
                    -2 => format!("L::splat(1.0) / ({x} * {x})"),
                    _ => format!("L::powi({x}, {n})"),
                }
            }
            Expr::Sqrt(a) => format!("L::sqrt({})", op(a)),
            Expr::Sin(a) => format!("L::sin({})", op(a)),
            Expr::Cos(a) => format!("L::cos({})", op(a)),
            Expr::Exp(a) => format!("L::exp({})", op(a)),
            Expr::Ln(a) => format!("L::ln({})", op(a)),
        };
        let _ = writeln!(out, "let t{i} = {rhs};");
    }
    let outputs: Vec<String> = program.outputs.iter().map(op).collect();
    let _ = writeln!(out, "[{}]", outputs.join(", "));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(g: &mut Graph, k: f64) -> SpringSpec {
        SpringParams {
            a: g.constant(1.0),
            r1: g.constant(0.8),
            r2: g.constant(0.8),
            k: g.constant(k),
            l0: g.constant(1.68),
        }
    }

    #[test]
    fn neighbouring_springs_share_the_trig_of_their_common_rotor() {
        let mut g = Graph::new();
        let law = SpringLaw::harmonic(&mut g);
        let springs: Vec<_> = (0..4).map(|_| params(&mut g, 2.0)).collect();
        let out = ChainOutputs::unrolled(&mut g, &law, &springs, &|g, i| g.symbol(&format!("theta[{i}]")));
        let sins = (0..g.len()).filter(|&i| matches!(g.node(Id(i as u32)), Node::Sin(_))).count();
        assert_eq!(sins, 5, "one sine per rotor, shared by both springs");
        assert_eq!(out.gradient.len(), 5);
        assert_eq!(out.hessian_off.len(), 4);
        let namer = out.leaf_namer(&g);
        assert_eq!(namer(out.trig[3].1).as_deref(), Some("c[3usize]"));
    }

    #[test]
    fn kernel_renders_every_function_and_names_only_its_arguments() {
        let k = Kernel::new(&SpringLaw::harmonic);
        let src = k.render().unwrap();
        for f in &KERNEL_FUNCTIONS {
            assert!(src.contains(&format!("pub struct {};", f.name)));
            assert!(src.contains(&format!("for {} {{", f.name)));
        }
        assert_eq!(
            src.matches("L::sqrt(").count(),
            KERNEL_FUNCTIONS.len(),
            "one sqrt per kernel, fused ones too"
        );
        assert!(!src.contains("sin("), "angles enter only through the s1, c1, s2, c2 arguments");
        assert!(!src.contains("f64 *") && !src.contains("* 0."), "constants are splat into lanes");
    }
}
