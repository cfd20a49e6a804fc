//! Phase 4: emit the code. Two strategies from the one derivation:
//! - unrolled (n <= `unroll`, default 16): every function is straight-line code, with the
//!   sines and cosines of all angles taken in one `sin_cos_into` call into two local arrays and
//!   every spring's parameters folded in;
//! - looped: the per-spring kernel (rendered once, as a hidden module) driven by
//!   `chain-core`'s loops, so n = 100000 compiles fast.
//!
//! Everything generated besides the user's struct sits in one anonymous `const _: () = { .. };`,
//! so the hidden kernel module needs no name derived from the struct's (two structs whose names
//! differ only in case or underscores cannot collide). Generated code reaches support items only
//! through `::rotor_chain::__private`.
//!
//! Unrolled code holds no `let` per value: temporaries live in a few reused registers, outputs
//! are stored into their arrays as soon as they are computed, and the angles' sines and cosines
//! are arrays, so a function has a few dozen `let`s whatever the chain's length (rustc nests a
//! scope per `let`, and thousands of them crash it, or LLVM's debug info, in debug builds).

use chain_symbolic::chain::{ChainOutputs, Kernel};
use chain_symbolic::lower::{Schedule, lower_with};
use chain_symbolic::{Float, Graph, Id, SpringLaw};
use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};
use syn::ItemStruct;

use crate::attr;
use crate::ctxt::Ctxt;
use crate::fallback::{self, Stubs};
use crate::model::{PRIVATE, float_type, math_prefix, value_tokens_f64};
use crate::traits::{self, SliceMethod};
use crate::valid::{self, Model, Uniform};

/// The stack a generated method may use in a debug build, its caller's copy of the result
/// included: 1 MiB, half the 2 MiB stack of a thread Rust spawns (and of a test), so the caller
/// keeps the other half. A method that would need more is not generated; the slice methods of
/// `ChainModel` (`gradient_into`, ...) write into the caller's buffers and exist for every chain.
/// Release builds use about a third of this (`docs/macro.md`, measured).
pub const STACK_BUDGET: usize = 1 << 20;

/// The part of [`STACK_BUDGET`] kept for the evaluation itself, whatever `n`: in a debug build the
/// vectorised kernel drivers keep every lane temporary of the rendered kernel in its own stack
/// slot. Measured by shrinking the thread of `tests/hostile/stack.rs` until it overflowed: the
/// looped methods at the old limits needed between 224 and 256 KiB beyond their results.
pub const EVALUATION_STACK: usize = 256 << 10;

/// How many copies of its result a method holds on the stack at once in a debug build, measured
/// (`docs/macro.md`): an array, the method's and the caller's; a banded matrix, one more for its
/// constructor; the dense Hessian, nine (nalgebra's constructors copy it in debug builds).
#[derive(Clone, Copy)]
pub(crate) enum Returns {
    Array = 2,
    Banded = 3,
    Dense = 9,
}

/// Whether a method returning `values` numbers of type `float` of the kind `returns` fits
/// [`STACK_BUDGET`] beside [`EVALUATION_STACK`]: in `f64`, arrays up to 49152 values (`gradient`
/// of 49152 rotors), banded matrices up to 32768 values (16384 rotors), the dense Hessian up to
/// 104 rotors (147 in `f32`).
pub(crate) fn fits_on_stack(values: usize, returns: Returns, float: Float) -> bool {
    values.saturating_mul(float.bytes()).saturating_mul(returns as usize) <= STACK_BUDGET - EVALUATION_STACK
}

pub fn expand(attr: TokenStream, item: TokenStream) -> TokenStream {
    let parsed = match syn::parse2::<syn::Item>(item.clone()) {
        Ok(syn::Item::Struct(s)) => s,
        Ok(other) => {
            // Point at the item's keyword (`enum`, `union`); the stubs keep calls on the item
            // from adding errors of their own.
            let (err, stubs) = match &other {
                syn::Item::Enum(e) => (
                    syn::Error::new_spanned(e.enum_token, "#[rotor_chain] goes on a struct, not an enum"),
                    Some(Stubs::new(&e.ident, &e.generics, None, Float::F64)),
                ),
                syn::Item::Union(u) => (
                    syn::Error::new_spanned(u.union_token, "#[rotor_chain] goes on a struct, not a union"),
                    Some(Stubs::new(&u.ident, &u.generics, None, Float::F64)),
                ),
                other => (syn::Error::new_spanned(other, "#[rotor_chain] goes on a struct"), None),
            };
            return fallback::emit(&item, stubs.as_ref(), err);
        }
        Err(_) => {
            let err = syn::Error::new(Span::call_site(), "#[rotor_chain] goes on a struct");
            return fallback::emit(&item, None, err);
        }
    };
    let cx = Ctxt::new();
    let spec = attr::parse(&cx, attr);
    let n = spec.n.as_ref().map(|n| n.value).filter(|&n| chain_geometry::check_rotor_count(n).is_ok());
    let float = spec.float.as_ref().map_or(Float::F64, |f| f.value);
    let model = valid::validate(&cx, spec, &parsed);
    if let Some(model) = &model {
        check_unrolled_size(&cx, model);
    }
    let stubs = || Stubs::new(&parsed.ident, &parsed.generics, n, float);
    match cx.check() {
        Err(errors) => fallback::emit(&item, Some(&stubs()), errors),
        Ok(()) => match model {
            Some(model) => {
                let generated = emit(&parsed, &model);
                quote! {
                    #item
                    #generated
                }
            }
            None => {
                let err = syn::Error::new(Span::call_site(), "#[rotor_chain]: the model is incomplete");
                fallback::emit(&item, Some(&stubs()), err)
            }
        },
    }
}

/// Unrolled code grows with the chain and with the law: the unrolled strategy takes chains up
/// to the size of [`valid::MAX_UNROLL`] harmonic springs, measured by the nodes of one spring's
/// derivation. A law whose derivation is `x` times the harmonic one unrolls up to
/// `MAX_UNROLL / x` rotors; a longer chain is an error at the law, which `unroll = 0` resolves.
fn check_unrolled_size(cx: &Ctxt, model: &Model) {
    if !model.unrolled() || model.law.is_none() {
        return;
    }
    let harmonic = Kernel::new(&SpringLaw::harmonic).graph.len();
    let law = model.spring_cost();
    let largest = valid::MAX_UNROLL.saturating_mul(harmonic) / law.max(1);
    if model.n > largest {
        let remedy = match model.float {
            Float::F64 => "give `unroll = 0` to use the per-spring kernel in a loop",
            Float::F32 => {
                "a chain declared with `float = f32` is unrolled only, so compute this one in `f64`"
            }
        };
        let message = format!(
            "this law is too large to unroll {} rotors: one spring's derivation has {law} terms \
             ({harmonic} for the harmonic law), so chains of at most {largest} rotors are unrolled \
             with it; {remedy}",
            model.n,
        );
        match &model.law_tokens {
            Some(tokens) => cx.error_spanned_by(tokens, message),
            None => cx.error_at(Span::call_site(), message),
        }
    }
}

fn private() -> TokenStream {
    PRIVATE.parse().expect("path")
}

fn parse_block(src: &str) -> TokenStream {
    format!("{{\n{src}\n}}").parse().expect("generated source parses")
}

/// `{ assert!(i < count); match i { 3 => v3, _ => default } }`: an out-of-range index is a
/// programming error and panics, as it does for `RuntimeChain`.
fn indexed(
    index: &Ident,
    count: usize,
    what: &str,
    overrides: Vec<(usize, TokenStream)>,
    default: TokenStream,
) -> TokenStream {
    let message = format!("{what} index {{}} is out of range: the chain has {count} {what}s");
    let check = quote!(assert!(#index < #count, #message, #index););
    if overrides.is_empty() {
        return quote!({
            #check
            #default
        });
    }
    let arms = overrides.into_iter().map(|(i, v)| quote!(#i => #v,));
    quote!({
        #check
        match #index { #(#arms)* _ => #default }
    })
}

/// What an unrolled method returns, and the places its outputs are stored into.
enum Shape<'a> {
    Scalar(Id),
    Array(&'a [Id]),
    /// `diag` (n) and `off` (n - 1).
    Tridiagonal(&'a [Id], &'a [Id]),
    /// `left` and `right` (n - 1 each).
    Bidiagonal(&'a [Id], &'a [Id]),
    /// The fused methods: the energy (its partial sums, see [`fused_outputs`]), the gradient and,
    /// if given, the tangent stiffness's `diag` and `off`.
    Fused {
        energy_partial: &'a [Id],
        gradient: &'a [Id],
        stiffness: Option<(&'a [Id], &'a [Id])>,
    },
}

/// Straight-line code for one method: sines and cosines into two arrays, then the steps in a
/// few registers, each output stored into its place as soon as it is known. The outputs are
/// visited rotor by rotor (the two bands of a matrix interleaved), so the values a rotor's
/// outputs share die before the next rotor's are computed.
fn unrolled_body(g: &Graph, out: &ChainOutputs, shape: Shape, float: Float) -> TokenStream {
    let (n, p, ty, math) = (out.n, PRIVATE, float.name(), math_prefix(float));
    let m = n - 1;
    let place = |name: &str, k: usize, id: Id| (id, format!("{name}[{k}usize]"));
    let interleave = |a: (&str, &[Id]), b: (&str, &[Id])| -> Vec<(Id, String)> {
        let len = a.1.len().max(b.1.len());
        (0..len)
            .flat_map(|k| {
                let first = a.1.get(k).map(|&id| place(a.0, k, id));
                let second = b.1.get(k).map(|&id| place(b.0, k, id));
                first.into_iter().chain(second)
            })
            .collect()
    };
    let (decls, outputs, value): (String, Vec<(Id, String)>, String) = match shape {
        Shape::Scalar(id) => (format!("let mut out = 0.0{ty};"), vec![(id, "out".into())], "out".into()),
        Shape::Array(ids) => (
            format!("let mut out = [0.0{ty}; {}];", ids.len()),
            ids.iter().enumerate().map(|(k, &id)| place("out", k, id)).collect(),
            "out".into(),
        ),
        Shape::Tridiagonal(diag, off) => (
            format!("let mut diag = [0.0{ty}; {n}];\nlet mut off = [0.0{ty}; {m}];"),
            interleave(("diag", diag), ("off", off)),
            format!("{p}::Tridiagonal::new(diag, off)"),
        ),
        Shape::Bidiagonal(left, right) => (
            format!("let mut left = [0.0{ty}; {m}];\nlet mut right = [0.0{ty}; {m}];"),
            interleave(("left", left), ("right", right)),
            format!("{p}::Bidiagonal::new(left, right)"),
        ),
        Shape::Fused { energy_partial, gradient, stiffness } => {
            fused_outputs(n, energy_partial, gradient, stiffness)
        }
    };
    let (ids, sinks): (Vec<Id>, Vec<String>) = outputs.into_iter().unzip();
    let namer = out.leaf_namer(g);
    let program =
        lower_with(g, &ids, &namer, Schedule::DepthFirst).expect("every symbol is a field or an angle");
    let steps = program.render_into("t", float, &math, &sinks);
    parse_block(&format!(
        "let mut s = [0.0{ty}; {n}];\nlet mut c = [0.0{ty}; {n}];\n\
         {math}sin_cos_into(theta, &mut s, &mut c);\n{decls}\n{steps}{value}"
    ))
}

/// Declarations, outputs in schedule order, and the value of a fused unrolled method.
///
/// Rotor by rotor: its gradient entry (and stiffness entries), then the energy summed up to the
/// spring that rotor completes. Scheduled depth-first in that order, each spring's length and
/// terms are computed once and die with its two rotors, so the fused method needs as few
/// registers as the separate ones; the partial sums before the last are scheduling points
/// only (assigned to `_`), and the last is the energy.
fn fused_outputs(
    n: usize,
    energy_partial: &[Id],
    gradient: &[Id],
    stiffness: Option<(&[Id], &[Id])>,
) -> (String, Vec<(Id, String)>, String) {
    let (m, p) = (n - 1, PRIVATE);
    let mut outputs = Vec::new();
    for i in 0..n {
        outputs.push((gradient[i], format!("grad[{i}usize]")));
        if let Some((diag, off)) = stiffness {
            outputs.push((diag[i], format!("diag[{i}usize]")));
            if let Some(&o) = off.get(i) {
                outputs.push((o, format!("off[{i}usize]")));
            }
        }
        if i >= 1 {
            let sink = if i == m { "energy".to_owned() } else { "_".to_owned() };
            outputs.push((energy_partial[i - 1], sink));
        }
    }
    match stiffness {
        None => (
            format!("let mut energy = 0.0f64;\nlet mut grad = [0.0f64; {n}];"),
            outputs,
            "(energy, grad)".into(),
        ),
        Some(_) => (
            format!(
                "let mut energy = 0.0f64;\nlet mut grad = [0.0f64; {n}];\nlet mut diag = [0.0f64; {n}];\n\
                 let mut off = [0.0f64; {m}];"
            ),
            outputs,
            format!("(energy, grad, {p}::Tridiagonal::new(diag, off))"),
        ),
    }
}

/// The bodies of the fused inherent methods (`None`: not generated, see [`STACK_BUDGET`]).
struct FusedBodies {
    energy_and_gradient: Option<TokenStream>,
    energy_gradient_stiffness: Option<TokenStream>,
}

/// Whether the fused methods fit [`STACK_BUDGET`]: energy and gradient as an array, energy,
/// gradient and stiffness as a banded matrix (their results together).
fn fused_fit(n: usize) -> (bool, bool) {
    (fits_on_stack(n + 1, Returns::Array, Float::F64), fits_on_stack(3 * n, Returns::Banded, Float::F64))
}

/// The unrolled fused methods: one straight-line body each, every angle's `sin_cos` once.
fn unrolled_fused_bodies(n: usize, g: &Graph, out: &ChainOutputs) -> FusedBodies {
    let (eg, egk) = fused_fit(n);
    let shape =
        |stiffness| Shape::Fused { energy_partial: &out.energy_partial, gradient: &out.gradient, stiffness };
    FusedBodies {
        energy_and_gradient: eg.then(|| unrolled_body(g, out, shape(None), Float::F64)),
        energy_gradient_stiffness: egk
            .then(|| unrolled_body(g, out, shape(Some((&out.hessian_diag, &out.hessian_off))), Float::F64)),
    }
}

/// A slice method's body, by the method's name (`traits::SLICE_METHODS`).
type SliceBodies = Vec<(&'static str, TokenStream)>;

/// The unrolled strategy's fused slice methods: copies of the inherent results.
fn unrolled_fused_trait_bodies(ident: &Ident) -> SliceBodies {
    let p = private();
    let theta = quote!(#p::as_array(theta));
    vec![
        (
            "energy_and_gradient_into",
            quote!({
                let (energy, grad) = #ident::energy_and_gradient(self, #theta);
                out.copy_from_slice(&grad);
                energy
            }),
        ),
        (
            "energy_gradient_stiffness_into",
            quote!({
                let (energy, g, t) = #ident::energy_gradient_stiffness(self, #theta);
                grad.copy_from_slice(&g);
                diag.copy_from_slice(&t.diag);
                off.copy_from_slice(&t.off);
                energy
            }),
        ),
    ]
}

/// The looped strategy's fused methods: the slice methods call the fused drivers, the inherent
/// array methods run them on their own results, where they fit [`STACK_BUDGET`].
fn looped_fused_bodies(model: &Model) -> (FusedBodies, SliceBodies) {
    let p = private();
    let (n, m) = (model.n, model.springs());
    let eg = looped_call(model, "energy_and_gradient", "EnergyGradient", quote!(out));
    let egk =
        looped_call(model, "energy_gradient_stiffness", "EnergyGradientHessian", quote!(grad, diag, off));
    let (fits_eg, fits_egk) = fused_fit(n);
    let bodies = FusedBodies {
        // One local, the result itself, filled in place (as `looped_bodies` does): separate
        // locals gathered into a tuple at the end were copied into it.
        energy_and_gradient: fits_eg.then(|| {
            quote!({
                let mut result = (0.0f64, [0.0f64; #n]);
                result.0 = {
                    let out = &mut result.1[..];
                    #eg
                };
                result
            })
        }),
        energy_gradient_stiffness: fits_egk.then(|| {
            quote!({
                let mut result = (0.0f64, [0.0f64; #n], #p::Tridiagonal::new([0.0f64; #n], [0.0f64; #m]));
                result.0 = {
                    let (grad, diag, off) = (&mut result.1[..], &mut result.2.diag[..], &mut result.2.off[..]);
                    #egk
                };
                result
            })
        }),
    };
    (bodies, vec![("energy_and_gradient_into", eg), ("energy_gradient_stiffness_into", egk)])
}

/// The inherent fused methods' items.
fn fused_methods(n: usize, m: usize, bodies: FusedBodies, doc_strategy: &str) -> TokenStream {
    let p = private();
    let eg = bodies.energy_and_gradient.map(|body| {
        quote! {
            /// The energy and its gradient in one pass, each angle's `sin_cos` and each spring's
            /// length computed once: `(V, dV/dtheta)`.
            #[doc = #doc_strategy]
            pub fn energy_and_gradient(&self, theta: &[f64; #n]) -> (f64, [f64; #n]) #body
        }
    });
    let egk = bodies.energy_gradient_stiffness.map(|body| {
        quote! {
            /// The energy, its gradient and the tridiagonal tangent stiffness in one pass:
            /// `(V, dV/dtheta, d2V/dtheta2)` (paper Eq. `eq:prestress8`).
            #[doc = #doc_strategy]
            pub fn energy_gradient_stiffness(&self, theta: &[f64; #n]) -> (f64, [f64; #n], #p::Tridiagonal<#n, #m>) #body
        }
    });
    quote!(#eg #egk)
}

/// The springs' parameters for the kernel drivers: shared values splat into lanes (literals fold
/// into the kernel), with the springs whose parameters differ (overrides, and the two springs of
/// an overridden rotor) listed as exceptions, read through `__rotor_chain_spring`.
fn looped_springs(model: &Model) -> TokenStream {
    let p = private();
    let (a, r, k) = (model.value(&model.a), model.value(&model.r), model.value(&model.k));
    let mut exceptions: Vec<usize> = model.springs.keys().copied().collect();
    for &i in model.rotors.keys() {
        exceptions.extend(i.checked_sub(1));
        if i < model.springs() {
            exceptions.push(i);
        }
    }
    exceptions.sort_unstable();
    exceptions.dedup();
    quote!(#p::kernel::UniformSprings {
        params: [#a, #r, #r, #k, lbar],
        exceptions: &[#(#exceptions),*],
        each: |p: usize| self.__rotor_chain_spring(lbar, p),
    })
}

/// A looped method's body: `kernel::<driver>::<__rotor_chain_kernel::<kernel>>(theta, springs, outs)`.
fn looped_call(model: &Model, driver: &str, kernel: &str, outs: TokenStream) -> TokenStream {
    let p = private();
    let n = model.n;
    let lbar = model.rest_length_tokens();
    let springs = looped_springs(model);
    let (driver, kernel) = (format_ident!("{driver}"), format_ident!("{kernel}"));
    let kmod = format_ident!("__rotor_chain_kernel");
    // The default rest length is computed once per call, not once per spring.
    quote!({
        let lbar = #lbar;
        #p::kernel::#driver::<#kmod::#kernel>(#p::as_array::<f64, #n>(theta), #springs, #outs)
    })
}

/// The bodies of the inherent methods (`None`: not generated, see [`STACK_BUDGET`]).
struct Bodies {
    energy: TokenStream,
    gradient: Option<TokenStream>,
    tangent_stiffness: Option<TokenStream>,
    material: Option<TokenStream>,
    stress: Option<TokenStream>,
    lengths: Option<TokenStream>,
    tensions: Option<TokenStream>,
    compatibility: Option<TokenStream>,
    support: TokenStream,
}

fn unrolled_bodies(model: &Model, g: &Graph, out: &ChainOutputs) -> Bodies {
    let body = |shape| Some(unrolled_body(g, out, shape, model.float));
    Bodies {
        energy: unrolled_body(g, out, Shape::Scalar(out.energy), model.float),
        gradient: body(Shape::Array(&out.gradient)),
        tangent_stiffness: body(Shape::Tridiagonal(&out.hessian_diag, &out.hessian_off)),
        material: body(Shape::Tridiagonal(&out.material_diag, &out.material_off)),
        stress: body(Shape::Tridiagonal(&out.stress_diag, &out.stress_off)),
        lengths: body(Shape::Array(&out.lengths)),
        tensions: body(Shape::Array(&out.tensions)),
        compatibility: body(Shape::Bidiagonal(&out.compatibility_left, &out.compatibility_right)),
        support: TokenStream::new(),
    }
}

/// The looped strategy: the kernel module, and the trait's slice methods as kernel-driver calls
/// that write straight into the caller's buffers (no `n`-sized arrays on the stack, so very long
/// chains work through the trait with heap buffers). The inherent array methods wrap them, where
/// they fit [`STACK_BUDGET`].
fn looped_bodies(model: &Model) -> (Bodies, SliceBodies) {
    let p = private();
    let (n, m) = (model.n, model.springs());
    let kmod = format_ident!("__rotor_chain_kernel");
    let kernel: TokenStream = model.kernel_source().parse().expect("kernel source parses");
    let support = quote! {
        #[doc(hidden)]
        #[allow(non_snake_case, clippy::all)]
        mod #kmod {
            use #p::kernel::{Lane, SpringFn};
            #kernel
        }
    };
    let call = |driver: &str, kernel: &str, outs: TokenStream| looped_call(model, driver, kernel, outs);
    let energy = call("sum", "Energy", quote!());
    let gradient = call("assemble_pairs", "Gradient", quote!(out));
    let hessian = call("assemble_blocks", "Hessian", quote!(diag, off));
    let material = call("assemble_blocks", "Material", quote!(diag, off));
    let stress = call("assemble_blocks", "Stress", quote!(diag, off));
    let length = call("per_spring", "Length", quote!(out));
    let tension = call("per_spring", "Tension", quote!(out));
    let compatibility = call("per_spring_pairs", "Compatibility", quote!(left, right));
    let trait_bodies = vec![
        ("energy", energy.clone()),
        ("gradient_into", gradient.clone()),
        ("tangent_stiffness_into", hessian.clone()),
        ("material_stiffness_into", material.clone()),
        ("stress_matrix_into", stress.clone()),
        ("spring_lengths_into", length.clone()),
        ("tensions_into", tension.clone()),
        ("compatibility_into", compatibility.clone()),
    ];
    // One local, the result itself, filled in place by the driver.
    let blocks = |call: TokenStream| {
        fits_on_stack(n + m, Returns::Banded, Float::F64).then(|| {
            quote!({
                let mut result = #p::Tridiagonal::new([0.0f64; #n], [0.0f64; #m]);
                {
                    let (diag, off) = (&mut result.diag[..], &mut result.off[..]);
                    #call
                }
                result
            })
        })
    };
    let per_spring = |call: TokenStream| {
        fits_on_stack(m, Returns::Array, Float::F64).then(|| {
            quote!({
                let mut result = [0.0f64; #m];
                {
                    let out = &mut result[..];
                    #call
                }
                result
            })
        })
    };
    let bodies = Bodies {
        energy: energy.clone(),
        gradient: fits_on_stack(n, Returns::Array, Float::F64).then(|| {
            quote!({
                let mut result = [0.0f64; #n];
                {
                    let out = &mut result[..];
                    #gradient
                }
                result
            })
        }),
        tangent_stiffness: blocks(hessian),
        material: blocks(material),
        stress: blocks(stress),
        lengths: per_spring(length),
        tensions: per_spring(tension),
        compatibility: fits_on_stack(2 * m, Returns::Banded, Float::F64).then(|| {
            quote!({
                let mut result = #p::Bidiagonal::new([0.0f64; #m], [0.0f64; #m]);
                {
                    let (left, right) = (&mut result.left[..], &mut result.right[..]);
                    #compatibility
                }
                result
            })
        }),
        support,
    };
    (bodies, trait_bodies)
}

/// The unrolled strategy's slice methods: copies of the inherent (array) results.
fn unrolled_trait_bodies(ident: &Ident) -> SliceBodies {
    let p = private();
    let theta = quote!(#p::as_array(theta));
    let blocks = |method: TokenStream| {
        quote!({
            let t = #ident::#method(self, #theta);
            diag.copy_from_slice(&t.diag);
            off.copy_from_slice(&t.off);
        })
    };
    vec![
        ("energy", quote!({ #ident::energy(self, #theta) })),
        ("gradient_into", quote!({ out.copy_from_slice(&#ident::gradient(self, #theta)); })),
        ("tangent_stiffness_into", blocks(quote!(tangent_stiffness))),
        ("material_stiffness_into", blocks(quote!(material_stiffness))),
        ("stress_matrix_into", blocks(quote!(stress_matrix))),
        ("spring_lengths_into", quote!({ out.copy_from_slice(&#ident::spring_lengths(self, #theta)); })),
        ("tensions_into", quote!({ out.copy_from_slice(&#ident::tensions(self, #theta)); })),
        (
            "compatibility_into",
            quote!({
                let c = #ident::compatibility(self, #theta);
                left.copy_from_slice(&c.left);
                right.copy_from_slice(&c.right);
            }),
        ),
    ]
}

/// The run-time rules of `check()`: `chain-geometry`'s, in `f64` (the values of an `f32` chain
/// widen exactly).
fn check_body(model: &Model) -> TokenStream {
    let p = private();
    let value = |v| value_tokens_f64(v, model.float);
    let (a, r, k, mass) = (value(&model.a), value(&model.r), value(&model.k), value(&model.mass));
    let uniform = match &model.uniform {
        Uniform::ThetaBar(tb) => {
            let tb = value(tb);
            quote!(g::check_flipper_phase(#a, #r, #tb)?;)
        }
        Uniform::RestLength(rl) => {
            let rl = value(rl);
            quote!(g::check_flipper_phase(#a, #r, g::theta_bar_from_rest_length(#a, #r, #rl)?)?;)
        }
    };
    let springs = model.springs.values().flat_map(|(k, l0)| {
        let k = k.as_ref().map(|v| {
            let v = value(v);
            quote!(g::check_positive(g::Key::Stiffness, #v)?;)
        });
        let l0 = l0.as_ref().map(|v| {
            let v = value(v);
            quote!(g::check_positive(g::Key::RestLength, #v)?;)
        });
        k.into_iter().chain(l0)
    });
    let rotors = model.rotors.values().map(|v| {
        let v = value(v);
        quote!(g::check_positive(g::Key::RotorLength, #v)?;)
    });
    quote!({
        use #p::geometry as g;
        g::check_positive(g::Key::LatticeSpacing, #a)?;
        g::check_positive(g::Key::RotorLength, #r)?;
        g::check_positive(g::Key::Stiffness, #k)?;
        g::check_positive(g::Key::Mass, #mass)?;
        #uniform
        #(#springs)*
        #(#rotors)*
        Ok(())
    })
}

/// The four trait impls (the capability ladder, `traits`): the accessors from the model, the
/// slice methods from `slices`, in the chain's float type.
fn trait_impls(ident: &Ident, model: &Model, slices: &SliceBodies) -> TokenStream {
    let p = private();
    let (n, m) = (model.n, model.springs());
    let a = model.value(&model.a);
    let mass = model.value(&model.mass);
    let lbar = model.rest_length_tokens();
    let theta_bar = model.theta_bar_tokens();
    let accessors = |name: &str| match name {
        "dof_count" => quote!({ #n }),
        "inertia" => quote!({
            let r = self.__rotor_chain_rotor_length(i);
            #mass * r * r
        }),
        "energy_floor" => quote!({ #p::chain_energy_floor(self) }),
        "stiffness_layout" => quote!({ #p::StiffnessLayout::Tridiagonal }),
        "spring_count" => quote!({ #m }),
        "spring_constant" => quote!({ self.__rotor_chain_stiffness(p) }),
        "rest_length" => quote!({ self.__rotor_chain_rest_length(#lbar, p) }),
        "compatibility_layout" => quote!({ #p::CompatibilityLayout::Bidiagonal }),
        "lattice_spacing" => quote!({ #a }),
        "rotor_length" => quote!({ self.__rotor_chain_rotor_length(i) }),
        "mass" => quote!({ #mass }),
        "theta_bar" => quote!({ #theta_bar }),
        other => unreachable!("no accessor {other}"),
    };
    let float = model.float;
    let slices = |method: &SliceMethod| {
        slices
            .iter()
            .find(|(name, _)| *name == method.name)
            .map(|(name, body)| traits::slice_method(n, float, name, body.clone()))
    };
    traits::impls(ident, &syn::Generics::default(), float, &accessors, &slices)
}

fn emit(item: &ItemStruct, model: &Model) -> TokenStream {
    let p = private();
    let ident = &item.ident;
    let (n, m, float) = (model.n, model.springs(), model.float);
    let t = float_type(float);
    // One derivation of the unrolled chain serves the separate and the fused methods; the fused
    // methods exist on `f64` chains only (they serve the analyses and integrators).
    let (bodies, trait_bodies, fused, fused_trait_bodies) = if model.unrolled() {
        let (g, out) = model.unrolled_outputs();
        let fused = (float == Float::F64).then(|| unrolled_fused_bodies(n, &g, &out));
        let fused_trait_bodies =
            if fused.is_some() { unrolled_fused_trait_bodies(ident) } else { Vec::new() };
        (unrolled_bodies(model, &g, &out), unrolled_trait_bodies(ident), fused, fused_trait_bodies)
    } else {
        let (bodies, trait_bodies) = looped_bodies(model);
        let (fused, fused_trait_bodies) = looped_fused_bodies(model);
        (bodies, trait_bodies, Some(fused), fused_trait_bodies)
    };
    let Bodies {
        energy,
        gradient,
        tangent_stiffness,
        material,
        stress,
        lengths,
        tensions,
        compatibility,
        support,
    } = bodies;

    let a = model.value(&model.a);
    let (idx_i, idx_p) = (format_ident!("i"), format_ident!("p"));
    let rotor_overrides = model.rotors.iter().map(|(i, v)| (*i, model.value(v))).collect();
    let rotor_length = indexed(&idx_i, n, "rotor", rotor_overrides, model.value(&model.r));
    let k_overrides =
        model.springs.iter().filter_map(|(i, (k, _))| k.as_ref().map(|v| (*i, model.value(v)))).collect();
    let stiffness = indexed(&idx_p, m, "spring", k_overrides, model.value(&model.k));
    let l0_overrides =
        model.springs.iter().filter_map(|(i, (_, l0))| l0.as_ref().map(|v| (*i, model.value(v)))).collect();
    let rest_length = indexed(&idx_p, m, "spring", l0_overrides, quote!(lbar));
    let check = check_body(model);
    let strategy =
        if model.unrolled() { "unrolled straight-line code" } else { "the per-spring kernel in a loop" };
    let doc_strategy = match float {
        Float::F64 => format!(" Generated by `#[rotor_chain]` as {strategy}."),
        Float::F32 => format!(" Generated by `#[rotor_chain]` as {strategy}, computing in `f32`."),
    };
    let hessian = (fits_on_stack(n * n, Returns::Dense, float) && tangent_stiffness.is_some()).then(|| {
        quote! {
            /// The dense Hessian `d2V/dtheta_i dtheta_j` (the tangent stiffness as an `n x n` matrix).
            pub fn hessian(&self, theta: &[#t; #n]) -> #p::SMatrix<#t, #n, #n> {
                self.tangent_stiffness(theta).to_dense()
            }
        }
    });
    let gradient = gradient.map(|body| {
        quote! {
            /// `dV/dtheta_i` for every rotor (the forces are its negative).
            #[doc = #doc_strategy]
            pub fn gradient(&self, theta: &[#t; #n]) -> [#t; #n] #body
        }
    });
    let tangent_stiffness = tangent_stiffness.map(|body| {
        quote! {
            /// The tangent stiffness `d2V/dtheta_i dtheta_j`, tridiagonal (paper Eq. `eq:prestress8`).
            #[doc = #doc_strategy]
            pub fn tangent_stiffness(&self, theta: &[#t; #n]) -> #p::Tridiagonal<#n, #m, #t> #body
        }
    });
    let material = material.map(|body| {
        quote! {
            /// The material part `sum_p g^_p a_p a_p^T` of the tangent stiffness, `a_p = dl_p/dtheta`
            /// (paper Appendix D).
            pub fn material_stiffness(&self, theta: &[#t; #n]) -> #p::Tridiagonal<#n, #m, #t> #body
        }
    });
    let stress = stress.map(|body| {
        quote! {
            /// The stress matrix `sum_p S_p` (paper Appendix D): material part + stress matrix = tangent stiffness.
            pub fn stress_matrix(&self, theta: &[#t; #n]) -> #p::Tridiagonal<#n, #m, #t> #body
        }
    });
    let lengths = lengths.map(|body| {
        quote! {
            /// Spring lengths `l_p`.
            pub fn spring_lengths(&self, theta: &[#t; #n]) -> [#t; #m] #body
        }
    });
    let tensions = tensions.map(|body| {
        quote! {
            /// Spring tensions `t_p = dlaw/dl` at the current lengths.
            pub fn tensions(&self, theta: &[#t; #n]) -> [#t; #m] #body
        }
    });
    let fused = fused.map_or_else(TokenStream::new, |fused| fused_methods(n, m, fused, &doc_strategy));
    let compatibility = compatibility.map(|body| {
        quote! {
            /// The compatibility matrix `C[p][i] = dl_p / d(r_i theta_i)` (bidiagonal).
            pub fn compatibility(&self, theta: &[#t; #n]) -> #p::Bidiagonal<#m, #n, #t> #body
        }
    });
    // The stepper holds four arrays of `n` numbers, returned by value.
    let verlet = fits_on_stack(4 * n, Returns::Array, float).then(|| {
        quote! {
            /// A velocity-Verlet stepper (no heap, `no_std`) at angles `theta` and angular velocities
            /// `omega` at time 0, with time step `dt`: call `step(&chain)` on it. The one stepper of
            /// every run, `f64` and `f32` (`rotor_chain::integrate::Verlet`).
            pub fn verlet(
                &self,
                theta: [#t; #n],
                omega: [#t; #n],
                dt: #t,
            ) -> ::core::result::Result<#p::Verlet<#t, [#t; #n]>, #p::IntegrateError> {
                #p::Verlet::new(self, #p::Phase { time: 0.0, theta, omega }, dt)
            }
        }
    });
    let slice_bodies: SliceBodies = trait_bodies.into_iter().chain(fused_trait_bodies).collect();
    let traits = trait_impls(ident, model, &slice_bodies);

    quote! {
        const _: () = {
            #support

            #[automatically_derived]
            #[allow(clippy::all, clippy::pedantic, unused_variables, unused_parens, unused_mut, unused_assignments)]
            impl #ident {
                /// Number of rotors `n`.
                pub const N: usize = #n;
                /// Number of springs `n - 1`.
                pub const SPRINGS: usize = #m;

                /// Potential energy `V = sum_p law(l_p)`.
                #[doc = #doc_strategy]
                pub fn energy(&self, theta: &[#t; #n]) -> #t #energy

                #gradient
                #tangent_stiffness
                #hessian
                #material
                #stress
                #lengths
                #tensions
                #compatibility
                #verlet
                #fused

                /// Checks the parameters against the chain's rules at run time (literal values were
                /// already checked at compile time; this covers values read from fields).
                pub fn check(&self) -> ::core::result::Result<(), #p::ParameterError> #check

                #[doc(hidden)]
                #[inline(always)]
                fn __rotor_chain_rotor_length(&self, i: usize) -> #t #rotor_length

                #[doc(hidden)]
                #[inline(always)]
                fn __rotor_chain_stiffness(&self, p: usize) -> #t #stiffness

                #[doc(hidden)]
                #[inline(always)]
                fn __rotor_chain_rest_length(&self, lbar: #t, p: usize) -> #t #rest_length

                /// `[a, r_p, r_{p+1}, k_p, l0_p]` of spring `p`, given the default rest length `lbar`.
                #[doc(hidden)]
                #[inline(always)]
                fn __rotor_chain_spring(&self, lbar: #t, p: usize) -> [#t; 5] {
                    [
                        #a,
                        self.__rotor_chain_rotor_length(p),
                        self.__rotor_chain_rotor_length(p + 1),
                        self.__rotor_chain_stiffness(p),
                        self.__rotor_chain_rest_length(lbar, p),
                    ]
                }
            }

            #traits
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pretty(tokens: TokenStream) -> String {
        let file: syn::File = syn::parse2(tokens).expect("expansion parses as a file");
        prettyplease::unparse(&file)
    }

    /// The expansion of a 3-rotor chain, snapshotted (reviewed by eye when it changes).
    #[test]
    fn expansion_of_a_three_rotor_chain() {
        let out = expand(
            quote!(n = 3, r = 0.8, theta_bar = 0.58, k = 1.0e4, spring(1, k = k_imp)),
            quote!(
                pub struct Tiny {
                    pub k_imp: f64,
                }
            ),
        );
        insta::assert_snapshot!(pretty(out));
    }

    /// An `f32` chain's generated methods compute in `f32` throughout: single-precision math
    /// paths, `f32` literals and arrays, no `f64` in any method body but `check()` (whose rules are
    /// `chain-geometry`'s, in `f64`), and the model traits in `f32` (never their `f64` instance,
    /// `ChainModel`).
    #[test]
    fn an_f32_chain_computes_in_f32() {
        let out = expand(
            quote!(n = 3, r = 0.8, theta_bar = 0.58, k = k_imp, float = f32),
            quote!(
                pub struct Tiny {
                    pub k_imp: f32,
                }
            ),
        );
        let text = pretty(out);
        assert!(text.contains("math::single::sin_cos_into"), "{text}");
        for rung in ["Potential", "Stiffness", "SpringNetwork", "ChainGeometry"] {
            assert!(text.contains(&format!("{rung}<f32> for Tiny")), "{rung}: {text}");
            assert!(!text.contains(&format!("{rung}<f64> for Tiny")), "{rung}: {text}");
        }
        for method in ["energy", "gradient", "tangent_stiffness", "compatibility", "verlet"] {
            let start =
                text.find(&format!("pub fn {method}(")).unwrap_or_else(|| panic!("no {method}: {text}"));
            let body = &text[start..];
            let end = body[1..].find("pub fn ").map_or(body.len(), |e| e + 1);
            // The code, without the doc comments that precede the next method.
            let body: String = body[..end]
                .lines()
                .filter(|l| !l.trim_start().starts_with("///"))
                .collect::<Vec<_>>()
                .join("\n");
            assert!(!body.contains("f64"), "{method} mentions f64:\n{body}");
            assert!(body.contains("f32"), "{method} does not mention f32:\n{body}");
        }
    }

    #[test]
    fn looped_expansion_uses_the_kernel_module() {
        let out = expand(
            quote!(n = 3, r = 0.8, theta_bar = 0.58, k = 1.0e4, unroll = 2),
            quote!(
                struct Looped;
            ),
        );
        let text = pretty(out);
        assert!(text.contains("const _: () = {"), "{text}");
        assert!(text.contains("mod __rotor_chain_kernel {"), "{text}");
        assert!(text.contains("kernel::assemble_pairs"), "{text}");
    }

    #[test]
    fn methods_returning_on_the_stack_stop_at_the_budget() {
        let methods = |n: usize| {
            let attr: TokenStream = format!("n = {n}, r = 0.8, theta_bar = 0.58, k = 1.0e4").parse().unwrap();
            let text = expand(
                attr,
                quote!(
                    struct C;
                ),
            )
            .to_string();
            ["gradient", "spring_lengths", "tangent_stiffness", "compatibility", "hessian"]
                .map(|m| text.contains(&format!("pub fn {m} (& self")))
        };
        // [gradient, spring_lengths, tangent_stiffness, compatibility, hessian]
        assert_eq!(methods(104), [true; 5]);
        assert_eq!(methods(105), [true, true, true, true, false]);
        assert_eq!(methods(16384), [true, true, true, true, false]);
        assert_eq!(methods(16385), [true, true, false, true, false]);
        assert_eq!(methods(16386), [true, true, false, false, false]);
        assert_eq!(methods(49152), [true, true, false, false, false]);
        assert_eq!(methods(49153), [false, true, false, false, false]);
        assert_eq!(methods(49154), [false; 5]);
        assert_eq!(methods(chain_geometry::MAX_ROTORS), [false; 5]);
    }

    #[test]
    fn invalid_models_keep_the_struct_and_report_every_error() {
        let out = expand(
            quote!(n = 1, r = -1.0, theta_bar = 0.58, k = 1.0),
            quote!(
                struct Bad;
            ),
        );
        let text = out.to_string();
        assert!(text.contains("struct Bad"), "{text}");
        assert!(text.contains("at least 2"), "{text}");
        assert!(text.contains("must be a finite number > 0"), "{text}");
        // Stubs of the generated items, so calls add no errors of their own; their bodies are
        // never run (the crate does not compile).
        assert!(text.contains("fn energy"), "{text}");
        assert!(text.contains("invalid_chain"), "{text}");
        assert!(!text.contains("sin_cos"), "{text}");
    }
}
