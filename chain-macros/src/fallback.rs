//! When the model is invalid: emit the user's struct unchanged, the errors, and stubs of every
//! generated item (thiserror's `fallback.rs`), so the user sees the errors about the attribute and
//! not a cascade of "no method named `energy`" at every call.
//!
//! The stubs have the real signatures (`N` known) or signatures generic over the array length
//! (`n` itself invalid), and bodies that call `__private::invalid_chain()`: the crate does not
//! compile, because of the errors, so no stub can run.

use proc_macro2::{Ident, TokenStream};
use quote::quote;
use syn::Generics;

use crate::expand::{Returns, fits_on_stack};
use crate::model::PRIVATE;

/// What the stubs are generated for: the item's name and generics, and `n` if it is valid.
pub struct Stubs {
    ident: Ident,
    generics: Generics,
    n: Option<usize>,
}

impl Stubs {
    pub fn new(ident: &Ident, generics: &Generics, n: Option<usize>) -> Self {
        Self { ident: ident.clone(), generics: generics.clone(), n }
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
            None => {
                (quote!(<const K: usize>), quote!(<const K: usize, const L: usize>), quote!(K), quote!(L), 2)
            }
        };
        let m_value = n_value - 1;
        // The methods the real expansion would have for this `n` (all of them for an unknown `n`).
        let exists = |values: usize, result| self.n.is_none_or(|_| fits_on_stack(values, result));
        let theta = quote!(theta: &[f64; #n_ty]);
        let method = |name: TokenStream, values: usize, returns, ret: TokenStream, generics: &TokenStream| {
            exists(values, returns).then(|| quote!(pub fn #name #generics (&self, #theta) -> #ret #body))
        };
        let tridiagonal = quote!(#p::Tridiagonal<#n_ty, #m_ty>);
        let methods = [
            Some(quote!(pub fn energy #generic_n (&self, #theta) -> f64 #body)),
            method(quote!(gradient), n_value, Returns::Array, quote!([f64; #n_ty]), &generic_n),
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
            method(quote!(spring_lengths), m_value, Returns::Array, quote!([f64; #m_ty]), &generic_nm),
            method(quote!(tensions), m_value, Returns::Array, quote!([f64; #m_ty]), &generic_nm),
            method(
                quote!(compatibility),
                2 * m_value,
                Returns::Banded,
                quote!(#p::Bidiagonal<#m_ty, #n_ty>),
                &generic_nm,
            ),
            method(
                quote!(hessian),
                n_value * n_value,
                Returns::Dense,
                quote!(#p::SMatrix<f64, #n_ty, #n_ty>),
                &generic_n,
            ),
        ];
        let methods = methods.into_iter().flatten();
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

                #[automatically_derived]
                #[allow(unused_variables, clippy::all, clippy::pedantic)]
                impl #impl_generics #p::ChainModel for #ident #ty_generics #where_clause {
                    fn rotor_count(&self) -> usize #body
                    fn lattice_spacing(&self) -> f64 #body
                    fn rotor_length(&self, i: usize) -> f64 #body
                    fn mass(&self) -> f64 #body
                    fn theta_bar(&self) -> f64 #body
                    fn stiffness(&self, p: usize) -> f64 #body
                    fn rest_length(&self, p: usize) -> f64 #body
                    fn energy(&self, theta: &[f64]) -> f64 #body
                    fn gradient_into(&self, theta: &[f64], out: &mut [f64]) #body
                    fn tangent_stiffness_into(&self, theta: &[f64], diag: &mut [f64], off: &mut [f64]) #body
                    fn material_stiffness_into(&self, theta: &[f64], diag: &mut [f64], off: &mut [f64]) #body
                    fn stress_matrix_into(&self, theta: &[f64], diag: &mut [f64], off: &mut [f64]) #body
                    fn spring_lengths_into(&self, theta: &[f64], out: &mut [f64]) #body
                    fn tensions_into(&self, theta: &[f64], out: &mut [f64]) #body
                    fn compatibility_into(&self, theta: &[f64], left: &mut [f64], right: &mut [f64]) #body
                }
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
