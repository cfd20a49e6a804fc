//! Helpers shared by the integration tests (and, through `#[path]`, the examples).
// Each test binary and example uses a part of these helpers.
#![allow(dead_code)]

pub mod random;
pub mod ulp;
