//! The compatibility matrix: rows are bonds, columns degrees of freedom, `C u = extensions`.
//!
//! Bond `b` from node `f` (cell 0) to node `t` (cell `R`) with unit vector `e` (from `f` to
//! `t`) stretches by `e . (u_t(R) - u_f(0))` to first order, where `u` is the displacement of a
//! node's attachment point: a joint's `(dx, dy)`, a rotor tip's `r dphi (-sin phi, cos phi)`.
//! Its row is therefore `-e . d` on each of `f`'s degrees of freedom and `+e . d` on each of
//! `t`'s, with `d` the displacement per unit of that degree of freedom
//! ([`crate::Node::directions`]). Every column is a displacement in length units, so the
//! entries are dimensionless and the rank tolerance is scale-free.

use crate::cell::Cell;

/// One bond's row, split by end: `(column within the cell, entry)` pairs.
#[derive(Clone, Debug, PartialEq)]
pub struct BondRow {
    /// Entries on the `from` node's degrees of freedom (cell 0): `-e . d`.
    pub from: Vec<(usize, f64)>,
    /// Entries on the `to` node's degrees of freedom (cell `cell`): `+e . d`.
    pub to: Vec<(usize, f64)>,
    /// The cell offset of the `to` end.
    pub cell: [i64; 2],
}

/// The row of bond `b`.
pub fn bond_row(cell: &Cell, b: usize) -> BondRow {
    let bond = &cell.bonds()[b];
    let e = cell.bond_unit(b);
    let entries = |n: usize, sign: f64| {
        let node = &cell.nodes()[n];
        let offset = cell.dof_offset(n);
        let (d0, d1) = node.directions();
        let mut out = vec![(offset, sign * (e[0] * d0[0] + e[1] * d0[1]))];
        if let Some(d1) = d1 {
            out.push((offset + 1, sign * (e[0] * d1[0] + e[1] * d1[1])));
        }
        out
    };
    BondRow { from: entries(bond.from, -1.0), to: entries(bond.to, 1.0), cell: bond.cell }
}

/// The rows of every bond, in the cell's order.
pub fn bond_rows(cell: &Cell) -> Vec<BondRow> {
    (0..cell.bonds().len()).map(|b| bond_row(cell, b)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::ready;

    /// A row predicts the change of the bond's length to first order: against a central finite
    /// difference of the length itself, for joints and rotors.
    #[test]
    fn rows_are_first_derivatives_of_bond_lengths() {
        let cell = Cell::builder(2, &[[1.0, 0.1], [0.2, 1.3]])
            .joint("a", [0.1, 0.2])
            .rotor("p", [0.5, 0.4], 0.3, 0.7)
            .joint("c", [0.7, 0.9])
            .bond("a", "p", &[0, 0])
            .bond("p", "c", &[1, 0])
            .bond("c", "a", &[0, 1])
            .bond("p", "p", &[1, -1])
            .build()
            .unwrap();
        let h = 1e-6;
        for b in 0..cell.bonds().len() {
            let row = bond_row(&cell, b);
            let bond = &cell.bonds()[b];
            for (end, entries) in [(bond.from, &row.from), (bond.to, &row.to)] {
                for (k, &(col, value)) in entries.iter().enumerate() {
                    let local = col - cell.dof_offset(end);
                    assert_eq!(local, k);
                    // Move the node's attachment point by +-h along the degree of freedom.
                    let length = |s: f64| {
                        let point = |n: usize| {
                            let mut node = cell.nodes()[n].clone();
                            if n == end {
                                match &mut node.kind {
                                    crate::NodeKind::Joint { position } => position[local] += s,
                                    crate::NodeKind::Rotor { length, angle, .. } => *angle += s / *length,
                                }
                            }
                            node.point()
                        };
                        let (p, q, shift) = (point(bond.from), point(bond.to), cell.shift(bond.cell));
                        (q[0] + shift[0] - p[0]).hypot(q[1] + shift[1] - p[1])
                    };
                    // A bond from a node to its own image moves both ends: its row has both.
                    let expected = (length(h) - length(-h)) / (2.0 * h);
                    let total: f64 = if bond.from == bond.to {
                        row.from.iter().chain(&row.to).filter(|e| e.0 == col).map(|e| e.1).sum()
                    } else {
                        value
                    };
                    assert!((total - expected).abs() < 1e-8, "bond {b} col {col}: {total} vs {expected}");
                }
            }
        }
        let _ = ready::square();
    }
}
