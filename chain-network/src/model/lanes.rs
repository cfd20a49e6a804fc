//! The vector driver of the hot path (energy and gradient, the gradient alone: every Verlet step
//! and relaxation step): `V::LANES` bonds of a group at a time through the lane-generic kernel, at
//! the level chain-core's `simd` detects. Each bond's arguments are gathered into the lanes and
//! its gradient entries scattered back in bond order, so the gradient is bit for bit the scalar
//! driver's (the kernels' arithmetic is lane-for-lane IEEE); the energy is summed in lanes.

use super::NetworkModel;
use super::bonds::Group;
use super::law::Kernel;
use crate::kernel::BondFn;
use chain_core::simd::{Vector, WithLanes, dispatch};

/// The widest lane count of any level (AVX-512's 8).
const MAX_LANES: usize = 8;

/// Energy (when `ENERGY`, the kernel's first output) and gradient of every bond of `g`, the
/// gradient added into `out`.
#[inline(always)]
// The lane loops transpose bonds into lanes and back: they index two arrays by the lane.
#[allow(clippy::needless_range_loop)]
fn group<V: Vector, const A: usize, const M: usize, K: BondFn<A, M>, const ENERGY: bool>(
    g: &Group,
    x: &[f64],
    trig: &[[f64; 2]],
    rotor_of: &[u32],
    out: &mut [f64],
) -> f64 {
    let first = usize::from(ENERGY);
    let lanes = V::LANES.min(MAX_LANES);
    let n = g.len();
    let full = n - n % lanes;
    let mut energy = V::splat(0.0);
    let mut args = [[0.0f64; MAX_LANES]; A];
    let mut outs = [[0.0f64; MAX_LANES]; M];
    let mut i = 0;
    while i < full {
        for l in 0..lanes {
            let a = g.args::<A>(i + l, x, trig, rotor_of);
            for j in 0..A {
                args[j][l] = a[j];
            }
        }
        let values = K::eval::<V>(core::array::from_fn(|j| V::load(&args[j])));
        if ENERGY {
            energy = energy + values[0];
        }
        for j in first..M {
            values[j].store(&mut outs[j]);
        }
        for l in 0..lanes {
            for (k, &dof) in g.bond_dofs(i + l).iter().enumerate() {
                out[dof] += outs[first + k][l];
            }
        }
        i += lanes;
    }
    let mut energy = energy.sum();
    for i in full..n {
        let values = K::eval::<f64>(g.args::<A>(i, x, trig, rotor_of));
        if ENERGY {
            energy += values[0];
        }
        for (k, &dof) in g.bond_dofs(i).iter().enumerate() {
            out[dof] += values[first + k];
        }
    }
    energy
}

/// The work handed to `dispatch`: the fused energy and gradient (`ENERGY`) or the gradient.
pub(super) struct Gradient<'a, const ENERGY: bool> {
    pub model: &'a NetworkModel,
    pub x: &'a [f64],
    pub trig: &'a [[f64; 2]],
    pub out: &'a mut [f64],
}

macro_rules! groups {
    ($self:ident, $V:ident, $law:ident, [$a1:literal, $a2:literal, $a3:literal], $f:ident, [$m1:literal, $m2:literal, $m3:literal], $energy:literal) => {{
        use crate::kernel::$law::{joint_joint, joint_rotor, rotor_rotor};
        let m = $self.model;
        let [jj, jr, rr] = &m.groups;
        group::<$V, $a1, $m1, joint_joint::$f, $energy>(jj, $self.x, $self.trig, &m.rotor_of, $self.out)
            + group::<$V, $a2, $m2, joint_rotor::$f, $energy>(jr, $self.x, $self.trig, &m.rotor_of, $self.out)
            + group::<$V, $a3, $m3, rotor_rotor::$f, $energy>(rr, $self.x, $self.trig, &m.rotor_of, $self.out)
    }};
}

impl WithLanes for Gradient<'_, true> {
    type Output = f64;
    #[inline(always)]
    fn run<V: Vector>(self) -> f64 {
        match self.model.law {
            Kernel::Harmonic => groups!(self, V, harmonic, [8, 9, 10], EnergyGradient, [5, 4, 3], true),
            Kernel::Quartic => groups!(self, V, quartic, [8, 9, 10], EnergyGradient, [5, 4, 3], true),
            Kernel::Polynomial => groups!(self, V, polynomial, [13, 14, 15], EnergyGradient, [5, 4, 3], true),
        }
    }
}

impl WithLanes for Gradient<'_, false> {
    type Output = f64;
    #[inline(always)]
    fn run<V: Vector>(self) -> f64 {
        match self.model.law {
            Kernel::Harmonic => groups!(self, V, harmonic, [8, 9, 10], Gradient, [4, 3, 2], false),
            Kernel::Quartic => groups!(self, V, quartic, [8, 9, 10], Gradient, [4, 3, 2], false),
            Kernel::Polynomial => groups!(self, V, polynomial, [13, 14, 15], Gradient, [4, 3, 2], false),
        }
    }
}

impl NetworkModel {
    /// The gradient into `out` (zeroed first) and, with `ENERGY`, the energy, at the detected
    /// vector level.
    pub(super) fn gradient_lanes<const ENERGY: bool>(&self, x: &[f64], out: &mut [f64]) -> f64
    where
        for<'a> Gradient<'a, ENERGY>: WithLanes<Output = f64>,
    {
        let trig = self.trig(x);
        out.fill(0.0);
        dispatch(Gradient::<ENERGY> { model: self, x, trig: &trig, out })
    }
}
