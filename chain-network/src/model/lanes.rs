//! The vector driver of the hot path (energy and gradient, the gradient alone: every Verlet step
//! and relaxation step): `V::LANES` bonds of a run at a time through the lane-generic kernel, at
//! the level chain-core's `simd` detects. The runs and their structure-of-arrays buffers are
//! `stencil.rs`'s: a run's endpoints and its per-bond parameters (`k`, `l0`, a law's own
//! coefficients where its bonds do not share them) are contiguous loads, its gradient entries
//! contiguous adds (masked at a run's end). Each bond's arithmetic is the scalar kernel's, lane for
//! lane (IEEE, nothing fused); the gradient's sums are taken run by run, so they equal the scalar
//! bond-by-bond driver's to rounding (the order of a degree of freedom's terms differs).

use super::NetworkModel;
use super::stencil::{PARAMETERS, Parameter, Runs};
use crate::kernel::{BondFn, BondKernels, LawKernels};
use chain_core::simd::{Vector, WithLanes, dispatch};
use std::cell::RefCell;

/// `count` (at most `V::LANES`) bonds of `run` from its bond `i`, with a kernel of `A` arguments
/// of which the first `B` are the table's (`B - 2`, `B - 1` are `k` and `l0`; a law's own
/// parameters follow): the energy lanes (zero past `count`) when `ENERGY`, the gradient added
/// into `grad`.
#[inline(always)]
fn bonds<V: Vector, const A: usize, const B: usize, const M: usize, K: BondFn<A, M>, const ENERGY: bool>(
    runs: &Runs,
    run: usize,
    i: usize,
    count: usize,
    input: &[f64],
    grad: &mut [f64],
) -> V {
    const { assert!(A >= B && A + 2 - B <= PARAMETERS, "a run holds k, l0 and at most five coefficients") };
    let full = count == V::LANES;
    let r = &runs.runs[run];
    // No closures or `array::from_fn` here: they are not inlined into the level's function, and
    // its vector loads then become calls.
    let mut args = [V::splat(0.0); A];
    for a in 0..A {
        let s: &[f64] = if a < 4 {
            &input[r.ends[a] + i..]
        } else if a < B - 2 {
            args[a] = V::splat(r.constants[a - 4]);
            continue;
        } else {
            match r.parameters[a + 2 - B] {
                Parameter::Shared(v) => {
                    args[a] = V::splat(v);
                    continue;
                }
                Parameter::PerBond(at) => &runs.values[at + i..],
            }
        };
        args[a] = if full { V::load(s) } else { V::load_partial(&s[..count]) };
    }
    let values = K::eval::<V>(args);
    let first = usize::from(ENERGY);
    for a in 0..M - first {
        let (v, s) = (values[first + a], &mut grad[r.grads[a] + i..]);
        if full {
            (V::load(s) + v).store(s);
        } else {
            (V::load_partial(&s[..count]) + v).store_partial(&mut s[..count]);
        }
    }
    match (ENERGY, full) {
        (false, _) => V::splat(0.0),
        (true, true) => values[0],
        (true, false) => values[0].keep_first(count),
    }
}

/// Energy (when `ENERGY`, the kernel's first output) and gradient of every bond of `runs`, the
/// gradient added into `grad` (the stencil's layout); `A` and `B` as in [`bonds`].
#[inline(always)]
fn group<V: Vector, const A: usize, const B: usize, const M: usize, K: BondFn<A, M>, const ENERGY: bool>(
    runs: &Runs,
    input: &[f64],
    grad: &mut [f64],
) -> f64 {
    let mut energy = V::splat(0.0);
    for (run, r) in runs.runs.iter().enumerate() {
        let mut i = 0;
        while i + V::LANES <= r.len {
            energy = energy + bonds::<V, A, B, M, K, ENERGY>(runs, run, i, V::LANES, input, grad);
            i += V::LANES;
        }
        if i < r.len {
            energy = energy + bonds::<V, A, B, M, K, ENERGY>(runs, run, i, r.len - i, input, grad);
        }
    }
    energy.sum()
}

/// The work handed to `dispatch`: the fused energy and gradient (`ENERGY`) or the gradient, with
/// the law's kernels `K` (of `A1, A2, A3` arguments), on the stencil's buffers, from `x` into
/// `out` (both in the patch's order; the transposes run inside the level's function, where the
/// compiler may vectorise them).
pub(super) struct Gradient<'a, K, const A1: usize, const A2: usize, const A3: usize, const ENERGY: bool> {
    pub model: &'a NetworkModel,
    pub x: &'a [f64],
    pub input: &'a mut [f64],
    pub grad: &'a mut [f64],
    pub out: &'a mut [f64],
    pub kernels: core::marker::PhantomData<K>,
}

/// The three bond types' runs through kernel `$f` of the law `$K` (8, 9 and 10: the table's
/// argument counts of the three types, `Kind::args`).
macro_rules! groups {
    ($self:ident, $V:ident, $K:ty, $f:ident, [$m1:literal, $m2:literal, $m3:literal], $energy:literal) => {{
        type Jj<K, const A1: usize, const A2: usize, const A3: usize> =
            <<K as LawKernels<A1, A2, A3>>::JointJoint as BondKernels<A1, 4, 5, 10, 15>>::$f;
        type Jr<K, const A1: usize, const A2: usize, const A3: usize> =
            <<K as LawKernels<A1, A2, A3>>::JointRotor as BondKernels<A2, 3, 4, 6, 10>>::$f;
        type Rr<K, const A1: usize, const A2: usize, const A3: usize> =
            <<K as LawKernels<A1, A2, A3>>::RotorRotor as BondKernels<A3, 2, 3, 3, 6>>::$f;
        // Inline, not in a closure: a closure is not compiled for the level's target features.
        let (st, input, grad) = (&$self.model.stencil, $self.input, $self.grad);
        st.gather($self.x, input);
        grad.fill(0.0);
        let [jj, jr, rr] = &st.kinds;
        let energy = group::<$V, A1, 8, $m1, Jj<$K, A1, A2, A3>, $energy>(jj, input, grad)
            + group::<$V, A2, 9, $m2, Jr<$K, A1, A2, A3>, $energy>(jr, input, grad)
            + group::<$V, A3, 10, $m3, Rr<$K, A1, A2, A3>, $energy>(rr, input, grad);
        st.scatter(grad, $self.out);
        energy
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

std::thread_local! {
    /// The stencil's input and gradient buffers, kept between calls: a step's gradient should
    /// not allocate (16 B per degree of freedom and 16 B per rotor per thread that evaluates).
    static BUFFERS: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
}

/// The gradient into `out` and, with `ENERGY`, the energy, at the detected vector level, with the
/// law's kernels `K` (of `A1, A2, A3` arguments). The rotors' sines and cosines are taken into the
/// stencil's buffers (`_trig`, the caller's, is for the bond-by-bond passes).
pub(super) fn gradient<
    K: LawKernels<A1, A2, A3>,
    const A1: usize,
    const A2: usize,
    const A3: usize,
    const ENERGY: bool,
>(
    model: &NetworkModel,
    x: &[f64],
    _trig: &[[f64; 2]],
    out: &mut [f64],
) -> f64
where
    for<'a> Gradient<'a, K, A1, A2, A3, ENERGY>: WithLanes<Output = f64>,
{
    let st = &model.stencil;
    let (inputs, grads) = (st.input_len(), st.grad_len());
    let mut run = |buffers: &mut Vec<f64>| {
        if buffers.len() < inputs + grads {
            buffers.resize(inputs + grads, 0.0);
        }
        let (input, grad) = buffers.split_at_mut(inputs);
        let (grad, kernels) = (&mut grad[..grads], core::marker::PhantomData);
        dispatch(Gradient::<K, A1, A2, A3, ENERGY> { model, x, input, grad, out: &mut *out, kernels })
    };
    BUFFERS.with(|b| match b.try_borrow_mut() {
        Ok(mut buffers) => run(&mut buffers),
        // Only a re-entrant call (none today) finds the buffers taken: it gets its own.
        Err(_) => run(&mut Vec::new()),
    })
}
