//! The pass cases of `#[rotor_chain]`: each file under `tests/pass/` declares chains the attribute
//! must accept and runs them (`main`). They were trybuild pass cases; as modules of this ordinary
//! test binary they compile with the rest of the suite, and trybuild (`tests/ui.rs`) is left with
//! compile-fail cases only, which it checks with `cargo check` in one build instead of building
//! every dependency with code generation and each case in a build of its own.

/// Runs a case's `main` on a thread with the 8 MiB stack a binary's main thread has: the
/// longest unrolled chain (`limits.rs`, 49 152 rotors) returns its gradient by value, and
/// unoptimised code keeps its temporaries on the stack (a test thread has 2 MiB).
fn run(case: fn()) {
    std::thread::Builder::new()
        .stack_size(8 << 20)
        .spawn(case)
        .expect("a thread for the case")
        .join()
        .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
}

macro_rules! cases {
    ($($case:ident),* $(,)?) => {
        /// The cases, read from `tests/pass/` (an inline module of the crate root looks there).
        mod pass {
            $(pub mod $case;)*
        }
        $(
            #[test]
            fn $case() {
                run(pass::$case::main);
            }
        )*
    };
}

cases!(
    custom_law,
    f32_chain,
    field_parameters,
    hidden_names,
    issue_example,
    limits,
    looped_chain,
    other_fields,
    raw_identifiers,
    rest_length,
);
