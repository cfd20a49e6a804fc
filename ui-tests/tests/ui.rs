//! Compile-time checks of `#[rotor_chain]`: every rule has a compile-fail case whose `.stderr`
//! snapshot shows the message at the offending key, and the pass cases compile and run.
//! Regenerate the snapshots with `TRYBUILD=overwrite cargo test -p ui-tests --test ui`.

// The name is unique in the workspace: `cargo xtask test` runs this test beside the others and
// skips it in their run by this exact name (xtask/src/main.rs, `UI_TEST`).
#[test]
fn rotor_chain_compile_time_checks() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/compile_fail/**/*.rs");
    t.pass("tests/ui/pass/*.rs");
}
