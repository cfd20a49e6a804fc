//! [`CellBuilder`]: a cell assembled in Rust, validated by the same rules as a cell file.

use super::validate::{Raw, RawBond, RawLaw, RawNode, Val, validate_raw};
use super::{BondLaw, Cell};
use crate::error::CellError;

/// Builds a [`Cell`] node by node and bond by bond; [`CellBuilder::build`] validates it.
///
/// ```
/// use chain_cell::Cell;
///
/// // The square lattice: one joint, bonds to the neighbours along a1 and a2.
/// let cell = Cell::builder(2, &[[1.0, 0.0], [0.0, 1.0]])
///     .joint("a", [0.0, 0.0])
///     .bond("a", "a", &[1, 0])
///     .bond("a", "a", &[0, 1])
///     .build()?;
/// assert_eq!((cell.dof(), cell.bonds().len()), (2, 2));
/// # Ok::<(), chain_cell::CellError>(())
/// ```
#[derive(Clone, Debug)]
pub struct CellBuilder {
    raw: Raw,
}

impl CellBuilder {
    /// A cell of `dimension` (1 or 2) with lattice vectors `lattice` (rows).
    pub fn new(dimension: usize, lattice: &[[f64; 2]]) -> Self {
        let raw = Raw {
            dimension: Some(Val::plain(i64::try_from(dimension).unwrap_or(i64::MAX))),
            lattice: Some(Val::plain(lattice.iter().map(|a| a.to_vec()).collect())),
            ..Raw::default()
        };
        CellBuilder { raw }
    }

    /// Add a joint at `position`.
    pub fn joint(mut self, name: &str, position: [f64; 2]) -> Self {
        self.raw.nodes.push(RawNode {
            name: Some(Val::plain(name.to_owned())),
            kind: Some(Val::plain("joint".to_owned())),
            position: Some(Val::plain(position.to_vec())),
            ..RawNode::default()
        });
        self
    }

    /// Add a rotor on `pivot` of arm `length` at `angle` (radians, counter-clockwise from `+x`).
    pub fn rotor(mut self, name: &str, pivot: [f64; 2], length: f64, angle: f64) -> Self {
        self.raw.nodes.push(RawNode {
            name: Some(Val::plain(name.to_owned())),
            kind: Some(Val::plain("rotor".to_owned())),
            pivot: Some(Val::plain(pivot.to_vec())),
            length: Some(Val::plain(length)),
            angle: Some(Val::plain(angle)),
            ..RawNode::default()
        });
        self
    }

    /// Add a bond of stiffness 1 at its reference length from `from` (cell 0) to `to` in cell
    /// `cell` (one integer per lattice vector).
    pub fn bond(self, from: &str, to: &str, cell: &[i64]) -> Self {
        self.spring(from, to, cell, 1.0, None)
    }

    /// Add a bond with spring constant `k` and rest length `rest_length` (`None`: the reference
    /// length).
    pub fn spring(mut self, from: &str, to: &str, cell: &[i64], k: f64, rest_length: Option<f64>) -> Self {
        self.raw.bonds.push(RawBond {
            line: None,
            from: Some(Val::plain(from.to_owned())),
            to: Some(Val::plain(to.to_owned())),
            cell: Some(Val::plain(cell.to_vec())),
            k: Some(Val::plain(k)),
            rest_length: rest_length.map(Val::plain),
            law: None,
        });
        self
    }

    /// The spring law of every bond that sets none of its own (default harmonic).
    pub fn law(mut self, law: BondLaw) -> Self {
        self.raw.law = Some(Val::plain(RawLaw::Given(law)));
        self
    }

    /// The spring law of the bond added last (no effect before the first bond).
    pub fn bond_law(mut self, law: BondLaw) -> Self {
        if let Some(b) = self.raw.bonds.last_mut() {
            b.law = Some(Val::plain(RawLaw::Given(law)));
        }
        self
    }

    /// Validate and build. The rules (the same for cell files): `dimension` is 1 or 2;
    /// `lattice` has `dimension` rows of two finite numbers spanning a cell; at least one node;
    /// node names non-empty and unique; a joint has `position`, a rotor `pivot`, `length > 0`
    /// and `angle`, and neither takes the other's keys; every bond names two existing nodes, has
    /// `dimension` integer cell offsets, `k > 0` and `rest_length > 0` when given; no bond has
    /// zero length (below 1e-9 of the longest lattice vector); no two bonds join the same two
    /// node instances.
    pub fn build(self) -> Result<Cell, CellError> {
        validate_raw(self.raw)
    }
}

/// A cell as plain optional values, every key of the file format, for front ends that gather
/// them from elsewhere (Python keyword arguments, later an attribute macro): [`CellDescription::build`]
/// validates it by the same rules as a cell file, errors naming the key.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CellDescription {
    /// `dimension`.
    pub dimension: Option<i64>,
    /// `lattice`, rows.
    pub lattice: Option<Vec<Vec<f64>>>,
    /// The `[[node]]` tables.
    pub nodes: Vec<NodeDescription>,
    /// The `[[bond]]` tables.
    pub bonds: Vec<BondDescription>,
}

/// A `[[node]]` table.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NodeDescription {
    /// `name`.
    pub name: Option<String>,
    /// `kind`: `joint` or `rotor`.
    pub kind: Option<String>,
    /// `position` (joints).
    pub position: Option<Vec<f64>>,
    /// `pivot` (rotors).
    pub pivot: Option<Vec<f64>>,
    /// `length` (rotors).
    pub length: Option<f64>,
    /// `angle` (rotors).
    pub angle: Option<f64>,
}

/// A `[[bond]]` table.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BondDescription {
    /// `from`.
    pub from: Option<String>,
    /// `to`.
    pub to: Option<String>,
    /// `cell` (default zeros).
    pub cell: Option<Vec<i64>>,
    /// `k` (default 1).
    pub k: Option<f64>,
    /// `rest_length` (default: the reference length).
    pub rest_length: Option<f64>,
}

impl CellDescription {
    /// Validate and build (the rules of [`CellBuilder::build`]).
    pub fn build(self) -> Result<Cell, CellError> {
        let raw = Raw {
            dimension: self.dimension.map(Val::plain),
            lattice: self.lattice.map(Val::plain),
            law: None,
            line: None,
            nodes: self
                .nodes
                .into_iter()
                .map(|n| RawNode {
                    line: None,
                    name: n.name.map(Val::plain),
                    kind: n.kind.map(Val::plain),
                    position: n.position.map(Val::plain),
                    pivot: n.pivot.map(Val::plain),
                    length: n.length.map(Val::plain),
                    angle: n.angle.map(Val::plain),
                })
                .collect(),
            bonds: self
                .bonds
                .into_iter()
                .map(|b| RawBond {
                    line: None,
                    from: b.from.map(Val::plain),
                    to: b.to.map(Val::plain),
                    cell: b.cell.map(Val::plain),
                    k: b.k.map(Val::plain),
                    rest_length: b.rest_length.map(Val::plain),
                    law: None,
                })
                .collect(),
        };
        validate_raw(raw)
    }
}
