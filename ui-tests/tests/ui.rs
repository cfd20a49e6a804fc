//! Compile-time checks of `#[rotor_chain]`: every rule has a compile-fail case whose `.stderr`
//! snapshot shows the message at the offending key, and the pass cases compile and run.
//! Regenerate the snapshots with `TRYBUILD=overwrite cargo test -p ui-tests --test ui`.

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/compile_fail/**/*.rs");
    t.pass("tests/ui/pass/*.rs");
}
