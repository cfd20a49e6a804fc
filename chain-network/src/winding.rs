//! Winding numbers of `det Q(k)` and the topological polarization `R_T` (Kane and Lubensky,
//! Nature Physics 10, 39 (2014), arXiv:1308.0554, eq. 7 and the index theorem eqs. 3-8).
//!
//! **Convention** (issue 33). With `Q(k)` as in [`crate::bloch`] (rows = bonds, phase on the
//! `to` end), the winding `n_i` is the number of turns of `arg det Q(k)` as `k` crosses the
//! zone along `b_i` (`k . a_i` from 0 to `2 pi`) at a fixed, generic transverse `k`. It belongs
//! to the cell as written: moving a node or a bond to another cell changes it. The cell's
//! dipole (Kane and Lubensky's `r0`, their "standard unit cell" has `r0 = 0`) is
//! `r0 = sum_nodes dof_n p_n - sum_bonds m_b`, with `p_n` a node's attachment point (joint
//! position, rotor tip) and `m_b` the midpoint of bond `b` drawn from its `from` end in cell 0.
//! The polarization, which does not depend on how the cell is written, is
//! `R_T = -(n_1 a_1 + n_2 a_2) - r0`, i.e. `n_i = -b_i . (R_T + r0) / 2 pi`. (Kane and Lubensky's
//! equilibrium matrix `Q` is the transpose of ours in their Bloch convention; in their standard
//! gauge `R_T = sum_i n_i a_i` with their windings, which are minus ours.)
//!
//! **Method.** Along a path, `det Q` is a Laurent polynomial in `z = e^{i k . a_i}` whose
//! exponents lie between the sums of the bonds' negative and positive offsets along `a_i`. Its
//! coefficients are recovered exactly (to rounding) from as many samples by a discrete Fourier
//! transform; then `arg det Q` is followed on a grid fine enough that the polynomial's Lipschitz
//! bound `2 pi sum |m c_m|` keeps each step inside a disc around the sample that excludes 0, so
//! the unwrapped phase is certified. A path on which `|det Q|` falls below `1e-8` of Hadamard's
//! bound `prod_b |row_b|` passes through (or next to) a zero and is moved: [`WindingOptions::transverse`]
//! lists the transverse positions tried. If every path along a direction meets a zero (lines of
//! zeros: the square and regular kagome lattices), the winding is undefined
//! ([`NetworkError::WindingUndefined`]); if paths disagree, point zeros (Weyl points) lie between
//! them ([`NetworkError::WeylPoints`]). Paths avoid `k = 0`, the acoustic zero of joint lattices.

use crate::bloch;
use crate::cell::Cell;
use crate::compatibility::bond_rows;
use crate::error::NetworkError;
use chain_core::validate::{Fields, Validate};
use faer::{Mat, c64};
use std::f64::consts::TAU;

/// `|det Q|` below this fraction of Hadamard's bound `prod_b |row_b|` counts as a zero on the
/// path.
pub const ZERO_TOLERANCE: f64 = 1e-8;

/// The most samples of one path (the certified grid refines up to here).
pub const MAX_PATH_SAMPLES: usize = 1 << 22;

/// Where the paths cross the zone.
#[derive(Clone, Debug, PartialEq)]
pub struct WindingOptions {
    /// Transverse positions tried, as fractions of the other reciprocal vector (`k . a_j / 2 pi`).
    /// Default: five irrational-looking fractions spread over the zone, none near 0 (the acoustic
    /// zero at `k = 0`) nor 1/2 (where symmetric lattices have their zeros).
    pub transverse: Vec<f64>,
}

impl Default for WindingOptions {
    fn default() -> Self {
        WindingOptions { transverse: vec![0.1234, 0.2871, 0.4119, 0.6533, 0.8462] }
    }
}

impl Validate for WindingOptions {
    type Error = NetworkError;

    /// `transverse` holds at least one position (the value reported for an empty list is its
    /// length, 0), each finite. Any finite fraction is a position (the zone is periodic).
    fn validate(&self) -> Result<(), NetworkError> {
        // No `..`: a field added here does not compile until it is checked.
        let Self { transverse } = self;
        let fields = Fields("WindingOptions");
        fields.rule("transverse", 0.0, !transverse.is_empty(), "at least one transverse position")?;
        for &t in transverse {
            fields.finite("transverse", t)?;
        }
        Ok(())
    }
}

/// The winding numbers and polarization of a cell.
#[derive(Clone, Debug, PartialEq)]
pub struct Winding {
    /// `n_i`, one per lattice direction.
    pub winding: Vec<i64>,
    /// `R_T` in lattice coordinates: `R_T = sum_i polarization[i] a_i` (within
    /// [`SNAP_TOLERANCE`] of a multiple of 1/2: that multiple).
    pub polarization: Vec<f64>,
    /// The cell's dipole `r0` in lattice coordinates.
    pub dipole: Vec<f64>,
    /// The smallest `|det Q|` met on the paths used, relative to Hadamard's bound
    /// `prod_b |row_b|`: how far they stayed from zeros.
    pub closest_approach: f64,
}

/// The dipole `r0 = sum_nodes dof_n p_n - sum_bonds m_b` (Cartesian).
pub fn dipole(cell: &Cell) -> [f64; 2] {
    let mut r = [0.0; 2];
    for node in cell.nodes() {
        let p = node.point();
        r[0] += node.dof() as f64 * p[0];
        r[1] += node.dof() as f64 * p[1];
    }
    for b in 0..cell.bonds().len() {
        let m = cell.bond_midpoint(b);
        r[0] -= m[0];
        r[1] -= m[1];
    }
    r
}

/// Within this of a multiple of 1/2, a lattice coordinate of `r0` or `R_T` is that multiple: the
/// difference is the rounding of the positions (when every node's point lies in `2 dof` bonds,
/// `r0 = -sum_b R_b / 2` exactly).
pub const SNAP_TOLERANCE: f64 = 1e-9;

fn snap(x: f64) -> f64 {
    let half = (2.0 * x).round() / 2.0;
    if (x - half).abs() <= SNAP_TOLERANCE { half + 0.0 } else { x }
}

/// The winding along one path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PathWinding {
    /// The path stays clear of zeros: the winding and the smallest `|det Q|` relative to
    /// Hadamard's bound.
    Winds {
        /// Turns of `arg det Q`.
        winding: i64,
        /// Closest relative approach to zero.
        closest: f64,
    },
    /// `|det Q|` falls to `relative` of Hadamard's bound at `k . a_i = at` on the path.
    MeetsZero {
        /// Where (radians).
        at: f64,
        /// How small.
        relative: f64,
    },
}

/// Determinant of a small complex square matrix by elimination with partial pivoting.
pub fn determinant(q: &Mat<c64>) -> c64 {
    let n = q.nrows();
    let mut a: Vec<c64> = (0..n * n).map(|k| q[(k / n, k % n)]).collect();
    let mut det = c64::new(1.0, 0.0);
    for col in 0..n {
        let pivot =
            (col..n).max_by(|&i, &j| a[i * n + col].norm().total_cmp(&a[j * n + col].norm())).unwrap_or(col);
        if a[pivot * n + col].norm() == 0.0 {
            return c64::new(0.0, 0.0);
        }
        if pivot != col {
            for j in 0..n {
                a.swap(pivot * n + j, col * n + j);
            }
            det = -det;
        }
        let p = a[col * n + col];
        det *= p;
        for i in col + 1..n {
            let f = a[i * n + col] / p;
            if f.norm() != 0.0 {
                for j in col..n {
                    let v = a[col * n + j];
                    a[i * n + j] -= f * v;
                }
            }
        }
    }
    det
}

/// The winding of `arg det Q` along lattice direction `direction` (0 or 1) at transverse phase
/// `transverse = k . a_j` (ignored in one dimension).
pub fn path_winding(cell: &Cell, direction: usize, transverse: f64) -> Result<PathWinding, NetworkError> {
    let (bonds, dof) = (cell.bonds().len(), cell.dof());
    if bonds != dof {
        return Err(NetworkError::NotSquare { bonds, dof });
    }
    if direction >= cell.dimension() {
        return Err(NetworkError::Argument {
            what: "direction",
            problem: format!("{} > dimension {}", direction + 1, cell.dimension()),
        });
    }
    let m_min: i64 = cell.bonds().iter().map(|b| b.cell[direction].min(0)).sum();
    let m_max: i64 = cell.bonds().iter().map(|b| b.cell[direction].max(0)).sum();
    let terms = (m_max - m_min + 1) as usize;
    let samples = terms.next_power_of_two().max(16);
    let rows = bond_rows(cell);
    let mut q = Mat::<c64>::zeros(bonds, dof);
    let theta_at = |t: f64| {
        let mut theta = [transverse, transverse];
        theta[direction] = TAU * t;
        if cell.dimension() == 1 {
            theta[1] = 0.0;
        }
        theta
    };
    let values: Vec<c64> = (0..samples)
        .map(|j| {
            bloch::fill(&rows, theta_at(j as f64 / samples as f64), &mut q);
            determinant(&q)
        })
        .collect();
    // c_m = (1/P) sum_j det(t_j) e^{-2 pi i m t_j}, m = m_min..=m_max.
    let coefficients: Vec<(f64, c64)> = (m_min..=m_max)
        .map(|m| {
            let mut c = c64::new(0.0, 0.0);
            for (j, v) in values.iter().enumerate() {
                let a = -TAU * (m * j as i64).rem_euclid(samples as i64) as f64 / samples as f64;
                c += v * c64::new(a.cos(), a.sin());
            }
            (m as f64, c / samples as f64)
        })
        .collect();
    // What |det Q| is measured against: Hadamard's bound prod_b |row_b| with each row's norm
    // bounded for every phase by |from part| + |to part|. A cell whose det Q vanishes
    // identically (its coefficients are rounding) is then all zeros, not a winding of noise.
    let scale: f64 = rows
        .iter()
        .map(|r| {
            let norm = |e: &[(usize, f64)]| e.iter().map(|x| x.1 * x.1).sum::<f64>().sqrt();
            norm(&r.from) + norm(&r.to)
        })
        .product();
    let size: f64 = coefficients.iter().map(|(_, c)| c.norm()).sum();
    if scale == 0.0 || size <= ZERO_TOLERANCE * scale {
        return Ok(PathWinding::MeetsZero {
            at: 0.0,
            relative: if scale > 0.0 { size / scale } else { 0.0 },
        });
    }
    let lipschitz: f64 = TAU * coefficients.iter().map(|(m, c)| m.abs() * c.norm()).sum::<f64>();
    let eval = |t: f64| -> c64 {
        coefficients.iter().map(|(m, c)| c * c64::new((TAU * m * t).cos(), (TAU * m * t).sin())).sum()
    };
    let mut n = (8 * terms).max(64);
    loop {
        let p: Vec<c64> = (0..n).map(|j| eval(j as f64 / n as f64)).collect();
        let (arg_min, min) = p
            .iter()
            .enumerate()
            .map(|(j, v)| (j, v.norm()))
            .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
        if min <= ZERO_TOLERANCE * scale {
            return Ok(PathWinding::MeetsZero { at: TAU * arg_min as f64 / n as f64, relative: min / scale });
        }
        // Certified when every step h satisfies L h < |p| at its start.
        if lipschitz / n as f64 >= min {
            let needed = (2.0 * lipschitz / min).ceil() as usize;
            if needed > MAX_PATH_SAMPLES {
                return Ok(PathWinding::MeetsZero {
                    at: TAU * arg_min as f64 / n as f64,
                    relative: min / scale,
                });
            }
            n = needed.max(2 * n);
            continue;
        }
        let mut turns = 0.0;
        for j in 0..n {
            let ratio = p[(j + 1) % n] / p[j];
            turns += ratio.im.atan2(ratio.re);
        }
        let winding = (turns / TAU).round();
        return Ok(PathWinding::Winds { winding: winding as i64, closest: min / scale });
    }
}

/// The winding numbers and the polarization `R_T` of a square cell (bonds = degrees of freedom).
pub fn winding(cell: &Cell, options: &WindingOptions) -> Result<Winding, NetworkError> {
    let (bonds, dof) = (cell.bonds().len(), cell.dof());
    if bonds != dof {
        return Err(NetworkError::NotSquare { bonds, dof });
    }
    options.validate()?;
    let mut windings = Vec::with_capacity(cell.dimension());
    let mut closest_approach = f64::INFINITY;
    for i in 0..cell.dimension() {
        let transverse: Vec<f64> = if cell.dimension() == 1 {
            vec![0.0]
        } else {
            options.transverse.iter().map(|t| TAU * t).collect()
        };
        let mut found: Vec<(f64, i64, f64)> = Vec::new();
        let mut zeros: Vec<(f64, f64, f64)> = Vec::new();
        for &tau in &transverse {
            match path_winding(cell, i, tau)? {
                PathWinding::Winds { winding, closest } => found.push((tau, winding, closest)),
                PathWinding::MeetsZero { at, relative } => zeros.push((tau, at, relative)),
            }
        }
        if found.is_empty() {
            let where_ = zeros
                .iter()
                .map(|(tau, at, rel)| {
                    format!(
                        "k.a{} = {at:.4} at transverse {tau:.4} (|det Q| = {rel:.1e} of its Hadamard bound)",
                        i + 1
                    )
                })
                .collect::<Vec<_>>()
                .join("; ");
            let kind = if cell.dimension() == 1 {
                "the lattice is gapless on the path"
            } else {
                "a line of zeros: the lattice is gapless, as with straight lines of bonds"
            };
            return Err(NetworkError::WindingUndefined {
                direction: i + 1,
                reason: format!("{kind}; zeros met at {where_}"),
            });
        }
        if found.iter().any(|f| f.1 != found[0].1) {
            return Err(NetworkError::WeylPoints {
                direction: i + 1,
                transverse: found.iter().map(|f| f.0).collect(),
                windings: found.iter().map(|f| f.1).collect(),
            });
        }
        closest_approach = found.iter().map(|f| f.2).fold(closest_approach, f64::min);
        windings.push(found[0].1);
    }
    let r0: Vec<f64> = cell.lattice_coordinates(dipole(cell)).into_iter().map(snap).collect();
    let polarization = windings.iter().zip(&r0).map(|(n, r)| snap(-(*n as f64) - r)).collect();
    Ok(Winding { winding: windings, polarization, dipole: r0, closest_approach })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn determinant_of_a_known_matrix() {
        let q = Mat::<c64>::from_fn(3, 3, |i, j| {
            c64::new([[2.0, 1.0, 0.0], [1.0, 3.0, 1.0], [0.0, 1.0, 4.0]][i][j], 0.0) * c64::new(0.0, 1.0)
        });
        // det of the real matrix is 2*11 - 1*4 = 18; times i^3 = -i.
        let d = determinant(&q);
        assert!((d - c64::new(0.0, -18.0)).norm() < 1e-12, "{d}");
    }
}
