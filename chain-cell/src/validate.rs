//! The one validation of a cell, shared by the file reader, the Rust builder and Python: from the
//! unvalidated [`Raw`] form to a [`Cell`], or the first problem found as a [`CellError`] that
//! names its key (and line, for text).
//!
//! Rules: `dimension` is 1 or 2; `lattice` has `dimension` rows of two finite numbers spanning a
//! cell; at least one node and at most [`MAX_CELL_NODES`] nodes and [`MAX_CELL_BONDS`] bonds; node names non-empty and unique; a joint has `position`, a rotor
//! `pivot`, `length > 0` and `angle`, and neither takes the other's keys; every bond names two
//! existing nodes, has `dimension` integer cell offsets, `k > 0` and `rest_length > 0` when
//! given; no bond has zero length; no two bonds join the same two node instances; a `law` (of
//! the cell or of a bond) is `"harmonic"`, `"quartic"` or `{ polynomial = [c2, ...] }` with one
//! to five finite coefficients.

use std::collections::BTreeMap;

use super::{Bond, BondLaw, Cell, Node, NodeKind, Polynomial, PolynomialProblem};
use crate::error::{CellError, Location};

/// A value with the line it came from (for text).
#[derive(Clone, Debug)]
pub(crate) struct Val<T> {
    pub value: T,
    pub line: Option<usize>,
}

impl<T> Val<T> {
    pub fn plain(value: T) -> Self {
        Val { value, line: None }
    }
}

/// An unvalidated cell.
#[derive(Clone, Debug, Default)]
pub(crate) struct Raw {
    pub dimension: Option<Val<i64>>,
    pub lattice: Option<Val<Vec<Vec<f64>>>>,
    /// The law of every bond that names none.
    pub law: Option<Val<RawLaw>>,
    pub line: Option<usize>,
    pub nodes: Vec<RawNode>,
    pub bonds: Vec<RawBond>,
}

/// An unvalidated `[[node]]`.
#[derive(Clone, Debug, Default)]
pub(crate) struct RawNode {
    pub line: Option<usize>,
    pub name: Option<Val<String>>,
    pub kind: Option<Val<String>>,
    pub position: Option<Val<Vec<f64>>>,
    pub pivot: Option<Val<Vec<f64>>>,
    pub length: Option<Val<f64>>,
    pub angle: Option<Val<f64>>,
}

/// An unvalidated `[[bond]]`.
#[derive(Clone, Debug, Default)]
pub(crate) struct RawBond {
    pub line: Option<usize>,
    pub from: Option<Val<String>>,
    pub to: Option<Val<String>>,
    pub cell: Option<Val<Vec<i64>>>,
    pub k: Option<Val<f64>>,
    pub rest_length: Option<Val<f64>>,
    pub law: Option<Val<RawLaw>>,
}

/// An unvalidated `law`.
#[derive(Clone, Debug)]
pub(crate) enum RawLaw {
    /// A law given as a value (the Rust builder).
    Given(BondLaw),
    /// A name: `harmonic` or `quartic`.
    Name(String),
    /// `{ polynomial = [c2, c3, ...] }`.
    Polynomial(Vec<f64>),
    /// Anything else, described.
    Other(String),
}

/// The law `v` at `key`.
fn law(key: &str, v: &Val<RawLaw>) -> Result<BondLaw, CellError> {
    let problem = |problem: String| CellError::Law { at: at(key, v.line), problem };
    match &v.value {
        RawLaw::Given(law) => match law {
            BondLaw::Polynomial(p) => Polynomial::new(&p.coefficients)
                .map(BondLaw::Polynomial)
                .map_err(|e| polynomial_problem(key, v.line, e)),
            other => Ok(*other),
        },
        RawLaw::Name(name) => match name.as_str() {
            "harmonic" => Ok(BondLaw::Harmonic),
            "quartic" => Ok(BondLaw::Quartic),
            other => Err(problem(format!(
                "unknown law `{other}` (expected \"harmonic\", \"quartic\" or {{ polynomial = [c2, c3, ...] }})"
            ))),
        },
        RawLaw::Polynomial(c) => {
            Polynomial::new(c).map(BondLaw::Polynomial).map_err(|e| polynomial_problem(key, v.line, e))
        }
        RawLaw::Other(what) => Err(problem(format!(
            "{what} is not a law (expected \"harmonic\", \"quartic\" or {{ polynomial = [c2, c3, ...] }})"
        ))),
    }
}

fn polynomial_problem(key: &str, line: Option<usize>, e: PolynomialProblem) -> CellError {
    match e {
        PolynomialProblem::Count(found) => CellError::Length {
            at: at(key, line),
            expected: Polynomial::MAX_COEFFICIENTS,
            found,
            why: "one to five coefficients c2 .. c6",
        },
        PolynomialProblem::NotFinite { value, .. } => CellError::NotFinite { at: at(key, line), value },
    }
}

/// Relative size below which a bond counts as having zero length, and lattice vectors as
/// degenerate: far below any physical cell (lengths are relative to the longest lattice
/// vector) and far above rounding of the positions.
pub const RELATIVE_TOLERANCE: f64 = 1e-9;

/// The most nodes a unit cell may have: 1024 degrees of freedom, whose dense complex Bloch
/// matrices (`Q(k)`, `D(k)`) take a second per wave vector to decompose, and which no periodic
/// lattice of the literature's needs (a kagome cell has 3 nodes; a patch of many cells is built
/// from the cell, not written as one).
pub const MAX_CELL_NODES: usize = 512;
/// The most bonds a unit cell may have: four per degree of freedom at [`MAX_CELL_NODES`] (a
/// `Q(k)` of 2048 x 1024 complex numbers, 32 MiB).
pub const MAX_CELL_BONDS: usize = 2048;

fn at(key: impl Into<String>, line: Option<usize>) -> Location {
    Location { key: key.into(), line }
}

fn finite(key: &str, line: Option<usize>, value: f64) -> Result<f64, CellError> {
    if value.is_finite() { Ok(value) } else { Err(CellError::NotFinite { at: at(key, line), value }) }
}

fn vector(key: &str, v: &Val<Vec<f64>>, why: &'static str) -> Result<[f64; 2], CellError> {
    if v.value.len() != 2 {
        return Err(CellError::Length { at: at(key, v.line), expected: 2, found: v.value.len(), why });
    }
    Ok([finite(key, v.line, v.value[0])?, finite(key, v.line, v.value[1])?])
}

fn positive(key: &str, v: &Val<f64>) -> Result<f64, CellError> {
    let x = finite(key, v.line, v.value)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(CellError::OutOfRange { at: at(key, v.line), value: x, rule: "must be > 0" })
    }
}

/// Levenshtein distance, for "did you mean" on node names.
fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != *cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

/// Validate an unvalidated cell.
pub(crate) fn validate_raw(raw: Raw) -> Result<Cell, CellError> {
    let dim_val =
        raw.dimension.ok_or_else(|| CellError::Missing { at: at("dimension", raw.line), why: "1 or 2" })?;
    if !(1..=2).contains(&dim_val.value) {
        return Err(CellError::Dimension { at: at("dimension", dim_val.line), found: dim_val.value });
    }
    let dimension = dim_val.value as usize;
    let lattice_val = raw.lattice.ok_or_else(|| CellError::Missing {
        at: at("lattice", raw.line),
        why: "the lattice vectors as rows",
    })?;
    if lattice_val.value.len() != dimension {
        return Err(CellError::Length {
            at: at("lattice", lattice_val.line),
            expected: dimension,
            found: lattice_val.value.len(),
            why: "one row per dimension",
        });
    }
    let mut lattice = [[0.0; 2]; 2];
    for (i, row) in lattice_val.value.iter().enumerate() {
        let v = Val { value: row.clone(), line: lattice_val.line };
        lattice[i] = vector(&format!("lattice[{i}]"), &v, "lattice vectors have two components")?;
    }
    let lengths: Vec<f64> = lattice[..dimension].iter().map(|a| a[0].hypot(a[1])).collect();
    let (det, relative) = if dimension == 1 {
        (lengths[0], 1.0)
    } else {
        let det = (lattice[0][0] * lattice[1][1] - lattice[0][1] * lattice[1][0]).abs();
        (det, det / (lengths[0] * lengths[1]))
    };
    if det.is_nan() || relative.is_nan() || det <= 0.0 || relative <= RELATIVE_TOLERANCE {
        return Err(CellError::DegenerateLattice {
            at: at("lattice", lattice_val.line),
            det,
            relative,
            dimension,
        });
    }
    let scale = lengths.iter().cloned().fold(0.0, f64::max);

    if raw.nodes.is_empty() {
        return Err(CellError::Empty { at: at("node", raw.line) });
    }
    for (key, what, found, max) in [
        ("node", "nodes", raw.nodes.len(), MAX_CELL_NODES),
        ("bond", "bonds", raw.bonds.len(), MAX_CELL_BONDS),
    ] {
        if found > max {
            return Err(CellError::TooLarge { at: at(key, raw.line), what, found, max });
        }
    }
    let mut nodes: Vec<Node> = Vec::with_capacity(raw.nodes.len());
    let mut index: BTreeMap<&str, usize> = BTreeMap::new();
    for (i, n) in raw.nodes.iter().enumerate() {
        let key = |k: &str| format!("node[{i}].{k}");
        let name = n
            .name
            .as_ref()
            .ok_or_else(|| CellError::Missing { at: at(key("name"), n.line), why: "a unique name" })?;
        if name.value.is_empty() {
            return Err(CellError::BadName {
                at: at(key("name"), name.line),
                name: String::new(),
                problem: "is empty".into(),
            });
        }
        // A map, not a scan of the nodes so far: a cell of many nodes is checked in O(n log n).
        if let Some(&j) = index.get(name.value.as_str()) {
            return Err(CellError::BadName {
                at: at(key("name"), name.line),
                name: name.value.clone(),
                problem: format!("is already the name of node[{j}]"),
            });
        }
        index.insert(name.value.as_str(), i);
        let kind = n
            .kind
            .as_ref()
            .ok_or_else(|| CellError::Missing { at: at(key("kind"), n.line), why: "`joint` or `rotor`" })?;
        let kind = match kind.value.as_str() {
            "joint" => {
                for (k, present) in [
                    ("pivot", n.pivot.is_some()),
                    ("length", n.length.is_some()),
                    ("angle", n.angle.is_some()),
                ] {
                    if present {
                        return Err(CellError::NotForKind { at: at(key(k), n.line), kind: "joint" });
                    }
                }
                let p = n.position.as_ref().ok_or_else(|| CellError::Missing {
                    at: at(key("position"), n.line),
                    why: "for a joint",
                })?;
                NodeKind::Joint {
                    position: vector(
                        &key("position"),
                        p,
                        "positions have two components in both dimensions",
                    )?,
                }
            }
            "rotor" => {
                if n.position.is_some() {
                    return Err(CellError::NotForKind { at: at(key("position"), n.line), kind: "rotor" });
                }
                let p = n
                    .pivot
                    .as_ref()
                    .ok_or_else(|| CellError::Missing { at: at(key("pivot"), n.line), why: "for a rotor" })?;
                let l = n.length.as_ref().ok_or_else(|| CellError::Missing {
                    at: at(key("length"), n.line),
                    why: "for a rotor",
                })?;
                let a = n
                    .angle
                    .as_ref()
                    .ok_or_else(|| CellError::Missing { at: at(key("angle"), n.line), why: "for a rotor" })?;
                NodeKind::Rotor {
                    pivot: vector(&key("pivot"), p, "positions have two components in both dimensions")?,
                    length: positive(&key("length"), l)?,
                    angle: finite(&key("angle"), a.line, a.value)?,
                }
            }
            other => {
                return Err(CellError::UnknownKind {
                    at: at(key("kind"), kind.line),
                    found: other.to_owned(),
                });
            }
        };
        nodes.push(Node { name: name.value.clone(), kind });
    }

    let find = |key: String, v: &Option<Val<String>>, line: Option<usize>| -> Result<usize, CellError> {
        let v =
            v.as_ref().ok_or_else(|| CellError::Missing { at: at(key.clone(), line), why: "a node name" })?;
        index.get(v.value.as_str()).copied().ok_or_else(|| {
            let suggestion = nodes
                .iter()
                .map(|n| (distance(&n.name, &v.value), &n.name))
                .filter(|(d, name)| *d <= 2.max(name.len() / 3))
                .min_by_key(|(d, _)| *d)
                .map(|(_, name)| name.clone());
            CellError::UnknownNode { at: at(key, v.line), name: v.value.clone(), suggestion }
        })
    };
    let cell_law = match &raw.law {
        Some(v) => law("law", v)?,
        None => BondLaw::Harmonic,
    };
    let mut bonds = Vec::with_capacity(raw.bonds.len());
    for (i, b) in raw.bonds.iter().enumerate() {
        let key = |k: &str| format!("bond[{i}].{k}");
        let from = find(key("from"), &b.from, b.line)?;
        let to = find(key("to"), &b.to, b.line)?;
        let mut cell = [0i64; 2];
        if let Some(c) = &b.cell {
            if c.value.len() != dimension {
                return Err(CellError::Length {
                    at: at(key("cell"), c.line),
                    expected: dimension,
                    found: c.value.len(),
                    why: "one integer offset per lattice vector",
                });
            }
            cell[..dimension].copy_from_slice(&c.value);
            const MAX_OFFSET: i64 = 1 << 20;
            if let Some(&big) = c.value.iter().find(|x| x.abs() > MAX_OFFSET) {
                return Err(CellError::OutOfRange {
                    at: at(key("cell"), c.line),
                    value: big as f64,
                    rule: "|offset| <= 2^20",
                });
            }
        }
        let k = match &b.k {
            Some(v) => positive(&key("k"), v)?,
            None => 1.0,
        };
        let rest = match &b.rest_length {
            Some(v) => Some(positive(&key("rest_length"), v)?),
            None => None,
        };
        let law = match &b.law {
            Some(v) => law(&key("law"), v)?,
            None => cell_law,
        };
        bonds.push((Bond { from, to, cell, k, rest_length: rest.unwrap_or(f64::NAN), law }, b.line));
    }
    let cell = Cell::from_parts(dimension, lattice, nodes, bonds.iter().map(|(b, _)| b.clone()).collect());
    // Each bond's two node instances, to its index: duplicates found in O(b log b).
    let mut seen: BTreeMap<(usize, usize, [i64; 2]), usize> = BTreeMap::new();
    let mut finished = Vec::with_capacity(bonds.len());
    for (i, (mut bond, line)) in bonds.into_iter().enumerate() {
        let length = cell.bond_length(i);
        if length.is_nan() || length <= RELATIVE_TOLERANCE * scale {
            return Err(CellError::ZeroLengthBond {
                at: at(format!("bond[{i}]"), line),
                bond: i,
                length,
                scale,
            });
        }
        // The same two node instances, whichever end is written first.
        let neg = [-bond.cell[0], -bond.cell[1]];
        let canon = if bond.from < bond.to || (bond.from == bond.to && bond.cell >= neg) {
            (bond.from, bond.to, bond.cell)
        } else {
            (bond.to, bond.from, neg)
        };
        if let Some(&first) = seen.get(&canon) {
            return Err(CellError::DuplicateBond { at: at(format!("bond[{i}]"), line), first, second: i });
        }
        seen.insert(canon, i);
        if bond.rest_length.is_nan() {
            bond.rest_length = length;
        }
        finished.push(bond);
    }
    let Cell { dimension, lattice, nodes, .. } = cell;
    Ok(Cell::from_parts(dimension, lattice, nodes, finished))
}

#[cfg(test)]
mod tests {
    use super::distance;

    #[test]
    fn edit_distance() {
        assert_eq!(distance("kitten", "sitting"), 3);
        assert_eq!(distance("a", "a"), 0);
        assert_eq!(distance("", "ab"), 2);
    }
}
