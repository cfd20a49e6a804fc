//! Symbolic differentiation.
//!
//! One table of derivative rules: [`local_partials`] gives, for each operation, the partial
//! derivative of the node with respect to each of its children (num-dual's single chain rule fed
//! by each function's derivative). [`Differentiator::diff`] then applies the chain rule,
//! `d(node) = sum_k partial_k * d(child_k)`, memoised per node, so a derivative shares every
//! subexpression it can with the function and with other derivatives.

use std::collections::HashMap;

use crate::graph::{Graph, Id, Node};

/// The partial derivatives of node `id` with respect to its children, as graph nodes.
///
/// The rules reuse the node itself where the derivative contains it (`d exp(x) = exp(x)`,
/// `d sqrt(x) = 1 / (2 sqrt(x))`, `d(a / b)/db = -(a / b) / b`), so no transcendental is evaluated
/// twice in generated code.
pub fn local_partials(g: &mut Graph, id: Id) -> Vec<(Id, Id)> {
    match g.node(id) {
        Node::Const(_) | Node::Symbol(_) => vec![],
        Node::Add(a, b) => {
            let one = g.one();
            vec![(a, one), (b, one)]
        }
        Node::Sub(a, b) => {
            let one = g.one();
            let m1 = g.constant(-1.0);
            vec![(a, one), (b, m1)]
        }
        Node::Mul(a, b) => vec![(a, b), (b, a)],
        Node::Div(a, b) => {
            let one = g.one();
            let inv_b = g.div(one, b);
            let q = g.div(id, b);
            let dq_db = g.neg(q);
            vec![(a, inv_b), (b, dq_db)]
        }
        Node::Neg(a) => vec![(a, g.constant(-1.0))],
        Node::Powi(a, n) => {
            let c = g.constant(f64::from(n));
            // `Graph::powi` never stores `i32::MIN`, so `n - 1` fits.
            let p = g.powi(a, n.max(i32::MIN + 1) - 1);
            vec![(a, g.mul(c, p))]
        }
        Node::Sqrt(a) => {
            let half = g.constant(0.5);
            let d = g.div(half, id);
            vec![(a, d)]
        }
        Node::Sin(a) => vec![(a, g.cos(a))],
        Node::Cos(a) => {
            let s = g.sin(a);
            vec![(a, g.neg(s))]
        }
        Node::Exp(a) => vec![(a, id)],
        Node::Ln(a) => {
            let one = g.one();
            vec![(a, g.div(one, a))]
        }
    }
}

/// Forward symbolic differentiation with respect to one symbol, memoised per node.
pub struct Differentiator {
    wrt: Id,
    memo: HashMap<Id, Id>,
}

impl Differentiator {
    /// Differentiation with respect to the symbol node `wrt`.
    pub fn new(wrt: Id) -> Self {
        Self { wrt, memo: HashMap::new() }
    }

    /// `d e / d wrt`. Iterative: the nodes below `e` whose derivative is not known yet are
    /// differentiated children first, so expressions of any depth need no recursion.
    pub fn diff(&mut self, g: &mut Graph, e: Id) -> Id {
        let pending = g.reachable(&[e], &|id| self.memo.contains_key(&id));
        for id in pending {
            let d = match g.node(id) {
                Node::Const(_) => g.zero(),
                Node::Symbol(_) if id == self.wrt => g.one(),
                Node::Symbol(_) => g.zero(),
                _ => {
                    let mut total = g.zero();
                    for (child, partial) in local_partials(g, id) {
                        let dc = self.memo[&child];
                        // A term whose child does not depend on `wrt` is left out: a derivative
                        // is that of the function, not of its IEEE evaluation (`0 * inf`).
                        if g.as_const(dc) == Some(0.0) {
                            continue;
                        }
                        let term = g.mul(partial, dc);
                        total = g.add(total, term);
                    }
                    total
                }
            };
            self.memo.insert(id, d);
        }
        self.memo[&e]
    }
}

/// `d e / d wrt` in one call.
pub fn diff(g: &mut Graph, e: Id, wrt: Id) -> Id {
    Differentiator::new(wrt).diff(g, e)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central finite difference of the graph's own evaluation, an independent check of the rules.
    fn fd(g: &Graph, e: Id, x0: f64) -> f64 {
        let h = 1e-6;
        (g.eval(e, &|_| x0 + h) - g.eval(e, &|_| x0 - h)) / (2.0 * h)
    }

    #[test]
    fn every_rule_matches_a_finite_difference() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let three = g.constant(3.0);
        let sx = g.sin(x);
        let cx = g.cos(x);
        let ex = g.exp(x);
        let lx = g.ln(x);
        let rx = g.sqrt(x);
        let p3 = g.powi(x, 3);
        let pm2 = g.powi(x, -2);
        let q = g.div(sx, x);
        let prod = g.mul(cx, ex);
        let diffr = g.sub(lx, rx);
        let neg = g.neg(p3);
        let shifted = g.add(x, three);
        let nested = g.sqrt(shifted);
        let nested = g.mul(nested, q);
        for e in [sx, cx, ex, lx, rx, p3, pm2, q, prod, diffr, neg, nested] {
            let d = diff(&mut g, e, x);
            for x0 in [0.4, 1.3, 2.9] {
                let exact = g.eval(d, &|_| x0);
                let approx = fd(&g, e, x0);
                assert!(
                    (exact - approx).abs() <= 1e-7 * (1.0 + exact.abs()),
                    "node {e:?} at {x0}: symbolic {exact}, finite difference {approx}"
                );
            }
        }
    }

    #[test]
    fn derivative_of_a_constant_in_wrt_is_zero() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let y = g.symbol("y");
        let s = g.sin(y);
        let e = g.mul(s, y);
        let d = diff(&mut g, e, x);
        assert_eq!(g.as_const(d), Some(0.0));
    }

    #[test]
    fn derivative_reuses_the_sqrt_node() {
        let mut g = Graph::new();
        let x = g.symbol("x");
        let r = g.sqrt(x);
        let before = g.len();
        let _ = diff(&mut g, r, x);
        // 0.5 / sqrt(x) costs a constant and a division, never a second square root.
        let sqrt_count = (0..g.len()).filter(|&i| matches!(g.node(Id(i as u32)), Node::Sqrt(_))).count();
        assert_eq!(sqrt_count, 1);
        // New nodes: the constants 0, 1, 0.5, the reciprocal 1 / sqrt(x) and its product with 0.5.
        assert!(g.len() <= before + 5, "{} new nodes", g.len() - before);
    }
}
