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

/// The order in which a [`Program`]'s steps are emitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Schedule {
    /// Arena order: every step as soon as the graph created it.
    Arena,
    /// Depth-first from the outputs, in order: each output's steps just before it, so values
    /// die soon after they are made and few are live at once (the unrolled chain's outputs then
    /// need a few registers whatever the number of rotors).
    DepthFirst,
}

/// Lowers `outputs` of `g` in arena order. `leaf` names the nodes that are inputs of the
/// program; every symbol must be named by it (a symbol it does not name is returned as the
/// error).
pub fn lower(g: &Graph, outputs: &[Id], leaf: &dyn Fn(Id) -> Option<String>) -> Result<Program, String> {
    lower_with(g, outputs, leaf, Schedule::Arena)
}

/// [`lower`] with the steps in the order of `schedule`. Iterative: graphs of any depth.
pub fn lower_with(
    g: &Graph,
    outputs: &[Id],
    leaf: &dyn Fn(Id) -> Option<String>,
    schedule: Schedule,
) -> Result<Program, String> {
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
    let is_step = |id: Id| !leaves.contains_key(&id) && !matches!(g.node(id), Node::Const(_));
    let order: Vec<Id> = match schedule {
        Schedule::Arena => {
            (0..g.len()).filter(|&i| reachable[i]).map(|i| Id(i as u32)).filter(|&id| is_step(id)).collect()
        }
        Schedule::DepthFirst => depth_first(g, outputs, &is_step),
    };

    let mut steps = Vec::with_capacity(order.len());
    let mut operand_of: HashMap<Id, Operand> = HashMap::new();
    let operand = |id: Id, operand_of: &HashMap<Id, Operand>| -> Operand {
        if let Some(name) = leaves.get(&id) {
            return Operand::Leaf(name.clone());
        }
        match g.node(id) {
            Node::Const(bits) => Operand::Const(f64::from_bits(bits)),
            _ => operand_of[&id].clone(),
        }
    };
    for id in order {
        let op = |x: Id| operand(x, &operand_of);
        let expr = match g.node(id) {
            Node::Const(_) | Node::Symbol(_) => continue,
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
    let outputs = outputs.iter().map(|&id| operand(id, &operand_of)).collect();
    Ok(Program { steps, outputs })
}

/// The steps below `outputs` in depth-first post-order, output by output (iterative). At each
/// node the child needing more registers is computed first (Sethi-Ullman order), so that a long
/// sum `((e0 + e1) + e2) + ...` is accumulated as it goes instead of holding every term.
fn depth_first(g: &Graph, outputs: &[Id], is_step: &dyn Fn(Id) -> bool) -> Vec<Id> {
    // Registers each node needs (Sethi-Ullman numbers, computed on the DAG as if it were a tree),
    // children before parents.
    let mut need = vec![0u32; g.len()];
    for id in g.reachable(outputs, &|id| !is_step(id)) {
        let children: Vec<u32> = g.node(id).children().map(|c| need[c.index()]).collect();
        need[id.index()] = match children.as_slice() {
            [a, b] if a == b => a + 1,
            [a, b] => (*a).max(*b).max(1),
            [a] => (*a).max(1),
            _ => 1,
        };
    }
    let mut visited = vec![false; g.len()];
    let mut order = Vec::new();
    // (node, children already pushed)
    let mut stack: Vec<(Id, bool)> = Vec::new();
    for &root in outputs {
        stack.push((root, false));
        while let Some((id, expanded)) = stack.pop() {
            if expanded {
                order.push(id);
                continue;
            }
            if std::mem::replace(&mut visited[id.index()], true) || !is_step(id) {
                continue;
            }
            stack.push((id, true));
            let mut children: Vec<Id> = g.node(id).children().filter(|c| !visited[c.index()]).collect();
            // The stack pops the last pushed first: the neediest child goes on top.
            children.sort_by_key(|c| need[c.index()]);
            // In a DAG a node still being expanded is never a child of its descendants, so a
            // visited child is always finished.
            stack.extend(children.into_iter().map(|c| (c, false)));
        }
    }
    order
}

impl Operand {
    fn render(&self, prefix: &str, ty: Float) -> String {
        match self {
            Operand::Temp(i) => format!("{prefix}{i}"),
            Operand::Leaf(name) => name.clone(),
            Operand::Const(c) => ty.render_const(*c),
        }
    }
}

/// The float type rendered code computes in: `f64` (the default of every chain) or `f32` (a chain
/// declared with `float = f32`). The graph is the same for both: its constants are folded in
/// `f64` and rounded once, to the nearest `f32`, where they are written out.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Float {
    #[default]
    F64,
    F32,
}

impl Float {
    /// The Rust type: `"f64"` or `"f32"`.
    pub fn name(self) -> &'static str {
        match self {
            Float::F64 => "f64",
            Float::F32 => "f32",
        }
    }

    /// Bytes per value.
    pub fn bytes(self) -> usize {
        match self {
            Float::F64 => 8,
            Float::F32 => 4,
        }
    }

    /// `x` rounded to this type, as an `f64` (exact: every `f32` is an `f64`).
    pub fn round(self, x: f64) -> f64 {
        match self {
            Float::F64 => x,
            Float::F32 => f64::from(x as f32),
        }
    }

    /// A Rust expression of this type for the constant `c`, rounded to the type: exact, since
    /// `{:?}` prints the shortest digits that parse back to the same value; the non-finite values
    /// by their full path, which no user item can shadow. A constant beyond `f32::MAX` is an `f32`
    /// infinity, as the same value computed in `f32` would be.
    pub fn render_const(self, c: f64) -> String {
        let ty = self.name();
        let c = self.round(c);
        if c.is_nan() {
            format!("::core::primitive::{ty}::NAN")
        } else if c.is_infinite() {
            let name = if c > 0.0 { "INFINITY" } else { "NEG_INFINITY" };
            format!("::core::primitive::{ty}::{name}")
        } else {
            // `{:?}` of the value in its own type: the shortest digits for that type.
            let digits = match self {
                Float::F64 => format!("{c:?}"),
                Float::F32 => format!("{:?}", c as f32),
            };
            if c < 0.0 { format!("({digits}{ty})") } else { format!("{digits}{ty}") }
        }
    }
}

/// A Rust expression for the `f64` constant `c`: [`Float::render_const`] for `f64`.
pub fn render_const(c: f64) -> String {
    Float::F64.render_const(c)
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

/// Above this many steps [`Program::render`] holds its temporaries in reused registers instead of
/// one `let` each: rustc nests a scope per `let`, and a function with a few thousand of them
/// crashes rustc 1.95 in debug builds (measured: 2500 `let`s compile with `-g`, 3000 crash).
pub const LET_LIMIT: usize = 1000;

impl Program {
    /// Rust source for the steps: temporaries are named `{prefix}{index}`, and transcendental
    /// functions are called as `{math}sin(x)` etc. Up to [`LET_LIMIT`] steps this is one `let`
    /// per step (single assignment, readable); longer programs compute in a few reused
    /// registers `{prefix}r{k}` (linear-scan allocation) and bind only the outputs to their
    /// `{prefix}{index}` names, so [`Program::render_output`] names them either way.
    pub fn render(&self, prefix: &str, math: &str) -> String {
        if self.steps.len() > LET_LIMIT {
            let register_prefix = format!("{prefix}r");
            let mut named = std::collections::HashSet::new();
            let sinks: Vec<Option<String>> = self
                .outputs
                .iter()
                .map(|o| match o {
                    Operand::Temp(t) if named.insert(*t) => Some(format!("{prefix}{t}")),
                    _ => None,
                })
                .collect();
            let mut out = String::new();
            for name in sinks.iter().flatten() {
                let _ = writeln!(out, "let {name};");
            }
            out.push_str(&self.registers(&register_prefix, Float::F64, math, &sinks, false));
            return out;
        }
        let mut out = String::new();
        let r = |o: &Operand| o.render(prefix, Float::F64);
        for (i, step) in self.steps.iter().enumerate() {
            let _ = writeln!(out, "let {prefix}{i} = {};", step.render(&r, math));
        }
        out
    }

    /// Rust source for output `k` (a temporary, a constant or a leaf) in [`Program::render`]'s names.
    pub fn render_output(&self, k: usize, prefix: &str) -> String {
        self.outputs[k].render(prefix, Float::F64)
    }

    /// Rust source that computes the program in a few reused `let mut {prefix}{k}: {ty}`
    /// registers (linear-scan allocation over last uses) and assigns output `k` to the place
    /// `sinks[k]` (for example `out[3]`) as soon as it is computed, so outputs hold no register.
    /// Constants are written in `ty` (rounded to it), and `math` is the path prefix of `ty`'s
    /// functions (`sqrt`, `sin`, ...).
    ///
    /// Why: rustc nests a scope for every `let`, and a function with a few thousand of them
    /// overflows its stack or LLVM's debug-info emission (see [`LET_LIMIT`]). Assignments open
    /// no scope, so a program of any length compiles; LLVM's SSA construction makes the
    /// optimised code the same as with `let`s. Scheduled [`Schedule::DepthFirst`], an unrolled
    /// chain needs a few dozen registers whatever its length.
    pub fn render_into(&self, prefix: &str, ty: Float, math: &str, sinks: &[String]) -> String {
        let sinks: Vec<Option<String>> = sinks.iter().cloned().map(Some).collect();
        self.registers(prefix, ty, math, &sinks, true)
    }

    /// The register program; `typed`: the registers are declared with their type.
    fn registers(
        &self,
        prefix: &str,
        ty: Float,
        math: &str,
        sinks: &[Option<String>],
        typed: bool,
    ) -> String {
        const NEVER: usize = usize::MAX;
        // The last step that reads each temporary (NEVER: only outputs read it).
        let mut last_use = vec![NEVER; self.steps.len()];
        for (i, step) in self.steps.iter().enumerate() {
            for op in step.operands() {
                if let Operand::Temp(t) = op {
                    last_use[*t] = i;
                }
            }
        }
        let mut sinks_of: HashMap<usize, Vec<&str>> = HashMap::new();
        let mut late = String::new();
        for (o, sink) in self.outputs.iter().zip(sinks) {
            let Some(sink) = sink else { continue };
            match o {
                Operand::Temp(t) => sinks_of.entry(*t).or_default().push(sink),
                other => {
                    let _ = writeln!(late, "{sink} = {};", other.render(prefix, ty));
                }
            }
        }
        let mut register = vec![usize::MAX; self.steps.len()];
        let mut free: Vec<usize> = Vec::new();
        let mut count = 0usize;
        let mut body = String::new();
        for (i, step) in self.steps.iter().enumerate() {
            let r = |o: &Operand| match o {
                Operand::Temp(t) => format!("{prefix}{}", register[*t]),
                other => other.render(prefix, ty),
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
            for sink in sinks_of.get(&i).into_iter().flatten() {
                let _ = writeln!(body, "{sink} = {prefix}{reg};");
            }
            if last_use[i] == NEVER {
                free.push(reg);
            }
        }
        let mut decls = String::new();
        let annotation = if typed { format!(": {}", ty.name()) } else { String::new() };
        for reg in 0..count {
            let _ = writeln!(decls, "let mut {prefix}{reg}{annotation};");
        }
        decls + &body + &late
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

    /// Runs rendered register code (lines `lhs = a op b;` or `lhs = a;`) with `x = 0.3`.
    fn interpret(src: &str) -> HashMap<String, f64> {
        let mut regs = HashMap::<String, f64>::new();
        let val = |t: &str, regs: &HashMap<String, f64>| -> f64 {
            if t == "x" {
                0.3
            } else if let Some(v) = regs.get(t) {
                *v
            } else {
                t.trim_matches(|c| c == '(' || c == ')').trim_end_matches("f64").parse().unwrap()
            }
        };
        for line in src.lines().filter(|l| !l.starts_with("let")) {
            let (lhs, rhs) = line.trim_end_matches(';').split_once(" = ").unwrap();
            let parts: Vec<&str> = rhs.split(' ').collect();
            let v = match parts.as_slice() {
                [a] => val(a, &regs),
                [a, "+", b] => val(a, &regs) + val(b, &regs),
                [a, "*", b] => val(a, &regs) * val(b, &regs),
                _ => panic!("unexpected {rhs}"),
            };
            regs.insert(lhs.to_owned(), v);
        }
        regs
    }

    /// `e_{i+1} = c_i e_i + x`, `count` times; every tenth value is an output.
    fn recurrence(count: u32) -> (Graph, Id, Vec<Id>) {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let mut e = x;
        let mut outs = vec![];
        for i in 0..count {
            let c = g.constant(1.0 + f64::from(i) * 1e-3);
            e = g.mul(c, e);
            e = g.add(e, x);
            if i % 10 == 0 {
                outs.push(e);
            }
        }
        (g, x, outs)
    }

    #[test]
    fn registers_are_reused_and_outputs_go_to_their_sinks() {
        let (g, x, outs) = recurrence(50);
        let p = lower(&g, &outs, &|id| (id == x).then(|| "x".to_owned())).unwrap();
        let sinks: Vec<String> = (0..outs.len()).map(|k| format!("out[{k}]")).collect();
        let src = p.render_into("r", Float::F64, "", &sinks);
        let registers = src.matches("let mut").count();
        assert!(registers <= 3, "{registers} registers for {} steps", p.steps.len());
        // Interpret the register program and compare with the graph's own evaluation.
        let regs = interpret(&src);
        for (k, &o) in outs.iter().enumerate() {
            let expected = g.eval(o, &|_| 0.3);
            assert_eq!(regs[&sinks[k]], expected);
        }
    }

    #[test]
    fn long_programs_render_in_registers_under_their_output_names() {
        let (g, x, outs) = recurrence(2 * LET_LIMIT as u32);
        let p = lower(&g, &outs, &|id| (id == x).then(|| "x".to_owned())).unwrap();
        assert!(p.steps.len() > LET_LIMIT);
        let src = p.render("t", "");
        // One `let` per output name plus a few registers, not one per step.
        assert!(src.matches("let").count() <= outs.len() + 3, "{src}");
        let regs = interpret(&src);
        for (k, &o) in outs.iter().enumerate() {
            assert_eq!(regs[&p.render_output(k, "t")], g.eval(o, &|_| 0.3));
        }
    }

    #[test]
    fn depth_first_schedule_keeps_few_values_live() {
        // Many independent outputs created all before any is used: in arena order every one
        // would stay live; depth first, each is computed and stored before the next.
        let mut g = Graph::new();
        let x = g.symbol("x");
        let squares: Vec<Id> = (0..500)
            .map(|i| {
                let c = g.constant(f64::from(i) + 0.5);
                let s = g.add(x, c);
                g.mul(s, s)
            })
            .collect();
        let mut sums = vec![];
        for w in squares.windows(2) {
            sums.push(g.add(w[0], w[1]));
        }
        let leaf = |id: Id| (id == x).then(|| "x".to_owned());
        let sinks: Vec<String> = (0..sums.len()).map(|k| format!("out[{k}]")).collect();
        let arena = lower(&g, &sums, &leaf).unwrap().render_into("r", Float::F64, "", &sinks);
        let deep = lower_with(&g, &sums, &leaf, Schedule::DepthFirst).unwrap();
        let src = deep.render_into("r", Float::F64, "", &sinks);
        assert!(arena.matches("let mut").count() >= 500);
        assert!(src.matches("let mut").count() <= 4, "{}", src.matches("let mut").count());
        let regs = interpret(&src);
        for (k, &o) in sums.iter().enumerate() {
            assert_eq!(regs[&sinks[k]], g.eval(o, &|_| 0.3));
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

    #[test]
    fn constants_are_written_in_the_chosen_type() {
        assert_eq!(Float::F64.render_const(0.1), "0.1f64");
        assert_eq!(Float::F32.render_const(0.1), "0.1f32");
        // Rounded once to the nearest f32, then its shortest digits.
        assert_eq!(Float::F32.render_const(1.0 / 3.0), "0.33333334f32");
        assert_eq!(Float::F32.render_const(-2.5), "(-2.5f32)");
        assert_eq!(Float::F32.render_const(1e300), "::core::primitive::f32::INFINITY");
        assert_eq!(Float::F32.render_const(f64::NAN), "::core::primitive::f32::NAN");
        assert_eq!(render_const(-1e300), "(-1e300f64)");

        let (g, x, outs) = recurrence(3);
        let p = lower(&g, &outs, &|id| (id == x).then(|| "x".to_owned())).unwrap();
        let src = p.render_into("r", Float::F32, "m::", &["out[0]".to_owned()]);
        assert!(
            src.contains("let mut r0: f32;") && src.contains("2.0f32 * x") && !src.contains("f64"),
            "{src}"
        );
    }
}
