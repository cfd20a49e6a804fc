//! Phase 1 of `#[rotor_network]`: parse the attribute into a typed [`Spec`] that keeps the span of
//! every key and value, with the helpers of `#[rotor_chain]`'s parser (`crate::attr`): items split
//! at top-level commas and read from their own tokens, so one malformed item is one error and
//! the others still count; "did you mean" for unknown keys; duplicates refused.

use std::collections::BTreeSet;

use proc_macro2::{Delimiter, TokenStream, TokenTree};
use syn::Ident;
use syn::ext::IdentExt;

use crate::attr::{
    Keyed, first_span, numeric_literal, parse_usize, quoted, set_once, split_commas, starts_with_punct,
    unknown_key, unwrap_invisible,
};
use crate::ctxt::Ctxt;

/// Every key the attribute accepts, for "did you mean" suggestions.
pub const KEYS: [&str; 8] = ["cell", "ready", "cells", "boundary", "law", "mass", "spring", "node"];

/// `spring(p, k = .., l0 = ..)`: the constant and rest length of the patch's bond `p`.
#[derive(Clone)]
pub struct SpringOverride {
    pub index: Keyed<usize>,
    pub k: Option<Keyed<f64>>,
    pub l0: Option<Keyed<f64>>,
    /// An argument failed to parse (its error explains the override).
    pub inner_error: bool,
}

/// A node of the cell named by its index or its name in the cell file.
#[derive(Clone)]
pub enum NodeName {
    Index(usize),
    Name(String),
}

/// `node((i, j), node, mass = ..)`: the mass of one node of the patch, `node` (its index or name
/// in the cell) in cell `(i, j)` (`i` alone in one dimension).
#[derive(Clone)]
pub struct NodeOverride {
    /// The `node` key, for errors about the override as a whole.
    pub key: Ident,
    pub cell: Keyed<Vec<usize>>,
    pub node: Keyed<NodeName>,
    pub mass: Option<Keyed<f64>>,
    /// An argument failed to parse (its error explains the override).
    pub inner_error: bool,
}

/// The parsed attribute.
pub struct Spec {
    /// `cell = "path"`, relative to the crate's manifest directory.
    pub cell: Option<Keyed<syn::LitStr>>,
    /// `ready = "name"`, a ready cell of `chain-cell`.
    pub ready: Option<Keyed<syn::LitStr>>,
    /// `cells = (n1, n2)` or `cells = n` (one or two entries, as written).
    pub cells: Option<Keyed<Vec<usize>>>,
    /// `boundary = "free"` or `"periodic"`.
    pub boundary: Option<Keyed<syn::LitStr>>,
    /// The law's tokens, parsed by [`crate::law::parse`] in validation.
    pub law: Option<Keyed<TokenStream>>,
    /// `mass = ..`: every node's mass.
    pub mass: Option<Keyed<f64>>,
    pub springs: Vec<SpringOverride>,
    pub nodes: Vec<NodeOverride>,
    /// Tokens of the whole attribute, for errors about missing keys.
    pub tokens: TokenStream,
    /// Every key the user wrote or evidently meant: no "missing" error for these.
    pub seen: BTreeSet<String>,
}

/// A string literal.
fn parse_string(cx: &Ctxt, key: &str, tokens: &[TokenTree], example: &str) -> Option<syn::LitStr> {
    let tokens = unwrap_invisible(tokens.to_vec());
    if let [TokenTree::Literal(lit)] = tokens.as_slice()
        && let syn::Lit::Str(s) = syn::Lit::new(lit.clone())
    {
        return Some(s);
    }
    let stream: TokenStream = tokens.into_iter().collect();
    cx.error_spanned_by(stream, format!("`{key}` takes a string literal, e.g. `{key} = {example}`"));
    None
}

/// A float literal (integers accepted) or a negated one: validation checks its range.
fn parse_number(cx: &Ctxt, tokens: &[TokenTree]) -> Option<f64> {
    let tokens = unwrap_invisible(tokens.to_vec());
    let parsed = match tokens.as_slice() {
        [TokenTree::Literal(lit)] => numeric_literal(lit),
        [TokenTree::Punct(minus), TokenTree::Literal(lit)] if minus.as_char() == '-' => {
            numeric_literal(lit).map(|value| value.map(|v| -v))
        }
        _ => None,
    };
    let stream: TokenStream = tokens.iter().cloned().collect();
    match parsed {
        Some(Ok(value)) => Some(value),
        Some(Err(message)) => {
            cx.error_spanned_by(stream, message);
            None
        }
        None => {
            cx.error_spanned_by(
                stream,
                "expected a float literal (e.g. `2.0`): a network's model is built once per type, so its \
                 parameters are literals, not fields",
            );
            None
        }
    }
}

/// `(n1, n2)`, `(n1)` or `n1`.
fn parse_cells(cx: &Ctxt, tokens: &[TokenTree]) -> Option<Vec<usize>> {
    let tokens = unwrap_invisible(tokens.to_vec());
    let entries = match tokens.as_slice() {
        [TokenTree::Group(g)] if g.delimiter() == Delimiter::Parenthesis => split_commas(g.stream()),
        [TokenTree::Literal(_)] => vec![tokens.clone()],
        _ => {
            let stream: TokenStream = tokens.into_iter().collect();
            cx.error_spanned_by(
                stream,
                "`cells` takes the patch's size: `cells = (16, 16)`, or `cells = 60` in one dimension",
            );
            return None;
        }
    };
    if entries.is_empty() || entries.len() > 2 {
        let stream: TokenStream = tokens.into_iter().collect();
        cx.error_spanned_by(
            stream,
            format!("`cells` has one or two entries (one per lattice vector), found {}", entries.len()),
        );
        return None;
    }
    let mut cells = Vec::new();
    for entry in &entries {
        cells.push(parse_usize(cx, entry, "a cell count")?);
    }
    Some(cells)
}

/// Parses the attribute tokens. Errors go to `cx`; whatever parsed is returned.
pub fn parse(cx: &Ctxt, attr: TokenStream) -> Spec {
    let mut spec = Spec {
        cell: None,
        ready: None,
        cells: None,
        boundary: None,
        law: None,
        mass: None,
        springs: Vec::new(),
        nodes: Vec::new(),
        tokens: attr.clone(),
        seen: BTreeSet::new(),
    };
    for item in split_commas(attr) {
        let key = match &item[0] {
            TokenTree::Ident(ident) => ident.unraw(),
            other => {
                cx.error_at(other.span(), "expected a key such as `cell`, `cells` or `spring(..)`");
                continue;
            }
        };
        let name = key.to_string();
        let known = KEYS.contains(&name.as_str());
        if known {
            spec.seen.insert(name.clone());
        } else if let Some(s) = unknown_key(cx, &key, &KEYS, "") {
            spec.seen.insert(s.to_owned());
            continue;
        } else {
            continue;
        }
        match &item[1..] {
            [TokenTree::Punct(eq), value @ ..]
                if eq.as_char() == '=' && !starts_with_punct(value, &['=', '>']) =>
            {
                if value.is_empty() {
                    cx.error_at(eq.span(), format!("`{name}` needs a value after `=`"));
                } else {
                    parse_name_value(cx, &mut spec, key, value);
                }
            }
            [TokenTree::Group(args)] if args.delimiter() == Delimiter::Parenthesis && name == "spring" => {
                parse_spring(cx, &mut spec, key, args.stream())
            }
            [TokenTree::Group(args)] if args.delimiter() == Delimiter::Parenthesis && name == "node" => {
                parse_node(cx, &mut spec, key, args.stream())
            }
            [] if name == "spring" => {
                cx.error_spanned_by(&key, "`spring` takes arguments: `spring(index, k = ..)`")
            }
            [] if name == "node" => cx.error_spanned_by(&key, NODE_FORM),
            _ => cx.error_spanned_by(&key, format!("`{name}` needs a value: `{name} = ..`")),
        }
    }
    spec
}

/// `key = value`.
fn parse_name_value(cx: &Ctxt, spec: &mut Spec, key: Ident, value: &[TokenTree]) {
    let name = key.to_string();
    let tokens: TokenStream = value.iter().cloned().collect();
    match name.as_str() {
        "cell" => {
            if let Some(s) = parse_string(cx, "cell", value, "\"cells/kagome.toml\"") {
                set_once(cx, &mut spec.cell, Keyed { key, value: s, tokens }, "");
            }
        }
        "ready" => {
            if let Some(s) = parse_string(cx, "ready", value, "\"kagome\"") {
                set_once(cx, &mut spec.ready, Keyed { key, value: s, tokens }, "");
            }
        }
        "boundary" => {
            if let Some(s) = parse_string(cx, "boundary", value, "\"free\"") {
                set_once(cx, &mut spec.boundary, Keyed { key, value: s, tokens }, "");
            }
        }
        "cells" => {
            if let Some(c) = parse_cells(cx, value) {
                set_once(cx, &mut spec.cells, Keyed { key, value: c, tokens }, "");
            }
        }
        "law" => set_once(cx, &mut spec.law, Keyed { key, value: tokens.clone(), tokens }, ""),
        "mass" => {
            if let Some(m) = parse_number(cx, value) {
                set_once(cx, &mut spec.mass, Keyed { key, value: m, tokens }, "");
            }
        }
        "node" => cx.error_spanned_by(&key, NODE_FORM),
        _ => cx.error_spanned_by(&key, "`spring` takes arguments: `spring(index, k = ..)`"),
    }
}

/// How `node(..)` is written, for its errors.
const NODE_FORM: &str =
    "`node` takes arguments: `node((i, j), \"name\" or index, mass = ..)`, the cell and the node in it";

/// The cell position of `node(..)`: `(i, j)`, `(i)` or `i`.
fn parse_position(cx: &Ctxt, tokens: &[TokenTree]) -> Option<Vec<usize>> {
    let tokens = unwrap_invisible(tokens.to_vec());
    let entries = match tokens.as_slice() {
        [TokenTree::Group(g)] if g.delimiter() == Delimiter::Parenthesis => split_commas(g.stream()),
        [TokenTree::Literal(_)] => vec![tokens.clone()],
        _ => Vec::new(),
    };
    if entries.is_empty() || entries.len() > 2 {
        let stream: TokenStream = tokens.into_iter().collect();
        cx.error_spanned_by(
            stream,
            format!("expected the node's cell, `(i, j)` or `i` in one dimension: {NODE_FORM}"),
        );
        return None;
    }
    let mut position = Vec::new();
    for entry in &entries {
        position.push(parse_usize(cx, entry, "a cell position")?);
    }
    Some(position)
}

/// `node((i, j), node, mass = ..)`.
fn parse_node(cx: &Ctxt, spec: &mut Spec, key: Ident, args: TokenStream) {
    let mut items = split_commas(args).into_iter();
    let (Some(cell_tokens), Some(node_tokens)) = (items.next(), items.next()) else {
        cx.error_spanned_by(&key, NODE_FORM);
        return;
    };
    let mut inner_error = false;
    let cell = parse_position(cx, &cell_tokens);
    let node_tokens = unwrap_invisible(node_tokens);
    let node = match node_tokens.as_slice() {
        [TokenTree::Literal(lit)] => match syn::Lit::new(lit.clone()) {
            syn::Lit::Str(s) => Some(NodeName::Name(s.value())),
            _ => parse_usize(cx, &node_tokens, "a node index").map(NodeName::Index),
        },
        _ => {
            let stream: TokenStream = node_tokens.iter().cloned().collect();
            cx.error_spanned_by(
                stream,
                format!("expected the node's name (a string) or its index in the cell: {NODE_FORM}"),
            );
            None
        }
    };
    let context = " in `node(..)`";
    let mut mass = None;
    for item in items {
        let pkey = match item.as_slice() {
            [TokenTree::Ident(pkey), TokenTree::Punct(eq), _, ..] if eq.as_char() == '=' => pkey.unraw(),
            _ => {
                cx.error_at(first_span(&item, key.span()), format!("expected `mass = value`{context}"));
                inner_error = true;
                continue;
            }
        };
        if pkey != "mass" {
            unknown_key(cx, &pkey, &["mass"], context);
            inner_error = true;
            continue;
        }
        let tokens: TokenStream = item[2..].iter().cloned().collect();
        match parse_number(cx, &item[2..]) {
            Some(v) => set_once(cx, &mut mass, Keyed { key: pkey, value: v, tokens }, context),
            None => inner_error = true,
        }
    }
    let (Some(cell), Some(node)) = (cell, node) else { return };
    let cell = Keyed { key: key.clone(), value: cell, tokens: cell_tokens.into_iter().collect() };
    let node = Keyed { key: key.clone(), value: node, tokens: node_tokens.into_iter().collect() };
    spec.nodes.push(NodeOverride { key, cell, node, mass, inner_error });
}

/// `spring(p, k = .., l0 = ..)`.
fn parse_spring(cx: &Ctxt, spec: &mut Spec, key: Ident, args: TokenStream) {
    let mut items = split_commas(args).into_iter();
    let Some(index_tokens) = items.next() else {
        cx.error_spanned_by(&key, "`spring(..)` needs an index: `spring(index, k = ..)`");
        return;
    };
    let Some(index) = parse_usize(cx, &index_tokens, "the spring index") else { return };
    let index = Keyed { key: key.clone(), value: index, tokens: index_tokens.into_iter().collect() };
    let allowed: &[&str] = &["k", "l0"];
    let context = format!(" in `spring({}, ..)`", index.value);
    let (mut k, mut l0) = (None, None);
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
        let Some(v) = parse_number(cx, value) else {
            inner_error = true;
            continue;
        };
        let slot = if pname == "k" { &mut k } else { &mut l0 };
        set_once(cx, slot, Keyed { key: pkey, value: v, tokens }, &context);
    }
    spec.springs.push(SpringOverride { index, k, l0, inner_error });
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
            cell = "cells/kagome.toml",
            cells = (16, 16),
            boundary = "free",
            law = k * (l - l0).powi(2),
            mass = 2.0,
            spring(3, k = 1.5, l0 = 0.4)
        ));
        assert_eq!(spec.cell.unwrap().value.value(), "cells/kagome.toml");
        assert_eq!(spec.cells.unwrap().value, vec![16, 16]);
        assert_eq!(spec.boundary.unwrap().value.value(), "free");
        assert!(spec.law.is_some());
        assert_eq!(spec.mass.unwrap().value, 2.0);
        let s = &spec.springs[0];
        assert_eq!((s.index.value, s.k.as_ref().unwrap().value, s.l0.as_ref().unwrap().value), (3, 1.5, 0.4));
    }

    #[test]
    fn one_dimensional_sizes_parse_with_or_without_parentheses() {
        assert_eq!(parse_ok(quote!(cells = 60)).cells.unwrap().value, vec![60]);
        assert_eq!(parse_ok(quote!(cells = (60))).cells.unwrap().value, vec![60]);
    }

    #[test]
    fn reports_every_error_with_suggestions() {
        let msg = parse_err(quote!(
            cel = "a.toml",
            cells = (1, 2, 3),
            mass = m,
            boundary = "free",
            boundary = "free",
            spring(2, kk = 1.0)
        ));
        assert!(msg.contains("unknown key `cel`; did you mean `cell`?"), "{msg}");
        assert!(msg.contains("one or two entries"), "{msg}");
        assert!(msg.contains("parameters are literals, not fields"), "{msg}");
        assert!(msg.contains("duplicate key `boundary`"), "{msg}");
        assert!(msg.contains("unknown key `kk` in `spring(2, ..)`; did you mean `k`?"), "{msg}");
    }
}
