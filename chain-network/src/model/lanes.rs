//! The vector driver of the hot path (energy and gradient, the gradient alone: every Verlet step
//! and relaxation step): `V::LANES` bonds of a group at a time through the lane-generic kernel, at
//! the level chain-core's `simd` detects. Each bond's arguments are gathered into the lanes and
//! its gradient entries scattered back in bond order, so the gradient is bit for bit the scalar
//! driver's (the kernels' arithmetic is lane-for-lane IEEE); the energy is summed in lanes.

use super::NetworkModel;
use super::bonds::Group;
use crate::kernel::{BondFn, BondKernels, LawKernels};
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

/// The work handed to `dispatch`: the fused energy and gradient (`ENERGY`) or the gradient,
/// with the law's kernels `K`.
pub(super) struct Gradient<'a, K, const A1: usize, const A2: usize, const A3: usize, const ENERGY: bool> {
    pub model: &'a NetworkModel,
    pub x: &'a [f64],
    pub trig: &'a [[f64; 2]],
    pub out: &'a mut [f64],
    pub kernels: core::marker::PhantomData<K>,
}

macro_rules! groups {
    ($self:ident, $V:ident, $K:ty, $f:ident, [$m1:literal, $m2:literal, $m3:literal], $energy:literal) => {{
        let m = $self.model;
        let [jj, jr, rr] = &m.groups;
        group::<
            $V,
            A1,
            $m1,
            <<$K as LawKernels<A1, A2, A3>>::JointJoint as BondKernels<A1, 4, 5, 10, 15>>::$f,
            $energy,
        >(jj, $self.x, $self.trig, &m.rotor_of, $self.out)
            + group::<
                $V,
                A2,
                $m2,
                <<$K as LawKernels<A1, A2, A3>>::JointRotor as BondKernels<A2, 3, 4, 6, 10>>::$f,
                $energy,
            >(jr, $self.x, $self.trig, &m.rotor_of, $self.out)
            + group::<
                $V,
                A3,
                $m3,
                <<$K as LawKernels<A1, A2, A3>>::RotorRotor as BondKernels<A3, 2, 3, 3, 6>>::$f,
                $energy,
            >(rr, $self.x, $self.trig, &m.rotor_of, $self.out)
    }};
}

impl<K: LawKernels<A1, A2, A3>, const A1: usize, const A2: usize, const A3: usize> WithLanes
    for Gradient<'_, K, A1, A2, A3, true>
{
    type Output = f64;
    #[inline(always)]
    fn run<V: Vector>(self) -> f64 {
        groups!(self, V, K, EnergyGradient, [5, 4, 3], true)
    }
}

impl<K: LawKernels<A1, A2, A3>, const A1: usize, const A2: usize, const A3: usize> WithLanes
    for Gradient<'_, K, A1, A2, A3, false>
{
    type Output = f64;
    #[inline(always)]
    fn run<V: Vector>(self) -> f64 {
        groups!(self, V, K, Gradient, [4, 3, 2], false)
    }
}

/// The gradient into `out` (zeroed first) and, with `ENERGY`, the energy, at the detected
/// vector level, with the law's kernels `K`.
pub(super) fn gradient<
    K: LawKernels<A1, A2, A3>,
    const A1: usize,
    const A2: usize,
    const A3: usize,
    const ENERGY: bool,
>(
    model: &NetworkModel,
    x: &[f64],
    trig: &[[f64; 2]],
    out: &mut [f64],
) -> f64
where
    for<'a> Gradient<'a, K, A1, A2, A3, ENERGY>: WithLanes<Output = f64>,
{
    out.fill(0.0);
    dispatch(Gradient::<K, A1, A2, A3, ENERGY> { model, x, trig, out, kernels: core::marker::PhantomData })
}
