//! When the model is invalid: emit the user's struct unchanged plus the errors, so the user sees
//! the errors about the attribute and not a cascade of "no method `energy`" (thiserror's
//! `fallback.rs`).

use proc_macro2::TokenStream;
use quote::quote;

pub fn emit(item: &TokenStream, errors: syn::Error) -> TokenStream {
    let errors = errors.to_compile_error();
    quote! {
        #item
        #errors
    }
}
