//! The symbolic engine of `rotor-chain`.
//!
//! It knows nothing of `proc_macro`: the `#[rotor_chain]` macro builds a chain's energy here, and so
//! does the generator of `chain-core`'s runtime kernel, so both get their derivatives from one place.
//!
//! The pipeline, one module per phase:
//! - [`graph`]: a hash-consed arena of expression nodes, children before parents. Every node is
//!   interned, so common subexpressions are shared the moment they are built, and the smart
//!   constructors simplify as they go (constant folding, identities).
//! - [`diff`]: symbolic differentiation with one table of local partial derivatives per operation.
//! - [`lower()`]: a straight-line program (one `let` per shared node, in arena order) for a chosen set
//!   of outputs; it implements `Display` so generated code can be read and snapshotted.
//! - [`spring`]: the physics in symbols: the length of spring `p` in the rotor angles (paper
//!   Eq. `eq:instantlength`), a spring law, and everything derived from them (paper Appendix D).
//! - [`chain`]: a whole chain unrolled spring by spring, and the per-spring kernel rendered once.
//! - [`bond`]: a network's bond of each type (joint-joint, joint-rotor, rotor-rotor) and its
//!   kernels rendered once per law (issue 36).

pub mod bond;
pub mod diff;
pub mod graph;
pub mod lower;
pub mod spring;

pub use graph::{Graph, Id, Node};
pub use lower::{Float, Program, lower};
pub use spring::{SpringLaw, SpringParams, SpringTerms};
pub mod chain;
pub use chain::{ChainOutputs, SpringSpec};
