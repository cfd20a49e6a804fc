//! A one-dimensional rotor network seen in the chain's coordinates, so that the chain's analyses
//! (kinks, antikinks and the Peierls-Nabarro barrier, scattering, everything generic over
//! `ChainModel`) run on a network unchanged, its energies still the network's kernels.
//!
//! The chain measures rotor `i`'s angle `theta_i` from the vertical, alternately up and down
//! (`docs/theory.md` §1: tip `i` at `(i a + r sin theta_i, (-1)^i r cos theta_i)`); the network
//! measures `phi` counter-clockwise from `+x`. So `phi = pi/2 - theta` for an up rotor (even `i`)
//! and `phi = theta - pi/2` for a down one: `dphi/dtheta = s_i = -1, +1, -1, ...`. The view
//! implements the four rungs by that change of variables: gradients and compatibility columns
//! times `s_i`, the tangent stiffness and its parts times `s_i s_j`, inertia unchanged.

use super::NetworkModel;
use crate::cell::NodeKind;
use crate::error::NetworkError;
use crate::patch::{Boundary, Patch};
use chain_core::model::layout::{split_bidiagonal, split_tridiagonal};
use chain_core::model::{CompatibilityLayout, StiffnessLayout, chain_energy_floor};
use chain_core::{ChainGeometry, Potential, SpringNetwork, Stiffness};
use std::f64::consts::FRAC_PI_2;

/// A free one-dimensional patch of rotors as a rotor chain: see the module doc.
#[derive(Debug)]
pub struct ChainView {
    model: NetworkModel,
    a: f64,
    lengths: Vec<f64>,
    mass: f64,
    theta_bar: f64,
}

/// `dphi / dtheta` of rotor `i`: -1 up (even), +1 down (odd).
fn sign(i: usize) -> f64 {
    if i.is_multiple_of(2) { -1.0 } else { 1.0 }
}

impl ChainView {
    /// The chain view of `model`, the model of `patch`. The patch must be a free patch of a
    /// one-dimensional cell whose nodes are all rotors on pivots `(x0 + i a, y0)`, spring `p`
    /// joining rotors `p` and `p + 1`, every rotor of the same mass; `theta_bar` is read from
    /// rotor 0's reference angle. The error names the first rule broken.
    pub fn new(patch: &Patch, model: NetworkModel) -> Result<Self, NetworkError> {
        let refuse = |problem: String| Err(NetworkError::Argument { what: "chain view", problem });
        let cell = patch.cell();
        if cell.dimension() != 1 || patch.boundary() != Boundary::Free {
            return refuse(format!(
                "needs a free patch of a one-dimensional cell (dimension {}, {:?})",
                cell.dimension(),
                patch.boundary()
            ));
        }
        let mut pivots = Vec::new();
        let mut lengths = Vec::new();
        for c in 0..patch.cells()[0] {
            let shift = cell.shift([c as i64, 0]);
            for node in cell.nodes() {
                match node.kind {
                    NodeKind::Rotor { pivot, length, .. } => {
                        pivots.push([pivot[0] + shift[0], pivot[1] + shift[1]]);
                        lengths.push(length);
                    }
                    NodeKind::Joint { .. } => return refuse(format!("node `{}` is a joint", node.name)),
                }
            }
        }
        let n = pivots.len();
        if n < 2 {
            return refuse(format!("{n} rotor: a chain has at least 2"));
        }
        let a = pivots[1][0] - pivots[0][0];
        for (i, p) in pivots.iter().enumerate() {
            let expected = [pivots[0][0] + i as f64 * a, pivots[0][1]];
            if (p[0] - expected[0]).abs() > 1e-12 * a.abs() || (p[1] - expected[1]).abs() > 1e-12 * a.abs() {
                return refuse(format!("pivot {i} at {p:?}, not {expected:?} (a = {a})"));
            }
        }
        let CompatibilityLayout::Sparse(rows) = model.compatibility_layout() else {
            return refuse("the model's compatibility matrix is not sparse".into());
        };
        if model.spring_count() != n - 1 || (0..n - 1).any(|p| rows.row(p) != [p, p + 1]) {
            return refuse(format!(
                "{} springs: a chain of {n} rotors has {} springs, spring p joining rotors p and p + 1",
                model.spring_count(),
                n - 1
            ));
        }
        let mass = model.inertia(0) / (lengths[0] * lengths[0]);
        for (i, r) in lengths.iter().enumerate() {
            let m = model.inertia(i) / (r * r);
            if (m - mass).abs() > 1e-12 * mass {
                return refuse(format!("rotor {i} has mass {m}, rotor 0 {mass}: the chain has one mass"));
            }
        }
        let theta_bar = FRAC_PI_2 - model.reference[0];
        Ok(Self { model, a, lengths, mass, theta_bar })
    }

    /// The network model underneath.
    pub fn network(&self) -> &NetworkModel {
        &self.model
    }

    /// The network's angles `phi` of the chain's angles `theta`.
    pub fn to_network(&self, theta: &[f64]) -> Vec<f64> {
        theta
            .iter()
            .enumerate()
            .map(|(i, t)| if i.is_multiple_of(2) { FRAC_PI_2 - t } else { t - FRAC_PI_2 })
            .collect()
    }

    /// The chain's angles `theta` of the network's angles `phi`.
    pub fn to_chain(&self, phi: &[f64]) -> Vec<f64> {
        phi.iter()
            .enumerate()
            .map(|(i, p)| if i.is_multiple_of(2) { FRAC_PI_2 - p } else { p + FRAC_PI_2 })
            .collect()
    }

    /// Multiplies the values of a tridiagonal layout by `s_i s_j`.
    fn sign_tridiagonal(&self, values: &mut [f64]) {
        let n = self.lengths.len();
        let (_, off) = split_tridiagonal(n, values);
        // s_i s_{i+1} = -1 for every neighbouring pair; the diagonal's s_i^2 = 1.
        for v in off {
            *v = -*v;
        }
    }

    /// A network block (upper layout) at `theta`, as a tridiagonal layout in the chain's angles.
    fn block_into(&self, theta: &[f64], values: &mut [f64], which: fn(&NetworkModel, &[f64], &mut [f64])) {
        let mut upper = vec![0.0; self.model.stiffness_values()];
        which(&self.model, &self.to_network(theta), &mut upper);
        self.tridiagonal_of(&upper, values);
    }

    /// The upper layout's diagonal and superdiagonal (rows `[i, i + 1]`, the last `[n - 1]`) as
    /// a tridiagonal layout with the chain's signs.
    fn tridiagonal_of(&self, upper: &[f64], values: &mut [f64]) {
        let n = self.lengths.len();
        {
            let (diag, off) = split_tridiagonal(n, values);
            for i in 0..n {
                diag[i] = upper[2 * i];
                if i + 1 < n {
                    off[i] = upper[2 * i + 1];
                }
            }
        }
        self.sign_tridiagonal(values);
    }
}

impl Potential for ChainView {
    fn dof_count(&self) -> usize {
        self.lengths.len()
    }

    fn inertia(&self, i: usize) -> f64 {
        self.model.inertia(i)
    }

    fn energy(&self, theta: &[f64]) -> f64 {
        self.model.energy(&self.to_network(theta))
    }

    fn gradient_into(&self, theta: &[f64], out: &mut [f64]) {
        self.energy_and_gradient_into(theta, out);
    }

    fn energy_and_gradient_into(&self, theta: &[f64], out: &mut [f64]) -> f64 {
        let e = self.model.energy_and_gradient_into(&self.to_network(theta), out);
        for (i, g) in out.iter_mut().enumerate() {
            *g *= sign(i);
        }
        e
    }

    fn energy_floor(&self) -> f64 {
        chain_energy_floor(self)
    }
}

impl Stiffness for ChainView {
    fn stiffness_layout(&self) -> StiffnessLayout<'_> {
        StiffnessLayout::Tridiagonal
    }

    fn tangent_stiffness_into(&self, theta: &[f64], values: &mut [f64]) {
        self.block_into(theta, values, |m, x, v| m.tangent_stiffness_into(x, v));
    }

    fn energy_gradient_stiffness_into(&self, theta: &[f64], grad: &mut [f64], values: &mut [f64]) -> f64 {
        let mut upper = vec![0.0; self.model.stiffness_values()];
        let e = self.model.energy_gradient_stiffness_into(&self.to_network(theta), grad, &mut upper);
        for (i, g) in grad.iter_mut().enumerate() {
            *g *= sign(i);
        }
        self.tridiagonal_of(&upper, values);
        e
    }
}

impl SpringNetwork for ChainView {
    fn spring_count(&self) -> usize {
        self.model.spring_count()
    }

    fn spring_constant(&self, p: usize) -> f64 {
        self.model.spring_constant(p)
    }

    fn rest_length(&self, p: usize) -> f64 {
        self.model.rest_length(p)
    }

    fn spring_lengths_into(&self, theta: &[f64], out: &mut [f64]) {
        self.model.spring_lengths_into(&self.to_network(theta), out);
    }

    fn tensions_into(&self, theta: &[f64], out: &mut [f64]) {
        self.model.tensions_into(&self.to_network(theta), out);
    }

    fn compatibility_layout(&self) -> CompatibilityLayout<'_> {
        CompatibilityLayout::Bidiagonal
    }

    /// Row `p` is `[C[p][p], C[p][p + 1]]` in the network's sparse layout (its pattern checked by
    /// [`ChainView::new`]); each column is the tip's arc length, `r dphi = s_i r dtheta`.
    fn compatibility_into(&self, theta: &[f64], values: &mut [f64]) {
        let m = self.spring_count();
        let mut sparse = vec![0.0; 2 * m];
        self.model.compatibility_into(&self.to_network(theta), &mut sparse);
        let (left, right) = split_bidiagonal(m, values);
        for p in 0..m {
            left[p] = sign(p) * sparse[2 * p];
            right[p] = sign(p + 1) * sparse[2 * p + 1];
        }
    }

    fn material_stiffness_into(&self, theta: &[f64], values: &mut [f64]) {
        self.block_into(theta, values, |m, x, v| m.material_stiffness_into(x, v));
    }

    fn stress_matrix_into(&self, theta: &[f64], values: &mut [f64]) {
        self.block_into(theta, values, |m, x, v| m.stress_matrix_into(x, v));
    }
}

impl ChainGeometry for ChainView {
    fn lattice_spacing(&self) -> f64 {
        self.a
    }

    fn rotor_length(&self, i: usize) -> f64 {
        self.lengths[i]
    }

    fn mass(&self) -> f64 {
        self.mass
    }

    fn theta_bar(&self) -> f64 {
        self.theta_bar
    }
}
