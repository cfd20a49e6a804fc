//! The cell format: the issue's example reads, ready cells round-trip through TOML, and every
//! class of bad input is a typed error naming its key and line.

use chain_network::cell::ready;
use chain_network::{Cell, CellError, NodeKind};

const EXAMPLE: &str = r#"
dimension = 2                                       # 1 or 2
lattice = [[1.0, 0.0], [0.5, 0.8660254037844386]]   # lattice vectors as rows
[[node]]
name = "a"
kind = "joint"
position = [0.0, 0.0]
[[node]]
name = "p"
kind = "rotor"
pivot = [0.5, 0.0]
length = 0.8
angle = 1.2
[[bond]]
from = "a"
to = "p"
cell = [1, 0]
k = 1.0
"#;

#[test]
fn the_issue_example_reads() {
    let cell = Cell::from_toml_str(EXAMPLE).unwrap();
    assert_eq!(cell.dimension(), 2);
    assert_eq!(cell.dof(), 3);
    assert_eq!(cell.bonds()[0].cell, [1, 0]);
    // rest_length defaults to the reference length: from a (0, 0) to p's tip shifted by a1.
    let tip = [0.5 + 0.8 * 1.2f64.cos() + 1.0, 0.8 * 1.2f64.sin()];
    assert!((cell.bonds()[0].rest_length - tip[0].hypot(tip[1])).abs() < 1e-15);
    assert!(matches!(cell.nodes()[1].kind, NodeKind::Rotor { length, .. } if length == 0.8));
}

#[test]
fn ready_cells_round_trip_through_toml() {
    let cells = [
        ready::square(),
        ready::kagome(),
        ready::deformed_kagome(-0.05, 0.05, 0.05, 0.02).unwrap(),
        ready::twisted_kagome(0.3).unwrap(),
        ready::paper_chain(ready::Lean::Left),
    ];
    for cell in cells {
        let back = Cell::from_toml_str(&cell.to_toml()).unwrap();
        assert_eq!(back, cell);
    }
}

/// Deformed kagome geometry against Kane and Lubensky's definitions: with z = 0 and x1 = x2 = x3
/// (the twisted kagome lattice) every bond has length 1/2 cos(twist)^-1... here: all six bonds
/// equal, and the twist angle atan(2 sqrt3 x) between a bond and the undistorted one.
#[test]
fn twisted_kagome_has_equal_bonds_and_the_twist_angle() {
    let alpha = 0.2f64;
    let cell = ready::twisted_kagome(alpha).unwrap();
    let l0 = cell.bond_length(0);
    for b in 1..6 {
        assert!((cell.bond_length(b) - l0).abs() < 1e-12, "bond {b}");
    }
    let straight = ready::kagome();
    for b in 0..6 {
        let (u, v) = (cell.bond_unit(b), straight.bond_unit(b));
        let angle = (u[0] * v[1] - u[1] * v[0]).abs().asin();
        assert!((angle - alpha).abs() < 1e-12, "bond {b}: {angle}");
    }
    // a3 = -a1 - a2 (Kane and Lubensky's a_p sum to zero).
    let a = ready::kane_lubensky_vectors();
    assert!((a[0][0] + a[1][0] + a[2][0]).abs() < 1e-15 && (a[0][1] + a[1][1] + a[2][1]).abs() < 1e-15);
}

fn err(text: &str) -> CellError {
    Cell::from_toml_str(text).unwrap_err()
}

const HEAD: &str = "dimension = 2\nlattice = [[1.0, 0.0], [0.0, 1.0]]\n";

/// `count` joints named `n0`, `n1`, ... on a line inside the cell, and a bond between each pair of
/// neighbours (`bonds` of them).
fn many(count: usize, bonds: usize) -> String {
    let mut text = HEAD.to_owned();
    for i in 0..count {
        text +=
            &format!("[[node]]\nname = \"n{i}\"\nkind = \"joint\"\nposition = [{}, 0.5]\n", i as f64 * 1e-3);
    }
    for i in 0..bonds {
        text += &format!("[[bond]]\nfrom = \"n{i}\"\nto = \"n{}\"\n", i + 1);
    }
    text
}

#[test]
fn a_cell_is_bounded_and_read_in_one_pass() {
    use chain_network::cell::{MAX_CELL_BONDS, MAX_CELL_NODES};
    // At the bound it reads: nodes by name and duplicate bonds found through maps.
    let cell = Cell::from_toml_str(&many(MAX_CELL_NODES, MAX_CELL_NODES - 1)).unwrap();
    assert_eq!((cell.nodes().len(), cell.bonds().len()), (MAX_CELL_NODES, MAX_CELL_NODES - 1));
    let e = err(&many(MAX_CELL_NODES + 1, 0));
    assert!(
        matches!(&e, CellError::TooLarge { what: "nodes", found, max, .. } if *found == MAX_CELL_NODES + 1 && *max == MAX_CELL_NODES),
        "{e}"
    );
    assert!(
        e.to_string()
            .contains(&format!("{} nodes, more than the limit of {MAX_CELL_NODES}", MAX_CELL_NODES + 1)),
        "{e}"
    );
    // Bonds past their bound (between the same few nodes: counted before they are checked).
    let mut text = many(3, 0);
    for _ in 0..=MAX_CELL_BONDS {
        text += "[[bond]]\nfrom = \"n0\"\nto = \"n1\"\n";
    }
    let e = err(&text);
    assert!(
        matches!(&e, CellError::TooLarge { what: "bonds", found, .. } if *found == MAX_CELL_BONDS + 1),
        "{e}"
    );
    // A file of 100 000 nodes is refused after one pass over its text: the line of each value was
    // found by scanning the text before it, which took minutes (25 s for 10 000 nodes, debug).
    let e = err(&many(100_000, 0));
    assert!(matches!(&e, CellError::TooLarge { found: 100_000, .. }), "{e}");
    // A name used twice among many nodes names the first node that has it; the line is the
    // second's (each node takes 4 lines after the 2 of the head).
    let text = many(400, 0) + "[[node]]\nname = \"n123\"\nkind = \"joint\"\nposition = [0.9, 0.9]\n";
    let e = err(&text);
    assert!(
        e.to_string().contains("is already the name of node[123]") && e.line() == Some(2 + 4 * 400 + 2),
        "{e}"
    );
}

#[test]
fn bad_input_names_the_key_and_line() {
    // Unknown node name, with a suggestion.
    let e = err(&format!(
        "{HEAD}[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [0, 0]\n[[bond]]\nfrom = \"a\"\nto = \"b\"\ncell = [1, 0]\n"
    ));
    assert!(matches!(&e, CellError::UnknownNode { name, .. } if name == "b"), "{e}");
    assert_eq!(e.line(), Some(9));
    assert!(e.to_string().contains("bond[0].to"), "{e}");
    // Missing key.
    let e = err(&format!("{HEAD}[[node]]\nname = \"a\"\nkind = \"joint\"\n"));
    assert!(matches!(&e, CellError::Missing { .. }), "{e}");
    assert!(e.to_string().contains("node[0].position") && e.line() == Some(3), "{e}");
    let e = err("lattice = [[1.0, 0.0]]\n[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [0, 0]\n");
    assert!(e.to_string().contains("dimension"), "{e}");
    // Dimension mismatches: lattice rows, cell offsets, positions.
    let e = err(
        "dimension = 1\nlattice = [[1.0, 0.0], [0.0, 1.0]]\n[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [0, 0]\n",
    );
    assert!(matches!(&e, CellError::Length { expected: 1, found: 2, .. }) && e.line() == Some(2), "{e}");
    let e = err(&format!(
        "{HEAD}[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [0, 0]\n[[bond]]\nfrom = \"a\"\nto = \"a\"\ncell = [1]\n"
    ));
    assert!(
        matches!(&e, CellError::Length { expected: 2, found: 1, .. })
            && e.to_string().contains("bond[0].cell"),
        "{e}"
    );
    let e = err(&format!("{HEAD}[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [0, 0, 0]\n"));
    assert!(matches!(&e, CellError::Length { .. }) && e.line() == Some(6), "{e}");
    let e = err("dimension = 3\nlattice = []\n");
    assert!(matches!(&e, CellError::Dimension { found: 3, .. }) && e.line() == Some(1), "{e}");
    // Zero-length bond (a node to itself in its own cell) and duplicate bonds (either way round).
    let e = err(&format!(
        "{HEAD}[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [0, 0]\n[[bond]]\nfrom = \"a\"\nto = \"a\"\n"
    ));
    assert!(matches!(&e, CellError::ZeroLengthBond { bond: 0, .. }) && e.line() == Some(7), "{e}");
    let two = "[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [0, 0]\n[[node]]\nname = \"b\"\nkind = \"joint\"\nposition = [0.5, 0]\n";
    let e =
        err(&format!("{HEAD}{two}[[bond]]\nfrom = \"a\"\nto = \"b\"\n[[bond]]\nfrom = \"b\"\nto = \"a\"\n"));
    assert!(
        matches!(&e, CellError::DuplicateBond { first: 0, second: 1, .. }) && e.line() == Some(14),
        "{e}"
    );
    let e = err(&format!(
        "{HEAD}{two}[[bond]]\nfrom = \"a\"\nto = \"a\"\ncell = [1, 0]\n[[bond]]\nfrom = \"a\"\nto = \"a\"\ncell = [-1, 0]\n"
    ));
    assert!(matches!(&e, CellError::DuplicateBond { .. }), "{e}");
    // Non-finite numbers.
    let e = err(&format!("{HEAD}[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [nan, 0]\n"));
    assert!(matches!(&e, CellError::NotFinite { .. }) && e.to_string().contains("node[0].position"), "{e}");
    let e = err(
        "dimension = 2\nlattice = [[inf, 0.0], [0.0, 1.0]]\n[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [0, 0]\n",
    );
    assert!(matches!(&e, CellError::NotFinite { .. }), "{e}");
    // Empty cells, unknown keys and kinds, degenerate lattices, negative stiffness.
    assert!(matches!(err(HEAD), CellError::Empty { .. }));
    let e = err(&format!("{HEAD}[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [0, 0]\nmass = 2\n"));
    assert!(matches!(&e, CellError::Syntax { line: Some(7), .. }) && e.to_string().contains("mass"), "{e}");
    let e = err(&format!("{HEAD}[[node]]\nname = \"a\"\nkind = \"spring\"\nposition = [0, 0]\n"));
    assert!(matches!(&e, CellError::UnknownKind { .. }), "{e}");
    let e = err(
        "dimension = 2\nlattice = [[1.0, 0.0], [2.0, 0.0]]\n[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [0, 0]\n",
    );
    assert!(matches!(&e, CellError::DegenerateLattice { .. }), "{e}");
    let e = err(&format!(
        "{HEAD}[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [0, 0]\n[[bond]]\nfrom = \"a\"\nto = \"a\"\ncell = [1, 0]\nk = -1\n"
    ));
    assert!(matches!(&e, CellError::OutOfRange { .. }) && e.to_string().contains("bond[0].k"), "{e}");
    let e = err(&format!("{HEAD}[[node]]\nname = \"a\"\nkind = \"rotor\"\nposition = [0, 0]\n"));
    assert!(matches!(&e, CellError::NotForKind { kind: "rotor", .. }), "{e}");
    let e = err("dimension = 2\nlattice = [[1.0, 0.0], [0.0, 1.0]\n");
    assert!(matches!(&e, CellError::Syntax { line: Some(2), .. }), "{e}");
    let e = err(&format!(
        "{HEAD}[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [0, 0]\n[[node]]\nname = \"a\"\nkind = \"joint\"\nposition = [1, 0]\n"
    ));
    assert!(matches!(&e, CellError::BadName { .. }) && e.line() == Some(8), "{e}");
}
