//! Phase 1: parse the attribute into a typed [`Spec`] that keeps the span of every key and value.
//!
//! The attribute is split at its top-level commas and every item is read from its own tokens, so
//! a malformed item is one error and the other items still count (no "missing key" for keys the
//! user gave). Values are read token by token, never handed whole to a recursive parser: a law is
//! parsed iteratively by [`crate::law`], a parameter value is a literal, a negated literal or an
//! identifier. Keys and field names are compared without their raw prefix (`r#k` is `k`).

use std::collections::BTreeSet;

use chain_symbolic::Float;
use proc_macro2::{Delimiter, Span, TokenStream, TokenTree};
use quote::ToTokens;
use syn::Ident;
use syn::ext::IdentExt;

use crate::ctxt::Ctxt;

/// Every key the attribute accepts, for "did you mean" suggestions.
pub const KEYS: [&str; 12] =
    ["n", "a", "r", "theta_bar", "rest_length", "k", "mass", "unroll", "law", "float", "spring", "rotor"];

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
    /// An argument of the override failed to parse (its error explains the override).
    pub inner_error: bool,
}

/// `rotor(i, r = ..)`.
#[derive(Clone)]
pub struct RotorOverride {
    pub index: Keyed<usize>,
    pub r: Option<Keyed<Value>>,
    /// An argument of the override failed to parse (its error explains the override).
    pub inner_error: bool,
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
    /// The law's tokens, parsed by [`crate::law::parse`] in validation.
    pub law: Option<Keyed<TokenStream>>,
    /// The float type the chain computes in (`f64` if absent).
    pub float: Option<Keyed<Float>>,
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
pub(crate) fn unknown_key<'a>(cx: &Ctxt, ident: &Ident, known: &[&'a str], context: &str) -> Option<&'a str> {
    let name = ident.unraw().to_string();
    let list = quoted(known);
    let suggestion = suggest(&name, known);
    match suggestion {
        Some(s) => cx.error_spanned_by(ident, format!("unknown key `{name}`{context}; did you mean `{s}`?")),
        None => cx.error_spanned_by(ident, format!("unknown key `{name}`{context}; expected one of {list}")),
    }
    suggestion
}

/// Sets `slot` unless it is already set, in which case reports a duplicate.
pub(crate) fn set_once<T>(cx: &Ctxt, slot: &mut Option<Keyed<T>>, keyed: Keyed<T>, context: &str) {
    if slot.is_some() {
        cx.error_spanned_by(&keyed.key, format!("duplicate key `{}`{context}", keyed.key.unraw()));
    } else {
        *slot = Some(keyed);
    }
}

/// The items of an attribute or of an override's arguments: the tokens between top-level commas
/// (empty items, as after a trailing comma, are dropped).
pub(crate) fn split_commas(tokens: TokenStream) -> Vec<Vec<TokenTree>> {
    let mut items = vec![Vec::new()];
    for tt in tokens {
        match &tt {
            TokenTree::Punct(p) if p.as_char() == ',' => items.push(Vec::new()),
            _ => items.last_mut().map_or((), |item| item.push(tt)),
        }
    }
    items.retain(|item| !item.is_empty());
    items
}

/// `tokens` without the invisible groups a `macro_rules!` expansion wraps around a fragment.
pub(crate) fn unwrap_invisible(mut tokens: Vec<TokenTree>) -> Vec<TokenTree> {
    while let [TokenTree::Group(g)] = tokens.as_slice() {
        if g.delimiter() != Delimiter::None {
            break;
        }
        tokens = g.stream().into_iter().collect();
    }
    tokens
}

/// Why a literal with a type suffix (`0.8f32`, `1u8`) is refused: the suffix would be ignored
/// (the value is the chain's float type whatever it says), so it is more likely a mistake than a
/// choice.
const SUFFIX: &str = "write the number without a type suffix (`0.8`, not `0.8f32`): every parameter is in \
                          the chain's float type, its `float` key (`f64` by default)";

/// The value of a float or integer literal token (of a key's value or of a law): `None` if it
/// is not one (a string, a character), an error if it has a type suffix or does not fit an `f64`.
pub fn numeric_literal(lit: &proc_macro2::Literal) -> Option<Result<f64, &'static str>> {
    let (value, suffixed) = match syn::Lit::new(lit.clone()) {
        syn::Lit::Float(f) => (f.base10_parse::<f64>().ok(), !f.suffix().is_empty()),
        syn::Lit::Int(i) => (i.base10_parse::<f64>().ok(), !i.suffix().is_empty()),
        _ => return None,
    };
    Some(match value {
        _ if suffixed => Err(SUFFIX),
        Some(v) if v.is_finite() => Ok(v),
        _ => Err("literal out of range for `f64`"),
    })
}

/// A float literal (integers accepted), a negated one, or an identifier naming a field.
fn parse_value(cx: &Ctxt, tokens: &[TokenTree]) -> Option<Value> {
    let tokens = unwrap_invisible(tokens.to_vec());
    let parsed = match tokens.as_slice() {
        [TokenTree::Literal(lit)] => numeric_literal(lit),
        [TokenTree::Punct(minus), TokenTree::Literal(lit)] if minus.as_char() == '-' => {
            numeric_literal(lit).map(|value| value.map(|v| -v))
        }
        // `syn::Ident`'s parser refuses keywords, which cannot name a field unless raw.
        [TokenTree::Ident(ident)] => match syn::parse2::<Ident>(ident.to_token_stream()) {
            Ok(ident) => return Some(Value::Field(ident)),
            Err(_) => {
                cx.error_spanned_by(
                    ident,
                    format!("`{ident}` is a keyword: a field of that name is written `r#{ident}`"),
                );
                return None;
            }
        },
        _ => None,
    };
    let stream: TokenStream = tokens.iter().cloned().collect();
    match parsed {
        Some(Ok(value)) => Some(Value::Literal { value }),
        Some(Err(message)) => {
            cx.error_spanned_by(stream, message);
            None
        }
        None => {
            cx.error_spanned_by(
                stream,
                "expected a float literal (e.g. `0.8`) or the name of an `f64` field of the struct",
            );
            None
        }
    }
}

/// `f32` or `f64` (also as `core::primitive::f32` or `std::primitive::f32`). Anything else is an
/// error at the value, with the supported type it most likely meant.
fn parse_float(cx: &Ctxt, tokens: &[TokenTree]) -> Option<Float> {
    let tokens = unwrap_invisible(tokens.to_vec());
    let stream: TokenStream = tokens.iter().cloned().collect();
    const SUPPORTED: &str = "a chain computes in `f64` (the default) or `f32`";
    if let Ok(path) = syn::parse2::<syn::Path>(stream.clone()) {
        let names: Vec<String> = path.segments.iter().map(|s| s.ident.unraw().to_string()).collect();
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        match names.as_slice() {
            ["f64"] | ["core" | "std", "primitive", "f64"] => return Some(Float::F64),
            ["f32"] | ["core" | "std", "primitive", "f32"] => return Some(Float::F32),
            _ => {}
        }
        let last = names.last().copied().unwrap_or_default();
        let hint = match last.to_ascii_lowercase().as_str() {
            "f32" => Some("f32"),
            "f64" => Some("f64"),
            // Narrower than any supported type: the narrowest one.
            "f16" | "bf16" | "half" | "f8" | "single" | "float" => Some("f32"),
            "f128" | "f80" | "double" => Some("f64"),
            other => suggest(other, &["f64", "f32"]),
        };
        let written = compact_path(&names);
        let message = match hint {
            Some(h) => format!("unsupported float type `{written}`: {SUPPORTED}; did you mean `{h}`?"),
            None => format!("unsupported float type `{written}`: {SUPPORTED}"),
        };
        cx.error_spanned_by(stream, message);
        return None;
    }
    let message = match tokens.as_slice() {
        [TokenTree::Literal(lit)] => match syn::Lit::new(lit.clone()) {
            syn::Lit::Str(text) => {
                format!("`float` takes a type, not a string: write `float = {}` without quotes", text.value())
            }
            syn::Lit::Int(i) if i.base10_digits() == "32" || i.base10_digits() == "64" => {
                format!("`float` takes a type, not a number: did you mean `f{}`?", i.base10_digits())
            }
            _ => format!("`float` takes a type, not a literal: {SUPPORTED}, e.g. `float = f32`"),
        },
        _ => format!("expected a float type after `float =`: {SUPPORTED}, e.g. `float = f32`"),
    };
    cx.error_spanned_by(stream, message);
    None
}

/// A path as written, `a::b::c`.
fn compact_path(names: &[&str]) -> String {
    names.join("::")
}

pub(crate) fn parse_usize(cx: &Ctxt, tokens: &[TokenTree], what: &str) -> Option<usize> {
    let tokens = unwrap_invisible(tokens.to_vec());
    let mut message = format!("{what} must be a non-negative integer literal");
    if let [TokenTree::Literal(lit)] = tokens.as_slice()
        && let syn::Lit::Int(i) = syn::Lit::new(lit.clone())
    {
        match i.base10_parse::<usize>() {
            Ok(v) if i.suffix().is_empty() => return Some(v),
            Ok(_) => message = format!("{what} is written without a type suffix (`60`, not `60usize`)"),
            Err(_) => {}
        }
    }
    let stream: TokenStream = tokens.into_iter().collect();
    cx.error_spanned_by(stream, message);
    None
}

/// Whether `tokens` starts with one of the punctuation characters `chars` (`==` and `=>` are
/// not `=`).
pub(crate) fn starts_with_punct(tokens: &[TokenTree], chars: &[char]) -> bool {
    matches!(tokens.first(), Some(TokenTree::Punct(p)) if chars.contains(&p.as_char()))
}

/// The span of a token list (its first token), or `fallback` for an empty one.
pub(crate) fn first_span(tokens: &[TokenTree], fallback: Span) -> Span {
    tokens.first().map_or(fallback, TokenTree::span)
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
        float: None,
        springs: Vec::new(),
        rotors: Vec::new(),
        tokens: attr.clone(),
        seen: BTreeSet::new(),
    };
    for item in split_commas(attr) {
        let key = match &item[0] {
            TokenTree::Ident(ident) => ident.unraw(),
            other => {
                cx.error_at(other.span(), "expected a key such as `n`, `r` or `spring(..)`");
                continue;
            }
        };
        let name = key.to_string();
        let known = KEYS.contains(&name.as_str());
        if known {
            spec.seen.insert(name.clone());
        }
        match &item[1..] {
            [TokenTree::Punct(eq), value @ ..]
                if eq.as_char() == '=' && !starts_with_punct(value, &['=', '>']) =>
            {
                if !known {
                    unknown_top_level_key(cx, &mut spec, &key);
                } else if value.is_empty() {
                    cx.error_at(eq.span(), format!("`{name}` needs a value after `=`"));
                } else {
                    parse_name_value(cx, &mut spec, key, value);
                }
            }
            [TokenTree::Group(args)] if args.delimiter() == Delimiter::Parenthesis && known => {
                if name == "spring" || name == "rotor" {
                    parse_override(cx, &mut spec, key, args.stream());
                } else {
                    cx.error_spanned_by(&key, format!("`{name}` needs a value: `{name} = ..`"));
                }
            }
            [] if name == "spring" || name == "rotor" => {
                let inner = if name == "spring" { "k" } else { "r" };
                cx.error_spanned_by(&key, format!("`{name}` takes arguments: `{name}(index, {inner} = ..)`"))
            }
            [] if known => cx.error_spanned_by(&key, format!("`{name}` needs a value: `{name} = ..`")),
            _ if !known => unknown_top_level_key(cx, &mut spec, &key),
            [] => {}
            [unexpected, ..] => cx.error_at(
                unexpected.span(),
                format!(
                    "expected `=` after `{name}`: a key is written `{name} = ..`{}",
                    match name.as_str() {
                        "spring" => " or `spring(index, k = ..)`",
                        "rotor" => " or `rotor(index, r = ..)`",
                        _ => "",
                    }
                ),
            ),
        }
    }
    spec
}

fn unknown_top_level_key(cx: &Ctxt, spec: &mut Spec, key: &Ident) {
    if let Some(s) = unknown_key(cx, key, &KEYS, "") {
        spec.seen.insert(s.to_owned());
    }
}

/// `key = value`.
fn parse_name_value(cx: &Ctxt, spec: &mut Spec, key: Ident, value: &[TokenTree]) {
    let name = key.to_string();
    let tokens: TokenStream = value.iter().cloned().collect();
    match name.as_str() {
        "n" | "unroll" => {
            if let Some(v) = parse_usize(cx, value, &format!("`{name}`")) {
                let slot = if name == "n" { &mut spec.n } else { &mut spec.unroll };
                set_once(cx, slot, Keyed { key, value: v, tokens }, "");
            }
        }
        "law" => set_once(cx, &mut spec.law, Keyed { key, value: tokens.clone(), tokens }, ""),
        "float" => {
            if let Some(float) = parse_float(cx, value) {
                set_once(cx, &mut spec.float, Keyed { key, value: float, tokens }, "");
            }
        }
        "spring" | "rotor" => {
            let inner = if name == "spring" { "k" } else { "r" };
            cx.error_spanned_by(&key, format!("`{name}` takes arguments: `{name}(index, {inner} = ..)`"))
        }
        _ => {
            if let Some(v) = parse_value(cx, value) {
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
    }
}

/// `spring(p, k = .., l0 = ..)` or `rotor(i, r = ..)`.
fn parse_override(cx: &Ctxt, spec: &mut Spec, key: Ident, args: TokenStream) {
    let name = key.to_string();
    let mut items = split_commas(args).into_iter();
    let Some(index_tokens) = items.next() else {
        let inner = if name == "spring" { "k" } else { "r" };
        cx.error_spanned_by(&key, format!("`{name}(..)` needs an index: `{name}(index, {inner} = ..)`"));
        return;
    };
    let Some(index) = parse_usize(cx, &index_tokens, &format!("the {name} index")) else { return };
    let index = Keyed { key: key.clone(), value: index, tokens: index_tokens.into_iter().collect() };
    let allowed: &[&str] = if name == "spring" { &["k", "l0"] } else { &["r"] };
    let context = format!(" in `{name}({}, ..)`", index.value);
    let (mut k, mut l0, mut r) = (None, None, None);
    // Any inner error already explains what is wrong; "overrides nothing" would only repeat it.
    let mut inner_error = false;
    for item in items {
        let pkey = match item.as_slice() {
            [TokenTree::Ident(pkey), TokenTree::Punct(eq), _, ..] if eq.as_char() == '=' => pkey.unraw(),
            _ => {
                cx.error_at(
                    first_span(&item, key.span()),
                    format!("expected `key = value`{context}, with a key among {}", quoted(allowed)),
                );
                inner_error = true;
                continue;
            }
        };
        let pname = pkey.to_string();
        if !allowed.contains(&pname.as_str()) {
            unknown_key(cx, &pkey, allowed, &context);
            inner_error = true;
            continue;
        }
        let value = &item[2..];
        let tokens: TokenStream = value.iter().cloned().collect();
        let Some(v) = parse_value(cx, value) else {
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
        spec.springs.push(SpringOverride { index, k, l0, inner_error });
    } else {
        spec.rotors.push(RotorOverride { index, r, inner_error });
    }
}

pub(crate) fn quoted(keys: &[&str]) -> String {
    keys.iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", ")
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
