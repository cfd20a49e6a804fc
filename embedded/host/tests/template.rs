//! docs/embedded.md shows the template firmware in full ("Your own firmware"); the program that
//! `embedded/qemu-check` builds and runs under QEMU is `embedded/firmware/src/bin/first-chain.rs`.
//! The two must be the same code, so that the docs show what CI runs.

use std::fs;
use std::path::Path;

#[test]
fn the_template_in_the_docs_is_the_program_ci_runs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let docs = fs::read_to_string(root.join("docs/embedded.md")).unwrap();
    let program = fs::read_to_string(root.join("embedded/firmware/src/bin/first-chain.rs")).unwrap();
    // The docs' copy: the `rust,ignore` block after the `src/main.rs` item.
    let after = &docs[docs.find("- **`src/main.rs`**").expect("the template's item")..];
    let start = after.find("```rust,ignore\n").expect("the template's code block") + "```rust,ignore\n".len();
    let shown = &after[start..start + after[start..].find("```\n").expect("the block's end")];
    // The file without its module doc (the `//!` lines the docs replace with prose).
    let code: String =
        program.lines().skip_while(|l| l.starts_with("//!")).map(|l| format!("{l}\n")).collect();
    assert_eq!(shown, code, "docs/embedded.md's template differs from first-chain.rs");
}
