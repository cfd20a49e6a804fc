//! Phase 2 of `#[rotor_network]`: check the [`Spec`] (all errors at once, each at its key) and
//! read the cell through `chain-cell`, the one validation of a cell (its errors, which name the
//! key and the line, become errors at the `cell` string).
//!
//! The cell file is read relative to the crate's manifest directory (`CARGO_MANIFEST_DIR`). The
//! ui tests, which trybuild compiles in a project of its own, point the macro at their own
//! directory with `ROTOR_NETWORK_MANIFEST_DIR` (dtolnay/trybuild#202); nothing else sets it.

use std::path::PathBuf;

use chain_cell::Cell;
use chain_cell::ready::{self, Lean};
use proc_macro2::Span;

use super::attr::{NodeName, NodeOverride, Spec};
use crate::attr::suggest;
use crate::ctxt::Ctxt;
use crate::law::{self, Law};

/// The fewest cells a periodic direction may have (`chain_network::patch::MIN_PERIODIC_CELLS`:
/// with fewer, a bond to the neighbouring cell joins a node to itself or doubles another bond).
const MIN_PERIODIC_CELLS: usize = 3;

/// The most bonds, and degrees of freedom, a patch may have (`chain_network::patch::MAX_PATCH_BONDS`,
/// whose rule `Patch::new` applies at run time: 2^25, a mistyped size is an error, not an
/// allocation the machine cannot give).
const MAX_PATCH_BONDS: usize = 1 << 25;

/// The ready cells without parameters, by the names of `chain_network::cell::ready::by_name`.
const READY: [&str; 4] = ["square", "kagome", "paper-chain-right", "paper-chain-left"];

/// The ready cells that take parameters (written to a file to be used here).
const READY_WITH_PARAMETERS: [&str; 3] = ["deformed-kagome", "twisted-kagome", "rotor-chain"];

/// Where the cell comes from.
pub enum Source {
    /// A cell file, by its absolute path (for `include_str!`, so a change to it rebuilds).
    File(String),
    /// A ready cell, by name.
    Ready(String),
}

/// The validated network.
pub struct Model {
    pub source: Source,
    pub cells: [usize; 2],
    pub periodic: bool,
    /// The custom law (harmonic if `None`).
    pub law: Option<Law>,
    pub mass: f64,
    /// `(spring, k, l0)` overrides.
    pub springs: Vec<(usize, Option<f64>, Option<f64>)>,
    /// `(cell, node index in the cell, mass)` overrides.
    pub nodes: Vec<([usize; 2], usize, f64)>,
}

/// The number of bonds of a patch of `cells` of `cell`: every bond in every cell on a periodic
/// patch; on a free one, each bond in the cells whose `to` end lies in the patch.
pub fn patch_bonds(cell: &Cell, cells: [usize; 2], periodic: bool) -> usize {
    cell.bonds()
        .iter()
        .map(|b| {
            if periodic {
                cells[0].saturating_mul(cells[1])
            } else {
                let fit = |n: usize, c: i64| {
                    n.saturating_sub(usize::try_from(c.unsigned_abs()).unwrap_or(usize::MAX))
                };
                fit(cells[0], b.cell[0]).saturating_mul(fit(cells[1], b.cell[1]))
            }
        })
        .fold(0, usize::saturating_add)
}

fn manifest_dir() -> Option<PathBuf> {
    std::env::var_os("ROTOR_NETWORK_MANIFEST_DIR")
        .or_else(|| std::env::var_os("CARGO_MANIFEST_DIR"))
        .map(PathBuf::from)
}

/// The cell named by `cell = ..` or `ready = ..`.
fn read_cell(cx: &Ctxt, spec: &Spec) -> Option<(Source, Cell)> {
    match (&spec.cell, &spec.ready) {
        (Some(_), Some(ready)) => {
            cx.error_spanned_by(
                &ready.key,
                "give the cell once: `cell = \"file.toml\"` or `ready = \"name\"`, not both",
            );
            None
        }
        (Some(file), None) => {
            let written = file.value.value();
            let Some(dir) = manifest_dir() else {
                cx.error_spanned_by(&file.value, "CARGO_MANIFEST_DIR is not set: build with cargo");
                return None;
            };
            let path = dir.join(&written);
            let text = match std::fs::read_to_string(&path) {
                Ok(text) => text,
                Err(e) => {
                    cx.error_spanned_by(
                        &file.value,
                        format!(
                            "cannot read the cell file `{written}` (relative to the crate's Cargo.toml): {e}"
                        ),
                    );
                    return None;
                }
            };
            match Cell::from_toml_str(&text) {
                Ok(cell) => Some((Source::File(path.to_string_lossy().into_owned()), cell)),
                Err(e) => {
                    cx.error_spanned_by(&file.value, format!("`{written}`: {e}"));
                    None
                }
            }
        }
        (None, Some(ready)) => {
            let name = ready.value.value();
            let cell = match name.as_str() {
                "square" => ready::square(),
                "kagome" => ready::kagome(),
                "paper-chain-right" => ready::paper_chain(Lean::Right),
                "paper-chain-left" => ready::paper_chain(Lean::Left),
                other if READY_WITH_PARAMETERS.contains(&other) => {
                    cx.error_spanned_by(
                        &ready.value,
                        format!(
                            "the ready cell `{other}` takes parameters: write it to a file \
                             (`Cell::to_toml`) and give `cell = \"file.toml\"`"
                        ),
                    );
                    return None;
                }
                other => {
                    let all: Vec<&str> = READY.iter().chain(&READY_WITH_PARAMETERS).copied().collect();
                    let hint = match suggest(other, &all) {
                        Some(s) => format!("did you mean `{s}`?"),
                        None => format!("the ready cells are {}", crate::attr::quoted(&READY)),
                    };
                    cx.error_spanned_by(&ready.value, format!("unknown ready cell `{other}`; {hint}"));
                    return None;
                }
            };
            Some((Source::Ready(name), cell))
        }
        (None, None) => {
            let message = "missing the cell: give `cell = \"file.toml\"` (relative to the crate's Cargo.toml) or \
                           `ready = \"kagome\"`";
            missing(cx, spec, message);
            None
        }
    }
}

/// A missing-key error at the attribute (or the call site for a bare `#[rotor_network]`).
fn missing(cx: &Ctxt, spec: &Spec, message: &str) {
    if spec.tokens.is_empty() {
        cx.error_at(Span::call_site(), message);
    } else {
        cx.error_spanned_by(&spec.tokens, message);
    }
}

/// The patch's size checked against the cell's dimension and the boundary.
fn check_cells(cx: &Ctxt, spec: &Spec, cell: Option<&Cell>, periodic: Option<bool>) -> Option<[usize; 2]> {
    let Some(keyed) = &spec.cells else {
        if !spec.seen.contains("cells") {
            missing(cx, spec, "missing `cells`: the patch's size, e.g. `cells = (16, 16)`");
        }
        return None;
    };
    let written = &keyed.value;
    let dimension = cell.map(Cell::dimension);
    let cells = match (dimension, written.as_slice()) {
        (_, &[n1, n2]) => [n1, n2],
        (Some(1) | None, &[n]) => [n, 1],
        (None, _) => return None,
        (Some(d), _) => {
            cx.error_spanned_by(
                &keyed.tokens,
                format!("the cell is {d}-dimensional: `cells` needs {d} entries, e.g. `cells = (16, 16)`"),
            );
            return None;
        }
    };
    let mut ok = true;
    for (i, &n) in cells.iter().enumerate() {
        let rule = if dimension == Some(1) && i == 1 {
            (n != 1).then(|| "a one-dimensional cell has one lattice vector: write `cells = n`".to_owned())
        } else if n == 0 {
            Some("at least 1 cell".to_owned())
        } else if periodic == Some(true) && n < MIN_PERIODIC_CELLS {
            Some(format!(
                "a periodic direction needs at least {MIN_PERIODIC_CELLS} cells (fewer would make bonds to \
                 the node itself or doubled bonds)"
            ))
        } else {
            None
        };
        if let Some(rule) = rule {
            cx.error_spanned_by(&keyed.tokens, format!("{n} cells along lattice vector {}: {rule}", i + 1));
            ok = false;
        }
    }
    if ok && let Some(cell) = cell {
        // Patch::new's bound, on bonds and degrees of freedom both.
        let per_cell = cell.bonds().len().max(cell.dof());
        let size = cells[0].saturating_mul(cells[1]).saturating_mul(per_cell);
        if size > MAX_PATCH_BONDS {
            cx.error_spanned_by(
                &keyed.tokens,
                format!(
                    "a patch has at most {MAX_PATCH_BONDS} bonds and as many degrees of freedom: {} x {} cells of \
                     {} bonds and {} degrees of freedom ask for more",
                    cells[0],
                    cells[1],
                    cell.bonds().len(),
                    cell.dof()
                ),
            );
            ok = false;
        }
    }
    ok.then_some(cells)
}

fn check_boundary(cx: &Ctxt, spec: &Spec) -> Option<bool> {
    let Some(keyed) = &spec.boundary else {
        if !spec.seen.contains("boundary") {
            missing(cx, spec, "missing `boundary`: `boundary = \"free\"` or `boundary = \"periodic\"`");
        }
        return None;
    };
    match keyed.value.value().as_str() {
        "free" => Some(false),
        "periodic" => Some(true),
        other => {
            let hint = match suggest(&other.to_ascii_lowercase(), &["free", "periodic"]) {
                Some(s) => format!("did you mean `\"{s}\"`?"),
                None => "expected `\"free\"` or `\"periodic\"`".to_owned(),
            };
            cx.error_spanned_by(&keyed.value, format!("unknown boundary `{other}`; {hint}"));
            None
        }
    }
}

/// `Some(value)` if finite and positive, else an error at `tokens`.
fn positive(cx: &Ctxt, tokens: &proc_macro2::TokenStream, what: &str, value: f64) -> Option<f64> {
    if value.is_finite() && value > 0.0 {
        Some(value)
    } else {
        cx.error_spanned_by(tokens, format!("{what} must be positive, found {value}"));
        None
    }
}

/// Validates `spec`: the model if every check passed (errors are in `cx` otherwise).
pub fn validate(cx: &Ctxt, spec: Spec) -> Option<Model> {
    let read = read_cell(cx, &spec);
    let periodic = check_boundary(cx, &spec);
    let cells = check_cells(cx, &spec, read.as_ref().map(|(_, c)| c), periodic);
    let law = spec.law.as_ref().and_then(|l| law::parse(cx, &l.key, l.value.clone()));
    let law_ok = spec.law.is_none() || law.is_some();
    let mass = match &spec.mass {
        Some(m) => positive(cx, &m.tokens, "the mass", m.value),
        None => Some(1.0),
    };
    let bonds = match (&read, cells, periodic) {
        (Some((_, cell)), Some(cells), Some(periodic)) => Some(patch_bonds(cell, cells, periodic)),
        _ => None,
    };
    let mut springs = Vec::new();
    let mut springs_ok = true;
    for s in &spec.springs {
        if s.inner_error {
            springs_ok = false;
            continue;
        }
        let p = s.index.value;
        if let Some(count) = bonds
            && p >= count
        {
            cx.error_spanned_by(
                &s.index.tokens,
                format!(
                    "spring {p} does not exist: the patch has {count} springs (0 to {})",
                    count.saturating_sub(1)
                ),
            );
            springs_ok = false;
        }
        if s.k.is_none() && s.l0.is_none() {
            cx.error_spanned_by(
                &s.index.key,
                format!("`spring({p})` overrides nothing: give `k = ..` or `l0 = ..`"),
            );
            springs_ok = false;
        }
        let k = s.k.as_ref().map(|k| positive(cx, &k.tokens, "a spring constant", k.value));
        let l0 = s.l0.as_ref().map(|l| positive(cx, &l.tokens, "a rest length", l.value));
        if k.is_some_and(|k| k.is_none()) || l0.is_some_and(|l| l.is_none()) {
            springs_ok = false;
        }
        springs.push((p, k.flatten(), l0.flatten()));
    }
    let nodes: Vec<_> =
        spec.nodes.iter().map(|n| check_node(cx, n, read.as_ref().map(|(_, c)| c), cells)).collect();
    let (source, _) = read?;
    let (cells, periodic, mass) = (cells?, periodic?, mass?);
    let nodes: Option<Vec<_>> = nodes.into_iter().collect();
    (law_ok && springs_ok).then_some(Model { source, cells, periodic, law, mass, springs, nodes: nodes? })
}

/// One `node(..)` override: its cell inside the patch, its node in the cell (by index or name),
/// a positive mass. The override as `(cell, node index, mass)` if every check passed.
fn check_node(
    cx: &Ctxt,
    o: &NodeOverride,
    cell: Option<&Cell>,
    cells: Option<[usize; 2]>,
) -> Option<([usize; 2], usize, f64)> {
    let mass = match &o.mass {
        Some(m) => positive(cx, &m.tokens, "a node's mass", m.value),
        None => {
            if !o.inner_error {
                cx.error_spanned_by(&o.key, "`node(..)` overrides nothing: give `mass = ..`");
            }
            None
        }
    };
    let position = match (o.cell.value.as_slice(), cells) {
        (&[i, j], Some(cells)) if cells[1] > 1 || j == 0 => Some([i, j]),
        (&[i], Some(cells)) if cells[1] == 1 => Some([i, 0]),
        (_, Some(cells)) => {
            let want = if cells[1] == 1 { "`i` (one-dimensional)" } else { "`(i, j)` (two-dimensional)" };
            cx.error_spanned_by(&o.cell.tokens, format!("a cell of this patch is written {want}"));
            None
        }
        (_, None) => None,
    };
    let position = position.and_then(|[i, j]| {
        let [n1, n2] = cells?;
        if i < n1 && j < n2 {
            Some([i, j])
        } else {
            cx.error_spanned_by(
                &o.cell.tokens,
                format!(
                    "cell ({i}, {j}) is outside the patch of {n1} x {n2} cells (0 to {}, 0 to {})",
                    n1 - 1,
                    n2 - 1
                ),
            );
            None
        }
    });
    let index = cell.and_then(|cell| {
        let names: Vec<&str> = cell.nodes().iter().map(|n| n.name.as_str()).collect();
        match &o.node.value {
            NodeName::Index(k) if *k < names.len() => Some(*k),
            NodeName::Index(k) => {
                cx.error_spanned_by(
                    &o.node.tokens,
                    format!(
                        "node {k} does not exist: the cell's nodes are 0 to {} ({})",
                        names.len() - 1,
                        names.join(", ")
                    ),
                );
                None
            }
            NodeName::Name(name) => match names.iter().position(|n| n == name) {
                Some(k) => Some(k),
                None => {
                    let hint =
                        suggest(name, &names).map_or_else(String::new, |s| format!(": did you mean `{s}`?"));
                    cx.error_spanned_by(
                        &o.node.tokens,
                        format!("the cell has no node `{name}` (its nodes: {}){hint}", names.join(", ")),
                    );
                    None
                }
            },
        }
    });
    if o.inner_error {
        return None;
    }
    Some((position?, index?, mass?))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bonds of a free `n1 x n2` square patch in closed form: `n2 (n1 - 1)` along `a1`,
    /// `n1 (n2 - 1)` along `a2`; periodic: `2 n1 n2`.
    #[test]
    fn patch_bonds_of_the_square_lattice_in_closed_form() {
        let cell = ready::square();
        for (n1, n2) in [(1, 1), (1, 5), (4, 4), (7, 3)] {
            assert_eq!(patch_bonds(&cell, [n1, n2], false), n2 * (n1 - 1) + n1 * (n2 - 1));
            assert_eq!(patch_bonds(&cell, [n1, n2], true), 2 * n1 * n2);
        }
    }

    /// A bond reaching two cells along `a1`, counted by hand: `n1 - 2` cells of each row hold it.
    #[test]
    fn patch_bonds_of_a_longer_bond() {
        let cell = Cell::builder(2, &[[1.0, 0.0], [0.0, 1.0]])
            .joint("a", [0.0, 0.0])
            .bond("a", "a", &[2, -1])
            .build()
            .unwrap();
        assert_eq!(patch_bonds(&cell, [5, 3], false), 3 * 2);
        assert_eq!(patch_bonds(&cell, [1, 3], false), 0);
    }
}
