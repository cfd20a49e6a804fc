//! A custom spring law, `law = <expression in l, l0, k>`, turned into the symbolic graph.
//!
//! The law goes through the same engine as the chain, so its tension, axial stiffness and every
//! derivative in the angles come out of symbolic differentiation: nothing is derived by hand.
//! Accepted: float and integer literals, `l`, `l0`, `k`, `+ - * /`, unary `-`, parentheses, and
//! the methods `.powi(int)`, `.sqrt()`, `.sin()`, `.cos()`, `.exp()`, `.ln()`.

use chain_symbolic::{Graph, Id, SpringLaw};
use syn::{BinOp, Expr, Lit, UnOp};

use crate::ctxt::Ctxt;

const SYMBOLS: [&str; 3] = ["l", "l0", "k"];
const METHODS: [&str; 6] = ["powi", "sqrt", "sin", "cos", "exp", "ln"];

/// Reports every unsupported part of the law expression.
pub fn check(cx: &Ctxt, expr: &Expr) {
    let mut g = Graph::new();
    let _ = lower(&mut g, expr, Some(cx));
}

/// The law as a [`SpringLaw`] in `g`. The expression must have passed [`check`].
pub fn build(g: &mut Graph, expr: &Expr) -> SpringLaw {
    let energy = lower(g, expr, None).expect("law was checked in the validation phase");
    SpringLaw::custom(g, energy)
}

fn lower(g: &mut Graph, expr: &Expr, cx: Option<&Ctxt>) -> Option<Id> {
    let fail = |tokens: &dyn quote::ToTokens, msg: String| {
        if let Some(cx) = cx {
            cx.error_spanned_by(tokens.to_token_stream(), msg);
        }
        None
    };
    match expr {
        Expr::Lit(l) => match &l.lit {
            Lit::Float(f) => f.base10_parse::<f64>().ok().map(|v| g.constant(v)),
            Lit::Int(i) => i.base10_parse::<f64>().ok().map(|v| g.constant(v)),
            _ => fail(expr, "a spring law uses numeric literals only".to_owned()),
        },
        Expr::Path(p) => {
            let name = p.path.get_ident().map(ToString::to_string).unwrap_or_default();
            if SYMBOLS.contains(&name.as_str()) {
                let (l, l0, k) = SpringLaw::symbols(g);
                Some(match name.as_str() {
                    "l" => l,
                    "l0" => l0,
                    _ => k,
                })
            } else {
                fail(
                    expr,
                    format!(
                        "unknown symbol `{}` in `law`: a spring law is a function of `l` (length), `l0` (rest length) and `k` (stiffness)",
                        quote::quote!(#p).to_string().replace(' ', "")
                    ),
                )
            }
        }
        Expr::Paren(p) => lower(g, &p.expr, cx),
        Expr::Group(p) => lower(g, &p.expr, cx),
        Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => {
            let x = lower(g, &u.expr, cx)?;
            Some(g.neg(x))
        }
        Expr::Binary(b) => {
            let (l, r) = (lower(g, &b.left, cx), lower(g, &b.right, cx));
            let (l, r) = (l?, r?);
            match b.op {
                BinOp::Add(_) => Some(g.add(l, r)),
                BinOp::Sub(_) => Some(g.sub(l, r)),
                BinOp::Mul(_) => Some(g.mul(l, r)),
                BinOp::Div(_) => Some(g.div(l, r)),
                _ => fail(&b.op, "a spring law supports the operators `+ - * /` only".to_owned()),
            }
        }
        Expr::MethodCall(m) => {
            let method = m.method.to_string();
            let receiver = lower(g, &m.receiver, cx);
            let arity = if method == "powi" { 1 } else { 0 };
            if !METHODS.contains(&method.as_str()) {
                return fail(
                    &m.method,
                    format!("unsupported method `{method}` in `law`; supported: {}", METHODS.map(|m| format!("`.{m}()`")).join(", ")),
                );
            }
            if m.args.len() != arity {
                return fail(&m.method, format!("`.{method}()` takes {arity} argument(s)"));
            }
            let x = receiver?;
            Some(match method.as_str() {
                "powi" => {
                    let n = match &m.args[0] {
                        Expr::Lit(l) => match &l.lit {
                            Lit::Int(i) => i.base10_parse::<i32>().ok(),
                            _ => None,
                        },
                        Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => match &*u.expr {
                            Expr::Lit(l) => match &l.lit {
                                Lit::Int(i) => i.base10_parse::<i32>().ok().map(|v| -v),
                                _ => None,
                            },
                            _ => None,
                        },
                        _ => None,
                    };
                    let Some(n) = n else {
                        return fail(&m.args[0], "`.powi()` takes an integer literal".to_owned());
                    };
                    g.powi(x, n)
                }
                "sqrt" => g.sqrt(x),
                "sin" => g.sin(x),
                "cos" => g.cos(x),
                "exp" => g.exp(x),
                _ => g.ln(x),
            })
        }
        _ => fail(expr, "unsupported expression in `law`: use literals, `l`, `l0`, `k`, `+ - * /` and `.powi(n)`, `.sqrt()`, `.sin()`, `.cos()`, `.exp()`, `.ln()`".to_owned()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_papers_quartic_law_builds_and_evaluates() {
        let expr: Expr = syn::parse_quote!(k / (8.0 * l0 * l0) * (l * l - l0 * l0).powi(2));
        let cx = Ctxt::new();
        check(&cx, &expr);
        cx.check().unwrap();
        let mut g = Graph::new();
        let law = build(&mut g, &expr);
        let v = g.eval(law.energy, &|name| match name {
            chain_symbolic::spring::LAW_L => 2.0,
            chain_symbolic::spring::LAW_L0 => 1.5,
            _ => 4.0,
        });
        let expected = 4.0 / (8.0 * 1.5 * 1.5) * (4.0f64 - 2.25).powi(2);
        assert!((v - expected).abs() < 1e-14);
    }

    #[test]
    fn unknown_symbols_and_methods_are_errors() {
        let expr: Expr = syn::parse_quote!(k * (l - lbar).powi(2) + l.tanh());
        let cx = Ctxt::new();
        check(&cx, &expr);
        let msg = cx.check().unwrap_err().into_iter().map(|e| e.to_string()).collect::<Vec<_>>().join("\n");
        assert!(msg.contains("unknown symbol `lbar`"), "{msg}");
        assert!(msg.contains("unsupported method `tanh`"), "{msg}");
    }
}
