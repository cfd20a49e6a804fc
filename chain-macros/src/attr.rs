//! Phase 1: parse the attribute into a typed [`Spec`] that keeps the span of every key and value.

use proc_macro2::{Span, TokenStream};
use syn::parse::{ParseStream, Parser};
use syn::punctuated::Punctuated;
use syn::spanned::Spanned;
use syn::{Expr, Ident, Lit, Meta, Token, UnOp};

use crate::ctxt::Ctxt;

/// Every key the attribute accepts, for "did you mean" suggestions.
pub const KEYS: [&str; 11] = [
    "n",
    "a",
    "r",
    "theta_bar",
    "rest_length",
    "k",
    "mass",
    "unroll",
    "law",
    "spring",
    "rotor",
];

/// A parameter value: a float literal folded into the generated code, or a struct field read
/// at run time.
#[derive(Clone, Debug)]
pub enum Value {
    Literal { value: f64 },
    Field(Ident),
}

impl Value {
    pub fn literal(&self) -> Option<f64> {
        match self {
            Value::Literal { value, .. } => Some(*value),
            Value::Field(_) => None,
        }
    }
}

/// A value together with the key that introduced it.
#[derive(Clone)]
pub struct Keyed<T> {
    pub key: Ident,
    pub value: T,
    /// Span of the value.
    pub span: Span,
}

/// `spring(p, k = .., l0 = ..)`.
#[derive(Clone)]
pub struct SpringOverride {
    pub index: Keyed<usize>,
    pub k: Option<Keyed<Value>>,
    pub l0: Option<Keyed<Value>>,
}

/// `rotor(i, r = ..)`.
#[derive(Clone)]
pub struct RotorOverride {
    pub index: Keyed<usize>,
    pub r: Option<Keyed<Value>>,
}

/// The parsed attribute.
#[derive(Clone)]
pub struct Spec {
    pub n: Option<Keyed<usize>>,
    pub a: Option<Keyed<Value>>,
    pub r: Option<Keyed<Value>>,
    pub theta_bar: Option<Keyed<Value>>,
    pub rest_length: Option<Keyed<Value>>,
    pub k: Option<Keyed<Value>>,
    pub mass: Option<Keyed<Value>>,
    pub unroll: Option<Keyed<usize>>,
    pub law: Option<Keyed<Expr>>,
    pub springs: Vec<SpringOverride>,
    pub rotors: Vec<RotorOverride>,
    /// Span of the whole attribute, for errors about missing keys.
    pub span: Span,
}

/// The closest known key to `unknown`, if any is close enough to be a likely typo.
pub fn suggest<'a>(unknown: &str, known: &[&'a str]) -> Option<&'a str> {
    known
        .iter()
        .map(|k| (strsim::jaro_winkler(unknown, k), *k))
        .filter(|(score, _)| *score > 0.75)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, k)| k)
}

fn unknown_key(cx: &Ctxt, ident: &Ident, known: &[&str], context: &str) {
    let name = ident.to_string();
    let list = known
        .iter()
        .map(|k| format!("`{k}`"))
        .collect::<Vec<_>>()
        .join(", ");
    match suggest(&name, known) {
        Some(s) => cx.error_spanned_by(
            ident,
            format!("unknown key `{name}`{context}; did you mean `{s}`?"),
        ),
        None => cx.error_spanned_by(
            ident,
            format!("unknown key `{name}`{context}; expected one of {list}"),
        ),
    }
}

/// Sets `slot` unless it is already set, in which case reports a duplicate.
fn set_once<T>(cx: &Ctxt, slot: &mut Option<Keyed<T>>, keyed: Keyed<T>) {
    if slot.is_some() {
        cx.error_spanned_by(&keyed.key, format!("duplicate key `{}`", keyed.key));
    } else {
        *slot = Some(keyed);
    }
}

/// A float literal (integers accepted), a negated one, or an identifier naming a field.
fn parse_value(cx: &Ctxt, expr: &Expr) -> Option<Value> {
    let literal = |lit: &Lit, negate: bool| -> Option<f64> {
        let v = match lit {
            Lit::Float(f) => f.base10_parse::<f64>().ok()?,
            Lit::Int(i) => i.base10_parse::<f64>().ok()?,
            _ => return None,
        };
        Some(if negate { -v } else { v })
    };
    let parsed = match expr {
        Expr::Lit(l) => literal(&l.lit, false).map(|value| Value::Literal { value }),
        Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => match &*u.expr {
            Expr::Lit(l) => literal(&l.lit, true).map(|value| Value::Literal { value }),
            _ => None,
        },
        Expr::Path(p) if p.qself.is_none() => p.path.get_ident().cloned().map(Value::Field),
        _ => None,
    };
    if parsed.is_none() {
        cx.error_spanned_by(
            expr,
            "expected a float literal (e.g. `0.8`) or the name of an `f64` field of the struct",
        );
    }
    parsed
}

fn parse_usize(cx: &Ctxt, expr: &Expr, what: &str) -> Option<usize> {
    if let Expr::Lit(l) = expr
        && let Lit::Int(i) = &l.lit
        && let Ok(v) = i.base10_parse::<usize>()
    {
        return Some(v);
    }
    cx.error_spanned_by(
        expr,
        format!("{what} must be a non-negative integer literal"),
    );
    None
}

/// `p, key = value, ...` inside `spring(...)` or `rotor(...)`.
fn parse_override_args(input: ParseStream) -> syn::Result<(Expr, Vec<(Ident, Expr)>)> {
    let index: Expr = input.parse()?;
    let mut pairs = Vec::new();
    while !input.is_empty() {
        input.parse::<Token![,]>()?;
        if input.is_empty() {
            break;
        }
        let key: Ident = input.parse()?;
        input.parse::<Token![=]>()?;
        let value: Expr = input.parse()?;
        pairs.push((key, value));
    }
    Ok((index, pairs))
}

/// Parses the attribute tokens. Errors go to `cx`; whatever parsed is returned.
pub fn parse(cx: &Ctxt, attr: TokenStream) -> Spec {
    let span = if attr.is_empty() {
        Span::call_site()
    } else {
        attr.span()
    };
    let mut spec = Spec {
        n: None,
        a: None,
        r: None,
        theta_bar: None,
        rest_length: None,
        k: None,
        mass: None,
        unroll: None,
        law: None,
        springs: Vec::new(),
        rotors: Vec::new(),
        span,
    };
    let items = match Punctuated::<Meta, Token![,]>::parse_terminated.parse2(attr) {
        Ok(items) => items,
        Err(err) => {
            cx.syn_error(err);
            return spec;
        }
    };
    for item in items {
        let Some(key) = item.path().get_ident().cloned() else {
            cx.error_spanned_by(
                item.path(),
                "expected a key such as `n`, `r` or `spring(..)`",
            );
            continue;
        };
        let name = key.to_string();
        match item {
            Meta::NameValue(nv) => {
                let span = nv.value.span();
                match name.as_str() {
                    "n" | "unroll" => {
                        if let Some(v) = parse_usize(cx, &nv.value, &format!("`{name}`")) {
                            let slot = if name == "n" {
                                &mut spec.n
                            } else {
                                &mut spec.unroll
                            };
                            set_once(
                                cx,
                                slot,
                                Keyed {
                                    key,
                                    value: v,
                                    span,
                                },
                            );
                        }
                    }
                    "law" => set_once(
                        cx,
                        &mut spec.law,
                        Keyed {
                            key,
                            value: nv.value,
                            span,
                        },
                    ),
                    "a" | "r" | "theta_bar" | "rest_length" | "k" | "mass" => {
                        if let Some(v) = parse_value(cx, &nv.value) {
                            let slot = match name.as_str() {
                                "a" => &mut spec.a,
                                "r" => &mut spec.r,
                                "theta_bar" => &mut spec.theta_bar,
                                "rest_length" => &mut spec.rest_length,
                                "k" => &mut spec.k,
                                _ => &mut spec.mass,
                            };
                            set_once(
                                cx,
                                slot,
                                Keyed {
                                    key,
                                    value: v,
                                    span,
                                },
                            );
                        }
                    }
                    "spring" | "rotor" => cx.error_spanned_by(
                        &key,
                        format!(
                            "`{name}` takes arguments: `{name}(index, {} = ..)`",
                            if name == "spring" { "k" } else { "r" }
                        ),
                    ),
                    _ => unknown_key(cx, &key, &KEYS, ""),
                }
            }
            Meta::List(list) => {
                match name.as_str() {
                    "spring" | "rotor" => {
                        let (index_expr, pairs) =
                            match parse_override_args.parse2(list.tokens.clone()) {
                                Ok(parsed) => parsed,
                                Err(err) => {
                                    cx.syn_error(err);
                                    continue;
                                }
                            };
                        let Some(index) =
                            parse_usize(cx, &index_expr, &format!("the {name} index"))
                        else {
                            continue;
                        };
                        let index = Keyed {
                            key: key.clone(),
                            value: index,
                            span: index_expr.span(),
                        };
                        let allowed: &[&str] = if name == "spring" {
                            &["k", "l0"]
                        } else {
                            &["r"]
                        };
                        let mut k = None;
                        let mut l0 = None;
                        let mut r = None;
                        for (pkey, pvalue) in pairs {
                            let pname = pkey.to_string();
                            if !allowed.contains(&pname.as_str()) {
                                unknown_key(cx, &pkey, allowed, &format!(" in `{name}(..)`"));
                                continue;
                            }
                            let span = pvalue.span();
                            let Some(v) = parse_value(cx, &pvalue) else {
                                continue;
                            };
                            let slot = match pname.as_str() {
                                "k" => &mut k,
                                "l0" => &mut l0,
                                _ => &mut r,
                            };
                            set_once(
                                cx,
                                slot,
                                Keyed {
                                    key: pkey,
                                    value: v,
                                    span,
                                },
                            );
                        }
                        if name == "spring" {
                            if k.is_none() && l0.is_none() {
                                cx.error_spanned_by(&key, "`spring(..)` overrides nothing: give `k = ..` and/or `l0 = ..`");
                            }
                            spec.springs.push(SpringOverride { index, k, l0 });
                        } else {
                            if r.is_none() {
                                cx.error_spanned_by(
                                    &key,
                                    "`rotor(..)` overrides nothing: give `r = ..`",
                                );
                            }
                            spec.rotors.push(RotorOverride { index, r });
                        }
                    }
                    _ if KEYS.contains(&name.as_str()) => {
                        cx.error_spanned_by(&key, format!("`{name}` takes a value: `{name} = ..`"))
                    }
                    _ => unknown_key(cx, &key, &KEYS, ""),
                }
            }
            Meta::Path(_) => {
                if KEYS.contains(&name.as_str()) {
                    cx.error_spanned_by(&key, format!("`{name}` needs a value: `{name} = ..`"));
                } else {
                    unknown_key(cx, &key, &KEYS, "");
                }
            }
        }
    }
    spec
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    fn parse_ok(tokens: TokenStream) -> Spec {
        let cx = Ctxt::new();
        let spec = parse(&cx, tokens);
        cx.check().expect("no errors");
        spec
    }

    fn parse_err(tokens: TokenStream) -> String {
        let cx = Ctxt::new();
        let _ = parse(&cx, tokens);
        let err = cx.check().expect_err("an error");
        err.into_iter()
            .map(|e| e.to_string())
            .collect::<Vec<_>>()
            .join("\n")
    }

    #[test]
    fn parses_the_issue_example() {
        let spec = parse_ok(quote!(
            n = 60,
            a = 1.0,
            r = 0.8,
            theta_bar = 0.58,
            k = 1.0e4,
            mass = 1.0,
            spring(29, k = k_imp),
            spring(7, l0 = 2.30)
        ));
        assert_eq!(spec.n.unwrap().value, 60);
        assert_eq!(spec.k.unwrap().value.literal(), Some(1.0e4));
        assert_eq!(spec.springs.len(), 2);
        assert!(
            matches!(&spec.springs[0].k.as_ref().unwrap().value, Value::Field(f) if f == "k_imp")
        );
        assert_eq!(
            spec.springs[1].l0.as_ref().unwrap().value.literal(),
            Some(2.30)
        );
    }

    #[test]
    fn reports_every_error_with_suggestions() {
        let msg = parse_err(quote!(
            n = 60,
            thetabar = 0.5,
            k = 1.0,
            k = 2.0,
            spring(3, stiffness = 2.0)
        ));
        assert!(msg.contains("did you mean `theta_bar`"), "{msg}");
        assert!(msg.contains("duplicate key `k`"), "{msg}");
        assert!(msg.contains("in `spring(..)`"), "{msg}");
    }

    #[test]
    fn negative_literals_parse_for_validation_to_reject() {
        let spec = parse_ok(quote!(r = -0.8));
        assert_eq!(spec.r.unwrap().value.literal(), Some(-0.8));
    }
}
