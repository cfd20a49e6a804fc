//! The model traits a chain implements (`chain_core::model`: the capability ladder `Potential`,
//! `Stiffness`, `SpringNetwork`, `ChainGeometry`), as one table of their methods and signatures.
//! The expansion fills it with generated bodies and the fallback with stubs, so the two cannot
//! disagree on a signature.

use chain_symbolic::Float;
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};
use syn::Generics;

use crate::model::{PRIVATE, float_type};

/// A rung of the ladder, in order.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Rung {
    Potential,
    Stiffness,
    SpringNetwork,
    ChainGeometry,
}

impl Rung {
    const ALL: [Rung; 4] = [Rung::Potential, Rung::Stiffness, Rung::SpringNetwork, Rung::ChainGeometry];

    fn name(self) -> &'static str {
        match self {
            Rung::Potential => "Potential",
            Rung::Stiffness => "Stiffness",
            Rung::SpringNetwork => "SpringNetwork",
            Rung::ChainGeometry => "ChainGeometry",
        }
    }
}

/// The buffers a slice method fills after `theta`: one value per rotor, one per spring, or a
/// matrix in the chain's layout (tridiagonal `diag` then `off`; bidiagonal `left` then `right`),
/// which the body sees under those names.
pub(crate) enum Output {
    PerRotor(&'static str),
    PerSpring(&'static str),
    Tridiagonal,
    Bidiagonal,
}

/// A slice method of a rung: its name, buffers, and whether it returns the energy. `fused`
/// methods have defaults in the trait and are implemented only where a one-pass body exists.
pub(crate) struct SliceMethod {
    pub name: &'static str,
    rung: Rung,
    outputs: &'static [Output],
    energy: bool,
    pub fused: bool,
}

/// Every slice method, in the order of the traits.
pub(crate) const SLICE_METHODS: [SliceMethod; 10] = [
    SliceMethod { name: "energy", rung: Rung::Potential, outputs: &[], energy: true, fused: false },
    SliceMethod {
        name: "gradient_into",
        rung: Rung::Potential,
        outputs: &[Output::PerRotor("out")],
        energy: false,
        fused: false,
    },
    SliceMethod {
        name: "energy_and_gradient_into",
        rung: Rung::Potential,
        outputs: &[Output::PerRotor("out")],
        energy: true,
        fused: true,
    },
    SliceMethod {
        name: "tangent_stiffness_into",
        rung: Rung::Stiffness,
        outputs: &[Output::Tridiagonal],
        energy: false,
        fused: false,
    },
    SliceMethod {
        name: "energy_gradient_stiffness_into",
        rung: Rung::Stiffness,
        outputs: &[Output::PerRotor("grad"), Output::Tridiagonal],
        energy: true,
        fused: true,
    },
    SliceMethod {
        name: "spring_lengths_into",
        rung: Rung::SpringNetwork,
        outputs: &[Output::PerSpring("out")],
        energy: false,
        fused: false,
    },
    SliceMethod {
        name: "tensions_into",
        rung: Rung::SpringNetwork,
        outputs: &[Output::PerSpring("out")],
        energy: false,
        fused: false,
    },
    SliceMethod {
        name: "compatibility_into",
        rung: Rung::SpringNetwork,
        outputs: &[Output::Bidiagonal],
        energy: false,
        fused: false,
    },
    SliceMethod {
        name: "material_stiffness_into",
        rung: Rung::SpringNetwork,
        outputs: &[Output::Tridiagonal],
        energy: false,
        fused: false,
    },
    SliceMethod {
        name: "stress_matrix_into",
        rung: Rung::SpringNetwork,
        outputs: &[Output::Tridiagonal],
        energy: false,
        fused: false,
    },
];

/// What an accessor returns.
#[derive(Clone, Copy)]
enum Returns {
    Count,
    Float,
    StiffnessLayout,
    CompatibilityLayout,
}

/// The accessors every chain implements: rung, name, index parameter, return type.
const ACCESSORS: [(Rung, &str, Option<&str>, Returns); 12] = [
    (Rung::Potential, "dof_count", None, Returns::Count),
    (Rung::Potential, "inertia", Some("i"), Returns::Float),
    (Rung::Potential, "energy_floor", None, Returns::Float),
    (Rung::Stiffness, "stiffness_layout", None, Returns::StiffnessLayout),
    (Rung::SpringNetwork, "spring_count", None, Returns::Count),
    (Rung::SpringNetwork, "spring_constant", Some("p"), Returns::Float),
    (Rung::SpringNetwork, "rest_length", Some("p"), Returns::Float),
    (Rung::SpringNetwork, "compatibility_layout", None, Returns::CompatibilityLayout),
    (Rung::ChainGeometry, "lattice_spacing", None, Returns::Float),
    (Rung::ChainGeometry, "rotor_length", Some("i"), Returns::Float),
    (Rung::ChainGeometry, "mass", None, Returns::Float),
    (Rung::ChainGeometry, "theta_bar", None, Returns::Float),
];

fn private() -> TokenStream {
    PRIVATE.parse().expect("the private path parses")
}

/// The slice method `name` of a chain of `n` rotors in `float`, with `body` (a block): its
/// signature; the check that every buffer has one value per rotor or per spring, as
/// `RuntimeChain`'s methods check them (the panic names the slice and the counts, at the caller's
/// line); and a matrix buffer split into the bands the body names. Like `RuntimeChain`'s,
/// `energy_and_gradient_into` goes without `#[track_caller]`, the hot path of the integrators
/// (docs/benchmarks.md).
pub(crate) fn slice_method(n: usize, float: Float, name: &str, body: TokenStream) -> TokenStream {
    let (p, t) = (private(), float_type(float));
    let method = SLICE_METHODS.iter().find(|m| m.name == name).expect("a slice method of the model traits");
    let ident = format_ident!("{name}");
    let mut params = Vec::new();
    let (mut per_rotor, mut per_spring, mut splits) = (Vec::new(), Vec::new(), Vec::new());
    for output in method.outputs {
        match output {
            Output::PerRotor(s) | Output::PerSpring(s) => {
                let slice = format_ident!("{s}");
                params.push(quote!(#slice: &mut [#t]));
                let check = quote!((#s, #slice.len()));
                if matches!(output, Output::PerRotor(_)) {
                    per_rotor.push(check)
                } else {
                    per_spring.push(check)
                }
            }
            Output::Tridiagonal => {
                params.push(quote!(values: &mut [#t]));
                splits.push(quote!(let (diag, off) = #p::split_tridiagonal(#n, values);));
            }
            Output::Bidiagonal => {
                params.push(quote!(values: &mut [#t]));
                let m = n - 1;
                splits.push(quote!(let (left, right) = #p::split_bidiagonal(#m, values);));
            }
        }
    }
    let returns = method.energy.then(|| quote!(-> #t));
    let track = (name != "energy_and_gradient_into").then(|| quote!(#[track_caller]));
    quote! {
        #track
        fn #ident(&self, theta: &[#t] #(, #params)*) #returns {
            #p::check_lengths(#n, theta.len(), &[#(#per_rotor),*], &[#(#per_spring),*]);
            #(#splits)*
            #body
        }
    }
}

/// The signature of a stub slice method (any `n`), for the fallback.
fn stub_slice_method(float: Float, method: &SliceMethod, body: &TokenStream) -> TokenStream {
    let t = float_type(float);
    let ident = format_ident!("{}", method.name);
    let params = method.outputs.iter().map(|o| match o {
        Output::PerRotor(s) | Output::PerSpring(s) => {
            let slice = format_ident!("{s}");
            quote!(#slice: &mut [#t])
        }
        Output::Tridiagonal | Output::Bidiagonal => quote!(values: &mut [#t]),
    });
    let returns = method.energy.then(|| quote!(-> #t));
    quote!(fn #ident(&self, theta: &[#t] #(, #params)*) #returns #body)
}

/// An accessor with `body`.
fn accessor(
    float: Float,
    name: &str,
    index: Option<&str>,
    returns: Returns,
    body: &TokenStream,
) -> TokenStream {
    let (p, t) = (private(), float_type(float));
    let ident = format_ident!("{name}");
    let index = index.map(|i| {
        let i = format_ident!("{i}");
        quote!(, #i: usize)
    });
    let ret = match returns {
        Returns::Count => quote!(usize),
        Returns::Float => quote!(#t),
        Returns::StiffnessLayout => quote!(#p::StiffnessLayout<'_>),
        Returns::CompatibilityLayout => quote!(#p::CompatibilityLayout<'_>),
    };
    quote!(#[inline] fn #ident(&self #index) -> #ret #body)
}

/// The four impls of `ident` in `float`: every accessor with the body `accessors(name)` gives,
/// and the slice methods whose bodies `slices` holds (the fused ones only where present).
pub(crate) fn impls(
    ident: &Ident,
    generics: &Generics,
    float: Float,
    accessors: &dyn Fn(&str) -> TokenStream,
    slices: &dyn Fn(&SliceMethod) -> Option<TokenStream>,
) -> TokenStream {
    let (p, t) = (private(), float_type(float));
    let (impl_generics, ty_generics, where_clause) = generics.split_for_impl();
    let impls = Rung::ALL.map(|rung| {
        let trait_ident = format_ident!("{}", rung.name());
        let accessors = ACCESSORS
            .iter()
            .filter(|a| a.0 == rung)
            .map(|&(_, name, index, returns)| accessor(float, name, index, returns, &accessors(name)));
        let methods = SLICE_METHODS.iter().filter(|m| m.rung == rung).filter_map(slices);
        quote! {
            #[automatically_derived]
            #[allow(clippy::all, clippy::pedantic, unused_variables)]
            impl #impl_generics #p::#trait_ident<#t> for #ident #ty_generics #where_clause {
                #(#accessors)*
                #(#methods)*
            }
        }
    });
    quote!(#(#impls)*)
}

/// The four impls with stub bodies (the fallback of an invalid chain): the required methods only.
pub(crate) fn stub_impls(
    ident: &Ident,
    generics: &Generics,
    float: Float,
    body: &TokenStream,
) -> TokenStream {
    impls(ident, generics, float, &|_| body.clone(), &|m: &SliceMethod| {
        (!m.fused).then(|| stub_slice_method(float, m, body))
    })
}
