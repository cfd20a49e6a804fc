//! The law's kernels a model evaluates, chosen once when it is built: the passes over the bond
//! groups, each generic over the kernels `K` ([`LawKernels`]: the checked-in harmonic or quartic
//! ones of a [`Law`](chain_core::Law), or those the `#[rotor_network]` attribute renders at
//! compile time for its law), gathered into a table of function pointers ([`Kernels`]) that the
//! model holds, so the model and its capability traits are written once for every law.

use super::NetworkModel;
use super::bonds::{Group, each_bond};
use crate::kernel::LawKernels;

/// Which block a pass assembles.
#[derive(Clone, Copy, Debug)]
pub(super) enum Block {
    Hessian,
    Material,
    Stress,
    /// Energy, gradient and Hessian fused.
    All,
}

/// The rotors' `[sin, cos]`, rotor by rotor.
type Trig = [[f64; 2]];

/// A pass over every bond writing one output array.
type Pass<R> = fn(&NetworkModel, &[f64], &Trig, &mut [f64]) -> R;

/// The block pass: the values, which block, and for the fused block the gradient.
type BlockPass = fn(&NetworkModel, &[f64], &Trig, &mut [f64], Block, Option<&mut [f64]>) -> f64;

/// One law's passes (each takes the model, `x` and the rotors' `[sin, cos]`).
#[derive(Clone, Copy, Debug)]
pub(super) struct Kernels {
    pub energy: fn(&NetworkModel, &[f64], &Trig) -> f64,
    /// The gradient into the output (zeroed first), in vector lanes.
    pub gradient: Pass<f64>,
    /// The energy, and the gradient into the output (zeroed first), in vector lanes.
    pub energy_gradient: Pass<f64>,
    pub blocks: BlockPass,
    /// One value per spring: tensions (`true`) or lengths.
    pub per_spring: [Pass<()>; 2],
    pub compatibility: Pass<()>,
}

impl Kernels {
    /// The passes of the kernels `K` (of the table's argument counts).
    pub fn of<K: LawKernels>() -> Self {
        Self::with_arguments::<K, 8, 9, 10>()
    }

    /// The passes of the kernels `K` whose bond types take `A1, A2, A3` arguments (a law with
    /// parameters of its own: the polynomial's 13, 14, 15).
    pub fn with_arguments<K: LawKernels<A1, A2, A3>, const A1: usize, const A2: usize, const A3: usize>()
    -> Self {
        Self {
            energy: energy::<K, A1, A2, A3>,
            gradient: super::lanes::gradient::<K, A1, A2, A3, false>,
            energy_gradient: super::lanes::gradient::<K, A1, A2, A3, true>,
            blocks: blocks::<K, A1, A2, A3>,
            per_spring: [per_spring::<K, A1, A2, A3, false>, per_spring::<K, A1, A2, A3, true>],
            compatibility: compatibility::<K, A1, A2, A3>,
        }
    }
}

fn energy<K: LawKernels<A1, A2, A3>, const A1: usize, const A2: usize, const A3: usize>(
    m: &NetworkModel,
    x: &[f64],
    trig: &[[f64; 2]],
) -> f64 {
    let mut energy = 0.0;
    each_bond!(m, K, [A1, A2, A3], x, trig, Energy, [1, 1, 1], |_g, _i, out| { energy += out[0] });
    energy
}

/// Assembles `which` block of every bond into `values` (zeroed first) at its slots; for the
/// fused [`Block::All`], also the gradient into `grad`, returning the energy (else 0).
fn blocks<K: LawKernels<A1, A2, A3>, const A1: usize, const A2: usize, const A3: usize>(
    m: &NetworkModel,
    x: &[f64],
    trig: &[[f64; 2]],
    values: &mut [f64],
    which: Block,
    grad: Option<&mut [f64]>,
) -> f64 {
    let slots = &m.upper().slots;
    values.fill(0.0);
    let mut energy = 0.0;
    let mut grad = grad;
    if let Some(g) = grad.as_deref_mut() {
        g.fill(0.0);
    }
    let mut add = |g: &Group, i: usize, out: &[f64], from: usize| {
        let h = out.len() - from;
        let slot = &slots[g.kind as usize][i * h..(i + 1) * h];
        for (&s, &v) in slot.iter().zip(&out[from..]) {
            values[s] += v;
        }
    };
    match which {
        Block::Hessian => {
            each_bond!(m, K, [A1, A2, A3], x, trig, Hessian, [10, 6, 3], |g, i, out| { add(g, i, out, 0) })
        }
        Block::Material => {
            each_bond!(m, K, [A1, A2, A3], x, trig, Material, [10, 6, 3], |g, i, out| { add(g, i, out, 0) })
        }
        Block::Stress => {
            each_bond!(m, K, [A1, A2, A3], x, trig, Stress, [10, 6, 3], |g, i, out| { add(g, i, out, 0) })
        }
        Block::All => {
            let grad = grad.expect("the fused call passes the gradient");
            each_bond!(m, K, [A1, A2, A3], x, trig, EnergyGradientHessian, [15, 10, 6], |g, i, out| {
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
fn per_spring<
    K: LawKernels<A1, A2, A3>,
    const A1: usize,
    const A2: usize,
    const A3: usize,
    const TENSION: bool,
>(
    m: &NetworkModel,
    x: &[f64],
    trig: &Trig,
    out: &mut [f64],
) {
    if TENSION {
        each_bond!(m, K, [A1, A2, A3], x, trig, Tension, [1, 1, 1], |g, i, v| { out[g.spring[i]] = v[0] });
    } else {
        each_bond!(m, K, [A1, A2, A3], x, trig, Length, [1, 1, 1], |g, i, v| { out[g.spring[i]] = v[0] });
    }
}

/// The compatibility matrix's values at their slots.
fn compatibility<K: LawKernels<A1, A2, A3>, const A1: usize, const A2: usize, const A3: usize>(
    m: &NetworkModel,
    x: &[f64],
    trig: &[[f64; 2]],
    values: &mut [f64],
) {
    let rows = m.rows();
    each_bond!(m, K, [A1, A2, A3], x, trig, Compatibility, [4, 3, 2], |g, i, v| {
        let n = v.len();
        for (&s, &c) in rows.slots[g.kind as usize][i * n..(i + 1) * n].iter().zip(v) {
            values[s] = c;
        }
    });
}
