//! The hash-consed expression graph.
//!
//! Nodes live in one arena (`Vec<Node>`); a node refers to its children by [`Id`], and a child is
//! always created before its parent, so the arena order is a valid evaluation order. Nodes are
//! interned through a map, so building the same expression twice yields the same `Id` and common
//! subexpressions are shared for free (the design of egg's `RecExpr` and its memo).
//!
//! Simplification happens in the smart constructors ([`Graph::add`], [`Graph::mul`], ...): constant
//! folding, neutral elements, canonical operand order for commutative operations, and moving signs
//! and power-of-two factors outward. These are the rules that keep generated code short.
//!
//! # What simplification preserves
//!
//! Every rewrite is exact in IEEE-754 double arithmetic: for every value of the operands, including
//! `+-inf`, NaN, `+-0` and subnormal numbers, the simplified expression evaluates to the same number
//! as the expression as built, with two relaxations:
//!
//! 1. **The sign of a zero is not kept.** `x + 0` becomes `x` (which is `-0` for `x = -0`), `-(x - y)`
//!    becomes `y - x`, and the constant `-0.0` is stored as `0.0`; so neither is the sign of an
//!    infinity obtained by dividing by such a zero.
//! 2. **Moving a power-of-two factor** (`2 (3 x) -> 6 x`, `(0.5 x) y -> 0.5 (x y)`,
//!    `(0.5 x) / y -> 0.5 (x / y)`, `0.5 / x -> 0.5 (1 / x)`, `2 x + 2 y -> 2 (x + y)`) rounds
//!    nothing, but can change a result whose intermediate overflows (`|v| > f64::MAX`) or is
//!    subnormal (`|v| < f64::MIN_POSITIVE`) in one of the two orders.
//!
//! Operations on constants are folded when the graph is built, with the same IEEE operation
//! (`sqrt`, `sin`, `cos`, `exp`, `ln` and `powi` of a constant come from Rust's `std`, which can
//! differ by an ulp from `libm`, used by `no_std` builds at run time).
//!
//! Nothing is absorbed: `0 x`, `0 / x`, `x - x`, `x / x`, `sqrt(x)^2`, `(x^m)^n` and `ln(exp(x))`
//! are kept as built, because they are not `0`, `0`, `0`, `1`, `x`, `x^(mn)` and `x` for every `x`
//! (an infinite or NaN `x`, a negative one under the root, an overflowing `exp`). So a NaN or an
//! infinity propagates exactly as in the expression as written; `tests/simplifier.rs` checks this
//! against direct `f64` evaluation.

use std::collections::HashMap;

/// Index of a node in a [`Graph`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Id(pub u32);

impl Id {
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// One operation of the expression language.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A constant, stored by its bits so that nodes can be hashed.
    Const(u64),
    /// A named input: an angle, a parameter, a struct field, a law variable.
    Symbol(u32),
    Add(Id, Id),
    Sub(Id, Id),
    Mul(Id, Id),
    Div(Id, Id),
    Neg(Id),
    /// Integer power.
    Powi(Id, i32),
    Sqrt(Id),
    Sin(Id),
    Cos(Id),
    Exp(Id),
    Ln(Id),
}

impl Node {
    /// The children of this node, in order.
    pub fn children(&self) -> impl Iterator<Item = Id> {
        let (a, b) = match *self {
            Node::Const(_) | Node::Symbol(_) => (None, None),
            Node::Add(x, y) | Node::Sub(x, y) | Node::Mul(x, y) | Node::Div(x, y) => (Some(x), Some(y)),
            Node::Neg(x)
            | Node::Powi(x, _)
            | Node::Sqrt(x)
            | Node::Sin(x)
            | Node::Cos(x)
            | Node::Exp(x)
            | Node::Ln(x) => (Some(x), None),
        };
        a.into_iter().chain(b)
    }
}

/// The arena of interned nodes plus the symbol table.
#[derive(Default, Clone, Debug)]
pub struct Graph {
    nodes: Vec<Node>,
    memo: HashMap<Node, Id>,
    symbols: Vec<String>,
    symbol_ids: HashMap<String, Id>,
}

impl Graph {
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of nodes in the arena.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    pub fn node(&self, id: Id) -> Node {
        self.nodes[id.index()]
    }

    /// The name of symbol number `sym` (as stored in [`Node::Symbol`]).
    pub fn symbol_name(&self, sym: u32) -> &str {
        &self.symbols[sym as usize]
    }

    /// The constant value of `id`, if it is a constant.
    pub fn as_const(&self, id: Id) -> Option<f64> {
        match self.node(id) {
            Node::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    fn intern(&mut self, node: Node) -> Id {
        if let Some(&id) = self.memo.get(&node) {
            return id;
        }
        let id = Id(u32::try_from(self.nodes.len()).expect("expression graph exceeds u32 nodes"));
        self.nodes.push(node);
        self.memo.insert(node, id);
        id
    }

    /// The named input `name`; the same name always gives the same node.
    pub fn symbol(&mut self, name: &str) -> Id {
        if let Some(&id) = self.symbol_ids.get(name) {
            return id;
        }
        let sym = u32::try_from(self.symbols.len()).expect("too many symbols");
        self.symbols.push(name.to_owned());
        let id = self.intern(Node::Symbol(sym));
        self.symbol_ids.insert(name.to_owned(), id);
        id
    }

    /// A constant. `-0.0` is normalised to `0.0` so that the two share a node.
    pub fn constant(&mut self, value: f64) -> Id {
        let value = if value == 0.0 { 0.0 } else { value };
        self.intern(Node::Const(value.to_bits()))
    }

    pub fn zero(&mut self) -> Id {
        self.constant(0.0)
    }

    pub fn one(&mut self) -> Id {
        self.constant(1.0)
    }

    fn is_const(&self, id: Id, value: f64) -> bool {
        self.as_const(id) == Some(value)
    }

    /// The constant factor `c` of `c * x` if `c` is a power of two (see [`is_power_of_two`]).
    fn power_of_two_factor(&self, id: Id) -> Option<(Id, Id)> {
        match self.node(id) {
            Node::Mul(c, x) if self.as_const(c).is_some_and(is_power_of_two) => Some((c, x)),
            _ => None,
        }
    }

    /// `c x + c y = c (x + y)` and `c x - c y = c (x - y)` (with `-c` for the second factor
    /// too, the other operation) for a power of two `c`: both sides round the same number.
    fn factor_power_of_two(&mut self, a: Id, b: Id, subtract: bool) -> Option<Id> {
        let (ca, x) = self.power_of_two_factor(a)?;
        let (cb, y) = self.power_of_two_factor(b)?;
        let (va, vb) = (self.as_const(ca)?, self.as_const(cb)?);
        let same_sign = if va == vb {
            true
        } else if va == -vb {
            false
        } else {
            return None;
        };
        let inner = if same_sign != subtract { self.add(x, y) } else { self.sub(x, y) };
        Some(self.mul(ca, inner))
    }

    /// `a + b`. Rewrites: constant folding; `x + 0 = x` (signed zero not kept); `a + (-b) = a - b`;
    /// `x + x = 2 x`; `c x + c y = c (x + y)` for a power of two `c`.
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x + y);
        }
        if self.is_const(a, 0.0) {
            return b;
        }
        if self.is_const(b, 0.0) {
            return a;
        }
        // a + (-b) is a - b in IEEE arithmetic, and (-a) + b is b - a.
        if let Node::Neg(nb) = self.node(b) {
            return self.sub(a, nb);
        }
        if let Node::Neg(na) = self.node(a) {
            return self.sub(b, na);
        }
        // x + x rounds 2x exactly as 2 * x does.
        if a == b {
            let two = self.constant(2.0);
            return self.mul(two, a);
        }
        if let Some(factored) = self.factor_power_of_two(a, b, false) {
            return factored;
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Add(a, b))
    }

    /// `a - b`. Rewrites: constant folding; `x - 0 = x`; `0 - x = -x` (signed zero not kept);
    /// `a - (-b) = a + b`; `c x - c y = c (x - y)` for a power of two `c`. `x - x` is kept: it is
    /// NaN for infinite `x`.
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x - y);
        }
        if self.is_const(b, 0.0) {
            return a;
        }
        if self.is_const(a, 0.0) {
            return self.neg(b);
        }
        if let Node::Neg(nb) = self.node(b) {
            return self.add(a, nb);
        }
        if let Some(factored) = self.factor_power_of_two(a, b, true) {
            return factored;
        }
        self.intern(Node::Sub(a, b))
    }

    /// `-a`. Rewrites: constant folding; `-(-x) = x`; `-(x - y) = y - x` (signed zero not kept);
    /// `-(c x) = (-c) x`.
    pub fn neg(&mut self, a: Id) -> Id {
        match self.node(a) {
            Node::Const(bits) => self.constant(-f64::from_bits(bits)),
            Node::Neg(x) => x,
            Node::Sub(x, y) => self.sub(y, x),
            Node::Mul(c, x) if let Some(value) = self.as_const(c) => {
                let c = self.constant(-value);
                self.mul(c, x)
            }
            _ => self.intern(Node::Neg(a)),
        }
    }

    /// `a * b`. Rewrites: constant folding; `1 x = x`; `-1 x = -x`; `c (-x) = (-c) x`;
    /// `(-x) y = -(x y)`; `x x = x^2`; and, for a power of two `c`, `c1 (c2 x) = (c1 c2) x` and
    /// `(c x) y = c (x y)`. `0 x` is kept: it is NaN for infinite or NaN `x`.
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        // Constants go first so that `c * x` is the canonical scaled form.
        let (a, b) = if self.as_const(b).is_some() && self.as_const(a).is_none() { (b, a) } else { (a, b) };
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x * y);
        }
        if let Some(c) = self.as_const(a) {
            if c == 1.0 {
                return b;
            }
            if c == -1.0 {
                return self.neg(b);
            }
            if let Node::Mul(inner, x) = self.node(b)
                && let Some(c2) = self.as_const(inner)
                && let Some(product) = merged_factor(c, c2)
            {
                let c = self.constant(product);
                return self.mul(c, x);
            }
            if let Node::Neg(x) = self.node(b) {
                let c = self.constant(-c);
                return self.mul(c, x);
            }
            return self.intern(Node::Mul(a, b));
        }
        // (-x) * y = -(x y)
        if let Node::Neg(x) = self.node(a) {
            let p = self.mul(x, b);
            return self.neg(p);
        }
        if let Node::Neg(y) = self.node(b) {
            let p = self.mul(a, y);
            return self.neg(p);
        }
        // A power-of-two factor of either operand goes out front: (c x) y = c (x y).
        if let Some((c, x)) = self.power_of_two_factor(a) {
            let p = self.mul(x, b);
            return self.mul(c, p);
        }
        if let Some((c, y)) = self.power_of_two_factor(b) {
            let p = self.mul(a, y);
            return self.mul(c, p);
        }
        if a == b {
            return self.powi(a, 2);
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Mul(a, b))
    }

    /// `a / b`. Rewrites: constant folding; `x / 1 = x`; `x / -1 = -x`; `(-x) / y = -(x / y)` and
    /// `x / (-y) = -(x / y)`; for a power of two `c`, `x / c = (1 / c) x` (exact),
    /// `(c x) / y = c (x / y)` and `c / x = c (1 / x)`. `0 / x` and `x / x` are kept: they are NaN for `x` zero, infinite
    /// or NaN.
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x / y);
        }
        let divisor = self.as_const(b);
        if divisor == Some(1.0) {
            return a;
        }
        if divisor == Some(-1.0) {
            return self.neg(a);
        }
        if let Node::Neg(x) = self.node(a) {
            let q = self.div(x, b);
            return self.neg(q);
        }
        if let Node::Neg(y) = self.node(b) {
            let q = self.div(a, y);
            return self.neg(q);
        }
        // x / 2^k and x * 2^-k are both the correctly rounded x 2^-k: the same number.
        if let Some(c) = divisor
            && is_power_of_two(c)
        {
            let r = self.constant(1.0 / c);
            return self.mul(r, a);
        }
        if let Some((c, x)) = self.power_of_two_factor(a) {
            let q = self.div(x, b);
            return self.mul(c, q);
        }
        // c / x = c (1 / x) for a power of two c, so that c can merge with other factors.
        if let Some(c) = self.as_const(a)
            && c != 1.0
            && is_power_of_two(c)
        {
            let one = self.one();
            let inverse = self.div(one, b);
            return self.mul(a, inverse);
        }
        self.intern(Node::Div(a, b))
    }

    /// `a^n`. Rewrites: `x^0 = 1` (also for NaN, as IEEE `pown`), `x^1 = x`, constant folding,
    /// `(-x)^n = x^n` for even `n`. `sqrt(x)^2` is kept: it is NaN, not `x`, for `x < 0`, and
    /// `(x^m)^n` is kept: it overflows and rounds differently from `x^(m n)`. The one exponent
    /// whose derivative's `n - 1` does not fit in an `i32`, `i32::MIN`, is built as
    /// `1 / (x^(2^30))^2`, which is how `powi` computes it (31 squarings, then the reciprocal).
    pub fn powi(&mut self, a: Id, n: i32) -> Id {
        if n == 0 {
            return self.one();
        }
        if n == 1 {
            return a;
        }
        if let Some(x) = self.as_const(a) {
            return self.constant(x.powi(n));
        }
        if n == i32::MIN {
            // powi computes x^-2^31 as 1 / (x squared 31 times): the same operations, bit for
            // bit, and no exponent of the derivative overflows.
            let big = self.powi(a, 1 << 30);
            let square = self.powi(big, 2);
            let one = self.one();
            return self.div(one, square);
        }
        match self.node(a) {
            Node::Neg(x) if n % 2 == 0 => self.powi(x, n),
            _ => self.intern(Node::Powi(a, n)),
        }
    }

    pub fn sqrt(&mut self, a: Id) -> Id {
        match self.as_const(a) {
            Some(x) => self.constant(x.sqrt()),
            None => self.intern(Node::Sqrt(a)),
        }
    }

    pub fn sin(&mut self, a: Id) -> Id {
        match self.as_const(a) {
            Some(x) => self.constant(x.sin()),
            None => self.intern(Node::Sin(a)),
        }
    }

    pub fn cos(&mut self, a: Id) -> Id {
        match self.as_const(a) {
            Some(x) => self.constant(x.cos()),
            None => self.intern(Node::Cos(a)),
        }
    }

    pub fn exp(&mut self, a: Id) -> Id {
        match self.as_const(a) {
            Some(x) => self.constant(x.exp()),
            None => self.intern(Node::Exp(a)),
        }
    }

    /// `ln a`. Only constants fold: `ln(exp(x))` is kept, because `exp(x)` overflows for
    /// `x > 709.78`.
    pub fn ln(&mut self, a: Id) -> Id {
        match self.as_const(a) {
            Some(x) => self.constant(x.ln()),
            None => self.intern(Node::Ln(a)),
        }
    }

    /// Rebuilds the node `id` from new children, through the simplifying constructors.
    fn rebuild(&mut self, node: Node, child: &dyn Fn(Id) -> Id) -> Id {
        match node {
            Node::Const(bits) => self.constant(f64::from_bits(bits)),
            Node::Symbol(s) => self.intern(Node::Symbol(s)),
            Node::Add(a, b) => self.add(child(a), child(b)),
            Node::Sub(a, b) => self.sub(child(a), child(b)),
            Node::Mul(a, b) => self.mul(child(a), child(b)),
            Node::Div(a, b) => self.div(child(a), child(b)),
            Node::Neg(a) => self.neg(child(a)),
            Node::Powi(a, n) => self.powi(child(a), n),
            Node::Sqrt(a) => self.sqrt(child(a)),
            Node::Sin(a) => self.sin(child(a)),
            Node::Cos(a) => self.cos(child(a)),
            Node::Exp(a) => self.exp(child(a)),
            Node::Ln(a) => self.ln(child(a)),
        }
    }

    /// The nodes reachable from `roots`, children before parents (ascending ids), without
    /// descending into (or listing) the nodes for which `stop` holds. Iterative: graphs of any
    /// depth are walked without recursion.
    pub fn reachable(&self, roots: &[Id], stop: &dyn Fn(Id) -> bool) -> Vec<Id> {
        let mut seen = std::collections::HashSet::new();
        let mut stack: Vec<Id> = roots.to_vec();
        let mut out = Vec::new();
        while let Some(id) = stack.pop() {
            if stop(id) || !seen.insert(id) {
                continue;
            }
            out.push(id);
            stack.extend(self.node(id).children());
        }
        // A child is always created before its parent, so ascending ids are a valid order.
        out.sort_unstable();
        out
    }

    /// Rebuilds `e` with every node in `map` replaced, simplifying on the way.
    pub fn substitute(&mut self, e: Id, map: &HashMap<Id, Id>) -> Id {
        let mut done = map.clone();
        for id in self.reachable(&[e], &|id| map.contains_key(&id)) {
            let node = self.node(id);
            let out = match node {
                Node::Const(_) | Node::Symbol(_) => id,
                _ => self.rebuild(node, &|c| done[&c]),
            };
            done.insert(id, out);
        }
        done[&e]
    }

    /// Evaluates `e` numerically, with `value_of` giving each symbol's value (by name), in the
    /// same IEEE operations generated code performs. For tests and the generator's self-checks,
    /// never for generated code.
    pub fn eval(&self, e: Id, value_of: &dyn Fn(&str) -> f64) -> f64 {
        let mut v: HashMap<Id, f64> = HashMap::new();
        for id in self.reachable(&[e], &|_| false) {
            let x = |c: Id| v[&c];
            let out = match self.node(id) {
                Node::Const(bits) => f64::from_bits(bits),
                Node::Symbol(s) => value_of(self.symbol_name(s)),
                Node::Add(a, b) => x(a) + x(b),
                Node::Sub(a, b) => x(a) - x(b),
                Node::Mul(a, b) => x(a) * x(b),
                Node::Div(a, b) => x(a) / x(b),
                Node::Neg(a) => -x(a),
                Node::Powi(a, n) => x(a).powi(n),
                Node::Sqrt(a) => x(a).sqrt(),
                Node::Sin(a) => x(a).sin(),
                Node::Cos(a) => x(a).cos(),
                Node::Exp(a) => x(a).exp(),
                Node::Ln(a) => x(a).ln(),
            };
            v.insert(id, out);
        }
        v[&e]
    }

    /// Whether the symbol called `name` occurs in `e`.
    pub fn mentions(&self, e: Id, name: &str) -> bool {
        self.reachable(&[e], &|_| false)
            .into_iter()
            .any(|x| matches!(self.node(x), Node::Symbol(s) if self.symbol_name(s) == name))
    }
}

/// `c = +-2^k` with `c` and `1 / c` normal numbers: multiplying by `c` only shifts the exponent,
/// so it rounds nothing unless the result overflows or is subnormal.
pub fn is_power_of_two(c: f64) -> bool {
    c.is_normal() && c.to_bits() & ((1u64 << 52) - 1) == 0 && (1.0 / c).is_normal()
}

/// `c1 c2`, if merging the factors of `c1 (c2 x)` into `(c1 c2) x` rounds nothing: one of them
/// is a power of two and the product is a normal number.
fn merged_factor(c1: f64, c2: f64) -> Option<f64> {
    let product = c1 * c2;
    ((is_power_of_two(c1) || is_power_of_two(c2)) && product.is_normal()).then_some(product)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_expressions_share_one_node() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let y = g.symbol("y");
        let a = g.add(x, y);
        let b = g.add(y, x);
        assert_eq!(a, b, "commutative operands are put in canonical order");
        let s1 = g.sin(x);
        let s2 = g.sin(x);
        assert_eq!(s1, s2);
    }

    #[test]
    fn constants_fold_and_exact_identities_apply() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let two = g.constant(2.0);
        let three = g.constant(3.0);
        let zero = g.zero();
        let one = g.one();
        let p = g.mul(two, three);
        assert_eq!(g.as_const(p), Some(6.0));
        assert_eq!(g.add(x, zero), x);
        assert_eq!(g.sub(x, zero), x);
        assert_eq!(g.mul(one, x), x);
        assert_eq!(g.div(x, one), x);
        let nx = g.neg(x);
        assert_eq!(g.neg(nx), x);
        // 2 (3 x) = 6 x: one factor is a power of two, so nothing is rounded.
        let tx = g.mul(three, x);
        let sx = g.mul(two, tx);
        let six = g.constant(6.0);
        assert_eq!(sx, g.mul(six, x));
        // x + x = 2 x
        assert_eq!(g.add(x, x), g.mul(two, x));
        // x / 4 = 0.25 x (exact)
        let four = g.constant(4.0);
        let q = g.constant(0.25);
        assert_eq!(g.div(x, four), g.mul(q, x));
        // (-x)^2 = x^2
        let sq = g.powi(x, 2);
        assert_eq!(g.powi(nx, 2), sq);
    }

    #[test]
    fn identities_that_fail_somewhere_are_not_applied() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let zero = g.zero();
        let three = g.constant(3.0);
        let five = g.constant(5.0);
        // Each is wrong for some x: NaN or inf x, x = 0, x < 0, an overflowing exp, rounding.
        let kept = [
            (g.mul(zero, x), "0 x"),
            (g.div(zero, x), "0 / x"),
            (g.sub(x, x), "x - x"),
            (g.div(x, x), "x / x"),
            {
                let r = g.sqrt(x);
                (g.powi(r, 2), "sqrt(x)^2")
            },
            {
                let e = g.exp(x);
                (g.ln(e), "ln(exp(x))")
            },
            {
                let inv = g.powi(x, -1);
                (g.powi(inv, -1), "(x^-1)^-1")
            },
            {
                let tx = g.mul(three, x);
                (g.mul(five, tx), "5 (3 x)")
            },
            {
                let tx = g.mul(three, x);
                let fx = g.mul(five, x);
                (g.add(tx, fx), "3 x + 5 x")
            },
            (g.div(x, three), "x / 3"),
        ];
        for (id, what) in kept {
            assert!(id != x && id != zero && g.as_const(id).is_none(), "{what} was rewritten");
            assert!(g.mentions(id, "x"), "{what} lost x");
        }
    }

    #[test]
    fn substitution_simplifies() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let y = g.symbol("y");
        let xy = g.mul(x, y);
        let e = g.add(xy, x);
        let one = g.one();
        let map = HashMap::from([(y, one)]);
        // x 1 + x = x + x = 2 x
        let two = g.constant(2.0);
        assert_eq!(g.substitute(e, &map), g.mul(two, x));
    }

    #[test]
    fn eval_matches_direct_arithmetic() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let s = g.sin(x);
        let c = g.cos(x);
        let s2 = g.powi(s, 2);
        let c2 = g.powi(c, 2);
        let sum = g.add(s2, c2);
        let v = g.eval(sum, &|_| 0.7);
        assert!((v - 1.0).abs() < 1e-15);
    }
}
