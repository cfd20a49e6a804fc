//! The `#[rotor_chain]` attribute macro.
//!
//! A thin entry over a pipeline of named phases, one file each:
//! `attr` parses the attribute into a typed `attr::Spec` that keeps every span,
//! `valid` checks it against the chain's rules (all errors at once, each at its key),
//! `law` turns a custom spring law into the symbolic graph,
//! `model` builds the chain's energy in `chain-symbolic` and derives everything from it,
//! `expand` emits the code, and `fallback` emits the bare struct plus the errors when the
//! model is invalid. See `docs/macro.md` for the keys.
#![deny(missing_docs)]

mod attr;
mod ctxt;
mod expand;
mod fallback;
#[cfg(test)]
mod fuzz;
mod law;
mod model;
mod network;
mod traits;
mod valid;

use proc_macro::TokenStream;

/// *Defined in the `chain-macros` crate; documented, with a runnable example of every key, on its
/// re-export `rotor_chain::rotor_chain` (the facade's `src/attribute.md`, whose examples are the
/// facade's doctests: testing them here would need the facade as a dev-dependency of this
/// proc-macro crate, which builds the facade and its dependencies a second time, for the host).*
#[proc_macro_attribute]
pub fn rotor_chain(attr: TokenStream, item: TokenStream) -> TokenStream {
    expand::expand(attr.into(), item.into()).into()
}

/// *Defined in the `chain-macros` crate; documented, with runnable examples, on its re-export
/// `rotor_chain::rotor_network` (docs/network.md §10.1 and the facade's doctests).*
#[proc_macro_attribute]
pub fn rotor_network(attr: TokenStream, item: TokenStream) -> TokenStream {
    network::expand(attr.into(), item.into()).into()
}
