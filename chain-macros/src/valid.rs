//! Phase 2: check the parsed [`Spec`] against the chain's rules and resolve it into a [`Model`].
//!
//! The rules are `chain-geometry`'s, the same the runtime-sized chain applies, so a compile error
//! here and a runtime `ParameterError` there say the same thing. Literal values are checked now;
//! values read from struct fields are checked by the generated `check()` method at run time.

use std::collections::BTreeMap;

use chain_geometry::{self as geo, IndexKind, Key, ParameterError};
use proc_macro2::{Span, TokenStream};
use syn::ext::IdentExt;
use syn::{Fields, ItemStruct, Type};

use crate::attr::{Keyed, Spec, Value, suggest};
use crate::ctxt::Ctxt;
use crate::law::{self, Law};

/// Chains up to this many rotors are unrolled unless `unroll = ..` says otherwise.
pub const DEFAULT_UNROLL: usize = 128;

/// The largest `unroll`: unrolled code grows with the chain, and this is the longest chain whose
/// unrolled code builds in a reasonable time in debug and release (measured in
/// `docs/macro.md`). Longer chains use the per-spring kernel in a loop, at the same speed per
/// spring.
pub const MAX_UNROLL: usize = 512;

/// The uniform state, by its angle or by the springs' rest length.
#[derive(Clone, Debug)]
pub enum Uniform {
    ThetaBar(Value),
    RestLength(Value),
}

/// A validated chain, ready for the symbolic phase.
#[derive(Clone)]
pub struct Model {
    pub n: usize,
    pub unroll: usize,
    pub a: Value,
    pub r: Value,
    pub k: Value,
    pub mass: Value,
    pub uniform: Uniform,
    pub law: Option<Law>,
    /// The law's tokens, for errors about its size.
    pub law_tokens: Option<TokenStream>,
    /// Spring overrides by index: `(k, l0)`.
    pub springs: BTreeMap<usize, (Option<Value>, Option<Value>)>,
    /// Rotor-length overrides by index.
    pub rotors: BTreeMap<usize, Value>,
}

impl Model {
    pub fn springs(&self) -> usize {
        self.n - 1
    }

    /// Whether the generated code is unrolled (else: the per-spring kernel in a loop).
    pub fn unrolled(&self) -> bool {
        self.n <= self.unroll
    }
}

/// `f64`, `core::primitive::f64` or `std::primitive::f64` (a type alias cannot be resolved by a macro).
fn is_f64_path(path: &syn::Path) -> bool {
    let names: Vec<String> = path.segments.iter().map(|s| s.ident.unraw().to_string()).collect();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    matches!(names.as_slice(), ["f64"] | ["core" | "std", "primitive", "f64"])
}

/// A type as written, without the token stream's spaces: `Option < f64 >` becomes `Option<f64>`.
fn compact(ty: &str) -> String {
    let mut out = ty.replace(" ,", ",");
    for tight in ["<", ">", "::", "&", "(", ")", "[", "]", ";"] {
        out = out.replace(&format!(" {tight}"), tight).replace(&format!("{tight} "), tight);
    }
    out.replace(',', ", ").replace(';', "; ")
}

/// The `f64` fields of the struct, and every named field with its type (for error messages).
struct Fields64 {
    f64_fields: Vec<String>,
    all: BTreeMap<String, String>,
    struct_name: String,
}

impl Fields64 {
    fn of(item: &ItemStruct) -> Self {
        let mut f64_fields = Vec::new();
        let mut all = BTreeMap::new();
        if let Fields::Named(named) = &item.fields {
            for f in &named.named {
                let Some(ident) = &f.ident else { continue };
                let is_f64 = matches!(&f.ty, Type::Path(p) if p.qself.is_none() && is_f64_path(&p.path));
                if is_f64 {
                    f64_fields.push(ident.unraw().to_string());
                }
                let ty = &f.ty;
                all.insert(ident.unraw().to_string(), compact(&quote::quote!(#ty).to_string()));
            }
        }
        Self { f64_fields, all, struct_name: item.ident.unraw().to_string() }
    }

    fn check(&self, cx: &Ctxt, v: &Value) {
        let Value::Field(ident) = v else { return };
        let name = ident.unraw().to_string();
        if self.f64_fields.contains(&name) {
            return;
        }
        if let Some(ty) = self.all.get(&name) {
            cx.error_spanned_by(
                ident,
                format!(
                    "field `{name}` has type `{ty}`, but a chain parameter must be a field declared `f64`"
                ),
            );
            return;
        }
        let known: Vec<&str> = self.f64_fields.iter().map(String::as_str).collect();
        let hint = match suggest(&name, &known) {
            Some(s) => format!("; did you mean `{s}`?"),
            None if known.is_empty() => format!("; `{}` has no `f64` fields", self.struct_name),
            None => format!(
                "; its `f64` fields are {}",
                known.iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", ")
            ),
        };
        cx.error_spanned_by(
            ident,
            format!("`{name}` is not a field of `{}`: a parameter is a float literal or the name of an `f64` field{hint}", self.struct_name),
        );
    }
}

fn report(cx: &Ctxt, tokens: &TokenStream, err: ParameterError) {
    cx.error_spanned_by(tokens, err);
}

/// An override's error: at the `spring`/`rotor` key if it gives nothing, else at its index.
fn report_override(cx: &Ctxt, index: &Keyed<usize>, err: ParameterError) {
    match err {
        ParameterError::EmptyOverride { .. } => cx.error_spanned_by(&index.key, err),
        other => report(cx, &index.tokens, other),
    }
}

/// Positivity of a literal value (fields are checked at run time).
fn check_positive(cx: &Ctxt, key: Key, v: &Keyed<Value>) {
    if let Some(x) = v.value.literal()
        && let Err(e) = geo::check_positive(key, x)
    {
        report(cx, &v.tokens, e);
    }
}

fn literal_or(v: &Option<Keyed<Value>>, default: f64) -> Option<f64> {
    match v {
        None => Some(default),
        Some(k) => k.value.literal(),
    }
}

/// Validates `spec` for the struct `item`. Returns the model if every required key is present
/// (other errors are in `cx`).
pub fn validate(cx: &Ctxt, spec: Spec, item: &ItemStruct) -> Option<Model> {
    if !item.generics.params.is_empty() {
        cx.error_spanned_by(&item.generics, "#[rotor_chain] does not support generic structs");
    }
    let fields = Fields64::of(item);
    let values = [&spec.a, &spec.r, &spec.theta_bar, &spec.rest_length, &spec.k, &spec.mass];
    for v in values.into_iter().flatten() {
        fields.check(cx, &v.value);
    }
    for s in &spec.springs {
        for v in s.k.iter().chain(&s.l0) {
            fields.check(cx, &v.value);
        }
    }
    for r in spec.rotors.iter().flat_map(|r| &r.r) {
        fields.check(cx, &r.value);
    }

    // A key the user wrote (with a bad value) or evidently meant (a misspelling) already has its
    // error; reporting it missing too would only repeat it.
    let missing = |key: &str, what: &str| {
        if spec.seen.contains(key) {
            return;
        }
        let message = format!("missing key `{key}` ({what})");
        if spec.tokens.is_empty() {
            cx.error_at(Span::call_site(), message);
        } else {
            cx.error_spanned_by(&spec.tokens, message);
        }
    };
    let n = match &spec.n {
        None => {
            missing("n", "the number of rotors, e.g. `n = 60`");
            None
        }
        Some(n) => match geo::check_rotor_count(n.value) {
            Ok(v) => Some(v),
            Err(e) => {
                report(cx, &n.tokens, e);
                None
            }
        },
    };
    if spec.r.is_none() {
        missing("r", "the rotor length, e.g. `r = 0.8`");
    }
    if spec.k.is_none() {
        missing("k", "the spring stiffness, e.g. `k = 1.0e4`");
    }
    let keyed_checks = [
        (Key::LatticeSpacing, &spec.a),
        (Key::RotorLength, &spec.r),
        (Key::Stiffness, &spec.k),
        (Key::Mass, &spec.mass),
    ];
    for (key, v) in keyed_checks {
        if let Some(v) = v {
            check_positive(cx, key, v);
        }
    }

    // The uniform state: exactly one of theta_bar and rest_length.
    let uniform = match (&spec.theta_bar, &spec.rest_length) {
        (Some(_), Some(rl)) => {
            cx.error_spanned_by(
                &rl.key,
                "give either `theta_bar` or `rest_length`, not both: each determines the other",
            );
            None
        }
        (None, None) => {
            // A bad `rest_length` value already has its own error.
            if !spec.seen.contains("rest_length") {
                missing("theta_bar", "the equilibrium angle, e.g. `theta_bar = 0.58`; or give `rest_length`");
            }
            None
        }
        (Some(tb), None) => Some((Uniform::ThetaBar(tb.value.clone()), tb)),
        (None, Some(rl)) => Some((Uniform::RestLength(rl.value.clone()), rl)),
    };
    if let Some((u, keyed)) = &uniform
        && let (Some(a), Some(r)) =
            (literal_or(&spec.a, 1.0), spec.r.as_ref().and_then(|r| r.value.literal()))
        && a > 0.0
        && r > 0.0
    {
        let result = match u {
            Uniform::ThetaBar(v) => v.literal().map(|t| geo::check_flipper_phase(a, r, t)),
            Uniform::RestLength(v) => v.literal().map(|l| {
                geo::theta_bar_from_rest_length(a, r, l).and_then(|t| geo::check_flipper_phase(a, r, t))
            }),
        };
        if let Some(Err(e)) = result {
            report(cx, &keyed.tokens, e);
        }
    }

    // Overrides: chain-geometry's rules (index, a value given, once), shared with the runtime
    // builder. An override whose arguments failed to parse already has its error.
    let mut springs = BTreeMap::new();
    for s in &spec.springs {
        let gives_a_value = s.k.is_some() || s.l0.is_some() || s.inner_error;
        let rule = match n {
            Some(n) => geo::check_override(
                IndexKind::Spring,
                s.index.value,
                n - 1,
                gives_a_value,
                springs.contains_key(&s.index.value),
            ),
            None => Ok(s.index.value),
        };
        if let Err(e) = rule {
            report_override(cx, &s.index, e);
            continue;
        }
        if let Some(k) = &s.k {
            check_positive(cx, Key::Stiffness, k);
        }
        if let Some(l0) = &s.l0 {
            check_positive(cx, Key::RestLength, l0);
        }
        let entry = (s.k.as_ref().map(|v| v.value.clone()), s.l0.as_ref().map(|v| v.value.clone()));
        springs.insert(s.index.value, entry);
    }
    let mut rotors = BTreeMap::new();
    for ro in &spec.rotors {
        let rule = match n {
            Some(n) => geo::check_override(
                IndexKind::Rotor,
                ro.index.value,
                n,
                ro.r.is_some() || ro.inner_error,
                rotors.contains_key(&ro.index.value),
            ),
            None => Ok(ro.index.value),
        };
        if let Err(e) = rule {
            report_override(cx, &ro.index, e);
            continue;
        }
        let Some(r) = &ro.r else { continue };
        check_positive(cx, Key::RotorLength, r);
        rotors.insert(ro.index.value, r.value.clone());
    }

    if let Some(unroll) = &spec.unroll
        && unroll.value > MAX_UNROLL
    {
        cx.error_spanned_by(
            &unroll.tokens,
            format!(
                "`unroll` = {} is past the largest unrolled chain, {MAX_UNROLL} rotors: longer chains use \
                 the per-spring kernel in a loop, as fast per spring and quick to compile",
                unroll.value
            ),
        );
    }
    let law = spec.law.as_ref().and_then(|l| law::parse(cx, &l.key, l.value.clone()));

    Some(Model {
        n: n?,
        unroll: spec.unroll.map_or(DEFAULT_UNROLL, |u| u.value),
        a: spec.a.map_or(Value::Literal { value: 1.0 }, |v| v.value),
        r: spec.r?.value,
        k: spec.k?.value,
        mass: spec.mass.map_or(Value::Literal { value: 1.0 }, |v| v.value),
        uniform: uniform?.0,
        law_tokens: spec.law.as_ref().map(|l| l.tokens.clone()),
        law,
        springs,
        rotors,
    })
}
