//! Helpers shared by the integration tests (and, through `#[path]`, the examples).
pub mod ulp;
