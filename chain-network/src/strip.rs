//! Strips: periodic along lattice vector `a_I` with wave number `Q = k . a_I`, `M` cells wide
//! along the other lattice vector `a_J` with free edges (bonds leaving the strip are cut). A
//! one-dimensional cell's "strip" is the free chain of `M` cells (no periodic direction; `along`
//! must be 0 and `Q` is not used): its ends are the edges.
//!
//! The strip's compatibility matrix at `Q` has rows = the bonds of cells `m = 0 .. M-1` whose
//! `to` end stays in the strip, columns = the degrees of freedom of the `M` cells, and the
//! Bloch phase `e^{i Q R_I}` on the `to` end. Its null space (rank rule of
//! [`crate::linalg`]) holds the zero modes at `Q`.
//!
//! **Edges.** "low" is the edge at cell index 0 along `a_J`, "high" the edge at `M - 1`. A
//! degenerate null space is split into localized vectors by diagonalising the position
//! operator `X = diag(m)` (each degree of freedom's cell index) restricted to it,
//! `V^H X V`; each eigenvector is a zero mode with a definite centre `<m>`. A mode whose
//! centre lies below the middle `(M - 1)/2` is counted on the low edge, above it on the high
//! edge; a mode with more than 30 % of its weight in the middle third of the strip is reported
//! as a bulk mode instead (a uniform mode has a third there; a mode decaying from an edge over
//! a length `xi` has less than 30 % while `xi < 1.25 M`).
//!
//! **Prediction** (square cells). With `n_J` the winding of `det Q` along `b_J` at
//! `k . a_I = Q` ([`crate::winding::path_winding`]), `s_low = sum_b max(0, -R_bJ)` and
//! `s_high = sum_b max(0, R_bJ)` the bonds cut at each edge per cell: `low = n_J + s_low` and
//! `high = s_high - n_J`. (Re-attach every bond with `R_bJ < 0` to its other end: each such row
//! is multiplied by `e^{i k . a_J}`, adding one to the winding, and then no bond is cut at the
//! low edge, whose zero modes `u_m = z^m v` are the roots `|z| < 1` of `det Q`.)

use crate::cell::Cell;
use crate::compatibility::bond_rows;
use crate::error::NetworkError;
use crate::linalg;
use crate::winding::{PathWinding, path_winding};
use chain_core::validate::{Fields, Validate};
use faer::{Mat, c64};

/// The default wave number along the strip, `Q = k . a_I = 2.0` rad (issue 33): generic, away
/// from the acoustic `Q = 0` and the zone edge `Q = pi`.
pub const DEFAULT_Q: f64 = 2.0;

/// A zero mode with more of its weight than this in the middle third of the strip is bulk.
pub const BULK_WEIGHT: f64 = 0.3;

/// The widest strip: its dense complex decomposition has `(M dof)^2` entries.
pub const MAX_STRIP_DOF: usize = 4000;

/// A strip's geometry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Strip {
    /// The periodic lattice direction `I` (0 or 1).
    pub along: usize,
    /// Cells across, `M`.
    pub cells: usize,
    /// Wave number `Q = k . a_I` (radians).
    pub q: f64,
}

/// The zero modes of a strip and their edges.
#[derive(Clone, Debug)]
pub struct StripModes {
    /// The strip.
    pub strip: Strip,
    /// Zero modes at `Q`.
    pub zero_modes: usize,
    /// States of self-stress at `Q`.
    pub self_stresses: usize,
    /// Zero modes on the low edge (cell 0).
    pub low: usize,
    /// Zero modes on the high edge (cell `M - 1`).
    pub high: usize,
    /// Zero modes localized at neither edge.
    pub bulk: usize,
    /// The centre `<m>` of each localized zero mode (ascending).
    pub centres: Vec<f64>,
    /// The localized zero modes as columns (`M dof x N0`), in the order of `centres`.
    pub modes: Mat<c64>,
    /// The prediction `(low, high)` from the winding, for square cells whose path at `Q`
    /// clears every zero.
    pub predicted: Option<(i64, i64)>,
}

impl Strip {
    /// The lattice direction across the strip (in one dimension the only one, 0).
    pub fn across(&self, cell: &Cell) -> usize {
        if cell.dimension() == 1 { 0 } else { 1 - self.along }
    }

    /// The periodic direction, if the cell has one besides the one across.
    fn periodic(&self, cell: &Cell) -> Option<usize> {
        (cell.dimension() == 2).then_some(self.along)
    }

    /// [`Validate::validate`], then the direction in `cell` and the strip's size in its degrees
    /// of freedom.
    fn check(&self, cell: &Cell) -> Result<(), NetworkError> {
        self.validate()?;
        if self.along > cell.dimension() - 1 {
            return Err(NetworkError::Argument {
                what: "along",
                problem: format!("{}: the cell has {} lattice vector(s)", self.along + 1, cell.dimension()),
            });
        }
        if self.cells.saturating_mul(cell.dof()) > MAX_STRIP_DOF {
            return Err(NetworkError::PatchSize {
                what: "strip",
                direction: self.across(cell) + 1,
                found: self.cells,
                rule: format!(
                    "between 1 and {} cells ({} degrees of freedom at most)",
                    MAX_STRIP_DOF / cell.dof().max(1),
                    MAX_STRIP_DOF
                ),
            });
        }
        Ok(())
    }
}

impl Validate for Strip {
    type Error = NetworkError;

    /// `along` 0 or 1 (a lattice direction of a 2D cell; 1D cells take 0), `cells` between 1 and
    /// [`MAX_STRIP_DOF`] (a cell has at least one degree of freedom; the bound in degrees of
    /// freedom is checked against the cell), `q` finite.
    fn validate(&self) -> Result<(), NetworkError> {
        // No `..`: a field added here does not compile until it is checked.
        let Self { along, cells, q } = *self;
        let fields = Fields("Strip");
        fields.count_in("along", along as u64, 0, 1, "0 or 1 (a lattice direction)")?;
        let most = MAX_STRIP_DOF as u64;
        fields.count_in("cells", cells as u64, 1, most, "between 1 and MAX_STRIP_DOF = 4000 cells")?;
        fields.finite("q", q)?;
        Ok(())
    }
}

/// The strip's compatibility matrix at its wave number.
pub fn compatibility(cell: &Cell, strip: &Strip) -> Result<Mat<c64>, NetworkError> {
    strip.check(cell)?;
    let (i, j) = (strip.periodic(cell), strip.across(cell));
    let m = strip.cells as i64;
    let rows = bond_rows(cell);
    let dof = cell.dof();
    let mut kept = Vec::new();
    for c in 0..m {
        for (b, row) in rows.iter().enumerate() {
            let t = c + row.cell[j];
            if (0..m).contains(&t) {
                kept.push((b, c as usize, t as usize));
            }
        }
    }
    let mut out = Mat::<c64>::zeros(kept.len(), strip.cells * dof);
    for (r, &(b, c, t)) in kept.iter().enumerate() {
        let row = &rows[b];
        let phase = i.map_or(0.0, |i| strip.q * row.cell[i] as f64);
        let z = c64::new(phase.cos(), phase.sin());
        for &(col, v) in &row.from {
            out[(r, c * dof + col)] += c64::new(v, 0.0);
        }
        for &(col, v) in &row.to {
            out[(r, t * dof + col)] += z * v;
        }
    }
    Ok(out)
}

/// The zero modes of a strip, split by edge, with the winding's prediction.
pub fn strip_modes(cell: &Cell, strip: &Strip) -> Result<StripModes, NetworkError> {
    let q = compatibility(cell, strip)?;
    let svd = linalg::full_svd("strip compatibility matrix", q.as_ref())?;
    let largest = svd.s.first().copied().unwrap_or(0.0);
    let null = svd.right_null(largest);
    let self_stresses = svd.left_null(largest).ncols();
    let d = null.ncols();
    let dof = cell.dof();
    let position: Vec<f64> = (0..null.nrows()).map(|r| (r / dof) as f64).collect();
    // X restricted to the null space: V^H diag(m) V.
    let x = Mat::<c64>::from_fn(d, d, |a, b| {
        (0..null.nrows()).map(|r| null[(r, a)].conj() * null[(r, b)] * position[r]).sum()
    });
    let (centres, rotation) = linalg::hermitian_eigen("position operator on the zero modes", x.as_ref())?;
    let modes = &null * &rotation;
    let mid = (strip.cells as f64 - 1.0) / 2.0;
    let third = strip.cells as f64 / 3.0;
    let (mut low, mut high, mut bulk) = (0, 0, 0);
    for (a, &centre) in centres.iter().enumerate() {
        let middle: f64 = (0..modes.nrows())
            .filter(|&r| position[r] >= third - 0.5 && position[r] < 2.0 * third - 0.5)
            .map(|r| modes[(r, a)].norm_sqr())
            .sum();
        if middle > BULK_WEIGHT {
            bulk += 1;
        } else if centre < mid {
            low += 1;
        } else {
            high += 1;
        }
    }
    let predicted = if cell.bonds().len() == cell.dof() {
        match path_winding(cell, strip.across(cell), strip.q)? {
            PathWinding::Winds { winding, .. } => {
                let j = strip.across(cell);
                let s_low: i64 = cell.bonds().iter().map(|b| (-b.cell[j]).max(0)).sum();
                let s_high: i64 = cell.bonds().iter().map(|b| b.cell[j].max(0)).sum();
                Some((winding + s_low, s_high - winding))
            }
            PathWinding::MeetsZero { .. } => None,
        }
    } else {
        None
    };
    Ok(StripModes { strip: *strip, zero_modes: d, self_stresses, low, high, bulk, centres, modes, predicted })
}

/// The frequencies of a strip at wave number `q` (unit masses, `D = Q^H K Q`), ascending.
pub fn strip_frequencies(cell: &Cell, strip: &Strip) -> Result<Vec<f64>, NetworkError> {
    let q = compatibility(cell, strip)?;
    let j = strip.across(cell);
    // The stiffness of each kept row, in the order `compatibility` keeps them.
    let m = strip.cells as i64;
    let mut k = Vec::with_capacity(q.nrows());
    for c in 0..m {
        for bond in cell.bonds() {
            if (0..m).contains(&(c + bond.cell[j])) {
                k.push(bond.k);
            }
        }
    }
    let kq = Mat::<c64>::from_fn(q.nrows(), q.ncols(), |r, c| q[(r, c)] * k[r]);
    let d = q.adjoint() * kq;
    let ev = linalg::hermitian_eigenvalues("strip dynamical matrix", d.as_ref())?;
    Ok(ev.into_iter().map(|x| x.max(0.0).sqrt()).collect())
}
