//! Guest modes: the macroscopic strains a periodic lattice admits at no cost (Guest and
//! Hutchinson, J. Mech. Phys. Solids 51, 383 (2003); Lubensky et al., Rep. Prog. Phys. 78,
//! 073901 (2015), section 4.2.2).
//!
//! A uniform strain `eps` moves every anchor `x` (a joint's position, a rotor's pivot) by
//! `eps x`; together with a periodic displacement `u` (the `k = 0` block) bond `b` stretches by
//! `Q(0) u + e_b . eps d_b`, with `d_b` the bond's anchor-to-anchor vector (for joints, the bond
//! vector). The strains with some `u` that stretches no bond are the null space of
//! `[Q(0) | E]` projected on its strain columns. Strains are parametrised by the orthonormal
//! (Frobenius) basis `xx`, `yy`, `(xy + yx)/sqrt 2` in two dimensions and `a1 a1^T / |a1|^2` in
//! one, and scaled by the cell's length so that the columns are dimensionless like `Q`.

use crate::cell::Cell;
use crate::error::NetworkError;
use crate::linalg::{self, RANK_TOLERANCE};
use faer::Mat;

/// The Guest modes of a cell.
#[derive(Clone, Debug, PartialEq)]
pub struct GuestModes {
    /// How many independent strains cost nothing.
    pub count: usize,
    /// An orthonormal basis of those strains (symmetric 2 x 2 matrices, Frobenius norm 1).
    pub strains: Vec<[[f64; 2]; 2]>,
}

fn strain_basis(cell: &Cell) -> Vec<[[f64; 2]; 2]> {
    if cell.dimension() == 1 {
        let a = cell.lattice_vector(0);
        let n2 = a[0] * a[0] + a[1] * a[1];
        vec![[[a[0] * a[0] / n2, a[0] * a[1] / n2], [a[1] * a[0] / n2, a[1] * a[1] / n2]]]
    } else {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        vec![[[1.0, 0.0], [0.0, 0.0]], [[0.0, 0.0], [0.0, 1.0]], [[0.0, s], [s, 0.0]]]
    }
}

/// The Guest modes of `cell`.
pub fn guest_modes(cell: &Cell) -> Result<GuestModes, NetworkError> {
    let basis = strain_basis(cell);
    let (bonds, dof, ns) = (cell.bonds().len(), cell.dof(), basis.len());
    let q0 = crate::bloch::compatibility(cell, [0.0, 0.0]);
    let scale = cell.length_scale();
    let mut g = Mat::<f64>::zeros(bonds, dof + ns);
    for b in 0..bonds {
        for j in 0..dof {
            g[(b, j)] = q0[(b, j)].re;
        }
        let bond = &cell.bonds()[b];
        let e = cell.bond_unit(b);
        let (p, q) = (cell.nodes()[bond.from].anchor(), cell.nodes()[bond.to].anchor());
        let s = cell.shift(bond.cell);
        let d = [q[0] + s[0] - p[0], q[1] + s[1] - p[1]];
        for (c, eps) in basis.iter().enumerate() {
            let ed = [eps[0][0] * d[0] + eps[0][1] * d[1], eps[1][0] * d[0] + eps[1][1] * d[1]];
            g[(b, dof + c)] = (e[0] * ed[0] + e[1] * ed[1]) / scale;
        }
    }
    let svd = linalg::full_svd("Guest matrix [Q(0) | E]", g.as_ref())?;
    let largest = svd.s.first().copied().unwrap_or(0.0);
    let null = svd.right_null(largest);
    // The strain parts of the null vectors (unit columns): their rank is the number of Guest modes.
    let parts = Mat::<f64>::from_fn(ns, null.ncols(), |c, j| null[(dof + c, j)]);
    let proj = linalg::full_svd("strain parts", parts.as_ref())?;
    let count = proj.s.iter().filter(|&&s| s > RANK_TOLERANCE.sqrt()).count();
    let strains = (0..count)
        .map(|m| {
            let mut eps = [[0.0; 2]; 2];
            for (c, basis) in basis.iter().enumerate() {
                for r in 0..2 {
                    for k in 0..2 {
                        eps[r][k] += proj.u[(c, m)] * basis[r][k];
                    }
                }
            }
            eps
        })
        .collect();
    Ok(GuestModes { count, strains })
}
