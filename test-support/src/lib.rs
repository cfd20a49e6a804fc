//! Helpers shared by the tests and examples of every crate in the workspace (a dev-dependency
//! only, never published): the one reproducible random generator ([`random::SplitMix`]) and the
//! correctly rounded `sin`/`cos` reference with ulp distances ([`ulp`]), an address-space limit on
//! the test process ([`memory`]), and the checks of the
//! options tests of chain-core, chain-network and chain-sweep ([`options`]).

pub mod memory;
pub mod options;
pub mod random;
pub mod ulp;

/// The arbitrary-precision floats behind [`ulp::reference`], for tests that need more digits.
pub use dashu_float;
