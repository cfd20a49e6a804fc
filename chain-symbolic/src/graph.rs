//! The hash-consed expression graph.
//!
//! Nodes live in one arena (`Vec<Node>`); a node refers to its children by [`Id`], and a child is
//! always created before its parent, so the arena order is a valid evaluation order. Nodes are
//! interned through a map, so building the same expression twice yields the same `Id` and common
//! subexpressions are shared for free (the design of egg's `RecExpr` and its memo).
//!
//! Simplification happens in the smart constructors ([`Graph::add`], [`Graph::mul`], ...): constant
//! folding, neutral and absorbing elements, canonical operand order for commutative operations,
//! and a few cancellations. These are the rules that keep generated code short. For finite
//! operands no rule changes a value by more than the rounding of the folded constants; the
//! cancellations (`x - x = 0`, `x / x = 1`, `0 x = 0`, `sqrt(x)^2 = x`) assume finite operands
//! (and `x >= 0` under a square root), which holds for every expression of a chain in its domain.

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

    /// Splits `c * x` into `(c, x)`; any other node is `(1, node)`.
    fn coefficient(&self, id: Id) -> (f64, Option<Id>) {
        match self.node(id) {
            Node::Const(bits) => (f64::from_bits(bits), None),
            Node::Mul(a, b) => match self.as_const(a) {
                Some(c) => (c, Some(b)),
                None => (1.0, Some(id)),
            },
            Node::Neg(x) => {
                let (c, rest) = self.coefficient(x);
                (-c, rest)
            }
            _ => (1.0, Some(id)),
        }
    }

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
        // a + (-b) = a - b
        if let Node::Neg(nb) = self.node(b) {
            return self.sub(a, nb);
        }
        if let Node::Neg(na) = self.node(a) {
            return self.sub(b, na);
        }
        // c1 x + c2 x = (c1 + c2) x
        let (ca, ra) = self.coefficient(a);
        let (cb, rb) = self.coefficient(b);
        if let (Some(x), Some(y)) = (ra, rb) {
            if x == y {
                let c = self.constant(ca + cb);
                return self.mul(c, x);
            }
            // c x + c y = c (x + y) and c x - c y = c (x - y): one multiplication fewer.
            if ca == cb && ca != 1.0 {
                let c = self.constant(ca);
                let s = self.add(x, y);
                return self.mul(c, s);
            }
            if ca == -cb && ca != 1.0 && ca != -1.0 {
                let c = self.constant(ca);
                let d = self.sub(x, y);
                return self.mul(c, d);
            }
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Add(a, b))
    }

    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x - y);
        }
        if a == b {
            return self.zero();
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
        let (ca, ra) = self.coefficient(a);
        let (cb, rb) = self.coefficient(b);
        if let (Some(x), Some(y)) = (ra, rb) {
            if x == y {
                let c = self.constant(ca - cb);
                return self.mul(c, x);
            }
            if ca == cb && ca != 1.0 {
                let c = self.constant(ca);
                let d = self.sub(x, y);
                return self.mul(c, d);
            }
            if ca == -cb && ca != 1.0 && ca != -1.0 {
                let c = self.constant(ca);
                let s = self.add(x, y);
                return self.mul(c, s);
            }
        }
        self.intern(Node::Sub(a, b))
    }

    pub fn neg(&mut self, a: Id) -> Id {
        match self.node(a) {
            Node::Const(bits) => self.constant(-f64::from_bits(bits)),
            Node::Neg(x) => x,
            Node::Sub(x, y) => self.sub(y, x),
            Node::Mul(c, x) if self.as_const(c).is_some() => {
                let c = self.constant(-self.as_const(c).unwrap_or(0.0));
                self.mul(c, x)
            }
            _ => self.intern(Node::Neg(a)),
        }
    }

    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        // Constants go first so that `c * x` is the canonical scaled form.
        let (a, b) = if self.as_const(b).is_some() && self.as_const(a).is_none() { (b, a) } else { (a, b) };
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x * y);
        }
        if let Some(c) = self.as_const(a) {
            if c == 0.0 {
                return self.zero();
            }
            if c == 1.0 {
                return b;
            }
            if c == -1.0 {
                return self.neg(b);
            }
            // c1 * (c2 * x) = (c1 c2) x
            if let Node::Mul(inner, x) = self.node(b)
                && let Some(c2) = self.as_const(inner)
            {
                let c = self.constant(c * c2);
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
        // Pull a constant factor of either operand out front: (c x) y = c (x y).
        if let Node::Mul(c, x) = self.node(a)
            && self.as_const(c).is_some()
        {
            let p = self.mul(x, b);
            return self.mul(c, p);
        }
        if let Node::Mul(c, y) = self.node(b)
            && self.as_const(c).is_some()
        {
            let p = self.mul(a, y);
            return self.mul(c, p);
        }
        if a == b {
            return self.powi(a, 2);
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Mul(a, b))
    }

    pub fn div(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x / y);
        }
        if self.is_const(a, 0.0) {
            return self.zero();
        }
        // c / x = c (1 / x), so that c can merge with other constant factors.
        if let Some(c) = self.as_const(a)
            && c != 1.0
        {
            let one = self.one();
            let inv = self.div(one, b);
            return self.mul(a, inv);
        }
        if let Some(c) = self.as_const(b) {
            // Multiplying by the folded reciprocal is cheaper than a division; the rounding
            // differs by at most one ulp of the reciprocal.
            let r = self.constant(1.0 / c);
            return self.mul(r, a);
        }
        if a == b {
            return self.one();
        }
        if let Node::Neg(x) = self.node(a) {
            let q = self.div(x, b);
            return self.neg(q);
        }
        if let Node::Mul(c, x) = self.node(a)
            && self.as_const(c).is_some()
        {
            let q = self.div(x, b);
            return self.mul(c, q);
        }
        self.intern(Node::Div(a, b))
    }

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
        match self.node(a) {
            Node::Powi(x, m) => match m.checked_mul(n) {
                Some(mn) => self.powi(x, mn),
                None => self.intern(Node::Powi(a, n)),
            },
            Node::Neg(x) if n % 2 == 0 => self.powi(x, n),
            Node::Sqrt(x) if n % 2 == 0 => self.powi(x, n / 2),
            _ => self.intern(Node::Powi(a, n)),
        }
    }

    pub fn sqrt(&mut self, a: Id) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.constant(x.sqrt());
        }
        self.intern(Node::Sqrt(a))
    }

    pub fn sin(&mut self, a: Id) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.constant(x.sin());
        }
        self.intern(Node::Sin(a))
    }

    pub fn cos(&mut self, a: Id) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.constant(x.cos());
        }
        self.intern(Node::Cos(a))
    }

    pub fn exp(&mut self, a: Id) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.constant(x.exp());
        }
        self.intern(Node::Exp(a))
    }

    pub fn ln(&mut self, a: Id) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.constant(x.ln());
        }
        if let Node::Exp(x) = self.node(a) {
            return x;
        }
        self.intern(Node::Ln(a))
    }

    /// Rebuilds `e` with every node in `map` replaced, simplifying on the way.
    pub fn substitute(&mut self, e: Id, map: &HashMap<Id, Id>) -> Id {
        let mut memo = map.clone();
        self.substitute_memo(e, &mut memo)
    }

    fn substitute_memo(&mut self, e: Id, memo: &mut HashMap<Id, Id>) -> Id {
        if let Some(&done) = memo.get(&e) {
            return done;
        }
        let out = match self.node(e) {
            Node::Const(_) | Node::Symbol(_) => e,
            Node::Add(a, b) => {
                let (a, b) = (self.substitute_memo(a, memo), self.substitute_memo(b, memo));
                self.add(a, b)
            }
            Node::Sub(a, b) => {
                let (a, b) = (self.substitute_memo(a, memo), self.substitute_memo(b, memo));
                self.sub(a, b)
            }
            Node::Mul(a, b) => {
                let (a, b) = (self.substitute_memo(a, memo), self.substitute_memo(b, memo));
                self.mul(a, b)
            }
            Node::Div(a, b) => {
                let (a, b) = (self.substitute_memo(a, memo), self.substitute_memo(b, memo));
                self.div(a, b)
            }
            Node::Neg(a) => {
                let a = self.substitute_memo(a, memo);
                self.neg(a)
            }
            Node::Powi(a, n) => {
                let a = self.substitute_memo(a, memo);
                self.powi(a, n)
            }
            Node::Sqrt(a) => {
                let a = self.substitute_memo(a, memo);
                self.sqrt(a)
            }
            Node::Sin(a) => {
                let a = self.substitute_memo(a, memo);
                self.sin(a)
            }
            Node::Cos(a) => {
                let a = self.substitute_memo(a, memo);
                self.cos(a)
            }
            Node::Exp(a) => {
                let a = self.substitute_memo(a, memo);
                self.exp(a)
            }
            Node::Ln(a) => {
                let a = self.substitute_memo(a, memo);
                self.ln(a)
            }
        };
        memo.insert(e, out);
        out
    }

    /// Evaluates `e` numerically, with `value_of` giving each symbol's value (by name).
    /// Used by tests and by the generator's self-checks, never by generated code.
    pub fn eval(&self, e: Id, value_of: &dyn Fn(&str) -> f64) -> f64 {
        let mut values: HashMap<Id, f64> = HashMap::new();
        self.eval_memo(e, value_of, &mut values)
    }

    fn eval_memo(&self, e: Id, value_of: &dyn Fn(&str) -> f64, v: &mut HashMap<Id, f64>) -> f64 {
        if let Some(&x) = v.get(&e) {
            return x;
        }
        let mut ev = |x: Id| self.eval_memo(x, value_of, v);
        let out = match self.node(e) {
            Node::Const(bits) => f64::from_bits(bits),
            Node::Symbol(s) => value_of(self.symbol_name(s)),
            Node::Add(a, b) => ev(a) + ev(b),
            Node::Sub(a, b) => ev(a) - ev(b),
            Node::Mul(a, b) => ev(a) * ev(b),
            Node::Div(a, b) => ev(a) / ev(b),
            Node::Neg(a) => -ev(a),
            Node::Powi(a, n) => ev(a).powi(n),
            Node::Sqrt(a) => ev(a).sqrt(),
            Node::Sin(a) => ev(a).sin(),
            Node::Cos(a) => ev(a).cos(),
            Node::Exp(a) => ev(a).exp(),
            Node::Ln(a) => ev(a).ln(),
        };
        v.insert(e, out);
        out
    }

    /// Whether the symbol called `name` occurs in `e`.
    pub fn mentions(&self, e: Id, name: &str) -> bool {
        let mut stack = vec![e];
        let mut seen = vec![false; self.nodes.len()];
        while let Some(x) = stack.pop() {
            if std::mem::replace(&mut seen[x.index()], true) {
                continue;
            }
            let node = self.node(x);
            if let Node::Symbol(s) = node
                && self.symbol_name(s) == name
            {
                return true;
            }
            stack.extend(node.children());
        }
        false
    }
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
    fn constants_fold_and_identities_vanish() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let two = g.constant(2.0);
        let three = g.constant(3.0);
        let zero = g.zero();
        let one = g.one();
        let p = g.mul(two, three);
        assert_eq!(g.as_const(p), Some(6.0));
        assert_eq!(g.add(x, zero), x);
        assert_eq!(g.mul(one, x), x);
        assert_eq!(g.mul(x, zero), zero);
        assert_eq!(g.sub(x, x), zero);
        let nx = g.neg(x);
        assert_eq!(g.neg(nx), x);
        // 2 (3 x) = 6 x
        let tx = g.mul(three, x);
        let sx = g.mul(two, tx);
        let six = g.constant(6.0);
        assert_eq!(sx, g.mul(six, x));
        // x + x = 2 x
        assert_eq!(g.add(x, x), g.mul(two, x));
        // x / 4 = 0.25 x
        let four = g.constant(4.0);
        let q = g.constant(0.25);
        assert_eq!(g.div(x, four), g.mul(q, x));
        // sqrt(x)^2 = x
        let r = g.sqrt(x);
        assert_eq!(g.powi(r, 2), x);
    }

    #[test]
    fn substitution_simplifies() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let y = g.symbol("y");
        let xy = g.mul(x, y);
        let e = g.add(xy, x);
        let zero = g.zero();
        let map = HashMap::from([(y, zero)]);
        assert_eq!(g.substitute(e, &map), x);
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
