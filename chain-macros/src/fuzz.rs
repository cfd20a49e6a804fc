//! Property-based fuzzing of the macro pipeline's library functions (proptest, fixed seed, no
//! regression files).
//!
//! - **Laws.** Random law expressions (deep, wide and mixed; every supported operation; extreme
//!   literals and exponents) are rendered to Rust source with Rust's precedence, tokenised and
//!   run through [`law::parse`] and [`Law::build`]. Within the limits every law must parse, and
//!   the graph must evaluate to exactly what a direct `f64` evaluation of the written expression
//!   gives at random points, wherever no intermediate of either evaluation overflows, is
//!   subnormal or divides by zero (the simplifier's documented relaxations, `graph.rs`). Beyond
//!   the limits the law must be one error. The tension and axial stiffness (`d/dl`, `d2/dl2`)
//!   and, for smaller laws, the spring's gradient in the angles are checked against finite
//!   differences with a Richardson error estimate.
//! - **Attributes.** Random key sets (valid and invalid values, duplicates, unknown keys,
//!   overrides, laws, raw identifiers, stray tokens) on random items go through
//!   [`expand::expand`]: no panic, and the output is well-formed Rust items.
//!
//! `cargo test -p rotor-chain-macros fuzz` runs the CI size (2000 laws, 200 attributes, about 15 s in
//! debug). The long run multiplies both:
//! `ROTOR_CHAIN_FUZZ_CASES=100000 cargo test --release -p rotor-chain-macros fuzz -- --nocapture`.

use chain_symbolic::chain::Kernel;
use chain_symbolic::diff::diff;
use chain_symbolic::spring::{LAW_K, LAW_L, LAW_L0};
use chain_symbolic::{Graph, Id, Node, SpringLaw};
use proc_macro2::{Ident, Span, TokenStream, TokenTree};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestRunner};

use crate::ctxt::Ctxt;
use crate::expand;
use crate::law::{self, Law, MAX_NESTING, MAX_TERMS};

/// Law cases per run: `ROTOR_CHAIN_FUZZ_CASES`, default 2000; attribute cases are a tenth.
fn cases() -> u32 {
    std::env::var("ROTOR_CHAIN_FUZZ_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(2000)
}

fn runner(cases: u32, seed: u64) -> TestRunner {
    TestRunner::new(Config {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        max_shrink_iters: 2000,
        ..Config::default()
    })
}

/// A written law.
#[derive(Clone, Debug)]
enum Expr {
    Lit(f64),
    L,
    L0,
    K,
    Neg(Box<Expr>),
    Bin(char, Box<Expr>, Box<Expr>),
    Powi(Box<Expr>, i32),
    Fun(&'static str, Box<Expr>),
    Paren(Box<Expr>),
}

fn literal() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => prop_oneof![Just(0.0), Just(1.0), Just(2.0), Just(0.5), Just(3.0), Just(0.1)],
        2 => 1e-3f64..1e3,
        1 => prop_oneof![
            Just(5e-324),
            Just(1e-310),
            Just(f64::MIN_POSITIVE),
            Just(1e-300),
            Just(1e300),
            Just(f64::MAX),
            Just(1e16),
        ],
    ]
}

fn exponent() -> impl Strategy<Value = i32> {
    prop_oneof![
        6 => -4i32..=4,
        1 => prop_oneof![Just(i32::MIN), Just(i32::MAX), Just(-1025), Just(1024), Just(i32::MIN + 1)],
        1 => any::<i32>(),
    ]
}

fn leaf() -> impl Strategy<Value = Expr> {
    prop_oneof![literal().prop_map(Expr::Lit), Just(Expr::L), Just(Expr::L0), Just(Expr::K)]
}

const FUNCTIONS: [&str; 5] = ["sqrt", "sin", "cos", "exp", "ln"];

/// One level of structure over `inner`.
fn node(inner: BoxedStrategy<Expr>) -> impl Strategy<Value = Expr> {
    prop_oneof![
        inner.clone().prop_map(|a| Expr::Neg(a.into())),
        (prop::sample::select(vec!['+', '-', '*', '/']), inner.clone(), inner.clone())
            .prop_map(|(op, a, b)| Expr::Bin(op, a.into(), b.into())),
        (inner.clone(), exponent()).prop_map(|(a, n)| Expr::Powi(a.into(), n)),
        (prop::sample::select(FUNCTIONS.to_vec()), inner.clone()).prop_map(|(f, a)| Expr::Fun(f, a.into())),
        inner.prop_map(|a| Expr::Paren(a.into())),
    ]
}

/// Mixed laws, deep chains (nesting near the limit, long method chains) and wide sums and
/// products (term counts near the limit).
fn law_expr() -> impl Strategy<Value = Expr> {
    let mixed = leaf().prop_recursive(10, 96, 2, |inner| node(inner.boxed()));
    let deep = (leaf(), prop::collection::vec(0u8..7, 1..80)).prop_map(|(mut e, steps)| {
        for s in steps {
            e = match s {
                0 => Expr::Neg(e.into()),
                1 => Expr::Paren(e.into()),
                2 => Expr::Powi(e.into(), 2),
                3..=6 => Expr::Fun(FUNCTIONS[usize::from(s) - 2], e.into()),
                _ => e,
            };
        }
        e
    });
    let wide = prop::collection::vec((leaf(), prop::sample::select(vec!['+', '-', '*', '/'])), 1..600)
        .prop_map(|terms| {
            let mut it = terms.into_iter();
            let first = it.next().map_or(Expr::L, |t| t.0);
            it.fold(first, |acc, (t, op)| Expr::Bin(op, acc.into(), t.into()))
        });
    prop_oneof![6 => mixed, 2 => deep, 1 => wide]
}

fn precedence(e: &Expr) -> u8 {
    match e {
        Expr::Bin('+' | '-', ..) => 1,
        Expr::Bin(..) => 2,
        Expr::Neg(_) => 3,
        _ => 4,
    }
}

/// Rust source with the fewest parentheses that keep the tree (Rust's precedence, left
/// associativity), so the parser's precedence handling is exercised. Iterative.
fn render(e: &Expr) -> String {
    enum Job<'a> {
        Expr(&'a Expr),
        Text(String),
    }
    let mut out = String::new();
    let mut stack = vec![Job::Expr(e)];
    // Pushes `e`, in parentheses if `paren`.
    fn wrap<'a>(stack: &mut Vec<Job<'a>>, e: &'a Expr, paren: bool) {
        if paren {
            stack.push(Job::Text(")".into()));
            stack.push(Job::Expr(e));
            stack.push(Job::Text("(".into()));
        } else {
            stack.push(Job::Expr(e));
        }
    }
    while let Some(job) = stack.pop() {
        let e = match job {
            Job::Text(t) => {
                out.push_str(&t);
                continue;
            }
            Job::Expr(e) => e,
        };
        match e {
            Expr::Lit(v) => out.push_str(&format!("{v:?}")),
            Expr::L => out.push('l'),
            Expr::L0 => out.push_str("l0"),
            Expr::K => out.push('k'),
            Expr::Neg(a) => {
                wrap(&mut stack, a, precedence(a) < 3);
                out.push_str("- ");
            }
            Expr::Bin(op, a, b) => {
                let p = precedence(e);
                wrap(&mut stack, b, precedence(b) <= p);
                stack.push(Job::Text(format!(" {op} ")));
                wrap(&mut stack, a, precedence(a) < p);
            }
            Expr::Powi(a, n) => {
                stack.push(Job::Text(format!(".powi({n})")));
                wrap(&mut stack, a, precedence(a) < 4);
            }
            Expr::Fun(f, a) => {
                stack.push(Job::Text(format!(".{f}()")));
                wrap(&mut stack, a, precedence(a) < 4);
            }
            Expr::Paren(a) => wrap(&mut stack, a, true),
        }
    }
    out
}

/// A value and whether it is "irregular": subnormal, or infinite from finite operands
/// (overflow, a pole), or the result of dividing by a zero (whose sign the simplifier need not
/// keep). Exactness is promised only where neither evaluation meets one.
/// `peak` is the largest magnitude of any intermediate: the scale of the rounding noise.
#[derive(Clone, Copy)]
struct Value {
    v: f64,
    irregular: bool,
    peak: f64,
}

fn step(v: f64, operands: &[Value], pole: bool) -> Value {
    let finite_in = operands.iter().all(|o| o.v.is_finite());
    // An exact result below the normal range can round up to MIN_POSITIVE, one above it down to
    // MAX: both are at the edge, where a rounding may have changed the exponent range.
    let subnormal = v != 0.0 && v.is_finite() && v.abs() <= f64::MIN_POSITIVE;
    let overflow = finite_in && (v.is_infinite() || v.abs() == f64::MAX);
    Value {
        v,
        irregular: operands.iter().any(|o| o.irregular) || subnormal || overflow || pole,
        peak: operands.iter().fold(v.abs(), |m, o| m.max(o.peak)),
    }
}

fn binary(op: char, a: Value, b: Value) -> Value {
    let v = match op {
        '+' => a.v + b.v,
        '-' => a.v - b.v,
        '*' => a.v * b.v,
        _ => a.v / b.v,
    };
    step(v, &[a, b], op == '/' && b.v == 0.0)
}

fn unary(f: &str, a: Value) -> Value {
    let v = match f {
        "sqrt" => a.v.sqrt(),
        "sin" => a.v.sin(),
        "cos" => a.v.cos(),
        "exp" => a.v.exp(),
        _ => a.v.ln(),
    };
    step(v, &[a], f == "ln" && a.v == 0.0)
}

fn powi(a: Value, n: i32) -> Value {
    step(a.v.powi(n), &[a], n < 0 && a.v == 0.0)
}

/// Direct `f64` evaluation of the written expression (iterative, postorder).
fn direct(e: &Expr, l: f64, l0: f64, k: f64) -> Value {
    let mut todo = vec![(e, false)];
    let mut values: Vec<Value> = Vec::new();
    while let Some((e, done)) = todo.pop() {
        if !done {
            todo.push((e, true));
            match e {
                Expr::Neg(a) | Expr::Powi(a, _) | Expr::Fun(_, a) | Expr::Paren(a) => todo.push((a, false)),
                Expr::Bin(_, a, b) => {
                    todo.push((b, false));
                    todo.push((a, false));
                }
                _ => {}
            }
            continue;
        }
        let value = match e {
            Expr::Lit(v) => step(*v, &[], false),
            Expr::L => step(l, &[], false),
            Expr::L0 => step(l0, &[], false),
            Expr::K => step(k, &[], false),
            Expr::Neg(_) => {
                let a = values.pop().expect("operand");
                Value { v: -a.v, ..a }
            }
            Expr::Paren(_) => values.pop().expect("operand"),
            Expr::Powi(_, n) => powi(values.pop().expect("operand"), *n),
            Expr::Fun(f, _) => unary(f, values.pop().expect("operand")),
            Expr::Bin(op, ..) => {
                let b = values.pop().expect("operand");
                let a = values.pop().expect("operand");
                binary(*op, a, b)
            }
        };
        values.push(value);
    }
    values.pop().expect("a value")
}

/// The graph's evaluation at the law's symbols `l`, `l0`, `k`, with irregularity tracking.
fn graph_value(g: &Graph, e: Id, l: f64, l0: f64, k: f64) -> Value {
    graph_value_with(g, e, &|name| match name {
        LAW_L => l,
        LAW_L0 => l0,
        LAW_K => k,
        other => panic!("unexpected symbol {other}"),
    })
}

/// The graph's evaluation with the same irregularity tracking as [`direct`].
fn graph_value_with(g: &Graph, e: Id, symbol: &dyn Fn(&str) -> f64) -> Value {
    let mut v: std::collections::HashMap<Id, Value> = std::collections::HashMap::new();
    for id in g.reachable(&[e], &|_| false) {
        let x = |c: Id| v[&c];
        let out = match g.node(id) {
            Node::Const(bits) => step(f64::from_bits(bits), &[], false),
            Node::Symbol(s) => step(symbol(g.symbol_name(s)), &[], false),
            Node::Add(a, b) => binary('+', x(a), x(b)),
            Node::Sub(a, b) => binary('-', x(a), x(b)),
            Node::Mul(a, b) => binary('*', x(a), x(b)),
            Node::Div(a, b) => binary('/', x(a), x(b)),
            Node::Neg(a) => Value { v: -x(a).v, ..x(a) },
            Node::Powi(a, n) => powi(x(a), n),
            Node::Sqrt(a) => unary("sqrt", x(a)),
            Node::Sin(a) => unary("sin", x(a)),
            Node::Cos(a) => unary("cos", x(a)),
            Node::Exp(a) => unary("exp", x(a)),
            Node::Ln(a) => unary("ln", x(a)),
        };
        v.insert(id, out);
    }
    v[&e]
}

/// Terms as [`law`] counts them, and the deepest nesting of groups in the rendered source.
fn size(e: &Expr, source: &TokenStream) -> (usize, usize) {
    let mut terms = 0;
    let mut stack = vec![e];
    while let Some(e) = stack.pop() {
        match e {
            Expr::Paren(a) => stack.push(a),
            Expr::Neg(a) | Expr::Powi(a, _) | Expr::Fun(_, a) => {
                terms += 1;
                stack.push(a);
            }
            Expr::Bin(_, a, b) => {
                terms += 1;
                stack.push(a);
                stack.push(b);
            }
            _ => terms += 1,
        }
    }
    let mut deepest = 0;
    let mut groups = vec![(source.clone().into_iter(), 0usize)];
    while let Some((iter, depth)) = groups.last_mut() {
        let depth = *depth;
        match iter.next() {
            Some(TokenTree::Group(g)) => {
                deepest = deepest.max(depth + 1);
                groups.push((g.stream().into_iter(), depth + 1));
            }
            Some(_) => {}
            None => {
                groups.pop();
            }
        }
    }
    (terms, deepest)
}

fn same(a: f64, b: f64) -> bool {
    a == b || (a.is_nan() && b.is_nan())
}

/// The derivative `d` of `f` at `x` against central differences, over steps `h` from `1e-2` to
/// `1e-9` (relative): `d` must agree with the difference at some step within that step's error
/// estimate (Richardson's `|D(h) - D(h/2)|` plus rounding noise `eps (peak + |x f'|) / h`, `peak`
/// the largest intermediate of the evaluation). A step
/// too coarse for a fast oscillation can alias, a step too fine drowns in rounding; the step that
/// resolves `f` agrees with a right derivative, and a wrong one would have to fall within a
/// tight estimate of some difference by chance. Functions varying more than a million times
/// faster than their size are skipped.
fn check_derivative(what: &str, d: f64, f: &dyn Fn(f64) -> (f64, f64), x: f64) -> Result<(), TestCaseError> {
    let noise = |x: f64| f(x).1;
    let f = |x: f64| f(x).0;
    let fx = f(x);
    if !(fx.is_finite() && d.is_finite()) || d.abs() * x.abs().max(1.0) > 1e6 * (fx.abs() + 1.0) {
        return Ok(());
    }
    let fd = |h: f64| (f(x + h) - f(x - h)) / (2.0 * h);
    let mut seen = Vec::new();
    for k in 2..=9 {
        let h = 10f64.powi(-k) * x.abs().max(1.0);
        let (coarse, fine) = (fd(h), fd(h / 2.0));
        if !(coarse.is_finite() && fine.is_finite()) {
            continue;
        }
        // Rounding noise of f: its own magnitude, and the argument's rounding carried through
        // (|x f'|), with room for the intermediates of a nested law.
        let scale = noise(x).max(noise(x + h)).max(noise(x - h)) + (x * fine).abs();
        let estimate = (coarse - fine).abs() + 64.0 * f64::EPSILON * scale / h;
        if (d - fine).abs() <= 4.0 * estimate + 1e-12 * d.abs() + 1e-300 {
            return Ok(());
        }
        seen.push((h, fine, estimate));
    }
    prop_assert!(seen.is_empty(), "{what} at {x}: symbolic {d}, finite differences (h, D, error) {seen:?}");
    Ok(())
}

fn moderate(e: &Expr) -> bool {
    let mut stack = vec![e];
    while let Some(e) = stack.pop() {
        match e {
            Expr::Lit(v) if *v != 0.0 && !(1e-3..=1e3).contains(v) => return false,
            Expr::Powi(_, n) if n.unsigned_abs() > 8 => return false,
            Expr::Powi(a, _) => stack.push(a),
            Expr::Neg(a) | Expr::Fun(_, a) | Expr::Paren(a) => stack.push(a),
            Expr::Bin(_, a, b) => {
                stack.push(a);
                stack.push(b);
            }
            _ => {}
        }
    }
    true
}

fn check_law(e: &Expr, points: &[(f64, f64, f64)]) -> Result<(), TestCaseError> {
    let source = render(e);
    let tokens: TokenStream =
        source.parse().map_err(|err| TestCaseError::fail(format!("{err}: {source}")))?;
    let (terms, depth) = size(e, &tokens);
    let cx = Ctxt::new();
    let parsed = law::parse(&cx, &Ident::new("law", Span::call_site()), tokens);
    let errors: Vec<String> =
        cx.check().err().map(|e| e.into_iter().map(|e| e.to_string()).collect()).unwrap_or_default();
    if terms > MAX_TERMS || depth > MAX_NESTING {
        prop_assert!(parsed.is_none() && errors.len() == 1, "{terms} terms, depth {depth}: {errors:?}");
        return Ok(());
    }
    let Some(parsed) = parsed else {
        return Err(TestCaseError::fail(format!("{errors:?}: {source}")));
    };
    prop_assert!(errors.is_empty());
    let mut g = Graph::new();
    let built: SpringLaw = Law::build(&parsed, &mut g);
    for &(l, l0, k) in points {
        let (graph, written) = (graph_value(&g, built.energy, l, l0, k), direct(e, l, l0, k));
        if !graph.irregular && !written.irregular {
            prop_assert!(
                same(graph.v, written.v),
                "law {source} at l = {l}, l0 = {l0}, k = {k}: graph {:e}, direct {:e}",
                graph.v,
                written.v
            );
        }
    }
    if !moderate(e) || terms > 200 {
        return Ok(());
    }
    // Derivatives in l (tension, axial stiffness) against finite differences of the written law.
    let tension = diff(&mut g, built.energy, built.l);
    let axial = diff(&mut g, tension, built.l);
    // Only at the moderate points: at the extreme ones differences drown in rounding.
    for &(l, l0, k) in &points[..points.len().min(3)] {
        let at = |id: Id, l: f64| graph_value(&g, id, l, l0, k);
        let t = at(tension, l).v;
        let written = |x: f64| {
            let v = direct(e, x, l0, k);
            (v.v, v.peak)
        };
        check_derivative(&format!("tension of {source}"), t, &written, l)?;
        let a = at(axial, l).v;
        check_derivative(
            &format!("axial stiffness of {source}"),
            a,
            &|x| (at(tension, x).v, at(tension, x).peak),
            l,
        )?;
    }
    if terms > 40 {
        return Ok(());
    }
    // The spring's gradient in the angles (the whole derivation) against finite differences of
    // its energy.
    let kernel = Kernel::new(&|g: &mut Graph| Law::build(&parsed, g));
    let value = |theta1: f64, theta2: f64, id: Id| {
        let v = graph_value_with(&kernel.graph, id, &|n| match n {
            "theta1" => theta1,
            "theta2" => theta2,
            "a" => 1.0,
            "r1" => 0.8,
            "r2" => 0.7,
            "k" => 2.0,
            _ => 1.6,
        });
        (v.v, v.peak)
    };
    for (t1, t2) in [(0.3, -0.2), (1.1, 0.9)] {
        let g1 = value(t1, t2, kernel.terms.gradient[0]).0;
        check_derivative("dE/dtheta1", g1, &|x| value(x, t2, kernel.terms.energy), t1)?;
        let g2 = value(t1, t2, kernel.terms.gradient[1]).0;
        check_derivative("dE/dtheta2", g2, &|x| value(t1, x, kernel.terms.energy), t2)?;
    }
    Ok(())
}

#[test]
fn fuzz_laws_parse_evaluate_and_differentiate_as_written() {
    let points = prop::collection::vec((0.05f64..4.0, 0.05f64..3.0, 0.1f64..10.0), 3);
    let extreme = prop::sample::select(vec![0.0, 1e-310, 1e300, 700.0, 710.0, -1.0]);
    let mut runner = runner(cases(), 0x5eed_1a35);
    let result = runner.run(&(law_expr(), points, extreme), |(e, mut points, x)| {
        points.push((x, 1.5, 2.0));
        points.push((1.3, x, 2.0));
        check_law(&e, &points)
    });
    if let Err(failure) = result {
        panic!("{failure}");
    }
}

/// An attribute item: key sets valid and invalid.
fn attribute_item() -> impl Strategy<Value = String> {
    let value = prop::sample::select(vec![
        "0.8", "-0.8", "0", "1e400", "1.0e4", "2", "kf", "r#kf", "nope", "type", "1.0 2.0", "(0.5)", "",
        "- x", "0.58", "1.7", "f64::MAX", "\"0.8\"",
    ]);
    let index = prop::sample::select(vec!["0", "1", "3", "7", "99", "18446744073709551616", "-1", "x", ""]);
    let count = prop::sample::select(vec![
        "0",
        "1",
        "2",
        "3",
        "5",
        "8",
        "100001",
        "100000001",
        "18446744073709551615",
        "2.5",
        "x",
    ]);
    let key = prop::sample::select(vec![
        "a",
        "r",
        "k",
        "mass",
        "theta_bar",
        "rest_length",
        "thetabar",
        "stiffness",
        "r#k",
    ]);
    let small_law = leaf().prop_recursive(3, 12, 2, |inner| node(inner.boxed())).prop_map(|e| render(&e));
    prop_oneof![
        4 => (key, value.clone()).prop_map(|(k, v)| format!("{k} = {v}")),
        2 => count.clone().prop_map(|n| format!("n = {n}")),
        1 => count.prop_map(|n| format!("unroll = {n}")),
        2 => (index.clone(), value.clone(), value.clone(), 0u8..4).prop_map(|(i, k, l0, which)| match which {
            0 => format!("spring({i}, k = {k})"),
            1 => format!("spring({i}, l0 = {l0})"),
            2 => format!("spring({i}, k = {k}, l0 = {l0})"),
            _ => format!("spring({i})"),
        }),
        1 => (index, value).prop_map(|(i, r)| format!("rotor({i}, r = {r})")),
        2 => small_law.prop_map(|l| format!("law = {l}")),
        1 => prop::sample::select(vec![
            "law = struct Foo;", "spring", "rotor", "n", "= 5", "n == 3", "#", "[1]", "'a", "::x = 1", "law =",
            "spring(3 k = 1.0)", "spring()", "k: 1.0", "r#n = 4", "law = l.powi(2.5)",
        ])
        .prop_map(String::from),
    ]
}

fn item() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![
        "struct C;",
        "pub struct C { pub kf: f64 }",
        "struct r#C { r#kf: f64, m: u32 }",
        "struct G<T> { t: T, kf: f64 }",
        "enum E { A }",
        "union U { a: f64 }",
        "fn f() {}",
    ])
}

#[test]
fn fuzz_attributes_never_panic_and_expand_to_well_formed_items() {
    let base = prop::sample::select(vec![
        "n = 4, r = 0.8, theta_bar = 0.58, k = 1.0e4",
        "n = 100001, r = 0.8, theta_bar = 0.58, k = kf",
        "n = 6, r = 0.8, rest_length = 1.7, k = 1.0e4, unroll = 0",
        "",
    ]);
    let items = prop::collection::vec(attribute_item(), 0..6);
    let mut runner = runner((cases() / 10).max(1), 0x5eed_a77c);
    let result = runner.run(&(base, items, item(), any::<bool>()), |(base, items, item, trailing)| {
        let mut attr: Vec<String> = if base.is_empty() { vec![] } else { vec![base.to_owned()] };
        attr.extend(items);
        let mut text = attr.join(", ");
        if trailing {
            text.push(',');
        }
        let Ok(attr) = text.parse::<TokenStream>() else { return Ok(()) };
        let item_tokens: TokenStream = item.parse().expect("item parses");
        let out = expand::expand(attr, item_tokens);
        let file = syn::parse2::<syn::File>(out.clone());
        prop_assert!(file.is_ok(), "#[rotor_chain({text})] {item} expands to {out}");
        let text_out = out.to_string();
        // A struct, enum or union always gets its impls (generated or stubs): no cascade.
        if !item.starts_with("fn") {
            prop_assert!(text_out.contains("Potential <"), "{text} / {item}: {text_out}");
        }
        Ok(())
    });
    if let Err(failure) = result {
        panic!("{failure}");
    }
}

#[test]
fn the_renderer_keeps_the_tree() {
    // The harness's own check: the rendering parses back (through the law parser) to the same
    // values as the tree, including where minimal parentheses matter.
    let cases = [
        Expr::Bin('-', Expr::L.into(), Expr::Bin('-', Expr::L0.into(), Expr::K.into()).into()),
        Expr::Bin('/', Expr::Bin('/', Expr::L.into(), Expr::L0.into()).into(), Expr::K.into()),
        Expr::Powi(Expr::Neg(Expr::L.into()).into(), 3),
        Expr::Neg(Expr::Neg(Expr::Fun("sqrt", Expr::L.into()).into()).into()),
    ];
    let expected = ["l - (l0 - k)", "l / l0 / k", "(- l).powi(3)", "- - l.sqrt()"];
    for (e, text) in cases.iter().zip(expected) {
        assert_eq!(render(e), text);
        check_law(e, &[(1.7, 0.6, 2.3)]).unwrap();
    }
}
