//! Phase 2: check the parsed [`Spec`] against the chain's rules and resolve it into a [`Model`].
//!
//! The rules are `chain-geometry`'s, the same the runtime-sized chain applies, so a compile error
//! here and a runtime `ParameterError` there say the same thing. Literal values are checked now;
//! values read from struct fields are checked by the generated `check()` method at run time.

use std::collections::BTreeMap;

use chain_geometry::{self as geo, IndexKind, Key, ParameterError};
use chain_symbolic::Float;
use proc_macro2::{Span, TokenStream};
use syn::ext::IdentExt;
use syn::{Fields, ItemStruct, Type};

use crate::attr::{Keyed, Spec, Value, suggest};
use crate::ctxt::Ctxt;
use crate::law::{self, Law};

/// `f64` chains up to this many rotors are unrolled unless `unroll = ..` says otherwise (`f32`
/// chains are unrolled only, up to [`MAX_UNROLL`]).
///
/// Set by measurement (`cargo bench --bench simd`, `crossover_*`, docs/benchmarks.md): with
/// run-time dispatch to AVX2 or AVX-512, the looped kernel's vectorised drivers are as fast as
/// the unrolled scalar code at n = 16 and faster from n = 32 on (1.2-1.5x at 32, 1.3-1.9x at
/// 64, 1.9x at 512 with AVX-512). On a CPU without AVX2 (or in `no_std`, scalar libm), unrolled
/// code stays about 3x faster: give such chains `unroll = 512`.
pub const DEFAULT_UNROLL: usize = 16;

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
    /// The float type of every generated computation; literal values are rounded to it.
    pub float: Float,
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

/// `f64`, `core::primitive::f64` or `std::primitive::f64` (or the same for `f32`): the float type
/// `ty` (a type alias cannot be resolved by a macro).
fn is_float_path(path: &syn::Path, ty: &str) -> bool {
    let names: Vec<String> = path.segments.iter().map(|s| s.ident.unraw().to_string()).collect();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    match names.as_slice() {
        [t] | ["core" | "std", "primitive", t] => *t == ty,
        _ => false,
    }
}

/// A type as written, without the token stream's spaces: `Option < f64 >` becomes `Option<f64>`.
fn compact(ty: &str) -> String {
    let mut out = ty.replace(" ,", ",");
    for tight in ["<", ">", "::", "&", "(", ")", "[", "]", ";"] {
        out = out.replace(&format!(" {tight}"), tight).replace(&format!("{tight} "), tight);
    }
    out.replace(',', ", ").replace(';', "; ")
}

/// The fields of the struct in the chain's float type (`f64`, or `f32` for `float = f32`), and
/// every named field with its type (for error messages).
struct FloatFields {
    float_fields: Vec<String>,
    all: BTreeMap<String, String>,
    struct_name: String,
    float: Float,
}

impl FloatFields {
    fn of(item: &ItemStruct, float: Float) -> Self {
        let mut float_fields = Vec::new();
        let mut all = BTreeMap::new();
        if let Fields::Named(named) = &item.fields {
            for f in &named.named {
                let Some(ident) = &f.ident else { continue };
                let typed = matches!(&f.ty, Type::Path(p) if p.qself.is_none() && is_float_path(&p.path, float.name()));
                if typed {
                    float_fields.push(ident.unraw().to_string());
                }
                let ty = &f.ty;
                all.insert(ident.unraw().to_string(), compact(&quote::quote!(#ty).to_string()));
            }
        }
        Self { float_fields, all, struct_name: item.ident.unraw().to_string(), float }
    }

    fn check(&self, cx: &Ctxt, v: &Value) {
        let Value::Field(ident) = v else { return };
        let name = ident.unraw().to_string();
        if self.float_fields.contains(&name) {
            return;
        }
        let ty = self.float.name();
        if let Some(declared) = self.all.get(&name) {
            let message = match self.float {
                Float::F64 => format!(
                    "field `{name}` has type `{declared}`, but a chain parameter must be a field declared `f64`"
                ),
                Float::F32 => format!(
                    "field `{name}` has type `{declared}`, but a parameter of a chain declared with \
                     `float = f32` must be a field declared `f32`: the chain computes in `f32`"
                ),
            };
            cx.error_spanned_by(ident, message);
            return;
        }
        let known: Vec<&str> = self.float_fields.iter().map(String::as_str).collect();
        let hint = match suggest(&name, &known) {
            Some(s) => format!("; did you mean `{s}`?"),
            None if known.is_empty() => format!("; `{}` has no `{ty}` fields", self.struct_name),
            None => format!(
                "; its `{ty}` fields are {}",
                known.iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", ")
            ),
        };
        cx.error_spanned_by(
            ident,
            format!("`{name}` is not a field of `{}`: a parameter is a float literal or the name of an `{ty}` field{hint}", self.struct_name),
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
pub fn validate(cx: &Ctxt, mut spec: Spec, item: &ItemStruct) -> Option<Model> {
    if !item.generics.params.is_empty() {
        cx.error_spanned_by(&item.generics, "#[rotor_chain] does not support generic structs");
    }
    let float = spec.float.as_ref().map_or(Float::F64, |f| f.value);
    round_literals(cx, &mut spec, float);
    let fields = FloatFields::of(item, float);
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
    // An `f32` chain is unrolled only, so without an `unroll` key it is unrolled up to the limit.
    let default_unroll = match spec.float.as_ref().map(|f| f.value) {
        Some(Float::F32) => MAX_UNROLL,
        _ => DEFAULT_UNROLL,
    };
    if let (Some(keyed), Some(n)) = (&spec.float, n) {
        check_single_precision_strategy(
            cx,
            keyed,
            n,
            spec.unroll.as_ref().map_or(default_unroll, |u| u.value),
        );
    }

    Some(Model {
        n: n?,
        unroll: spec.unroll.map_or(default_unroll, |u| u.value),
        a: spec.a.map_or(Value::Literal { value: 1.0 }, |v| v.value),
        r: spec.r?.value,
        k: spec.k?.value,
        mass: spec.mass.map_or(Value::Literal { value: 1.0 }, |v| v.value),
        uniform: uniform?.0,
        law_tokens: spec.law.as_ref().map(|l| l.tokens.clone()),
        law,
        springs,
        rotors,
        float,
    })
}

/// An `f32` chain is unrolled code only: the looped strategy's kernel drivers are vectorised over
/// `f64` lanes (`chain_core::kernel`), and a microcontroller's chain is small. A chain longer than
/// its `unroll` is an error at the `float` key, saying how to resolve it.
fn check_single_precision_strategy(cx: &Ctxt, float: &Keyed<Float>, n: usize, unroll: usize) {
    if float.value != Float::F32 || n <= unroll {
        return;
    }
    let remedy = if n <= MAX_UNROLL {
        format!("give `unroll = {n}` (at most {MAX_UNROLL}) or compute in `f64`")
    } else {
        format!(
            "the largest unrolled chain has {MAX_UNROLL} rotors, so compute a chain of {n} rotors in `f64`"
        )
    };
    cx.error_spanned_by(
        &float.tokens,
        format!(
            "a chain declared with `float = f32` is generated as unrolled code only (the per-spring loop \
             computes in `f64` vector lanes), but n = {n} is more than `unroll` = {unroll}: {remedy}"
        ),
    );
}

/// For an `f32` chain, every literal parameter becomes the `f32` nearest to it, the value the chain
/// computes with; the rules are then checked on that value. A literal beyond `f32`'s range, or a
/// non-zero one that rounds to zero, is an error at the literal.
fn round_literals(cx: &Ctxt, spec: &mut Spec, float: Float) {
    if float == Float::F64 {
        return;
    }
    let round = |v: &mut Keyed<Value>| {
        let Value::Literal { value } = &mut v.value else { return };
        let rounded = float.round(*value);
        // After an error the value is left as written, so the rules add no second error about it.
        if !rounded.is_finite() {
            cx.error_spanned_by(&v.tokens, format!("literal out of range for `{}`", float.name()));
        } else if rounded == 0.0 && *value != 0.0 {
            cx.error_spanned_by(
                &v.tokens,
                format!("literal {value:e} is too small for `{}`: it rounds to 0", float.name()),
            );
        } else {
            *value = rounded;
        }
    };
    let Spec { a, r, theta_bar, rest_length, k, mass, springs, rotors, .. } = spec;
    for v in [a, r, theta_bar, rest_length, k, mass].into_iter().flatten() {
        round(v);
    }
    for s in springs {
        s.k.iter_mut().chain(s.l0.iter_mut()).for_each(&round);
    }
    for ro in rotors {
        ro.r.iter_mut().for_each(&round);
    }
}
