//! Per-spring kernels rendered by the symbolic engine (`chain-symbolic`), and the loops that
//! drive them over the springs of a chain, several springs at a time in vector lanes.
//!
//! The kernels are checked in so that `chain-core` needs no build script. They are the same
//! source the `#[rotor_chain]` macro emits for large chains; `tests/kernels_are_current.rs`
//! regenerates them and fails if they differ (run it with `UPDATE_KERNELS=1` to rewrite them
//! after changing the engine).
//!
//! Each kernel is a unit type implementing [`SpringFn<M>`]: `eval` takes
//! `x = [s1, c1, s2, c2, a, r1, r2, k, l0]` (sine and cosine of the two rotor angles, lattice
//! spacing, the two rotor lengths, the spring's stiffness and rest length) over any [`Lane`]
//! type and returns `M` outputs. The drivers below:
//! 1. take the `sin_cos` of a chunk of angles, each angle once, in vector lanes;
//! 2. evaluate the kernel on `LANES` consecutive springs at once (sines, cosines and parameters
//!    are contiguous, so they load straight into lanes), summing the energy in lanes;
//! 3. assemble the rotor sums (`out[p] += left_p`, `out[p + 1] += right_p`) from the chunk's
//!    per-spring outputs.
//!
//! Everything runs at the level [`crate::simd`] detects at run time (the scalar level is the same
//! code with `f64` lanes). Kernel arithmetic is lane-for-lane IEEE, so levels differ only through
//! `sin_cos` (within 2 ulp of the correctly rounded values at every level).
//!
//! `springs` gives `[a, r_p, r_{p+1}, k_p, l0_p]` of spring `p`: a closure
//! `Fn(usize) -> [f64; 5]` (the macro's looped code), or [`SpringSlices`] (the runtime chain),
//! whose contiguous parameters load into lanes without a gather.

use crate::simd::{self, Vector, WithLanes};

pub use crate::simd::Lane;

/// The harmonic law `k (l - l0)^2 / 2` (paper Eq. `eq:discretelagrangian`).
#[rustfmt::skip]
pub mod harmonic;

/// The paper's quartic approximation `k (l^2 - l0^2)^2 / (8 l0^2)` (Eq. `eq:discretepotential`).
#[rustfmt::skip]
pub mod quartic;

/// One rendered per-spring kernel with `M` outputs, generic over the lane type.
pub trait SpringFn<const M: usize> {
    /// The outputs for `x = [s1, c1, s2, c2, a, r1, r2, k, l0]`, lane by lane.
    fn eval<L: Lane>(x: [L; 9]) -> [L; M];
}

/// The parameters of a chain's springs.
pub trait Springs {
    /// `[a, r_p, r_{p+1}, k_p, l0_p]` of spring `p`.
    fn params(&self, p: usize) -> [f64; 5];
    /// The same as contiguous slices, if the chain stores them that way (then the drivers load
    /// them into lanes directly).
    fn slices(&self) -> Option<SpringSlices<'_>> {
        None
    }
}

impl<F: Fn(usize) -> [f64; 5]> Springs for F {
    #[inline(always)]
    fn params(&self, p: usize) -> [f64; 5] {
        self(p)
    }
}

/// Spring parameters held in slices: `rotor_lengths` has `n` entries, `stiffness` and
/// `rest_lengths` `n - 1`.
#[derive(Clone, Copy, Debug)]
pub struct SpringSlices<'a> {
    /// Lattice spacing `a`.
    pub a: f64,
    /// Rotor lengths `r_i`, one per rotor.
    pub rotor_lengths: &'a [f64],
    /// Spring stiffnesses `k_p`, one per spring.
    pub stiffness: &'a [f64],
    /// Spring rest lengths `l0_p`, one per spring.
    pub rest_lengths: &'a [f64],
}

impl Springs for SpringSlices<'_> {
    #[inline(always)]
    fn params(&self, p: usize) -> [f64; 5] {
        [self.a, self.rotor_lengths[p], self.rotor_lengths[p + 1], self.stiffness[p], self.rest_lengths[p]]
    }
    #[inline(always)]
    fn slices(&self) -> Option<SpringSlices<'_>> {
        Some(*self)
    }
}

/// Springs per chunk: the stack buffers hold `CHUNK + 1` sines and cosines and `CHUNK` values of
/// each per-spring output, so the drivers need no allocation (`no_std`).
const CHUNK: usize = 64;

/// Per-spring outputs of one chunk.
type Chunk<const M: usize> = [[f64; CHUNK]; M];

/// Evaluates `K` on every spring of the chain with angles `theta`, `V::LANES` springs at a time.
/// With `SUM`, output 0 is summed (in lanes) and returned; the outputs are stored per spring and
/// handed to `visit(first_spring, count, outputs)` chunk by chunk.
#[inline(always)]
fn drive<V: Vector, K: SpringFn<M>, const M: usize, const SUM: bool>(
    theta: &[f64],
    springs: &impl Springs,
    mut visit: impl FnMut(usize, usize, &Chunk<M>),
) -> f64 {
    let n = theta.len();
    if n < 2 {
        return 0.0;
    }
    let m = n - 1;
    let slices = springs.slices();
    if let Some(s) = &slices {
        assert!(
            s.rotor_lengths.len() == n && s.stiffness.len() == m && s.rest_lengths.len() == m,
            "one parameter per rotor or spring"
        );
    }
    // Angles start..=start + count of the chunk at offsets 0..=count; room for a padded vector.
    let (mut sin, mut cos) = ([0.0; CHUNK + 1 + 8], [0.0; CHUNK + 1 + 8]);
    let mut outs: Chunk<M> = [[0.0; CHUNK]; M];
    let mut acc = V::splat(0.0);
    let mut start = 0;
    while start < m {
        let count = (m - start).min(CHUNK);
        if start == 0 {
            simd::sin_cos_lanes::<V>(&theta[..=count], &mut sin, &mut cos);
        } else {
            simd::sin_cos_lanes::<V>(&theta[start + 1..=start + count], &mut sin[1..], &mut cos[1..]);
        }
        let mut j = 0;
        while j < count {
            let p = start + j;
            // The last springs of the chain, fewer than a vector, go in a vector with the
            // remaining lanes unused: their sines and cosines are the buffer's slack, their
            // parameters zero (slices) or repeated (gathered); nothing of them is stored or summed.
            let rest = (count - j).min(V::LANES);
            let [a, r1, r2, k, l0] = match &slices {
                Some(s) if rest == V::LANES => [
                    V::splat(s.a),
                    V::load(&s.rotor_lengths[p..]),
                    V::load(&s.rotor_lengths[p + 1..]),
                    V::load(&s.stiffness[p..]),
                    V::load(&s.rest_lengths[p..]),
                ],
                Some(s) => [
                    V::splat(s.a),
                    V::load_partial(&s.rotor_lengths[p..p + rest]),
                    V::load_partial(&s.rotor_lengths[p + 1..p + 1 + rest]),
                    V::load_partial(&s.stiffness[p..p + rest]),
                    V::load_partial(&s.rest_lengths[p..p + rest]),
                ],
                None => gather::<V>(springs, p, rest),
            };
            let x = [V::load(&sin[j..]), V::load(&cos[j..]), V::load(&sin[j + 1..]), V::load(&cos[j + 1..])];
            let y = K::eval([x[0], x[1], x[2], x[3], a, r1, r2, k, l0]);
            if rest == V::LANES {
                for (o, v) in outs.iter_mut().zip(y).skip(usize::from(SUM)) {
                    v.store(&mut o[j..]);
                }
                if SUM {
                    acc = acc + y[0];
                }
            } else {
                for (o, v) in outs.iter_mut().zip(y).skip(usize::from(SUM)) {
                    v.store_partial(&mut o[j..j + rest]);
                }
                if SUM {
                    let mut e = [0.0; 8];
                    y[0].store_partial(&mut e[..rest]);
                    acc = acc + V::load(&e);
                }
            }
            j += rest;
        }
        visit(start, count, &outs);
        (sin[0], cos[0]) = (sin[count], cos[count]);
        start += count;
    }
    acc.sum()
}

/// Parameters of springs `p..p + count` (`count <= V::LANES`; the last one repeated in the
/// remaining lanes) from a chain that does not store them in slices.
#[inline(always)]
fn gather<V: Vector>(springs: &impl Springs, p: usize, count: usize) -> [V; 5] {
    let mut lanes = [[0.0; 8]; 5];
    for j in 0..V::LANES {
        let x = springs.params(p + j.min(count - 1));
        for (l, v) in lanes.iter_mut().zip(x) {
            l[j] = v;
        }
    }
    lanes.map(|l| V::load(&l))
}

/// `out[i] = left[i] + right[i - 1]` over one chunk: the rotor sums of per-spring pairs, with
/// `carry` the right value of the spring before the chunk (0 for the first).
#[inline(always)]
fn rotor_sums(out: &mut [f64], left: &[f64], right: &[f64], carry: f64) {
    out[0] = left[0] + carry;
    for ((o, l), r) in out[1..].iter_mut().zip(&left[1..]).zip(right) {
        *o = l + r;
    }
}

/// A driver call with its output closure, run by [`simd::dispatch`] at the detected level.
struct Drive<'a, K, S, F, const M: usize, const SUM: bool> {
    theta: &'a [f64],
    springs: S,
    visit: F,
    kernel: core::marker::PhantomData<K>,
}

impl<K: SpringFn<M>, S: Springs, F: FnMut(usize, usize, &Chunk<M>), const M: usize, const SUM: bool> WithLanes
    for Drive<'_, K, S, F, M, SUM>
{
    type Output = f64;
    #[inline(always)]
    fn run<V: Vector>(self) -> f64 {
        drive::<V, K, M, SUM>(self.theta, &self.springs, self.visit)
    }
}

#[inline(always)]
fn run<K: SpringFn<M>, const M: usize, const SUM: bool>(
    theta: &[f64],
    springs: impl Springs,
    visit: impl FnMut(usize, usize, &Chunk<M>),
) -> f64 {
    simd::dispatch(Drive::<K, _, _, M, SUM> { theta, springs, visit, kernel: core::marker::PhantomData })
}

/// `sum_p kernel(p)`: the energy.
pub fn sum<K: SpringFn<1>>(theta: &[f64], springs: impl Springs) -> f64 {
    run::<K, 1, true>(theta, springs, |_, _, _| {})
}

/// Rotor sums of per-spring pairs: `out[p] += kernel[0]`, `out[p + 1] += kernel[1]` (the gradient).
pub fn assemble_pairs<K: SpringFn<2>>(theta: &[f64], springs: impl Springs, out: &mut [f64]) {
    assert_eq!(out.len(), theta.len(), "one entry per rotor");
    let mut carry = 0.0;
    run::<K, 2, false>(theta, springs, |p, count, [left, right]| {
        rotor_sums(&mut out[p..p + count], &left[..count], &right[..count - 1], carry);
        carry = right[count - 1];
    });
    if let Some(last) = out.last_mut() {
        *last = carry;
    }
}

/// Tridiagonal assembly of per-spring 2x2 blocks `[11, 12, 22]` (paper Eq. `eq:prestress8`).
pub fn assemble_blocks<K: SpringFn<3>>(
    theta: &[f64],
    springs: impl Springs,
    diag: &mut [f64],
    off: &mut [f64],
) {
    assert_eq!(diag.len(), theta.len(), "diag has one entry per rotor");
    assert_eq!(off.len() + 1, theta.len(), "off has one entry per spring");
    let mut carry = 0.0;
    run::<K, 3, false>(theta, springs, |p, count, [b11, b12, b22]| {
        rotor_sums(&mut diag[p..p + count], &b11[..count], &b22[..count - 1], carry);
        off[p..p + count].copy_from_slice(&b12[..count]);
        carry = b22[count - 1];
    });
    if let Some(last) = diag.last_mut() {
        *last = carry;
    }
}

/// One value per spring (lengths, tensions).
pub fn per_spring<K: SpringFn<1>>(theta: &[f64], springs: impl Springs, out: &mut [f64]) {
    assert_eq!(out.len() + 1, theta.len(), "one entry per spring");
    run::<K, 1, false>(theta, springs, |p, count, [v]| out[p..p + count].copy_from_slice(&v[..count]));
}

/// Two values per spring (the compatibility matrix's two bands).
pub fn per_spring_pairs<K: SpringFn<2>>(
    theta: &[f64],
    springs: impl Springs,
    left: &mut [f64],
    right: &mut [f64],
) {
    assert_eq!(left.len() + 1, theta.len(), "one entry per spring");
    assert_eq!(right.len() + 1, theta.len(), "one entry per spring");
    run::<K, 2, false>(theta, springs, |p, count, [l, r]| {
        left[p..p + count].copy_from_slice(&l[..count]);
        right[p..p + count].copy_from_slice(&r[..count]);
    });
}

/// Energy and gradient in one pass (`K` returns `[E, left, right]`): the gradient into `out`,
/// the energy returned.
pub fn energy_and_gradient<K: SpringFn<3>>(theta: &[f64], springs: impl Springs, out: &mut [f64]) -> f64 {
    assert_eq!(out.len(), theta.len(), "one entry per rotor");
    let mut carry = 0.0;
    let energy = run::<K, 3, true>(theta, springs, |p, count, [_, left, right]| {
        rotor_sums(&mut out[p..p + count], &left[..count], &right[..count - 1], carry);
        carry = right[count - 1];
    });
    if let Some(last) = out.last_mut() {
        *last = carry;
    }
    energy
}

/// Energy, gradient and tridiagonal tangent stiffness in one pass (`K` returns
/// `[E, left, right, 11, 12, 22]`).
pub fn energy_gradient_stiffness<K: SpringFn<6>>(
    theta: &[f64],
    springs: impl Springs,
    grad: &mut [f64],
    diag: &mut [f64],
    off: &mut [f64],
) -> f64 {
    assert_eq!(grad.len(), theta.len(), "one gradient entry per rotor");
    assert_eq!(diag.len(), theta.len(), "diag has one entry per rotor");
    assert_eq!(off.len() + 1, theta.len(), "off has one entry per spring");
    let (mut carry_g, mut carry_d) = (0.0, 0.0);
    let energy = run::<K, 6, true>(theta, springs, |p, count, [_, left, right, b11, b12, b22]| {
        rotor_sums(&mut grad[p..p + count], &left[..count], &right[..count - 1], carry_g);
        rotor_sums(&mut diag[p..p + count], &b11[..count], &b22[..count - 1], carry_d);
        off[p..p + count].copy_from_slice(&b12[..count]);
        (carry_g, carry_d) = (right[count - 1], b22[count - 1]);
    });
    if let (Some(g), Some(d)) = (grad.last_mut(), diag.last_mut()) {
        *g = carry_g;
        *d = carry_d;
    }
    energy
}
