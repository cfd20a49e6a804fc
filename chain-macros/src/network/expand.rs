//! Phase 3 and 4 of `#[rotor_network]`: derive each bond type's kernels with the law in
//! `chain-symbolic` (`bond::BondKernels`, the derivation the run-time model's checked-in kernels
//! come from) and emit them as a hidden module, with the capability traits (`Potential`,
//! `Stiffness`, `SpringNetwork`) on the user's struct.
//!
//! The struct's model is a `chain_network::NetworkModel` built once, at the first call, from the
//! cell (a file's text taken in with `include_str!`, so a change to the file rebuilds the crate,
//! or a ready cell), the patch and the overrides, with the generated kernels
//! (`NetworkModelBuilder::kernels`): the patch building, the bond grouping, the sparse patterns
//! and the lane drivers are the run-time model's own. Every trait method forwards to it; on
//! errors the same methods are stubs (`fallback`). Generated code reaches support items only
//! through `::rotor_chain::__private`.

use chain_symbolic::bond::BondKernels;
use chain_symbolic::{Graph, SpringLaw};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};
use syn::ItemStruct;

use super::valid::{Model, Source};
use crate::model::PRIVATE;

fn private() -> TokenStream {
    PRIVATE.parse().expect("path")
}

/// One method of the capability traits the struct implements: the trait, the name, the
/// parameters (after `&self`) with their types, and the return type.
struct Method {
    rung: &'static str,
    name: &'static str,
    params: &'static [(&'static str, &'static str)],
    returns: &'static str,
}

const X: (&str, &str) = ("x", "&[f64]");
const OUT: (&str, &str) = ("out", "&mut [f64]");
const VALUES: (&str, &str) = ("values", "&mut [f64]");

/// Every method `NetworkModel` implements (the traits' provided methods keep their defaults,
/// as on the model).
const METHODS: [Method; 18] = [
    Method { rung: "Potential", name: "dof_count", params: &[], returns: "usize" },
    Method { rung: "Potential", name: "inertia", params: &[("i", "usize")], returns: "f64" },
    Method { rung: "Potential", name: "energy", params: &[X], returns: "f64" },
    Method { rung: "Potential", name: "gradient_into", params: &[X, OUT], returns: "()" },
    Method { rung: "Potential", name: "energy_and_gradient_into", params: &[X, OUT], returns: "f64" },
    Method { rung: "Potential", name: "energy_floor", params: &[], returns: "f64" },
    Method { rung: "Stiffness", name: "stiffness_layout", params: &[], returns: "StiffnessLayout<'_>" },
    Method { rung: "Stiffness", name: "tangent_stiffness_into", params: &[X, VALUES], returns: "()" },
    Method {
        rung: "Stiffness",
        name: "energy_gradient_stiffness_into",
        params: &[X, ("grad", "&mut [f64]"), VALUES],
        returns: "f64",
    },
    Method { rung: "SpringNetwork", name: "spring_count", params: &[], returns: "usize" },
    Method { rung: "SpringNetwork", name: "spring_constant", params: &[("p", "usize")], returns: "f64" },
    Method { rung: "SpringNetwork", name: "rest_length", params: &[("p", "usize")], returns: "f64" },
    Method { rung: "SpringNetwork", name: "spring_lengths_into", params: &[X, OUT], returns: "()" },
    Method { rung: "SpringNetwork", name: "tensions_into", params: &[X, OUT], returns: "()" },
    Method {
        rung: "SpringNetwork",
        name: "compatibility_layout",
        params: &[],
        returns: "CompatibilityLayout<'_>",
    },
    Method { rung: "SpringNetwork", name: "compatibility_into", params: &[X, VALUES], returns: "()" },
    Method { rung: "SpringNetwork", name: "material_stiffness_into", params: &[X, VALUES], returns: "()" },
    Method { rung: "SpringNetwork", name: "stress_matrix_into", params: &[X, VALUES], returns: "()" },
];

/// The three trait impls and the inherent `reference()` on `ident`, each trait method's body
/// made by `body(trait path, method, argument names)`: forwarding to the model, or a stub.
pub fn capability_impls(
    ident: &syn::Ident,
    body: &dyn Fn(&TokenStream, &syn::Ident, &[syn::Ident]) -> TokenStream,
    reference: TokenStream,
) -> TokenStream {
    let impls = ["Potential", "Stiffness", "SpringNetwork"].map(|rung| {
        let trait_path: TokenStream = format!("{PRIVATE}::{rung}").parse().expect("path");
        let methods = METHODS.iter().filter(|m| m.rung == rung).map(|m| {
            let name = format_ident!("{}", m.name);
            let args: Vec<syn::Ident> = m.params.iter().map(|(n, _)| format_ident!("{n}")).collect();
            let types: Vec<TokenStream> = m.params.iter().map(|(_, t)| t.parse().expect("type")).collect();
            let returns: TokenStream = match m.returns {
                "StiffnessLayout<'_>" | "CompatibilityLayout<'_>" => format!("{PRIVATE}::{}", m.returns),
                other => other.to_owned(),
            }
            .parse()
            .expect("type");
            let body = body(&trait_path, &name, &args);
            quote! {
                #[track_caller]
                fn #name(&self, #(#args: #types),*) -> #returns { #body }
            }
        });
        quote! {
            #[automatically_derived]
            #[allow(unused_variables)]
            impl #trait_path for #ident {
                #(#methods)*
            }
        }
    });
    quote! {
        #(#impls)*
        #[automatically_derived]
        impl #ident {
            /// The reference configuration of the network: every joint's position and every
            /// rotor's angle in the patch's cells, in the order of the degrees of freedom
            /// (stress-free at the cell's own rest lengths).
            pub fn reference(&self) -> ::std::vec::Vec<f64> { #reference }
        }
    }
}

/// The whole expansion for a valid network.
pub fn emit(item: &ItemStruct, model: &Model) -> TokenStream {
    let p = private();
    let ident = &item.ident;
    let law = model.law.clone();
    let kernels = BondKernels::new(&move |g: &mut Graph| match &law {
        Some(law) => law.build(g),
        None => SpringLaw::harmonic(g),
    });
    let rendered: TokenStream = kernels
        .render()
        .expect("a bond kernel names only its arguments")
        .parse()
        .expect("rendered kernels parse");
    let source = match &model.source {
        Source::File(path) => {
            let path = Literal::string(path);
            quote!(#p::network::CellSource::Toml(::core::include_str!(#path)))
        }
        Source::Ready(name) => {
            let name = Literal::string(name);
            quote!(#p::network::CellSource::Ready(#name))
        }
    };
    let [n1, n2] = model.cells;
    let periodic = model.periodic;
    let mass = Literal::f64_suffixed(model.mass);
    let option = |v: Option<f64>| match v {
        Some(v) => {
            let v = Literal::f64_suffixed(v);
            quote!(::core::option::Option::Some(#v))
        }
        None => quote!(::core::option::Option::None),
    };
    let springs = model.springs.iter().map(|&(s, k, l0)| {
        let (k, l0) = (option(k), option(l0));
        quote!((#s, #k, #l0))
    });
    let nodes = model.nodes.iter().map(|&([i, j], node, mass)| {
        let mass = Literal::f64_suffixed(mass);
        quote!(([#i, #j], #node, #mass))
    });
    let impls = capability_impls(
        ident,
        &|trait_path, name, args| quote!(#trait_path::#name(__rotor_network_model(), #(#args),*)),
        quote!(__rotor_network_model().reference()),
    );
    quote! {
        const _: () = {
            #p::require_network!();

            /// The bond kernels of the law, derived by the symbolic engine at compile time.
            #[doc(hidden)]
            #[allow(dead_code, unused_imports, clippy::all)]
            mod __rotor_network_kernels {
                use ::rotor_chain::__private::network::{BondFn, BondKernels, Lane, LawKernels};
                #rendered
            }

            /// The model, built at the first call.
            fn __rotor_network_model() -> &'static #p::network::NetworkModel {
                static MODEL: #p::network::OnceLock<#p::network::NetworkModel> = #p::network::OnceLock::new();
                MODEL.get_or_init(|| {
                    #p::network::model::<__rotor_network_kernels::Law>(
                        #source,
                        [#n1, #n2],
                        #periodic,
                        #mass,
                        &[#(#springs),*],
                        &[#(#nodes),*],
                    )
                })
            }

            #impls
        };
    }
}
