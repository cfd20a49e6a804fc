//! Phase 4: emit the code. Two strategies from the one derivation:
//! - unrolled (n <= `unroll`, default 128): every function is straight-line code, one `sin_cos`
//!   per angle, every spring's parameters folded in;
//! - looped: the per-spring kernel (rendered once, as a hidden module) driven by
//!   `chain-core`'s loops, so n = 100000 compiles fast.
//!
//! Generated code reaches support items only through `::rotor_chain::__private`.

use chain_symbolic::chain::ChainOutputs;
use chain_symbolic::{Graph, Id, lower};
use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};
use syn::ItemStruct;

use crate::attr;
use crate::ctxt::Ctxt;
use crate::fallback;
use crate::model::{PRIVATE, math_prefix, value_tokens};
use crate::valid::{self, Model, Uniform};

/// The dense `hessian()` (an `N x N` matrix on the stack) is emitted up to this many rotors;
/// larger chains use the banded `tangent_stiffness()`.
pub const DENSE_LIMIT: usize = 256;

pub fn expand(attr: TokenStream, item: TokenStream) -> TokenStream {
    let parsed: ItemStruct = match syn::parse2(item.clone()) {
        Ok(s) => s,
        Err(_) => {
            // Point at the item's keyword (`enum`, `union`) when it is an item at all.
            let err = match syn::parse2::<syn::Item>(item.clone()) {
                Ok(syn::Item::Enum(e)) => {
                    syn::Error::new_spanned(e.enum_token, "#[rotor_chain] goes on a struct, not an enum")
                }
                Ok(syn::Item::Union(u)) => {
                    syn::Error::new_spanned(u.union_token, "#[rotor_chain] goes on a struct, not a union")
                }
                Ok(other) => syn::Error::new_spanned(other, "#[rotor_chain] goes on a struct"),
                Err(_) => syn::Error::new(Span::call_site(), "#[rotor_chain] goes on a struct"),
            };
            return fallback::emit(&item, err);
        }
    };
    let cx = Ctxt::new();
    let spec = attr::parse(&cx, attr);
    let model = valid::validate(&cx, spec, &parsed);
    match cx.check() {
        Err(errors) => fallback::emit(&item, errors),
        Ok(()) => {
            let model = model.expect("validation without errors yields a model");
            let generated = emit(&parsed, &model);
            quote! {
                #item
                #generated
            }
        }
    }
}

fn private() -> TokenStream {
    PRIVATE.parse().expect("path")
}

fn parse_block(src: &str) -> TokenStream {
    format!("{{\n{src}\n}}").parse().expect("generated source parses")
}

/// `match i { 3 => v3, _ => default }` (or just `default`).
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

enum Shape {
    Scalar,
    Array,
    Tridiagonal,
    Bidiagonal,
}

fn unrolled_body(g: &Graph, out: &ChainOutputs, ids: &[Id], shape: Shape) -> TokenStream {
    let math = math_prefix();
    let namer = out.leaf_namer(g);
    let program = lower(g, ids, &namer).expect("every symbol is a field or an angle");
    let mut src = String::new();
    for i in out.angles_used(g, ids) {
        src.push_str(&format!("let (s{i}, c{i}) = {math}sin_cos(theta[{i}]);\n"));
    }
    let (steps, outs) = program.render_registers("t", &math);
    src.push_str(&steps);
    let n = out.n;
    let p = PRIVATE;
    let value = match shape {
        Shape::Scalar => outs[0].clone(),
        Shape::Array => format!("[{}]", outs.join(", ")),
        Shape::Tridiagonal => {
            format!("{p}::Tridiagonal::new([{}], [{}])", outs[..n].join(", "), outs[n..].join(", "))
        }
        Shape::Bidiagonal => {
            let m = n - 1;
            format!("{p}::Bidiagonal::new([{}], [{}])", outs[..m].join(", "), outs[m..].join(", "))
        }
    };
    src.push_str(&value);
    parse_block(&src)
}

struct Bodies {
    energy: TokenStream,
    gradient: TokenStream,
    tangent_stiffness: TokenStream,
    material: TokenStream,
    stress: TokenStream,
    lengths: TokenStream,
    tensions: TokenStream,
    compatibility: TokenStream,
    support: TokenStream,
}

fn unrolled_bodies(model: &Model) -> Bodies {
    let (g, out) = model.unrolled_outputs();
    let cat = |a: &[Id], b: &[Id]| -> Vec<Id> { a.iter().chain(b).copied().collect() };
    Bodies {
        energy: unrolled_body(&g, &out, &[out.energy], Shape::Scalar),
        gradient: unrolled_body(&g, &out, &out.gradient, Shape::Array),
        tangent_stiffness: unrolled_body(
            &g,
            &out,
            &cat(&out.hessian_diag, &out.hessian_off),
            Shape::Tridiagonal,
        ),
        material: unrolled_body(&g, &out, &cat(&out.material_diag, &out.material_off), Shape::Tridiagonal),
        stress: unrolled_body(&g, &out, &cat(&out.stress_diag, &out.stress_off), Shape::Tridiagonal),
        lengths: unrolled_body(&g, &out, &out.lengths, Shape::Array),
        tensions: unrolled_body(&g, &out, &out.tensions, Shape::Array),
        compatibility: unrolled_body(
            &g,
            &out,
            &cat(&out.compatibility_left, &out.compatibility_right),
            Shape::Bidiagonal,
        ),
        support: TokenStream::new(),
    }
}

/// The looped strategy: the kernel module, and the trait's slice methods as kernel-driver calls
/// that write straight into the caller's buffers (no `n`-sized arrays on the stack, so very long
/// chains work through the trait with heap buffers). The inherent array methods wrap them.
fn looped_bodies(model: &Model, ident: &Ident) -> (Bodies, TokenStream) {
    let p = private();
    let (n, m) = (model.n, model.springs());
    let kmod = format_ident!("__rotor_chain_kernel_{}", valid::snake_name(ident));
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
    let blocks = |method: TokenStream| {
        quote!({
            let mut diag = [0.0f64; #n];
            let mut off = [0.0f64; #m];
            #t::#method(self, theta, &mut diag, &mut off);
            #p::Tridiagonal::new(diag, off)
        })
    };
    let per_spring = |method: TokenStream| {
        quote!({
            let mut out = [0.0f64; #m];
            #t::#method(self, theta, &mut out);
            out
        })
    };
    let bodies = Bodies {
        energy: quote!({ #t::energy(self, theta) }),
        gradient: quote!({
            let mut out = [0.0f64; #n];
            #t::gradient_into(self, theta, &mut out);
            out
        }),
        tangent_stiffness: blocks(quote!(tangent_stiffness_into)),
        material: blocks(quote!(material_stiffness_into)),
        stress: blocks(quote!(stress_matrix_into)),
        lengths: per_spring(quote!(spring_lengths_into)),
        tensions: per_spring(quote!(tensions_into)),
        compatibility: quote!({
            let mut left = [0.0f64; #m];
            let mut right = [0.0f64; #m];
            #t::compatibility_into(self, theta, &mut left, &mut right);
            #p::Bidiagonal::new(left, right)
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
        looped_bodies(model, ident)
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
    let hessian = (n <= DENSE_LIMIT).then(|| {
        quote! {
            /// The dense Hessian `d2V/dtheta_i dtheta_j` (the tangent stiffness as an `n x n` matrix).
            pub fn hessian(&self, theta: &[f64; #n]) -> #p::SMatrix<f64, #n, #n> {
                self.tangent_stiffness(theta).to_dense()
            }
        }
    });
    let strategy =
        if model.unrolled() { "unrolled straight-line code" } else { "the per-spring kernel in a loop" };
    let doc_strategy = format!(" Generated by `#[rotor_chain]` as {strategy}.");

    quote! {
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

            /// `dV/dtheta_i` for every rotor (the forces are its negative).
            #[doc = #doc_strategy]
            pub fn gradient(&self, theta: &[f64; #n]) -> [f64; #n] #gradient

            /// The tangent stiffness `d2V/dtheta_i dtheta_j`, tridiagonal (paper Eq. `eq:prestress8`).
            #[doc = #doc_strategy]
            pub fn tangent_stiffness(&self, theta: &[f64; #n]) -> #p::Tridiagonal<#n, #m> #tangent_stiffness

            #hessian

            /// The material part `sum_p g^_p a_p a_p^T` of the tangent stiffness, `a_p = dl_p/dtheta`
            /// (paper Appendix D).
            pub fn material_stiffness(&self, theta: &[f64; #n]) -> #p::Tridiagonal<#n, #m> #material

            /// The stress matrix `sum_p S_p` (paper Appendix D): material part + stress matrix = tangent stiffness.
            pub fn stress_matrix(&self, theta: &[f64; #n]) -> #p::Tridiagonal<#n, #m> #stress

            /// Spring lengths `l_p`.
            pub fn spring_lengths(&self, theta: &[f64; #n]) -> [f64; #m] #lengths

            /// Spring tensions `t_p = dlaw/dl` at the current lengths.
            pub fn tensions(&self, theta: &[f64; #n]) -> [f64; #m] #tensions

            /// The compatibility matrix `C[p][i] = dl_p / d(r_i theta_i)` (bidiagonal).
            pub fn compatibility(&self, theta: &[f64; #n]) -> #p::Bidiagonal<#m, #n> #compatibility

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
        assert!(text.contains("mod __rotor_chain_kernel_looped"), "{text}");
        assert!(text.contains("kernel::assemble_pairs"), "{text}");
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
        assert!(!text.contains("fn energy"), "{text}");
    }
}
