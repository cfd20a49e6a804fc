//! A custom spring law, `law = <expression in l, l0, k>`, parsed from the attribute's tokens and
//! turned into the symbolic graph.
//!
//! The law goes through the same engine as the chain, so its tension, axial stiffness and every
//! derivative in the angles come out of symbolic differentiation: nothing is derived by hand.
//! Accepted: float and integer literals, `l`, `l0`, `k`, `+ - * /`, unary `-`, parentheses, and
//! the methods `.powi(int)`, `.sqrt()`, `.sin()`, `.cos()`, `.exp()`, `.ln()`.
//!
//! **Iterative.** The tokens are read without recursion: groups are flattened with an explicit
//! stack and the expression is parsed by operator precedence with explicit operator and operand
//! stacks, straight into postfix form ([`Law`]); building it into the graph is a loop over that
//! form. A law of any length or depth therefore costs no stack in the macro, and none in rustc:
//! the generated code is straight-line assignments. The limits [`MAX_TERMS`] and [`MAX_NESTING`]
//! bound the size of the generated code, each with an error at the law.
//!
//! One error per real problem: unknown symbols and methods are reported and parsing goes on; a
//! syntax error (an operand or an operator missing, an unsupported construct) stops it there.

use chain_symbolic::{Graph, Id, SpringLaw};
use proc_macro2::{Delimiter, Ident, Literal, Spacing, Span, TokenStream, TokenTree};
use syn::ext::IdentExt;

use crate::attr::numeric_literal;
use crate::ctxt::Ctxt;

/// The most terms a law may have: literals, symbols and operations (a method call and a unary
/// minus count one each). A law is differentiated three times and instantiated once per spring,
/// so its size multiplies the generated code; see `docs/macro.md` for the measurement.
pub const MAX_TERMS: usize = 1000;

/// The deepest nesting of parentheses in a law.
pub const MAX_NESTING: usize = 64;

const METHODS: [&str; 6] = ["powi", "sqrt", "sin", "cos", "exp", "ln"];
const SUPPORTED: &str = "use literals, `l`, `l0`, `k`, `+ - * /` and `.powi(n)`, `.sqrt()`, `.sin()`, `.cos()`, `.exp()`, `.ln()`";
const OPERATORS_ONLY: &str = "a spring law supports the operators `+ - * /` only";

/// One step of a law in postfix form.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Op {
    Const(f64),
    L,
    L0,
    K,
    Neg,
    Add,
    Sub,
    Mul,
    Div,
    Powi(i32),
    Sqrt,
    Sin,
    Cos,
    Exp,
    Ln,
}

/// A parsed law, in postfix form (operands before their operation).
#[derive(Clone, Debug, PartialEq)]
pub struct Law {
    ops: Vec<Op>,
}

impl Law {
    /// The law as a [`SpringLaw`] in `g` (a loop over the postfix form).
    pub fn build(&self, g: &mut Graph) -> SpringLaw {
        let (l, l0, k) = SpringLaw::symbols(g);
        let mut stack: Vec<Id> = Vec::new();
        for &op in &self.ops {
            let value = match op {
                Op::Const(c) => g.constant(c),
                Op::L => l,
                Op::L0 => l0,
                Op::K => k,
                Op::Add | Op::Sub | Op::Mul | Op::Div => {
                    // The parser only emits complete expressions: two operands are there.
                    let (b, a) = (stack.pop().unwrap_or(l), stack.pop().unwrap_or(l));
                    match op {
                        Op::Add => g.add(a, b),
                        Op::Sub => g.sub(a, b),
                        Op::Mul => g.mul(a, b),
                        _ => g.div(a, b),
                    }
                }
                unary => {
                    let x = stack.pop().unwrap_or(l);
                    match unary {
                        Op::Neg => g.neg(x),
                        Op::Powi(n) => g.powi(x, n),
                        Op::Sqrt => g.sqrt(x),
                        Op::Sin => g.sin(x),
                        Op::Cos => g.cos(x),
                        Op::Exp => g.exp(x),
                        _ => g.ln(x),
                    }
                }
            };
            stack.push(value);
        }
        let energy = stack.pop().unwrap_or_else(|| g.zero());
        SpringLaw::custom(g, energy)
    }
}

/// A token of the flattened law: groups become an opening and a closing marker.
#[derive(Clone)]
enum Tok {
    Open(Delimiter, Span),
    Close(Span),
    Ident(Ident),
    Punct(char, Spacing, Span),
    Lit(Literal),
}

impl Tok {
    fn span(&self) -> Span {
        match self {
            Tok::Open(_, s) | Tok::Close(s) | Tok::Punct(_, _, s) => *s,
            Tok::Ident(i) => i.span(),
            Tok::Lit(l) => l.span(),
        }
    }

    fn is_punct(&self, ch: char) -> bool {
        matches!(self, Tok::Punct(c, _, _) if *c == ch)
    }
}

/// The tokens of `tokens` with groups flattened, without recursion. `None` (after an error) if
/// the law is deeper than [`MAX_NESTING`] or has more than a few tokens per allowed term.
fn flatten(cx: &Ctxt, tokens: TokenStream) -> Option<Vec<Tok>> {
    // A term takes at most six tokens (`.powi(-2)`) besides redundant parentheses.
    let limit = 8 * MAX_TERMS;
    let mut flat = Vec::new();
    let mut stack = vec![(tokens.into_iter(), None::<Span>)];
    while let Some((iter, close)) = stack.last_mut() {
        let close = *close;
        let Some(tt) = iter.next() else {
            stack.pop();
            if let Some(span) = close {
                flat.push(Tok::Close(span));
            }
            continue;
        };
        if flat.len() >= limit {
            cx.error_at(
                tt.span(),
                format!("`law` is too long: at most {MAX_TERMS} terms ({limit} tokens) are allowed"),
            );
            return None;
        }
        match tt {
            TokenTree::Group(group) => {
                if stack.len() > MAX_NESTING {
                    cx.error_at(
                        group.span_open(),
                        format!("`law` nests parentheses more than {MAX_NESTING} deep"),
                    );
                    return None;
                }
                flat.push(Tok::Open(group.delimiter(), group.span_open()));
                stack.push((group.stream().into_iter(), Some(group.span_close())));
            }
            TokenTree::Ident(i) => flat.push(Tok::Ident(i)),
            TokenTree::Punct(p) => flat.push(Tok::Punct(p.as_char(), p.spacing(), p.span())),
            TokenTree::Literal(l) => flat.push(Tok::Lit(l)),
        }
    }
    Some(flat)
}

/// Operators waiting on the stack.
#[derive(Clone, Copy)]
enum Pending {
    Binary(Op, u8),
    Neg,
    Group,
}

fn precedence(op: Op) -> u8 {
    match op {
        Op::Add | Op::Sub => 1,
        _ => 2,
    }
}

fn is_keyword(ident: &Ident) -> bool {
    syn::parse2::<Ident>(TokenTree::Ident(ident.clone()).into()).is_err()
}

/// Placeholder tokens carrying the spans of `toks`, for an error that underlines all of them.
fn span_of(toks: &[Tok]) -> TokenStream {
    toks.iter()
        .map(|t| -> TokenTree {
            let mut punct = proc_macro2::Punct::new('.', Spacing::Alone);
            punct.set_span(t.span());
            punct.into()
        })
        .collect()
}

/// Parses a law from the tokens after `law =`. Every problem is reported to `cx`; the law is
/// returned only if there was none. `key` is the `law` key, for an empty law.
pub fn parse(cx: &Ctxt, key: &Ident, tokens: TokenStream) -> Option<Law> {
    let toks = flatten(cx, tokens)?;
    if toks.is_empty() {
        cx.error_spanned_by(key, "`law` needs an expression in `l`, `l0` and `k`");
        return None;
    }
    let mut ops: Vec<Op> = Vec::new();
    let mut pending: Vec<Pending> = Vec::new();
    let mut failed = false;
    let mut expect_operand = true;
    // The last operator read, for "an operand must follow" errors.
    let mut last_operator = toks[0].span();
    let mut i = 0;
    let stop = |span: Span, message: &str| {
        cx.error_at(span, message);
        None
    };
    // Pops pending operators down to (not including) the first one that binds looser than `min`.
    let unwind = |pending: &mut Vec<Pending>, ops: &mut Vec<Op>, min: u8| {
        while let Some(&top) = pending.last() {
            match top {
                Pending::Neg => ops.push(Op::Neg),
                Pending::Binary(op, p) if p >= min => ops.push(op),
                _ => break,
            }
            pending.pop();
        }
    };
    while i < toks.len() {
        let tok = &toks[i];
        if expect_operand {
            match tok {
                Tok::Punct('-', _, span) => {
                    pending.push(Pending::Neg);
                    last_operator = *span;
                    i += 1;
                    continue;
                }
                Tok::Lit(lit) => {
                    match numeric_literal(lit).unwrap_or(Err("a spring law uses numeric literals only")) {
                        Ok(v) => ops.push(Op::Const(v)),
                        Err(message) => {
                            cx.error_at(lit.span(), message);
                            failed = true;
                            ops.push(Op::Const(0.0));
                        }
                    }
                }
                Tok::Ident(ident) if ident == "true" || ident == "false" => {
                    cx.error_at(ident.span(), "a spring law uses numeric literals only");
                    failed = true;
                    ops.push(Op::Const(0.0));
                }
                Tok::Ident(ident) if is_keyword(ident) => return stop(ident.span(), &unsupported()),
                Tok::Ident(ident) => {
                    // A path `a::b::c` is one (unknown) symbol.
                    let mut end = i + 1;
                    while toks.get(end).is_some_and(|t| t.is_punct(':'))
                        && toks.get(end + 1).is_some_and(|t| t.is_punct(':'))
                        && matches!(toks.get(end + 2), Some(Tok::Ident(_)))
                    {
                        end += 3;
                    }
                    if let Some(Tok::Open(Delimiter::Parenthesis, _)) = toks.get(end) {
                        let name = ident.unraw().to_string();
                        let message = if end == i + 1 && METHODS.contains(&name.as_str()) {
                            format!(
                                "function-call syntax is not supported in `law`: write `x.{name}()` for `{name}(x)`"
                            )
                        } else {
                            format!("unsupported function call `{name}(..)` in `law`: {}", SUPPORTED)
                        };
                        return stop(ident.span(), &message);
                    }
                    let name = ident.unraw().to_string();
                    let op = match name.as_str() {
                        "l" if end == i + 1 => Some(Op::L),
                        "l0" if end == i + 1 => Some(Op::L0),
                        "k" if end == i + 1 => Some(Op::K),
                        _ => None,
                    };
                    match op {
                        Some(op) => ops.push(op),
                        None => {
                            let path: String = toks[i..end]
                                .iter()
                                .map(|t| match t {
                                    Tok::Ident(id) => id.unraw().to_string(),
                                    _ => ":".to_owned(),
                                })
                                .collect();
                            cx.error_spanned_by(
                                span_of(&toks[i..end]),
                                format!(
                                    "unknown symbol `{path}` in `law`: a spring law is a function of `l` (length), \
                                     `l0` (rest length) and `k` (stiffness)"
                                ),
                            );
                            failed = true;
                            ops.push(Op::Const(0.0));
                        }
                    }
                    i = end;
                    expect_operand = false;
                    continue;
                }
                Tok::Open(Delimiter::Parenthesis | Delimiter::None, _) => {
                    pending.push(Pending::Group);
                    i += 1;
                    continue;
                }
                Tok::Close(..) => return stop(tok.span(), &missing_operand(&toks, i)),
                _ => return stop(tok.span(), &unsupported()),
            }
            i += 1;
            expect_operand = false;
            continue;
        }
        // After an operand: a binary operator, a method call, or the end of a group.
        match tok {
            Tok::Punct(ch @ ('+' | '-' | '*' | '/'), spacing, span) => {
                let compound = *spacing == Spacing::Joint && toks.get(i + 1).is_some_and(|t| t.is_punct('='));
                let arrow = *ch == '-'
                    && *spacing == Spacing::Joint
                    && toks.get(i + 1).is_some_and(|t| t.is_punct('>'));
                if compound || arrow {
                    return stop(*span, OPERATORS_ONLY);
                }
                let op = match ch {
                    '+' => Op::Add,
                    '-' => Op::Sub,
                    '*' => Op::Mul,
                    _ => Op::Div,
                };
                unwind(&mut pending, &mut ops, precedence(op));
                pending.push(Pending::Binary(op, precedence(op)));
                last_operator = *span;
                expect_operand = true;
                i += 1;
            }
            Tok::Punct('%' | '^' | '<' | '>' | '=' | '!' | '&' | '|', _, span) => {
                // Another binary operator: reported, then read as one so that the rest of the
                // law is still checked.
                cx.error_at(*span, OPERATORS_ONLY);
                failed = true;
                i += 1;
                while let Some(Tok::Punct('=' | '<' | '>' | '&' | '|', _, _)) = toks.get(i) {
                    i += 1;
                }
                unwind(&mut pending, &mut ops, 1);
                pending.push(Pending::Binary(Op::Add, 1));
                last_operator = *span;
                expect_operand = true;
            }
            Tok::Punct('.', Spacing::Alone, _) => {
                let Some(Tok::Ident(method)) = toks.get(i + 1) else {
                    return stop(tok.span(), &unsupported());
                };
                let Some(Tok::Open(Delimiter::Parenthesis, open)) = toks.get(i + 2) else {
                    return stop(method.span(), &unsupported());
                };
                // The arguments run to the matching close.
                let (mut depth, mut end) = (0usize, i + 2);
                loop {
                    match toks.get(end) {
                        Some(Tok::Open(..)) => depth += 1,
                        Some(Tok::Close(..)) => {
                            depth -= 1;
                            if depth == 0 {
                                break;
                            }
                        }
                        Some(_) => {}
                        None => return stop(*open, &unsupported()),
                    }
                    end += 1;
                }
                let args = &toks[i + 3..end];
                let name = method.unraw().to_string();
                i = end + 1;
                if !METHODS.contains(&name.as_str()) {
                    cx.error_at(
                        method.span(),
                        format!(
                            "unsupported method `{name}` in `law`; supported: {}",
                            METHODS.map(|m| format!("`.{m}()`")).join(", ")
                        ),
                    );
                    failed = true;
                    continue;
                }
                let op = match name.as_str() {
                    "powi" => match powi_exponent(args) {
                        Some(n) => Op::Powi(n),
                        None => {
                            let at = if args.is_empty() { method.span() } else { args[0].span() };
                            cx.error_at(at, "`.powi()` takes an integer literal that fits an `i32`");
                            failed = true;
                            continue;
                        }
                    },
                    other => {
                        if !args.is_empty() {
                            cx.error_at(args[0].span(), format!("`.{other}()` takes no argument"));
                            failed = true;
                            continue;
                        }
                        match other {
                            "sqrt" => Op::Sqrt,
                            "sin" => Op::Sin,
                            "cos" => Op::Cos,
                            "exp" => Op::Exp,
                            _ => Op::Ln,
                        }
                    }
                };
                // A method binds tighter than any operator: it applies to the operand just read.
                ops.push(op);
            }
            Tok::Close(span) => {
                unwind(&mut pending, &mut ops, 0);
                if !matches!(pending.pop(), Some(Pending::Group)) {
                    return stop(*span, &unsupported());
                }
                i += 1;
            }
            _ => return stop(tok.span(), &unsupported()),
        }
    }
    if expect_operand {
        return stop(last_operator, &missing_operand(&toks, toks.len()));
    }
    unwind(&mut pending, &mut ops, 0);
    if ops.len() > MAX_TERMS {
        cx.error_at(
            toks[0].span(),
            format!("`law` is too long: it has {} terms, at most {MAX_TERMS} are allowed", ops.len()),
        );
        return None;
    }
    (!failed).then_some(Law { ops })
}

fn unsupported() -> String {
    format!("unsupported expression in `law`: {SUPPORTED}")
}

/// The message for an operand missing before token `at`.
fn missing_operand(toks: &[Tok], at: usize) -> String {
    if at == 0 || matches!(toks.get(at.wrapping_sub(1)), Some(Tok::Open(..))) {
        "empty parentheses in `law`: an expression must go inside".to_owned()
    } else {
        "`law` is incomplete: an operand (a literal, `l`, `l0`, `k` or a parenthesised expression) must follow this operator".to_owned()
    }
}

/// The exponent of `.powi(..)`: an integer literal, possibly negated, that fits an `i32`.
fn powi_exponent(args: &[Tok]) -> Option<i32> {
    let (negative, lit) = match args {
        [Tok::Lit(lit)] => (false, lit),
        [Tok::Punct('-', _, _), Tok::Lit(lit)] => (true, lit),
        _ => return None,
    };
    let syn::Lit::Int(int) = syn::Lit::new(lit.clone()) else { return None };
    let magnitude = int.base10_parse::<i64>().ok()?;
    i32::try_from(if negative { -magnitude } else { magnitude }).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    fn parse_ok(tokens: TokenStream) -> Law {
        let cx = Ctxt::new();
        let law = parse(&cx, &Ident::new("law", Span::call_site()), tokens);
        cx.check().expect("no errors");
        law.expect("a law")
    }

    fn parse_err(tokens: TokenStream) -> Vec<String> {
        let cx = Ctxt::new();
        let law = parse(&cx, &Ident::new("law", Span::call_site()), tokens);
        assert!(law.is_none());
        cx.check().unwrap_err().into_iter().map(|e| e.to_string()).collect()
    }

    fn eval(law: &Law, l: f64, l0: f64, k: f64) -> f64 {
        let mut g = Graph::new();
        let built = law.build(&mut g);
        g.eval(built.energy, &|name| match name {
            chain_symbolic::spring::LAW_L => l,
            chain_symbolic::spring::LAW_L0 => l0,
            _ => k,
        })
    }

    #[test]
    fn the_papers_quartic_law_builds_and_evaluates() {
        let law = parse_ok(quote!(k / (8.0 * l0 * l0) * (l * l - l0 * l0).powi(2)));
        let expected = 4.0 / (8.0 * 1.5 * 1.5) * (4.0f64 - 2.25).powi(2);
        assert!((eval(&law, 2.0, 1.5, 4.0) - expected).abs() < 1e-14);
    }

    #[test]
    fn precedence_and_associativity_are_rusts() {
        type Direct = fn(f64, f64, f64) -> f64;
        let cases: [(TokenStream, Direct); 7] = [
            (quote!(l - l0 - k), |l, l0, k| l - l0 - k),
            (quote!(l / l0 / k), |l, l0, k| l / l0 / k),
            (quote!(l + l0 * k - l / k), |l, l0, k| l + l0 * k - l / k),
            (quote!(-l.powi(2)), |l, _, _| -l.powi(2)),
            (quote!((-l).powi(3) * -k), |l, _, k| (-l).powi(3) * -k),
            (quote!(l - -l0 * -(k - l)), |l, l0, k| l - -l0 * -(k - l)),
            (quote!((l).sqrt().ln().exp() - l0.sin() * k.cos()), |l, l0, k| {
                l.sqrt().ln().exp() - l0.sin() * k.cos()
            }),
        ];
        for (tokens, direct) in cases {
            let law = parse_ok(tokens.clone());
            let (l, l0, k) = (1.7, 0.6, 2.3);
            assert_eq!(eval(&law, l, l0, k), direct(l, l0, k), "{tokens}");
        }
    }

    #[test]
    fn unknown_symbols_and_methods_are_errors_and_parsing_goes_on() {
        let msgs = parse_err(quote!(k * (l - lbar).powi(2) + l.tanh() + std::f64::consts::PI));
        assert_eq!(msgs.len(), 3, "{msgs:?}");
        assert!(msgs[0].contains("unknown symbol `lbar`"), "{msgs:?}");
        assert!(msgs[1].contains("unsupported method `tanh`"), "{msgs:?}");
        assert!(msgs[2].contains("unknown symbol `std::f64::consts::PI`"), "{msgs:?}");
    }

    #[test]
    fn syntax_errors_are_reported_once() {
        for (tokens, expected) in [
            (
                quote!(
                    struct Foo;
                ),
                "unsupported expression",
            ),
            (quote!(l+), "incomplete"),
            (quote!(()), "empty parentheses"),
            (quote!(sqrt(l)), "write `x.sqrt()`"),
            (quote!(l.powi(2.5)), "integer literal"),
            (quote!(l.powi(3000000000)), "integer literal"),
            (quote!(l.sqrt(2)), "takes no argument"),
            (quote!(l % 2.0), "operators `+ - * /` only"),
            (quote!(l l0), "unsupported expression"),
            (quote!(1e400 * l), "out of range"),
            (quote!("one" * l), "numeric literals only"),
            (quote!([l]), "unsupported expression"),
            (quote!(|x| x), "unsupported expression"),
            (quote!(l += 1.0), "operators `+ - * /` only"),
        ] {
            let msgs = parse_err(tokens.clone());
            assert_eq!(msgs.len(), 1, "{tokens}: {msgs:?}");
            assert!(msgs[0].contains(expected), "{tokens}: {msgs:?}");
        }
    }

    #[test]
    fn powi_takes_every_i32_exponent() {
        let law = parse_ok(quote!(l.powi(-2147483648) + l.powi(2147483647)));
        let v = eval(&law, 1.0, 1.0, 1.0);
        assert_eq!(v, 2.0);
    }

    #[test]
    fn deep_and_long_laws_are_parsed_without_recursion_or_rejected_at_the_limit() {
        let deep: TokenStream =
            format!("{}l{}", "(".repeat(MAX_NESTING), ")".repeat(MAX_NESTING)).parse().unwrap();
        assert_eq!(eval(&parse_ok(deep), 2.0, 0.0, 0.0), 2.0);
        let deeper: TokenStream =
            format!("{}l{}", "(".repeat(MAX_NESTING + 1), ")".repeat(MAX_NESTING + 1)).parse().unwrap();
        assert!(parse_err(deeper)[0].contains("deep"));
        let terms = MAX_TERMS.div_ceil(2);
        let long: TokenStream = vec!["l"; terms].join(" + ").parse().unwrap();
        assert_eq!(eval(&parse_ok(long), 1.0, 0.0, 0.0), terms as f64);
        let chain: TokenStream = format!("l{}", ".sqrt()".repeat(MAX_TERMS - 1)).parse().unwrap();
        assert_eq!(eval(&parse_ok(chain), 1.0, 0.0, 0.0), 1.0);
        let longer: TokenStream = vec!["l"; MAX_TERMS + 1].join(" - ").parse().unwrap();
        assert!(parse_err(longer)[0].contains("too long"));
        let huge: TokenStream = vec!["l"; 50 * MAX_TERMS].join(" * ").parse().unwrap();
        assert!(parse_err(huge)[0].contains("too long"));
    }
}
