//! The capability ladder on a [`NetworkModel`]: every method one pass over the bond groups with
//! one generated kernel (the fused ones where the trait has a fused method).

use super::NetworkModel;
use super::bonds::{Rows, Upper};
use super::kernels::Block;
use chain_core::model::{CompatibilityLayout, StiffnessLayout};
use chain_core::{Potential, SpringNetwork, Stiffness};

impl NetworkModel {
    pub(super) fn upper(&self) -> &Upper {
        self.stiffness.get_or_init(|| Upper::new(self.inertia.len(), &self.groups))
    }

    pub(super) fn rows(&self) -> &Rows {
        self.compatibility.get_or_init(|| Rows::new(self.inertia.len(), self.springs.len(), &self.groups))
    }

    /// Assembles `which` block (and for [`Block::All`] the gradient into `grad`, returning the
    /// energy) with the model's kernels.
    fn blocks_into(&self, x: &[f64], values: &mut [f64], which: Block, grad: Option<&mut [f64]>) -> f64 {
        (self.kernels.blocks)(self, x, &self.trig(x), values, which, grad)
    }

    /// One value per spring: tensions (`true`) or lengths.
    fn per_spring(&self, x: &[f64], out: &mut [f64], tension: bool) {
        (self.kernels.per_spring[usize::from(tension)])(self, x, &self.trig(x), out)
    }
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
        (self.kernels.energy)(self, x, &self.trig(x))
    }

    #[track_caller]
    fn gradient_into(&self, x: &[f64], out: &mut [f64]) {
        self.check(x.len(), &[("gradient", out.len(), x.len())]);
        (self.kernels.gradient)(self, x, &self.trig(x), out);
    }

    #[track_caller]
    fn energy_and_gradient_into(&self, x: &[f64], out: &mut [f64]) -> f64 {
        self.check(x.len(), &[("gradient", out.len(), x.len())]);
        (self.kernels.energy_gradient)(self, x, &self.trig(x), out)
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
        (self.kernels.compatibility)(self, x, &self.trig(x), values);
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
