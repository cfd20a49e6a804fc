//! Compile-time checks of `#[rotor_chain]` and `#[rotor_network]`: every rule has a compile-fail case whose `.stderr`
//! snapshot shows the message at the offending key. The pass cases are an ordinary test (`tests/pass.rs`),
//! so that trybuild checks with `cargo check` only (no code generation for the dependencies).
//! Regenerate the snapshots with `TRYBUILD=overwrite cargo test -p ui-tests --test ui`.

// The name is unique in the workspace: `cargo xtask test` runs this test beside the others and
// skips it in their run by this exact name (xtask/src/main.rs, `UI_TEST`).
#[test]
fn rotor_chain_compile_time_checks() {
    // `#[rotor_network]` reads cell files relative to the crate's manifest folder; trybuild
    // compiles the cases in a project of its own, so point the macro at this package's folder
    // (dtolnay/trybuild#202). SAFETY: set before any other thread of this test binary reads the
    // environment (the one test here, trybuild's cargo inherits it).
    unsafe { std::env::set_var("ROTOR_NETWORK_MANIFEST_DIR", env!("CARGO_MANIFEST_DIR")) };
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/compile_fail/**/*.rs");
}
