//! The Bloch compatibility matrix `Q(k)`, the dynamical matrix and its bands.
//!
//! **Bloch convention** (issue 33): a displacement wave `u(R) = u e^{i k . R}` on the cells `R`
//! stretches bond `b` (from `f` in cell 0 to `t` in cell `R_b`) by `Q(k) u`, with row
//! `-e . d` on `f` and `+e . d e^{i k . R_b}` on `t`: the phase sits on the `to` end. Rows are
//! bonds, columns degrees of freedom, as in [`crate::compatibility`]. `k` enters only through
//! the phases `theta_i = k . a_i`, which is how every function here takes it; `Q` is periodic
//! in each `theta_i` with period `2 pi`.
//!
//! The dynamical matrix is `D(k) = Q(k)^H K Q(k)` with `K = diag(k_b)` and unit mass per degree
//! of freedom (the file format has no masses: a joint or a rotor's tip of mass 1), so the
//! frequencies are `omega = sqrt(eig D)`. Pre-stress (rest lengths other than the reference
//! lengths) adds a stress matrix that this linear analysis leaves out.

use crate::cell::Cell;
use crate::compatibility::{BondRow, bond_rows};
use crate::error::NetworkError;
use crate::linalg;
use faer::{Mat, c64};
use std::f64::consts::TAU;

/// The phases `theta_i = k . a_i` of a Cartesian wave vector `k` (one in one dimension).
pub fn phases(cell: &Cell, k: [f64; 2]) -> [f64; 2] {
    let mut out = [0.0; 2];
    for (i, a) in cell.lattice().iter().enumerate() {
        out[i] = k[0] * a[0] + k[1] * a[1];
    }
    out
}

/// The Cartesian wave vector `k = f1 b1 + f2 b2` of reduced coordinates `f`.
pub fn wave_vector(cell: &Cell, reduced: [f64; 2]) -> [f64; 2] {
    let mut k = [0.0; 2];
    for (i, f) in reduced.iter().enumerate().take(cell.dimension()) {
        let b = cell.reciprocal_vector(i);
        k[0] += f * b[0];
        k[1] += f * b[1];
    }
    k
}

/// `Q(k)` for the phases `theta_i = k . a_i`: bonds x dof, complex.
pub fn compatibility(cell: &Cell, theta: [f64; 2]) -> Mat<c64> {
    let rows = bond_rows(cell);
    let mut q = Mat::<c64>::zeros(rows.len(), cell.dof());
    fill(&rows, theta, &mut q);
    q
}

/// Fill `q` (bonds x dof, zeroed here) with `Q` at `theta` from the cell's rows.
pub(crate) fn fill(rows: &[BondRow], theta: [f64; 2], q: &mut Mat<c64>) {
    q.fill(c64::new(0.0, 0.0));
    for (i, row) in rows.iter().enumerate() {
        let phase = row.cell[0] as f64 * theta[0] + row.cell[1] as f64 * theta[1];
        let z = c64::new(phase.cos(), phase.sin());
        for &(j, v) in &row.from {
            q[(i, j)] += c64::new(v, 0.0);
        }
        for &(j, v) in &row.to {
            q[(i, j)] += z * v;
        }
    }
}

/// The dynamical matrix `D = Q^H K Q` at `theta` (unit masses).
pub fn dynamical_matrix(cell: &Cell, theta: [f64; 2]) -> Mat<c64> {
    let q = compatibility(cell, theta);
    let kq = Mat::<c64>::from_fn(q.nrows(), q.ncols(), |i, j| q[(i, j)] * cell.bonds()[i].k);
    q.adjoint() * kq
}

/// The frequencies `omega_n(k) = sqrt(eig D(k))`, ascending; eigenvalues below zero by rounding
/// give 0.
pub fn frequencies(cell: &Cell, theta: [f64; 2]) -> Result<Vec<f64>, NetworkError> {
    let d = dynamical_matrix(cell, theta);
    let ev = linalg::hermitian_eigenvalues("dynamical matrix", d.as_ref())?;
    Ok(ev.into_iter().map(|x| x.max(0.0).sqrt()).collect())
}

/// A point of a band path: reduced coordinates (fractions of `b1`, `b2`) and a label.
#[derive(Clone, Debug, PartialEq)]
pub struct PathPoint {
    /// Its label (`G`, `X`, `M`, or the coordinates).
    pub label: String,
    /// `k = f1 b1 + f2 b2`.
    pub reduced: [f64; 2],
}

/// Parse a band path: points joined by `-`, each a name (`G` = (0, 0), `X` = (1/2, 0),
/// `Y` = (0, 1/2), `M` = (1/2, 1/2), `K` = (1/3, 1/3), `K'` = (2/3, 1/3)) or reduced
/// coordinates `f1,f2` (one number in one dimension), e.g. `G-X-M-G` or `0,0-0.5,0-0.5,0.5`.
pub fn parse_path(cell: &Cell, path: &str) -> Result<Vec<PathPoint>, NetworkError> {
    let bad = |problem: String| NetworkError::Argument { what: "path", problem };
    let points: Vec<PathPoint> = path
        .split('-')
        .map(|p| {
            let p = p.trim();
            let reduced = match p {
                "G" | "Γ" => [0.0, 0.0],
                "X" => [0.5, 0.0],
                "Y" => [0.0, 0.5],
                "M" => [0.5, 0.5],
                "K" => [1.0 / 3.0, 1.0 / 3.0],
                "K'" => [2.0 / 3.0, 1.0 / 3.0],
                _ => {
                    let v: Result<Vec<f64>, _> = p.split(',').map(|x| x.trim().parse::<f64>()).collect();
                    let v = v.map_err(|_| {
                        bad(format!("`{p}` is neither a named point (G X Y M K K') nor numbers f1,f2"))
                    })?;
                    if v.len() != cell.dimension() || v.iter().any(|x| !x.is_finite()) {
                        return Err(bad(format!(
                            "`{p}`: expected {} finite reduced coordinates",
                            cell.dimension()
                        )));
                    }
                    [v[0], v.get(1).copied().unwrap_or(0.0)]
                }
            };
            if cell.dimension() == 1 && reduced[1] != 0.0 {
                return Err(bad(format!("`{p}` has a second coordinate; the cell is one-dimensional")));
            }
            Ok(PathPoint { label: p.to_owned(), reduced })
        })
        .collect::<Result<_, _>>()?;
    if points.len() < 2 {
        return Err(bad(format!("`{path}`: at least two points joined by `-`")));
    }
    Ok(points)
}

/// Bands along a path.
#[derive(Clone, Debug, PartialEq)]
pub struct Bands {
    /// Distance along the path in `|k|` (inverse length units), one per sample.
    pub distance: Vec<f64>,
    /// The phases `theta` of each sample.
    pub theta: Vec<[f64; 2]>,
    /// `frequencies[s][n]`: band `n` (ascending) at sample `s`.
    pub frequencies: Vec<Vec<f64>>,
    /// The path's corners: distance and label.
    pub ticks: Vec<(f64, String)>,
}

/// The bands along `path` with `samples` points per segment (at least 2).
pub fn bands(cell: &Cell, path: &[PathPoint], samples: usize) -> Result<Bands, NetworkError> {
    const MAX_SAMPLES: usize = 100_000;
    if !(2..=MAX_SAMPLES).contains(&samples) {
        return Err(NetworkError::Argument {
            what: "samples",
            problem: format!("{samples}: between 2 and {MAX_SAMPLES} per segment"),
        });
    }
    let mut out =
        Bands { distance: Vec::new(), theta: Vec::new(), frequencies: Vec::new(), ticks: Vec::new() };
    let mut s = 0.0;
    out.ticks.push((0.0, path[0].label.clone()));
    for w in path.windows(2) {
        let (a, b) = (wave_vector(cell, w[0].reduced), wave_vector(cell, w[1].reduced));
        let length = (b[0] - a[0]).hypot(b[1] - a[1]);
        let first = if out.distance.is_empty() { 0 } else { 1 };
        for i in first..samples {
            let t = i as f64 / (samples - 1) as f64;
            let f = [
                w[0].reduced[0] + t * (w[1].reduced[0] - w[0].reduced[0]),
                w[0].reduced[1] + t * (w[1].reduced[1] - w[0].reduced[1]),
            ];
            let theta = [TAU * f[0], TAU * f[1]];
            out.distance.push(s + t * length);
            out.theta.push(theta);
            out.frequencies.push(frequencies(cell, theta)?);
        }
        s += length;
        out.ticks.push((s, w[1].label.clone()));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::ready;

    /// The square lattice's closed form: omega^2 = 2 - 2 cos kx and 2 - 2 cos ky.
    #[test]
    fn square_lattice_bands_are_the_closed_form() {
        let cell = ready::square();
        for (kx, ky) in [(0.3, 1.1), (2.0, -0.4), (3.1, 3.1)] {
            let w = frequencies(&cell, phases(&cell, [kx, ky])).unwrap();
            let mut expected = [(2.0 - 2.0 * f64::cos(kx)).sqrt(), (2.0 - 2.0 * f64::cos(ky)).sqrt()];
            expected.sort_by(f64::total_cmp);
            assert!(
                (w[0] - expected[0]).abs() < 1e-12 && (w[1] - expected[1]).abs() < 1e-12,
                "{w:?} {expected:?}"
            );
        }
    }

    /// The phase sits on the `to` end: a 1D chain of joints with one bond to the next cell has
    /// Q(k) = [-1 + e^{ik}] on its x column.
    #[test]
    fn the_bloch_phase_is_on_the_to_end() {
        let cell =
            Cell::builder(1, &[[1.0, 0.0]]).joint("a", [0.0, 0.0]).bond("a", "a", &[1]).build().unwrap();
        let k = 0.7;
        let q = compatibility(&cell, [k, 0.0]);
        let expected = c64::new(k.cos() - 1.0, k.sin());
        assert!((q[(0, 0)] - expected).norm() < 1e-15 && q[(0, 1)].norm() < 1e-15);
    }

    #[test]
    fn reciprocal_vectors_are_dual() {
        let cell = ready::kagome();
        for i in 0..2 {
            for j in 0..2 {
                let a = cell.lattice_vector(i);
                let b = cell.reciprocal_vector(j);
                let dot = a[0] * b[0] + a[1] * b[1];
                assert!((dot - if i == j { TAU } else { 0.0 }).abs() < 1e-12);
            }
        }
        let p = parse_path(&cell, "G-X-M-G").unwrap();
        assert_eq!(p.len(), 4);
        assert!(parse_path(&cell, "G").is_err() && parse_path(&cell, "G-Q").is_err());
    }
}
