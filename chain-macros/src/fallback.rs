//! When the model is invalid: emit the user's struct unchanged, the errors, and stubs of every
//! generated item (thiserror's `fallback.rs`), so the user sees the errors about the attribute and
//! not a cascade of "no method named `energy`" at every call.
//!
//! The stubs have the real signatures (`N` known) or signatures generic over the array length
//! (`n` itself invalid), and bodies that call `__private::invalid_chain()`: the crate does not
//! compile, because of the errors, so no stub can run.

use chain_symbolic::Float;
use proc_macro2::{Ident, TokenStream};
use quote::quote;
use syn::Generics;

use crate::expand::{Returns, fits_on_stack};
use crate::model::{PRIVATE, float_type};

/// What the stubs are generated for: the item's name and generics, `n` if it is valid, and the
/// float type (`f64` unless `float = f32` was given and valid).
pub struct Stubs {
    ident: Ident,
    generics: Generics,
    n: Option<usize>,
    float: Float,
}

impl Stubs {
    pub fn new(ident: &Ident, generics: &Generics, n: Option<usize>, float: Float) -> Self {
        Self { ident: ident.clone(), generics: generics.clone(), n, float }
    }

    fn tokens(&self) -> TokenStream {
        let p: TokenStream = PRIVATE.parse().expect("path");
        let body = quote!({ #p::invalid_chain() });
        let ident = &self.ident;
        let (impl_generics, ty_generics, where_clause) = self.generics.split_for_impl();
        // Per method: its generic parameters, the array length of `theta`, and the return type.
        let (generic_n, generic_nm, n_ty, m_ty, n_value) = match self.n {
            Some(n) => {
                let m = n - 1;
                (quote!(), quote!(), quote!(#n), quote!(#m), n)
            }
            // An invalid `n`: the length of `theta` fixes `K`, and the spring count is `K` too
            // (a free `L` could not be inferred from the arguments, so an unannotated
            // `let t = chain.tangent_stiffness(&theta);` added a "type annotations needed" error).
            None => (quote!(<const K: usize>), quote!(<const K: usize>), quote!(K), quote!(K), 2),
        };
        let m_value = n_value - 1;
        // The methods the real expansion would have for this `n` (all of them for an unknown `n`).
        let exists = |values: usize, result| self.n.is_none_or(|_| fits_on_stack(values, result, self.float));
        let t = float_type(self.float);
        let theta = quote!(theta: &[#t; #n_ty]);
        let method = |name: TokenStream, values: usize, returns, ret: TokenStream, generics: &TokenStream| {
            exists(values, returns).then(|| quote!(pub fn #name #generics (&self, #theta) -> #ret #body))
        };
        let tridiagonal = quote!(#p::Tridiagonal<#n_ty, #m_ty, #t>);
        let verlet = quote!(::core::result::Result<#p::Verlet<#t, [#t; #n_ty]>, #p::IntegrateError>);
        let methods = [
            Some(quote!(pub fn energy #generic_n (&self, #theta) -> #t #body)),
            method(quote!(gradient), n_value, Returns::Array, quote!([#t; #n_ty]), &generic_n),
            method(
                quote!(tangent_stiffness),
                n_value + m_value,
                Returns::Banded,
                tridiagonal.clone(),
                &generic_nm,
            ),
            method(
                quote!(material_stiffness),
                n_value + m_value,
                Returns::Banded,
                tridiagonal.clone(),
                &generic_nm,
            ),
            method(quote!(stress_matrix), n_value + m_value, Returns::Banded, tridiagonal, &generic_nm),
            method(quote!(spring_lengths), m_value, Returns::Array, quote!([#t; #m_ty]), &generic_nm),
            method(quote!(tensions), m_value, Returns::Array, quote!([#t; #m_ty]), &generic_nm),
            method(
                quote!(compatibility),
                2 * m_value,
                Returns::Banded,
                quote!(#p::Bidiagonal<#m_ty, #n_ty, #t>),
                &generic_nm,
            ),
            // The fused methods exist on `f64` chains only (`expand::emit`).
            method(
                quote!(energy_and_gradient),
                n_value + 1,
                Returns::Array,
                quote!((f64, [f64; #n_ty])),
                &generic_n,
            )
            .filter(|_| self.float == Float::F64),
            method(
                quote!(energy_gradient_stiffness),
                3 * n_value,
                Returns::Banded,
                quote!((f64, [f64; #n_ty], #p::Tridiagonal<#n_ty, #m_ty>)),
                &generic_nm,
            )
            .filter(|_| self.float == Float::F64),
            method(
                quote!(hessian),
                n_value * n_value,
                Returns::Dense,
                quote!(#p::SMatrix<#t, #n_ty, #n_ty>),
                &generic_n,
            ),
            exists(4 * n_value, Returns::Array).then(|| {
                quote!(pub fn verlet #generic_n (&self, theta: [#t; #n_ty], omega: [#t; #n_ty], dt: #t) -> #verlet #body)
            }),
        ];
        let methods = methods.into_iter().flatten();
        let traits = crate::traits::stub_impls(ident, &self.generics, self.float, &body);
        quote! {
            const _: () = {
                #[automatically_derived]
                #[allow(unused_variables, dead_code, clippy::all, clippy::pedantic)]
                impl #impl_generics #ident #ty_generics #where_clause {
                    pub const N: usize = #n_value;
                    pub const SPRINGS: usize = #m_value;
                    #(#methods)*
                    pub fn check(&self) -> ::core::result::Result<(), #p::ParameterError> #body
                }

                #traits
            };
        }
    }
}

/// The item unchanged, the errors, and the stubs (if the item can carry them).
pub fn emit(item: &TokenStream, stubs: Option<&Stubs>, errors: syn::Error) -> TokenStream {
    let errors = errors.to_compile_error();
    let stubs = stubs.map(Stubs::tokens);
    quote! {
        #item
        #errors
        #stubs
    }
}
