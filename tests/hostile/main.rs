//! Hostile inputs (issue 10), one module per class, in one test binary to keep the suite's build
//! short. What each layer guarantees is in `docs/guarantees.md`.

mod builder_rules;
mod linkage_law;
mod output_lengths;
mod stack;
mod statics_inputs;
