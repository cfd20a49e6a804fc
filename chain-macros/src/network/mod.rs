//! The `#[rotor_network]` attribute: a patch of a periodic network (a cell file or a ready cell,
//! its size and boundary, a spring law, overrides) as a struct implementing the capability
//! traits, with the bond kernels derived at compile time. The pipeline of `#[rotor_chain]`, one
//! file per phase and its pieces reused (the error collector, the key helpers and "did you
//! mean", the law parser): `attr` parses, `valid` checks and reads the cell through `chain-cell`,
//! `expand` derives the kernels and emits.

mod attr;
mod expand;
mod valid;

use proc_macro2::{Span, TokenStream};
use quote::quote;

use crate::ctxt::Ctxt;
use crate::model::PRIVATE;

/// The expansion of `#[rotor_network(attr)] item`.
pub fn expand(attr: TokenStream, item: TokenStream) -> TokenStream {
    let parsed = match syn::parse2::<syn::ItemStruct>(item.clone()) {
        Ok(s) => s,
        Err(_) => {
            let err = syn::Error::new(Span::call_site(), "#[rotor_network] goes on a struct");
            return fallback(&item, None, err);
        }
    };
    let cx = Ctxt::new();
    if !parsed.generics.params.is_empty() {
        cx.error_spanned_by(
            &parsed.generics,
            "#[rotor_network] goes on a struct without generic parameters: its model is built once per type",
        );
    }
    let spec = attr::parse(&cx, attr);
    let model = valid::validate(&cx, spec);
    let stubs = parsed.generics.params.is_empty().then_some(&parsed.ident);
    match (cx.check(), model) {
        (Err(errors), _) => fallback(&item, stubs, errors),
        (Ok(()), Some(model)) => {
            let generated = expand::emit(&parsed, &model);
            quote! {
                #item
                #generated
            }
        }
        (Ok(()), None) => {
            let err = syn::Error::new(Span::call_site(), "#[rotor_network]: the model is incomplete");
            fallback(&item, stubs, err)
        }
    }
}

/// The user's item unchanged, the errors, and (for a struct without generics) stubs of every
/// generated method, so the user sees the errors about the attribute and not a cascade of
/// "the trait `Potential` is not implemented" at every use. The stubs need no `network`
/// feature and cannot run: the crate does not compile.
fn fallback(item: &TokenStream, ident: Option<&syn::Ident>, errors: syn::Error) -> TokenStream {
    let errors = errors.to_compile_error();
    let p: TokenStream = PRIVATE.parse().expect("path");
    let stubs = ident.map(|ident| {
        let stub = quote!(#p::invalid_chain());
        let impls = expand::capability_impls(ident, &|_, _, _| stub.clone(), stub.clone());
        quote!(const _: () = { #impls };)
    });
    quote! {
        #item
        #errors
        #stubs
    }
}

#[cfg(test)]
mod tests {
    use quote::quote;

    /// A cell file's text enters the output through `include_str!` of its absolute path, so
    /// rustc tracks the file and a change to it rebuilds the crate; a ready cell needs no file.
    #[test]
    fn a_cell_file_is_included_so_that_a_change_rebuilds() {
        let item = quote!(
            struct Kagome;
        );
        let file = super::expand(
            quote!(cell = "../docs/cells/kagome.toml", cells = (2, 2), boundary = "free"),
            item.clone(),
        )
        .to_string();
        let dir = env!("CARGO_MANIFEST_DIR");
        assert!(
            file.contains(&format!(":: core :: include_str ! (\"{dir}/../docs/cells/kagome.toml\")")),
            "{file}"
        );
        assert!(!file.contains("compile_error"), "a valid declaration");
        let ready =
            super::expand(quote!(ready = "kagome", cells = (2, 2), boundary = "free"), item).to_string();
        assert!(!ready.contains("include_str") && ready.contains("CellSource :: Ready (\"kagome\")"));
    }
}
