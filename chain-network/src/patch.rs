//! Finite patches of `N1 x N2` cells (`N2 = 1` in one dimension), periodic or free.
//!
//! Cell `(c1, c2)` holds a copy of every node; its degrees of freedom are numbered
//! `(c1 + N1 c2) * dof + j`. A **periodic** patch keeps every bond, its `to` end wrapped into the
//! patch; a **free** patch keeps every bond whose two ends lie in the patch (issue 33).

use crate::cell::Cell;
use crate::compatibility::bond_rows;
use crate::error::NetworkError;
use faer::Mat;

/// The boundary of a patch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Boundary {
    /// Periodic along every lattice vector (a torus).
    Periodic,
    /// Free: bonds leaving the patch are cut.
    Free,
}

/// The fewest cells a periodic direction may have: with fewer, a bond to the neighbouring
/// cell joins a node to itself or doubles another bond (issue 33).
pub const MIN_PERIODIC_CELLS: usize = 3;

/// The most bonds (and degrees of freedom) a patch may have: 2^25 (33.5 million; 1.3 GB for the patch's bond list alone,
/// and a multiple of it for a model or a matrix built on it). A 1000 x 1000 kagome patch has
/// 6 million; the bound turns a mistyped size (`--cells 100000x100000`) into an error naming it
/// instead of an allocation the machine cannot give.
pub const MAX_PATCH_BONDS: usize = 1 << 25;

/// One bond of a patch: the cell's bond `bond` from cell `from_cell` to cell `to_cell`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PatchBond {
    /// The bond of the unit cell.
    pub bond: usize,
    /// The cell of its `from` end.
    pub from_cell: [usize; 2],
    /// The cell of its `to` end (wrapped, for a periodic patch).
    pub to_cell: [usize; 2],
}

/// A finite patch of a cell.
#[derive(Clone, Debug)]
pub struct Patch<'a> {
    cell: &'a Cell,
    cells: [usize; 2],
    boundary: Boundary,
    bonds: Vec<PatchBond>,
}

impl<'a> Patch<'a> {
    /// A patch of `cells = [N1, N2]` cells (`N2 = 1` in one dimension). Periodic directions need
    /// at least [`MIN_PERIODIC_CELLS`] cells, and no bond may join a node to itself or repeat
    /// another bond once wrapped.
    pub fn new(cell: &'a Cell, cells: [usize; 2], boundary: Boundary) -> Result<Self, NetworkError> {
        let what = match boundary {
            Boundary::Periodic => "periodic patch",
            Boundary::Free => "free patch",
        };
        for (i, &n) in cells.iter().enumerate() {
            if i >= cell.dimension() {
                if n != 1 {
                    return Err(NetworkError::PatchSize {
                        what,
                        direction: i + 1,
                        found: n,
                        rule: "a one-dimensional cell has one lattice vector: use 1".into(),
                    });
                }
            } else if n == 0 {
                return Err(NetworkError::PatchSize {
                    what,
                    direction: i + 1,
                    found: n,
                    rule: "at least 1 cell".into(),
                });
            } else if boundary == Boundary::Periodic && n < MIN_PERIODIC_CELLS {
                return Err(NetworkError::PatchSize {
                    what,
                    direction: i + 1,
                    found: n,
                    rule: format!(
                        "a periodic direction needs at least {MIN_PERIODIC_CELLS} cells (fewer would make bonds to the node itself or doubled bonds)"
                    ),
                });
            }
        }
        // Bonds and degrees of freedom both (a cell of many nodes and few bonds has more of the latter).
        let per_cell = cell.bonds().len().max(cell.dof());
        let size = cells[0].checked_mul(cells[1]).and_then(|t| t.checked_mul(per_cell));
        if size.is_none_or(|s| s > MAX_PATCH_BONDS) {
            return Err(NetworkError::PatchSize {
                what,
                direction: 1,
                found: cells[0],
                rule: format!(
                    "at most {MAX_PATCH_BONDS} bonds and as many degrees of freedom in a patch ({} x {} cells of \
                     {} bonds and {} degrees of freedom ask for more)",
                    cells[0],
                    cells[1],
                    cell.bonds().len(),
                    cell.dof()
                ),
            });
        }
        let count = cells[0] * cells[1] * cell.bonds().len();
        if boundary == Boundary::Periodic {
            check_periodic_images(cell, cells)?;
        }
        let mut bonds = chain_core::allocation::try_vec(count, "the patch's bonds")?;
        for c2 in 0..cells[1] {
            for c1 in 0..cells[0] {
                for (b, bond) in cell.bonds().iter().enumerate() {
                    let t = [c1 as i64 + bond.cell[0], c2 as i64 + bond.cell[1]];
                    let n = [cells[0] as i64, cells[1] as i64];
                    let to_cell = match boundary {
                        Boundary::Periodic => {
                            [t[0].rem_euclid(n[0]) as usize, t[1].rem_euclid(n[1]) as usize]
                        }
                        Boundary::Free => {
                            if t[0] < 0 || t[1] < 0 || t[0] >= n[0] || t[1] >= n[1] {
                                continue;
                            }
                            [t[0] as usize, t[1] as usize]
                        }
                    };
                    bonds.push(PatchBond { bond: b, from_cell: [c1, c2], to_cell });
                }
            }
        }
        Ok(Patch { cell, cells, boundary, bonds })
    }

    /// The unit cell.
    pub fn cell(&self) -> &'a Cell {
        self.cell
    }

    /// `[N1, N2]`.
    pub fn cells(&self) -> [usize; 2] {
        self.cells
    }

    /// Periodic or free.
    pub fn boundary(&self) -> Boundary {
        self.boundary
    }

    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.cells[0] * self.cells[1]
    }

    /// Degrees of freedom of the patch.
    pub fn dof(&self) -> usize {
        self.cell_count() * self.cell.dof()
    }

    /// The bonds of the patch, cell by cell (`c1` fastest) and in the cell's order within a cell.
    pub fn bonds(&self) -> &[PatchBond] {
        &self.bonds
    }

    /// The linear index of cell `c`.
    pub fn cell_index(&self, c: [usize; 2]) -> usize {
        c[0] + self.cells[0] * c[1]
    }

    /// The column of degree of freedom `j` (of the cell) in cell `c`.
    pub fn column(&self, c: [usize; 2], j: usize) -> usize {
        self.cell_index(c) * self.cell.dof() + j
    }

    /// The dense compatibility matrix (bonds x dof).
    pub fn compatibility_matrix(&self) -> Result<Mat<f64>, NetworkError> {
        let (m, n) = (self.bonds.len(), self.dof());
        if m.saturating_mul(n) > crate::linalg::MAX_DENSE_ENTRIES {
            return Err(NetworkError::TooLarge {
                what: "compatibility matrix",
                rows: m,
                cols: n,
                limit: crate::linalg::MAX_DENSE_ENTRIES,
            });
        }
        let rows = bond_rows(self.cell);
        let mut c = Mat::<f64>::zeros(m, n);
        for (i, pb) in self.bonds.iter().enumerate() {
            let row = &rows[pb.bond];
            for &(j, v) in &row.from {
                c[(i, self.column(pb.from_cell, j))] += v;
            }
            for &(j, v) in &row.to {
                c[(i, self.column(pb.to_cell, j))] += v;
            }
        }
        Ok(c)
    }

    /// The attachment point (joint position, rotor tip) of node `n` in cell `c`.
    pub fn point(&self, c: [usize; 2], n: usize) -> [f64; 2] {
        let p = self.cell.nodes()[n].point();
        let s = self.cell.shift([c[0] as i64, c[1] as i64]);
        [p[0] + s[0], p[1] + s[1]]
    }
}

/// On a periodic patch of `cells`, no bond may join a node instance to itself and no two bonds
/// the same two instances.
fn check_periodic_images(cell: &Cell, cells: [usize; 2]) -> Result<(), NetworkError> {
    let n = [cells[0] as i64, cells[1] as i64];
    let wrap = |r: [i64; 2]| [r[0].rem_euclid(n[0]), r[1].rem_euclid(n[1])];
    let mut seen: Vec<(usize, usize, [i64; 2])> = Vec::new();
    for (b, bond) in cell.bonds().iter().enumerate() {
        let r = wrap(bond.cell);
        let minus = wrap([-bond.cell[0], -bond.cell[1]]);
        if bond.from == bond.to && r == [0, 0] {
            return Err(NetworkError::PeriodicImage {
                cells,
                bond: b,
                problem: format!(
                    "joins node `{}` to itself (its offset {:?} wraps to zero)",
                    cell.nodes()[bond.from].name,
                    bond.cell
                ),
            });
        }
        let key = if bond.from < bond.to || (bond.from == bond.to && r <= minus) {
            (bond.from, bond.to, r)
        } else {
            (bond.to, bond.from, minus)
        };
        if let Some(first) = seen.iter().position(|s| *s == key) {
            return Err(NetworkError::PeriodicImage {
                cells,
                bond: b,
                problem: format!("joins the same two nodes as bond {first} once wrapped"),
            });
        }
        seen.push(key);
    }
    Ok(())
}
