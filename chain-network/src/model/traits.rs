//! The capability ladder on a [`NetworkModel`]: every method one pass over the bond groups with
//! one generated kernel (the fused ones where the trait has a fused method).

use super::NetworkModel;
use super::bonds::{Rows, Upper, each_bond};
use chain_core::model::{CompatibilityLayout, StiffnessLayout};
use chain_core::{Potential, SpringNetwork, Stiffness};

impl NetworkModel {
    fn upper(&self) -> &Upper {
        self.stiffness.get_or_init(|| Upper::new(self.inertia.len(), &self.groups))
    }

    fn rows(&self) -> &Rows {
        self.compatibility.get_or_init(|| Rows::new(self.inertia.len(), self.springs.len(), &self.groups))
    }

    /// Assembles `which` block of every bond into `values` (zeroed first) at its slots; for the
    /// fused [`Block::All`], also the gradient into `grad`, returning the energy (else 0).
    fn blocks_into(&self, x: &[f64], values: &mut [f64], which: Block, grad: Option<&mut [f64]>) -> f64 {
        let slots = &self.upper().slots;
        let trig = self.trig(x);
        values.fill(0.0);
        let mut energy = 0.0;
        let mut grad = grad;
        if let Some(g) = grad.as_deref_mut() {
            g.fill(0.0);
        }
        let mut add = |g: &super::bonds::Group, i: usize, out: &[f64], from: usize| {
            let h = out.len() - from;
            let slot = &slots[g.kind as usize][i * h..(i + 1) * h];
            for (&s, &v) in slot.iter().zip(&out[from..]) {
                values[s] += v;
            }
        };
        match which {
            Block::Hessian => {
                each_bond!(self, x, &trig, Hessian, [10, 6, 3], |g, i, out| { add(g, i, out, 0) })
            }
            Block::Material => {
                each_bond!(self, x, &trig, Material, [10, 6, 3], |g, i, out| { add(g, i, out, 0) })
            }
            Block::Stress => {
                each_bond!(self, x, &trig, Stress, [10, 6, 3], |g, i, out| { add(g, i, out, 0) })
            }
            Block::All => {
                let grad = grad.expect("the fused call passes the gradient");
                each_bond!(self, x, &trig, EnergyGradientHessian, [15, 10, 6], |g, i, out| {
                    let d = g.bond_dofs(i);
                    energy += out[0];
                    for (&dof, &v) in d.iter().zip(&out[1..]) {
                        grad[dof] += v;
                    }
                    add(g, i, out, 1 + d.len());
                })
            }
        }
        energy
    }

    /// One value per spring from a one-output kernel, into `out` by spring index.
    fn per_spring(&self, x: &[f64], out: &mut [f64], tension: bool) {
        let trig = self.trig(x);
        if tension {
            each_bond!(self, x, &trig, Tension, [1, 1, 1], |g, i, v| { out[g.spring[i]] = v[0] });
        } else {
            each_bond!(self, x, &trig, Length, [1, 1, 1], |g, i, v| { out[g.spring[i]] = v[0] });
        }
    }
}

/// Which block a pass assembles.
#[derive(Clone, Copy)]
enum Block {
    Hessian,
    Material,
    Stress,
    /// Energy, gradient and Hessian fused.
    All,
}

impl Potential for NetworkModel {
    fn dof_count(&self) -> usize {
        self.inertia.len()
    }

    fn inertia(&self, i: usize) -> f64 {
        self.inertia[i]
    }

    #[track_caller]
    fn energy(&self, x: &[f64]) -> f64 {
        self.check(x.len(), &[]);
        let trig = self.trig(x);
        let mut energy = 0.0;
        each_bond!(self, x, &trig, Energy, [1, 1, 1], |_g, _i, out| { energy += out[0] });
        energy
    }

    #[track_caller]
    fn gradient_into(&self, x: &[f64], out: &mut [f64]) {
        self.check(x.len(), &[("gradient", out.len(), x.len())]);
        self.gradient_lanes::<false>(x, out);
    }

    #[track_caller]
    fn energy_and_gradient_into(&self, x: &[f64], out: &mut [f64]) -> f64 {
        self.check(x.len(), &[("gradient", out.len(), x.len())]);
        self.gradient_lanes::<true>(x, out)
    }

    /// `1e-12 k_max s^2` with `s` the cell's length scale: the energy of the stiffest bond
    /// stretched by a millionth of the cell (the chain's floor with `a` the cell).
    fn energy_floor(&self) -> f64 {
        let k = self.springs.iter().map(|s| s[0]).fold(0.0, f64::max);
        1e-12 * k * self.length_scale * self.length_scale
    }
}

impl Stiffness for NetworkModel {
    fn stiffness_layout(&self) -> StiffnessLayout<'_> {
        StiffnessLayout::Upper(self.upper().pattern())
    }

    #[track_caller]
    fn tangent_stiffness_into(&self, x: &[f64], values: &mut [f64]) {
        self.check(x.len(), &[("stiffness values", values.len(), self.upper().columns.len())]);
        self.blocks_into(x, values, Block::Hessian, None);
    }

    #[track_caller]
    fn energy_gradient_stiffness_into(&self, x: &[f64], grad: &mut [f64], values: &mut [f64]) -> f64 {
        let entries = self.upper().columns.len();
        self.check(
            x.len(),
            &[("gradient", grad.len(), x.len()), ("stiffness values", values.len(), entries)],
        );
        self.blocks_into(x, values, Block::All, Some(grad))
    }
}

impl SpringNetwork for NetworkModel {
    fn spring_count(&self) -> usize {
        self.springs.len()
    }

    fn spring_constant(&self, p: usize) -> f64 {
        self.springs[p][0]
    }

    fn rest_length(&self, p: usize) -> f64 {
        self.springs[p][1]
    }

    #[track_caller]
    fn spring_lengths_into(&self, x: &[f64], out: &mut [f64]) {
        self.check(x.len(), &[("lengths", out.len(), self.springs.len())]);
        self.per_spring(x, out, false);
    }

    #[track_caller]
    fn tensions_into(&self, x: &[f64], out: &mut [f64]) {
        self.check(x.len(), &[("tensions", out.len(), self.springs.len())]);
        self.per_spring(x, out, true);
    }

    fn compatibility_layout(&self) -> CompatibilityLayout<'_> {
        CompatibilityLayout::Sparse(self.rows().pattern())
    }

    #[track_caller]
    fn compatibility_into(&self, x: &[f64], values: &mut [f64]) {
        let rows = self.rows();
        self.check(x.len(), &[("compatibility values", values.len(), rows.columns.len())]);
        let trig = self.trig(x);
        each_bond!(self, x, &trig, Compatibility, [4, 3, 2], |g, i, v| {
            let n = v.len();
            for (&s, &c) in rows.slots[g.kind as usize][i * n..(i + 1) * n].iter().zip(v) {
                values[s] = c;
            }
        });
    }

    #[track_caller]
    fn material_stiffness_into(&self, x: &[f64], values: &mut [f64]) {
        self.check(x.len(), &[("material values", values.len(), self.upper().columns.len())]);
        self.blocks_into(x, values, Block::Material, None);
    }

    #[track_caller]
    fn stress_matrix_into(&self, x: &[f64], values: &mut [f64]) {
        self.check(x.len(), &[("stress values", values.len(), self.upper().columns.len())]);
        self.blocks_into(x, values, Block::Stress, None);
    }
}
