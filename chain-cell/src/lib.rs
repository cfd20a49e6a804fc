//! # chain-cell
//!
//! The unit cell of a periodic network of joints and rotors, described once (STYLE.md
//! "Networks"): its typed model ([`Cell`]), read from the TOML cell format of issue 33
//! ([`Cell::from_toml_str`], [`Cell::from_toml_file`]), built in Rust ([`CellBuilder`]) or taken
//! ready-made ([`ready`]). Every route goes through one validation (the rules are listed on
//! [`CellBuilder::build`]), so the library, the command line, Python and the attribute agree on
//! what a valid cell is.
//!
//! This crate is light on purpose (serde, toml and thiserror, no linear algebra): the
//! proc-macro crate reads cell files through it without compiling faer. `chain-network`
//! re-exports everything here unchanged (`chain_network::cell`, `chain_network::CellError`).
//!
//! # Conventions
//! - Positions are two-component vectors in both dimensions; a 1D cell has one lattice vector.
//! - A **joint** has two degrees of freedom, its displacement `(dx, dy)`. A **rotor** (a rigid
//!   arm of length `r` on a fixed pivot, at angle `phi` counter-clockwise from `+x`) has one, the
//!   arc length `r dphi` of its tip, so that every column of the compatibility matrix is a
//!   displacement in length units. The tip moves along `t = (-sin phi, cos phi)`.
//! - A bond joins `from` (in cell 0) to `to` in the cell shifted by `R = n1 a1 + n2 a2`
//!   (`cell = [n1, n2]`); its unit vector `e` points from the `from` end to the `to` end.
//! - Degrees of freedom are numbered node by node in the file's order (a joint's `x` then `y`).
#![deny(missing_docs)]

mod builder;
pub mod error;
mod law;
mod text;
mod validate;

pub mod ready;

pub use builder::{BondDescription, CellBuilder, CellDescription, NodeDescription};
pub use error::{CellError, Location};
pub use law::{BondLaw, Polynomial, PolynomialProblem};
use std::path::Path;
pub use validate::{MAX_CELL_BONDS, MAX_CELL_NODES};

/// What a node is.
#[derive(Clone, Debug, PartialEq)]
pub enum NodeKind {
    /// A point mass free in the plane: two degrees of freedom.
    Joint {
        /// Its reference position.
        position: [f64; 2],
    },
    /// A rigid arm on a fixed pivot: one degree of freedom, its tip's arc length `r dphi`.
    Rotor {
        /// The fixed pivot.
        pivot: [f64; 2],
        /// The arm's length `r` (> 0).
        length: f64,
        /// The arm's reference angle `phi`, counter-clockwise from `+x` (radians).
        angle: f64,
    },
}

/// A node of the cell: a joint or a rotor.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// Its name, unique in the cell.
    pub name: String,
    /// Joint or rotor, with its geometry.
    pub kind: NodeKind,
}

impl Node {
    /// Degrees of freedom: 2 for a joint, 1 for a rotor.
    pub fn dof(&self) -> usize {
        match self.kind {
            NodeKind::Joint { .. } => 2,
            NodeKind::Rotor { .. } => 1,
        }
    }

    /// Where bonds attach: a joint's position, a rotor's tip `pivot + r (cos phi, sin phi)`.
    pub fn point(&self) -> [f64; 2] {
        match self.kind {
            NodeKind::Joint { position } => position,
            NodeKind::Rotor { pivot, length, angle } => {
                [pivot[0] + length * angle.cos(), pivot[1] + length * angle.sin()]
            }
        }
    }

    /// The point that a macroscopic strain moves affinely (a joint's position, a rotor's pivot).
    pub fn anchor(&self) -> [f64; 2] {
        match self.kind {
            NodeKind::Joint { position } => position,
            NodeKind::Rotor { pivot, .. } => pivot,
        }
    }

    /// The displacement of the attachment point per unit of each degree of freedom: `(1, 0)` and
    /// `(0, 1)` for a joint, the tip's unit tangent `(-sin phi, cos phi)` for a rotor.
    pub fn directions(&self) -> ([f64; 2], Option<[f64; 2]>) {
        match self.kind {
            NodeKind::Joint { .. } => ([1.0, 0.0], Some([0.0, 1.0])),
            NodeKind::Rotor { angle, .. } => ([-angle.sin(), angle.cos()], None),
        }
    }
}

/// A spring between two nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct Bond {
    /// The index of the `from` node (in cell 0).
    pub from: usize,
    /// The index of the `to` node (in cell `cell`).
    pub to: usize,
    /// The cell offset `[n1, n2]` of the `to` end (`n2 = 0` in one dimension).
    pub cell: [i64; 2],
    /// Spring constant (> 0; default 1).
    pub k: f64,
    /// Rest length (> 0; default: the reference length, so the reference is stress-free).
    pub rest_length: f64,
    /// The spring law (default: the cell's `law`, itself harmonic by default).
    pub law: BondLaw,
}

/// A validated unit cell. Build one with [`Cell::from_toml_str`], [`Cell::builder`] or a
/// function of [`ready`].
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    dimension: usize,
    lattice: [[f64; 2]; 2],
    nodes: Vec<Node>,
    bonds: Vec<Bond>,
    dof_offset: Vec<usize>,
    dof: usize,
}

impl Cell {
    /// Read a cell from the TOML text of the cell format; errors name the key and the line.
    pub fn from_toml_str(text: &str) -> Result<Cell, CellError> {
        validate::validate_raw(text::parse(text)?)
    }

    /// Read a cell file. An unreadable file is a [`CellError::Syntax`] without a line.
    pub fn from_toml_file(path: impl AsRef<Path>) -> Result<Cell, CellError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| CellError::Syntax {
            line: None,
            column: None,
            message: format!("cannot read {}: {e}", path.display()),
        })?;
        Cell::from_toml_str(&text)
    }

    /// A builder for a cell of `dimension` 1 or 2 with lattice vectors `lattice` (rows).
    pub fn builder(dimension: usize, lattice: &[[f64; 2]]) -> CellBuilder {
        CellBuilder::new(dimension, lattice)
    }

    pub(crate) fn from_parts(
        dimension: usize,
        lattice: [[f64; 2]; 2],
        nodes: Vec<Node>,
        bonds: Vec<Bond>,
    ) -> Cell {
        let mut dof_offset = Vec::with_capacity(nodes.len());
        let mut dof = 0;
        for node in &nodes {
            dof_offset.push(dof);
            dof += node.dof();
        }
        Cell { dimension, lattice, nodes, bonds, dof_offset, dof }
    }

    /// 1 or 2.
    pub fn dimension(&self) -> usize {
        self.dimension
    }

    /// Lattice vector `a_i` (`i` = 0 or 1; 1 only in two dimensions).
    pub fn lattice_vector(&self, i: usize) -> [f64; 2] {
        self.lattice[i]
    }

    /// The lattice vectors as rows (one row in one dimension).
    pub fn lattice(&self) -> &[[f64; 2]] {
        &self.lattice[..self.dimension]
    }

    /// Reciprocal vector `b_i` with `a_i . b_j = 2 pi delta_ij` (in one dimension
    /// `b_1 = 2 pi a_1 / |a_1|^2`).
    pub fn reciprocal_vector(&self, i: usize) -> [f64; 2] {
        let tau = std::f64::consts::TAU;
        let [a1, a2] = self.lattice;
        if self.dimension == 1 {
            let n2 = a1[0] * a1[0] + a1[1] * a1[1];
            return [tau * a1[0] / n2, tau * a1[1] / n2];
        }
        let det = a1[0] * a2[1] - a1[1] * a2[0];
        match i {
            0 => [tau * a2[1] / det, -tau * a2[0] / det],
            _ => [-tau * a1[1] / det, tau * a1[0] / det],
        }
    }

    /// The nodes, in the file's order.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The bonds, in the file's order.
    pub fn bonds(&self) -> &[Bond] {
        &self.bonds
    }

    /// Degrees of freedom per cell.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// The index of node `n`'s first degree of freedom.
    pub fn dof_offset(&self, n: usize) -> usize {
        self.dof_offset[n]
    }

    /// The node index of each degree of freedom.
    pub fn dof_nodes(&self) -> Vec<usize> {
        self.nodes.iter().enumerate().flat_map(|(n, node)| std::iter::repeat_n(n, node.dof())).collect()
    }

    /// The index of the node called `name`.
    pub fn node_index(&self, name: &str) -> Option<usize> {
        self.nodes.iter().position(|n| n.name == name)
    }

    /// The translation `n1 a1 + n2 a2` of cell offset `cell`.
    pub fn shift(&self, cell: [i64; 2]) -> [f64; 2] {
        let [a1, a2] = self.lattice;
        let (n1, n2) = (cell[0] as f64, cell[1] as f64);
        [n1 * a1[0] + n2 * a2[0], n1 * a1[1] + n2 * a2[1]]
    }

    /// Bond `b`'s vector from its `from` end to its `to` end in the reference configuration.
    pub fn bond_vector(&self, b: usize) -> [f64; 2] {
        let bond = &self.bonds[b];
        let p = self.nodes[bond.from].point();
        let q = self.nodes[bond.to].point();
        let s = self.shift(bond.cell);
        [q[0] + s[0] - p[0], q[1] + s[1] - p[1]]
    }

    /// Bond `b`'s length in the reference configuration.
    pub fn bond_length(&self, b: usize) -> f64 {
        let d = self.bond_vector(b);
        d[0].hypot(d[1])
    }

    /// Bond `b`'s unit vector `e`, from `from` to `to`.
    pub fn bond_unit(&self, b: usize) -> [f64; 2] {
        let d = self.bond_vector(b);
        let l = d[0].hypot(d[1]);
        [d[0] / l, d[1] / l]
    }

    /// Bond `b`'s midpoint, with its `from` end in cell 0.
    pub fn bond_midpoint(&self, b: usize) -> [f64; 2] {
        let p = self.nodes[self.bonds[b].from].point();
        let d = self.bond_vector(b);
        [p[0] + 0.5 * d[0], p[1] + 0.5 * d[1]]
    }

    /// Coordinates of a vector `v` in the lattice basis: `v = c1 a1 + c2 a2` (`v . b_i / 2 pi`).
    pub fn lattice_coordinates(&self, v: [f64; 2]) -> Vec<f64> {
        (0..self.dimension)
            .map(|i| {
                let b = self.reciprocal_vector(i);
                (v[0] * b[0] + v[1] * b[1]) / std::f64::consts::TAU
            })
            .collect()
    }

    /// A typical length of the cell: the longest lattice vector (for relative tolerances).
    pub fn length_scale(&self) -> f64 {
        self.lattice().iter().map(|a| a[0].hypot(a[1])).fold(0.0, f64::max)
    }

    /// The cell in the TOML cell format; numbers are written so that they read back exactly
    /// (`Cell::from_toml_str(&cell.to_toml())` equals `cell`).
    pub fn to_toml(&self) -> String {
        use std::fmt::Write;
        let v = |p: [f64; 2]| format!("[{:?}, {:?}]", p[0], p[1]);
        let mut out = String::new();
        let rows: Vec<String> = self.lattice().iter().map(|a| v(*a)).collect();
        let _ = writeln!(out, "dimension = {}\nlattice = [{}]", self.dimension, rows.join(", "));
        for node in &self.nodes {
            let _ = writeln!(out, "\n[[node]]\nname = {:?}", node.name);
            match node.kind {
                NodeKind::Joint { position } => {
                    let _ = writeln!(out, "kind = \"joint\"\nposition = {}", v(position));
                }
                NodeKind::Rotor { pivot, length, angle } => {
                    let _ = writeln!(
                        out,
                        "kind = \"rotor\"\npivot = {}\nlength = {length:?}\nangle = {angle:?}",
                        v(pivot)
                    );
                }
            }
        }
        for bond in &self.bonds {
            let cell: Vec<String> = bond.cell[..self.dimension].iter().map(|c| c.to_string()).collect();
            let _ = writeln!(
                out,
                "\n[[bond]]\nfrom = {:?}\nto = {:?}\ncell = [{}]\nk = {:?}\nrest_length = {:?}",
                self.nodes[bond.from].name,
                self.nodes[bond.to].name,
                cell.join(", "),
                bond.k,
                bond.rest_length
            );
            if bond.law != BondLaw::Harmonic {
                let _ = writeln!(out, "law = {}", bond.law.to_toml());
            }
        }
        out
    }
}
