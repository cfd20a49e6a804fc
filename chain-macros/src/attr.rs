//! Phase 1: parse the attribute into a typed [`Spec`] that keeps the span of every key and value.

use std::collections::BTreeSet;

use proc_macro2::TokenStream;
use quote::ToTokens;
use syn::parse::{ParseStream, Parser};
use syn::punctuated::Punctuated;
use syn::{Expr, Ident, Lit, Meta, Token, UnOp};

use crate::ctxt::Ctxt;

/// Every key the attribute accepts, for "did you mean" suggestions.
pub const KEYS: [&str; 11] =
    ["n", "a", "r", "theta_bar", "rest_length", "k", "mass", "unroll", "law", "spring", "rotor"];

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
    /// Tokens of the value, for errors that underline all of it (a span cannot be joined on
    /// stable Rust, so the first and last token are kept instead).
    pub tokens: TokenStream,
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
    /// Tokens of the whole attribute, for errors about missing keys (empty for a bare
    /// `#[rotor_chain]`).
    pub tokens: TokenStream,
    /// Every key the user wrote or evidently meant (an unknown key's suggestion, a key whose
    /// value failed to parse): a missing-key error for these would only repeat another error.
    pub seen: BTreeSet<String>,
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

/// Reports an unknown key; returns the suggested key, if any.
fn unknown_key<'a>(cx: &Ctxt, ident: &Ident, known: &[&'a str], context: &str) -> Option<&'a str> {
    let name = ident.to_string();
    let list = known.iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", ");
    let suggestion = suggest(&name, known);
    match suggestion {
        Some(s) => cx.error_spanned_by(ident, format!("unknown key `{name}`{context}; did you mean `{s}`?")),
        None => cx.error_spanned_by(ident, format!("unknown key `{name}`{context}; expected one of {list}")),
    }
    suggestion
}

/// Sets `slot` unless it is already set, in which case reports a duplicate.
fn set_once<T>(cx: &Ctxt, slot: &mut Option<Keyed<T>>, keyed: Keyed<T>, context: &str) {
    if slot.is_some() {
        cx.error_spanned_by(&keyed.key, format!("duplicate key `{}`{context}", keyed.key));
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
    cx.error_spanned_by(expr, format!("{what} must be a non-negative integer literal"));
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
        tokens: attr.clone(),
        seen: BTreeSet::new(),
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
            cx.error_spanned_by(item.path(), "expected a key such as `n`, `r` or `spring(..)`");
            continue;
        };
        let name = key.to_string();
        spec.seen.insert(name.clone());
        match item {
            Meta::NameValue(nv) => parse_name_value(cx, &mut spec, key, nv.value),
            Meta::List(list) if name == "spring" || name == "rotor" => {
                parse_override(cx, &mut spec, key, list.tokens)
            }
            Meta::List(_) | Meta::Path(_) if KEYS.contains(&name.as_str()) => {
                cx.error_spanned_by(&key, format!("`{name}` needs a value: `{name} = ..`"))
            }
            Meta::List(_) | Meta::Path(_) => {
                if let Some(s) = unknown_key(cx, &key, &KEYS, "") {
                    spec.seen.insert(s.to_owned());
                }
            }
        }
    }
    spec
}

/// `key = value`.
fn parse_name_value(cx: &Ctxt, spec: &mut Spec, key: Ident, value: Expr) {
    let name = key.to_string();
    let tokens = value.to_token_stream();
    match name.as_str() {
        "n" | "unroll" => {
            if let Some(v) = parse_usize(cx, &value, &format!("`{name}`")) {
                let slot = if name == "n" { &mut spec.n } else { &mut spec.unroll };
                set_once(cx, slot, Keyed { key, value: v, tokens }, "");
            }
        }
        "law" => set_once(cx, &mut spec.law, Keyed { key, value, tokens }, ""),
        "a" | "r" | "theta_bar" | "rest_length" | "k" | "mass" => {
            if let Some(v) = parse_value(cx, &value) {
                let slot = match name.as_str() {
                    "a" => &mut spec.a,
                    "r" => &mut spec.r,
                    "theta_bar" => &mut spec.theta_bar,
                    "rest_length" => &mut spec.rest_length,
                    "k" => &mut spec.k,
                    _ => &mut spec.mass,
                };
                set_once(cx, slot, Keyed { key, value: v, tokens }, "");
            }
        }
        "spring" | "rotor" => {
            let inner = if name == "spring" { "k" } else { "r" };
            cx.error_spanned_by(&key, format!("`{name}` takes arguments: `{name}(index, {inner} = ..)`"))
        }
        _ => {
            if let Some(s) = unknown_key(cx, &key, &KEYS, "") {
                spec.seen.insert(s.to_owned());
            }
        }
    }
}

/// `spring(p, k = .., l0 = ..)` or `rotor(i, r = ..)`.
fn parse_override(cx: &Ctxt, spec: &mut Spec, key: Ident, tokens: TokenStream) {
    let name = key.to_string();
    let (index_expr, pairs) = match parse_override_args.parse2(tokens) {
        Ok(parsed) => parsed,
        Err(err) => return cx.syn_error(err),
    };
    let Some(index) = parse_usize(cx, &index_expr, &format!("the {name} index")) else { return };
    let index = Keyed { key: key.clone(), value: index, tokens: index_expr.to_token_stream() };
    let allowed: &[&str] = if name == "spring" { &["k", "l0"] } else { &["r"] };
    let context = format!(" in `{name}({}, ..)`", index.value);
    let (mut k, mut l0, mut r) = (None, None, None);
    // Any inner error already explains what is wrong; "overrides nothing" would only repeat it.
    let mut inner_error = false;
    for (pkey, pvalue) in pairs {
        let pname = pkey.to_string();
        if !allowed.contains(&pname.as_str()) {
            unknown_key(cx, &pkey, allowed, &context);
            inner_error = true;
            continue;
        }
        let tokens = pvalue.to_token_stream();
        let Some(v) = parse_value(cx, &pvalue) else {
            inner_error = true;
            continue;
        };
        let slot = match pname.as_str() {
            "k" => &mut k,
            "l0" => &mut l0,
            _ => &mut r,
        };
        set_once(cx, slot, Keyed { key: pkey, value: v, tokens }, &context);
    }
    if name == "spring" {
        if k.is_none() && l0.is_none() && !inner_error {
            cx.error_spanned_by(&key, "`spring(..)` overrides nothing: give `k = ..` and/or `l0 = ..`");
        }
        spec.springs.push(SpringOverride { index, k, l0 });
    } else {
        if r.is_none() && !inner_error {
            cx.error_spanned_by(&key, "`rotor(..)` overrides nothing: give `r = ..`");
        }
        spec.rotors.push(RotorOverride { index, r });
    }
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
        err.into_iter().map(|e| e.to_string()).collect::<Vec<_>>().join("\n")
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
        assert!(matches!(&spec.springs[0].k.as_ref().unwrap().value, Value::Field(f) if f == "k_imp"));
        assert_eq!(spec.springs[1].l0.as_ref().unwrap().value.literal(), Some(2.30));
    }

    #[test]
    fn reports_every_error_with_suggestions() {
        let msg = parse_err(quote!(n = 60, thetabar = 0.5, k = 1.0, k = 2.0, spring(3, stiffness = 2.0)));
        assert!(msg.contains("did you mean `theta_bar`"), "{msg}");
        assert!(msg.contains("duplicate key `k`"), "{msg}");
        assert!(msg.contains("in `spring(3, ..)`"), "{msg}");
    }

    #[test]
    fn negative_literals_parse_for_validation_to_reject() {
        let spec = parse_ok(quote!(r = -0.8));
        assert_eq!(spec.r.unwrap().value.literal(), Some(-0.8));
    }
}
