//! Lowering a set of outputs to a straight-line program.
//!
//! The reachable part of the graph is walked in arena order (children before parents), so the
//! program is a valid sequence of `let`s. Nodes the caller names as *leaves* (symbols, or any
//! subexpression such as `sin(theta_3)` that the caller computes itself) are not expanded;
//! constants are written inline. The program renders to Rust source ([`Program::render`]) and
//! implements `Display`, which is how generated code is read and snapshotted.

use std::collections::HashMap;
use std::fmt::{self, Write};

use crate::graph::{Graph, Id, Node};

/// A value used by a step: an earlier temporary, a constant, or a caller-named leaf.
#[derive(Clone, Debug, PartialEq)]
pub enum Operand {
    Temp(usize),
    Const(f64),
    Leaf(String),
}

/// The operation of one step.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    Add(Operand, Operand),
    Sub(Operand, Operand),
    Mul(Operand, Operand),
    Div(Operand, Operand),
    Neg(Operand),
    Powi(Operand, i32),
    Sqrt(Operand),
    Sin(Operand),
    Cos(Operand),
    Exp(Operand),
    Ln(Operand),
}

/// A straight-line program: `steps[i]` defines temporary `i`, and `outputs[k]` is output `k`.
#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    pub steps: Vec<Expr>,
    pub outputs: Vec<Operand>,
}

/// Lowers `outputs` of `g`. `leaf` names the nodes that are inputs of the program; every symbol
/// must be named by it (a symbol it does not name is returned as the error).
pub fn lower(g: &Graph, outputs: &[Id], leaf: &dyn Fn(Id) -> Option<String>) -> Result<Program, String> {
    // Mark what is reachable from the outputs, stopping at leaves.
    let mut reachable = vec![false; g.len()];
    let mut leaves: HashMap<Id, String> = HashMap::new();
    let mut stack: Vec<Id> = outputs.to_vec();
    while let Some(id) = stack.pop() {
        if std::mem::replace(&mut reachable[id.index()], true) {
            continue;
        }
        if let Some(name) = leaf(id) {
            leaves.insert(id, name);
            continue;
        }
        match g.node(id) {
            Node::Symbol(s) => return Err(g.symbol_name(s).to_owned()),
            node => stack.extend(node.children()),
        }
    }

    let mut steps = Vec::new();
    let mut operand_of: HashMap<Id, Operand> = HashMap::new();
    for (index, &is_reachable) in reachable.iter().enumerate() {
        if !is_reachable {
            continue;
        }
        let id = Id(index as u32);
        if let Some(name) = leaves.get(&id) {
            operand_of.insert(id, Operand::Leaf(name.clone()));
            continue;
        }
        let op = |x: Id| operand_of[&x].clone();
        let expr = match g.node(id) {
            Node::Const(bits) => {
                operand_of.insert(id, Operand::Const(f64::from_bits(bits)));
                continue;
            }
            Node::Symbol(_) => unreachable!("unnamed symbols were rejected above"),
            Node::Add(a, b) => Expr::Add(op(a), op(b)),
            Node::Sub(a, b) => Expr::Sub(op(a), op(b)),
            Node::Mul(a, b) => Expr::Mul(op(a), op(b)),
            Node::Div(a, b) => Expr::Div(op(a), op(b)),
            Node::Neg(a) => Expr::Neg(op(a)),
            Node::Powi(a, n) => Expr::Powi(op(a), n),
            Node::Sqrt(a) => Expr::Sqrt(op(a)),
            Node::Sin(a) => Expr::Sin(op(a)),
            Node::Cos(a) => Expr::Cos(op(a)),
            Node::Exp(a) => Expr::Exp(op(a)),
            Node::Ln(a) => Expr::Ln(op(a)),
        };
        operand_of.insert(id, Operand::Temp(steps.len()));
        steps.push(expr);
    }
    let outputs = outputs.iter().map(|id| operand_of[id].clone()).collect();
    Ok(Program { steps, outputs })
}

impl Operand {
    fn render(&self, prefix: &str) -> String {
        match self {
            Operand::Temp(i) => format!("{prefix}{i}"),
            Operand::Leaf(name) => name.clone(),
            Operand::Const(c) => render_const(*c),
        }
    }
}

/// A Rust expression for the constant `c` (exact: `{:?}` prints the shortest round-trip form).
pub fn render_const(c: f64) -> String {
    if c.is_nan() {
        "f64::NAN".to_owned()
    } else if c.is_infinite() {
        if c > 0.0 { "f64::INFINITY".to_owned() } else { "f64::NEG_INFINITY".to_owned() }
    } else if c < 0.0 {
        format!("({c:?}f64)")
    } else {
        format!("{c:?}f64")
    }
}

impl Expr {
    /// The operands of this step.
    fn operands(&self) -> impl Iterator<Item = &Operand> {
        let (a, b) = match self {
            Expr::Add(a, b) | Expr::Sub(a, b) | Expr::Mul(a, b) | Expr::Div(a, b) => (a, Some(b)),
            Expr::Neg(a)
            | Expr::Powi(a, _)
            | Expr::Sqrt(a)
            | Expr::Sin(a)
            | Expr::Cos(a)
            | Expr::Exp(a)
            | Expr::Ln(a) => (a, None),
        };
        std::iter::once(a).chain(b)
    }

    /// Rust source of the right-hand side, operands rendered by `r`.
    fn render(&self, r: &dyn Fn(&Operand) -> String, math: &str) -> String {
        match self {
            Expr::Add(a, b) => format!("{} + {}", r(a), r(b)),
            Expr::Sub(a, b) => format!("{} - {}", r(a), r(b)),
            Expr::Mul(a, b) => format!("{} * {}", r(a), r(b)),
            Expr::Div(a, b) => format!("{} / {}", r(a), r(b)),
            Expr::Neg(a) => format!("-{}", r(a)),
            Expr::Powi(a, n) => render_powi(&r(a), *n, math),
            Expr::Sqrt(a) => format!("{math}sqrt({})", r(a)),
            Expr::Sin(a) => format!("{math}sin({})", r(a)),
            Expr::Cos(a) => format!("{math}cos({})", r(a)),
            Expr::Exp(a) => format!("{math}exp({})", r(a)),
            Expr::Ln(a) => format!("{math}ln({})", r(a)),
        }
    }
}

impl Program {
    /// Rust source for the steps in single-assignment form, one `let` per line: temporaries are
    /// named `{prefix}{index}`, and transcendental functions are called as `{math}sin(x)` etc.
    pub fn render(&self, prefix: &str, math: &str) -> String {
        let mut out = String::new();
        let r = |o: &Operand| o.render(prefix);
        for (i, step) in self.steps.iter().enumerate() {
            let _ = writeln!(out, "let {prefix}{i} = {};", step.render(&r, math));
        }
        out
    }

    /// Rust source for output `k` (a temporary, a constant or a leaf) in [`Program::render`]'s names.
    pub fn render_output(&self, k: usize, prefix: &str) -> String {
        self.outputs[k].render(prefix)
    }

    /// Rust source for the steps with temporaries held in a few reused `let mut` registers
    /// (linear-scan allocation over last uses), and the expressions of the outputs.
    ///
    /// Why: rustc opens a nested scope for every `let`, and a function with several thousand of
    /// them overflows its stack (measured: 6000 `let`s crash rustc 1.95, the same code in reused
    /// registers compiles in 0.3 s). Assignments open no scope, so an unrolled chain of any
    /// length compiles; LLVM's SSA construction makes the two forms identical in optimised code.
    pub fn render_registers(&self, prefix: &str, math: &str) -> (String, Vec<String>) {
        const LIVE_TO_END: usize = usize::MAX;
        let mut last_use = vec![0usize; self.steps.len()];
        for (i, step) in self.steps.iter().enumerate() {
            for op in step.operands() {
                if let Operand::Temp(t) = op {
                    last_use[*t] = i;
                }
            }
        }
        for op in &self.outputs {
            if let Operand::Temp(t) = op {
                last_use[*t] = LIVE_TO_END;
            }
        }
        let mut register = vec![usize::MAX; self.steps.len()];
        let mut free: Vec<usize> = Vec::new();
        let mut count = 0usize;
        let mut body = String::new();
        for (i, step) in self.steps.iter().enumerate() {
            let r = |o: &Operand| match o {
                Operand::Temp(t) => format!("{prefix}{}", register[*t]),
                other => other.render(prefix),
            };
            let rhs = step.render(&r, math);
            // Operands that die here free their registers before the result takes one: the
            // right-hand side is evaluated before the assignment.
            for op in step.operands() {
                if let Operand::Temp(t) = op
                    && last_use[*t] == i
                    && !free.contains(&register[*t])
                {
                    free.push(register[*t]);
                }
            }
            let reg = free.pop().unwrap_or_else(|| {
                count += 1;
                count - 1
            });
            register[i] = reg;
            let _ = writeln!(body, "{prefix}{reg} = {rhs};");
        }
        let mut decls = String::new();
        for reg in 0..count {
            let _ = writeln!(decls, "let mut {prefix}{reg}: f64;");
        }
        let outputs = self
            .outputs
            .iter()
            .map(|o| match o {
                Operand::Temp(t) => format!("{prefix}{}", register[*t]),
                other => other.render(prefix),
            })
            .collect();
        (decls + &body, outputs)
    }
}

/// Small integer powers become products (no call, exact for |n| <= 4 up to rounding order).
fn render_powi(x: &str, n: i32, math: &str) -> String {
    match n {
        2 => format!("{x} * {x}"),
        3 => format!("{x} * {x} * {x}"),
        4 => format!("({x} * {x}) * ({x} * {x})"),
        -1 => format!("1.0 / {x}"),
        -2 => format!("1.0 / ({x} * {x})"),
        _ => format!("{math}powi({x}, {n})"),
    }
}

impl fmt::Display for Program {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.render("t", ""))?;
        let outs: Vec<String> = (0..self.outputs.len()).map(|k| self.render_output(k, "t")).collect();
        write!(f, "=> ({})", outs.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registers_are_reused_and_outputs_survive() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let mut e = x;
        let mut outs = vec![];
        for i in 0..50 {
            let c = g.constant(1.0 + f64::from(i) * 1e-3);
            e = g.mul(e, c);
            e = g.add(e, x);
            if i % 10 == 0 {
                outs.push(e);
            }
        }
        let p = lower(&g, &outs, &|id| (id == x).then(|| "x".to_owned())).unwrap();
        let (src, outputs) = p.render_registers("r", "");
        let registers = src.matches("let mut").count();
        assert!(registers <= outs.len() + 2, "{registers} registers for {} steps", p.steps.len());
        assert_eq!(outputs.len(), outs.len());
        // Interpret the register program and compare with the graph's own evaluation.
        let mut regs = std::collections::HashMap::<String, f64>::new();
        let val = |t: &str, regs: &std::collections::HashMap<String, f64>| -> f64 {
            if t == "x" {
                0.3
            } else if let Some(v) = regs.get(t) {
                *v
            } else {
                t.trim_end_matches("f64").parse().unwrap()
            }
        };
        for line in src.lines().filter(|l| !l.starts_with("let")) {
            let (lhs, rhs) = line.trim_end_matches(';').split_once(" = ").unwrap();
            let parts: Vec<&str> = rhs.split(' ').collect();
            let v = match parts[1] {
                "+" => val(parts[0], &regs) + val(parts[2], &regs),
                "*" => val(parts[0], &regs) * val(parts[2], &regs),
                op => panic!("unexpected {op}"),
            };
            regs.insert(lhs.to_owned(), v);
        }
        for (k, &o) in outs.iter().enumerate() {
            let expected = g.eval(o, &|_| 0.3);
            assert!((val(&outputs[k], &regs) - expected).abs() < 1e-12);
        }
    }

    #[test]
    fn shared_subexpressions_are_computed_once_in_order() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let y = g.symbol("y");
        let s = g.add(x, y);
        let a = g.sqrt(s);
        let b = g.mul(s, a);
        let p = lower(&g, &[a, b], &|id| match g.node(id) {
            Node::Symbol(k) => Some(g.symbol_name(k).to_owned()),
            _ => None,
        })
        .unwrap();
        assert_eq!(p.to_string(), "let t0 = x + y;\nlet t1 = sqrt(t0);\nlet t2 = t0 * t1;\n=> (t1, t2)");
    }

    #[test]
    fn an_unnamed_symbol_is_reported() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let y = g.symbol("mystery");
        let e = g.mul(x, y);
        let err = lower(&g, &[e], &|id| (id == x).then(|| "x".to_owned())).unwrap_err();
        assert_eq!(err, "mystery");
    }
}
