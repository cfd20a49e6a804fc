//! Phase 4: emit the code. Two strategies from the one derivation:
//! - unrolled (n <= `unroll`, default 128): every function is straight-line code, with the
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
use chain_symbolic::{Graph, Id, SpringLaw};
use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};
use syn::ItemStruct;

use crate::attr;
use crate::ctxt::Ctxt;
use crate::fallback::{self, Stubs};
use crate::model::{PRIVATE, math_prefix, value_tokens};
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

/// Whether a method returning `values` `f64`s of the kind `returns` fits [`STACK_BUDGET`] beside
/// [`EVALUATION_STACK`]: arrays up to 49152 values (`gradient` of 49152 rotors), banded matrices
/// up to 32768 values (16384 rotors), the dense Hessian up to 104 rotors.
pub(crate) fn fits_on_stack(values: usize, returns: Returns) -> bool {
    values.saturating_mul(8).saturating_mul(returns as usize) <= STACK_BUDGET - EVALUATION_STACK
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
                    Some(Stubs::new(&e.ident, &e.generics, None)),
                ),
                syn::Item::Union(u) => (
                    syn::Error::new_spanned(u.union_token, "#[rotor_chain] goes on a struct, not a union"),
                    Some(Stubs::new(&u.ident, &u.generics, None)),
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
    let model = valid::validate(&cx, spec, &parsed);
    if let Some(model) = &model {
        check_unrolled_size(&cx, model);
    }
    let stubs = || Stubs::new(&parsed.ident, &parsed.generics, n);
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
        let message = format!(
            "this law is too large to unroll {} rotors: one spring's derivation has {law} terms \
             ({harmonic} for the harmonic law), so chains of at most {largest} rotors are unrolled \
             with it; give `unroll = 0` to use the per-spring kernel in a loop",
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
}

/// Straight-line code for one method: sines and cosines into two arrays, then the steps in a
/// few registers, each output stored into its place as soon as it is known. The outputs are
/// visited rotor by rotor (the two bands of a matrix interleaved), so the values a rotor's
/// outputs share die before the next rotor's are computed.
fn unrolled_body(g: &Graph, out: &ChainOutputs, shape: Shape) -> TokenStream {
    let (n, p) = (out.n, PRIVATE);
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
        Shape::Scalar(id) => ("let mut out = 0.0f64;".into(), vec![(id, "out".into())], "out".into()),
        Shape::Array(ids) => (
            format!("let mut out = [0.0f64; {}];", ids.len()),
            ids.iter().enumerate().map(|(k, &id)| place("out", k, id)).collect(),
            "out".into(),
        ),
        Shape::Tridiagonal(diag, off) => (
            format!("let mut diag = [0.0f64; {n}];\nlet mut off = [0.0f64; {m}];"),
            interleave(("diag", diag), ("off", off)),
            format!("{p}::Tridiagonal::new(diag, off)"),
        ),
        Shape::Bidiagonal(left, right) => (
            format!("let mut left = [0.0f64; {m}];\nlet mut right = [0.0f64; {m}];"),
            interleave(("left", left), ("right", right)),
            format!("{p}::Bidiagonal::new(left, right)"),
        ),
    };
    let (ids, sinks): (Vec<Id>, Vec<String>) = outputs.into_iter().unzip();
    let namer = out.leaf_namer(g);
    let program =
        lower_with(g, &ids, &namer, Schedule::DepthFirst).expect("every symbol is a field or an angle");
    let steps = program.render_into("t", "f64", &math_prefix(), &sinks);
    parse_block(&format!(
        "let mut s = [0.0f64; {n}];\nlet mut c = [0.0f64; {n}];\n\
         {p}::math::sin_cos_into(theta, &mut s, &mut c);\n{decls}\n{steps}{value}"
    ))
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

fn unrolled_bodies(model: &Model) -> Bodies {
    let (g, out) = model.unrolled_outputs();
    let body = |shape| Some(unrolled_body(&g, &out, shape));
    Bodies {
        energy: unrolled_body(&g, &out, Shape::Scalar(out.energy)),
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
fn looped_bodies(model: &Model) -> (Bodies, TokenStream) {
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
    let lbar = model.rest_length_tokens();
    let theta = quote!(#p::as_array::<#n>(theta));
    // The default rest length is computed once per call, not once per spring.
    let params = quote!(|p: usize| self.__rotor_chain_spring(lbar, p));
    let call = |driver: &str, kernel: &str, outs: TokenStream| -> TokenStream {
        let (driver, kernel) = (format_ident!("{driver}"), format_ident!("{kernel}"));
        quote!({
            let lbar = #lbar;
            #p::kernel::#driver::<#kmod::#kernel>(#theta, #params, #outs)
        })
    };
    let energy = call("sum", "Energy", quote!());
    let gradient = call("assemble_pairs", "Gradient", quote!(out));
    let hessian = call("assemble_blocks", "Hessian", quote!(diag, off));
    let material = call("assemble_blocks", "Material", quote!(diag, off));
    let stress = call("assemble_blocks", "Stress", quote!(diag, off));
    let length = call("per_spring", "Length", quote!(out));
    let tension = call("per_spring", "Tension", quote!(out));
    let compatibility = call("per_spring_pairs", "Compatibility", quote!(left, right));
    let trait_bodies = quote! {
        fn energy(&self, theta: &[f64]) -> f64 #energy
        fn gradient_into(&self, theta: &[f64], out: &mut [f64]) #gradient
        fn tangent_stiffness_into(&self, theta: &[f64], diag: &mut [f64], off: &mut [f64]) #hessian
        fn material_stiffness_into(&self, theta: &[f64], diag: &mut [f64], off: &mut [f64]) #material
        fn stress_matrix_into(&self, theta: &[f64], diag: &mut [f64], off: &mut [f64]) #stress
        fn spring_lengths_into(&self, theta: &[f64], out: &mut [f64]) #length
        fn tensions_into(&self, theta: &[f64], out: &mut [f64]) #tension
        fn compatibility_into(&self, theta: &[f64], left: &mut [f64], right: &mut [f64]) #compatibility
    };
    let t = quote!(#p::ChainModel);
    // One local, the result itself, filled in place.
    let blocks = |method: TokenStream| {
        fits_on_stack(n + m, Returns::Banded).then(|| {
            quote!({
                let mut result = #p::Tridiagonal::new([0.0f64; #n], [0.0f64; #m]);
                #t::#method(self, theta, &mut result.diag, &mut result.off);
                result
            })
        })
    };
    let per_spring = |method: TokenStream| {
        fits_on_stack(m, Returns::Array).then(|| {
            quote!({
                let mut out = [0.0f64; #m];
                #t::#method(self, theta, &mut out);
                out
            })
        })
    };
    let bodies = Bodies {
        energy: quote!({ #t::energy(self, theta) }),
        gradient: fits_on_stack(n, Returns::Array).then(|| {
            quote!({
                let mut out = [0.0f64; #n];
                #t::gradient_into(self, theta, &mut out);
                out
            })
        }),
        tangent_stiffness: blocks(quote!(tangent_stiffness_into)),
        material: blocks(quote!(material_stiffness_into)),
        stress: blocks(quote!(stress_matrix_into)),
        lengths: per_spring(quote!(spring_lengths_into)),
        tensions: per_spring(quote!(tensions_into)),
        compatibility: fits_on_stack(2 * m, Returns::Banded).then(|| {
            quote!({
                let mut result = #p::Bidiagonal::new([0.0f64; #m], [0.0f64; #m]);
                #t::compatibility_into(self, theta, &mut result.left, &mut result.right);
                result
            })
        }),
        support,
    };
    (bodies, trait_bodies)
}

/// The unrolled strategy's trait methods: copies of the inherent (array) results.
fn unrolled_trait_bodies(ident: &Ident) -> TokenStream {
    let p = private();
    let theta = quote!(#p::as_array(theta));
    quote! {
        fn energy(&self, theta: &[f64]) -> f64 {
            #ident::energy(self, #theta)
        }
        fn gradient_into(&self, theta: &[f64], out: &mut [f64]) {
            out.copy_from_slice(&#ident::gradient(self, #theta));
        }
        fn tangent_stiffness_into(&self, theta: &[f64], diag: &mut [f64], off: &mut [f64]) {
            let t = #ident::tangent_stiffness(self, #theta);
            diag.copy_from_slice(&t.diag);
            off.copy_from_slice(&t.off);
        }
        fn material_stiffness_into(&self, theta: &[f64], diag: &mut [f64], off: &mut [f64]) {
            let t = #ident::material_stiffness(self, #theta);
            diag.copy_from_slice(&t.diag);
            off.copy_from_slice(&t.off);
        }
        fn stress_matrix_into(&self, theta: &[f64], diag: &mut [f64], off: &mut [f64]) {
            let t = #ident::stress_matrix(self, #theta);
            diag.copy_from_slice(&t.diag);
            off.copy_from_slice(&t.off);
        }
        fn spring_lengths_into(&self, theta: &[f64], out: &mut [f64]) {
            out.copy_from_slice(&#ident::spring_lengths(self, #theta));
        }
        fn tensions_into(&self, theta: &[f64], out: &mut [f64]) {
            out.copy_from_slice(&#ident::tensions(self, #theta));
        }
        fn compatibility_into(&self, theta: &[f64], left: &mut [f64], right: &mut [f64]) {
            let c = #ident::compatibility(self, #theta);
            left.copy_from_slice(&c.left);
            right.copy_from_slice(&c.right);
        }
    }
}

fn check_body(model: &Model) -> TokenStream {
    let p = private();
    let (a, r, k, mass) =
        (value_tokens(&model.a), value_tokens(&model.r), value_tokens(&model.k), value_tokens(&model.mass));
    let uniform = match &model.uniform {
        Uniform::ThetaBar(tb) => {
            let tb = value_tokens(tb);
            quote!(g::check_flipper_phase(#a, #r, #tb)?;)
        }
        Uniform::RestLength(rl) => {
            let rl = value_tokens(rl);
            quote!(g::check_flipper_phase(#a, #r, g::theta_bar_from_rest_length(#a, #r, #rl)?)?;)
        }
    };
    let springs = model.springs.values().flat_map(|(k, l0)| {
        let k = k.as_ref().map(|v| {
            let v = value_tokens(v);
            quote!(g::check_positive(g::Key::Stiffness, #v)?;)
        });
        let l0 = l0.as_ref().map(|v| {
            let v = value_tokens(v);
            quote!(g::check_positive(g::Key::RestLength, #v)?;)
        });
        k.into_iter().chain(l0)
    });
    let rotors = model.rotors.values().map(|v| {
        let v = value_tokens(v);
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

fn emit(item: &ItemStruct, model: &Model) -> TokenStream {
    let p = private();
    let ident = &item.ident;
    let (n, m) = (model.n, model.springs());
    let (bodies, trait_bodies) = if model.unrolled() {
        (unrolled_bodies(model), unrolled_trait_bodies(ident))
    } else {
        looped_bodies(model)
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

    let a = value_tokens(&model.a);
    let mass = value_tokens(&model.mass);
    let lbar = model.rest_length_tokens();
    let theta_bar = model.theta_bar_tokens();
    let (idx_i, idx_p) = (format_ident!("i"), format_ident!("p"));
    let rotor_overrides = model.rotors.iter().map(|(i, v)| (*i, value_tokens(v))).collect();
    let rotor_length = indexed(&idx_i, n, "rotor", rotor_overrides, value_tokens(&model.r));
    let k_overrides =
        model.springs.iter().filter_map(|(i, (k, _))| k.as_ref().map(|v| (*i, value_tokens(v)))).collect();
    let stiffness = indexed(&idx_p, m, "spring", k_overrides, value_tokens(&model.k));
    let l0_overrides =
        model.springs.iter().filter_map(|(i, (_, l0))| l0.as_ref().map(|v| (*i, value_tokens(v)))).collect();
    let rest_length = indexed(&idx_p, m, "spring", l0_overrides, quote!(lbar));
    let check = check_body(model);
    let strategy =
        if model.unrolled() { "unrolled straight-line code" } else { "the per-spring kernel in a loop" };
    let doc_strategy = format!(" Generated by `#[rotor_chain]` as {strategy}.");
    let hessian = (fits_on_stack(n * n, Returns::Dense) && tangent_stiffness.is_some()).then(|| {
        quote! {
            /// The dense Hessian `d2V/dtheta_i dtheta_j` (the tangent stiffness as an `n x n` matrix).
            pub fn hessian(&self, theta: &[f64; #n]) -> #p::SMatrix<f64, #n, #n> {
                self.tangent_stiffness(theta).to_dense()
            }
        }
    });
    let gradient = gradient.map(|body| {
        quote! {
            /// `dV/dtheta_i` for every rotor (the forces are its negative).
            #[doc = #doc_strategy]
            pub fn gradient(&self, theta: &[f64; #n]) -> [f64; #n] #body
        }
    });
    let tangent_stiffness = tangent_stiffness.map(|body| {
        quote! {
            /// The tangent stiffness `d2V/dtheta_i dtheta_j`, tridiagonal (paper Eq. `eq:prestress8`).
            #[doc = #doc_strategy]
            pub fn tangent_stiffness(&self, theta: &[f64; #n]) -> #p::Tridiagonal<#n, #m> #body
        }
    });
    let material = material.map(|body| {
        quote! {
            /// The material part `sum_p g^_p a_p a_p^T` of the tangent stiffness, `a_p = dl_p/dtheta`
            /// (paper Appendix D).
            pub fn material_stiffness(&self, theta: &[f64; #n]) -> #p::Tridiagonal<#n, #m> #body
        }
    });
    let stress = stress.map(|body| {
        quote! {
            /// The stress matrix `sum_p S_p` (paper Appendix D): material part + stress matrix = tangent stiffness.
            pub fn stress_matrix(&self, theta: &[f64; #n]) -> #p::Tridiagonal<#n, #m> #body
        }
    });
    let lengths = lengths.map(|body| {
        quote! {
            /// Spring lengths `l_p`.
            pub fn spring_lengths(&self, theta: &[f64; #n]) -> [f64; #m] #body
        }
    });
    let tensions = tensions.map(|body| {
        quote! {
            /// Spring tensions `t_p = dlaw/dl` at the current lengths.
            pub fn tensions(&self, theta: &[f64; #n]) -> [f64; #m] #body
        }
    });
    let compatibility = compatibility.map(|body| {
        quote! {
            /// The compatibility matrix `C[p][i] = dl_p / d(r_i theta_i)` (bidiagonal).
            pub fn compatibility(&self, theta: &[f64; #n]) -> #p::Bidiagonal<#m, #n> #body
        }
    });

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
                pub fn energy(&self, theta: &[f64; #n]) -> f64 #energy

                #gradient
                #tangent_stiffness
                #hessian
                #material
                #stress
                #lengths
                #tensions
                #compatibility

                /// Checks the parameters against the chain's rules at run time (literal values were
                /// already checked at compile time; this covers values read from fields).
                pub fn check(&self) -> ::core::result::Result<(), #p::ParameterError> #check

                #[doc(hidden)]
                #[inline(always)]
                fn __rotor_chain_rotor_length(&self, i: usize) -> f64 #rotor_length

                #[doc(hidden)]
                #[inline(always)]
                fn __rotor_chain_stiffness(&self, p: usize) -> f64 #stiffness

                #[doc(hidden)]
                #[inline(always)]
                fn __rotor_chain_rest_length(&self, lbar: f64, p: usize) -> f64 #rest_length

                /// `[a, r_p, r_{p+1}, k_p, l0_p]` of spring `p`, given the default rest length `lbar`.
                #[doc(hidden)]
                #[inline(always)]
                fn __rotor_chain_spring(&self, lbar: f64, p: usize) -> [f64; 5] {
                    [
                        #a,
                        self.__rotor_chain_rotor_length(p),
                        self.__rotor_chain_rotor_length(p + 1),
                        self.__rotor_chain_stiffness(p),
                        self.__rotor_chain_rest_length(lbar, p),
                    ]
                }
            }

            #[automatically_derived]
            #[allow(clippy::all, clippy::pedantic)]
            impl #p::ChainModel for #ident {
                fn rotor_count(&self) -> usize { #n }
                fn lattice_spacing(&self) -> f64 { #a }
                fn rotor_length(&self, i: usize) -> f64 { self.__rotor_chain_rotor_length(i) }
                fn mass(&self) -> f64 { #mass }
                fn theta_bar(&self) -> f64 { #theta_bar }
                fn stiffness(&self, p: usize) -> f64 { self.__rotor_chain_stiffness(p) }
                fn rest_length(&self, p: usize) -> f64 { self.__rotor_chain_rest_length(#lbar, p) }
                #trait_bodies
            }
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
