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
//! 1. take the `sin_cos` of a chunk of angles, each angle once, in vector lanes, into aligned
//!    buffers; a group of springs loads its left rotors' values from there, and its right
//!    rotors' values one position further on;
//! 2. evaluate the kernel on `LANES` consecutive springs at once (parameters are splat, or
//!    loaded from contiguous slices), summing the energy in lanes;
//! 3. form the rotor sums (`out[p] += left_p`, `out[p + 1] += right_p`) in registers, with the
//!    previous group's right values shifted in by a lane, and store them once.
//!
//! Everything runs at the level [`crate::simd`] detects at run time (the scalar level is the same
//! code with `f64` lanes). Kernel arithmetic is lane-for-lane IEEE, so levels differ only through
//! `sin_cos` (within 2 ulp of the correctly rounded values at every level).
//!
//! `springs` gives `[a, r_p, r_{p+1}, k_p, l0_p]` of spring `p`: a closure
//! `Fn(usize) -> [f64; 5]` (the macro's looped code), or [`SpringSlices`] (the runtime chain),
//! whose contiguous parameters load into lanes without a gather.

use core::mem::MaybeUninit;

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
    /// Parameters `[a, r, r, k, l0]` shared by every spring except the listed ones (sorted, no
    /// repeats), which take [`Springs::params`]. The drivers splat them into lanes, so a group of
    /// springs without an exception costs no parameter loads, and literal values fold into the
    /// kernel's arithmetic.
    fn uniform(&self) -> Option<([f64; 5], &[usize])> {
        None
    }
    /// Whether [`Springs::chain_rotors`] can be `Some`: a constant, so that the drivers of one
    /// chain compile without the joins' bookkeeping.
    const BACK_TO_BACK: bool = false;
    /// Rotors per chain when the angles hold several chains of the same kind back to back (see
    /// [`BackToBack`]); `None` for one chain.
    fn chain_rotors(&self) -> Option<usize> {
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

/// Springs that share one set of parameters except a few (the macro's chains: overrides and the
/// springs beside an overridden rotor). `exceptions` must be sorted without repeats; `each(p)`
/// gives the parameters of any spring.
#[derive(Clone, Copy, Debug)]
pub struct UniformSprings<'a, F> {
    /// `[a, r, r, k, l0]` of every spring not in `exceptions`.
    pub params: [f64; 5],
    /// The springs whose parameters differ, sorted, without repeats.
    pub exceptions: &'a [usize],
    /// `each(p)`: the parameters of spring `p`, for the exceptions.
    pub each: F,
}

impl<F: Fn(usize) -> [f64; 5]> Springs for UniformSprings<'_, F> {
    #[inline(always)]
    fn params(&self, p: usize) -> [f64; 5] {
        (self.each)(p)
    }
    #[inline(always)]
    fn uniform(&self) -> Option<([f64; 5], &[usize])> {
        Some((self.params, self.exceptions))
    }
}

/// Several chains of `rotors` rotors each, their angles back to back in one slice (a batch of
/// configurations), driven as one long chain so that the vector loop runs without a break at
/// the ends of each configuration. `springs` describes the long chain: its spring `p` with
/// `p % rotors == rotors - 1` joins two configurations and belongs to neither; the drivers drop
/// its outputs (its lanes are zeroed whatever they hold, NaN included), so every configuration
/// gets exactly the sums it gets alone (a zero's sign aside: `0 + -0` is `+0`). Per-spring
/// outputs read `0` at those springs.
#[derive(Clone, Copy, Debug)]
pub struct BackToBack<S> {
    /// The parameters of the long chain (those of the joining springs are read but not used).
    pub springs: S,
    /// Rotors per configuration (at least 1).
    pub rotors: usize,
}

impl<S: Springs> Springs for BackToBack<S> {
    const BACK_TO_BACK: bool = true;
    #[inline(always)]
    fn params(&self, p: usize) -> [f64; 5] {
        self.springs.params(p)
    }
    #[inline(always)]
    fn slices(&self) -> Option<SpringSlices<'_>> {
        self.springs.slices()
    }
    #[inline(always)]
    fn uniform(&self) -> Option<([f64; 5], &[usize])> {
        self.springs.uniform()
    }
    #[inline(always)]
    fn chain_rotors(&self) -> Option<usize> {
        Some(self.rotors)
    }
}

/// Springs per chunk of [`stream`], and angles per refill of [`Angles`] (a multiple of every
/// lane count).
const TRIG_CHUNK: usize = 64;

/// The most lanes of any level: how far a chunk's angles reach past its springs.
const MAX_LANES: usize = 8;

/// A chunk's sines or cosines, aligned for the widest vector. Not initialized when made:
/// [`Angles::fill`] writes every value a chunk reads before handing it out (zeroing the two
/// buffers, 1.1 KB, cost 4-8 % of energy + gradient of 60 rotors, docs/benchmarks.md, eighth
/// round).
#[derive(Clone, Copy)]
#[repr(C, align(64))]
struct Aligned([MaybeUninit<f64>; TRIG_CHUNK + MAX_LANES]);

/// The sines and cosines of one chunk of a chain's angles, each angle's computed once. A chunk of
/// springs `start .. start + TRIG_CHUNK` needs angles `start .. start + TRIG_CHUNK + 1`: the
/// buffers hold `start .. start + TRIG_CHUNK + V::LANES`, whose last `V::LANES` values the next
/// chunk takes over as its first ones. A group's right rotors are then an unaligned load one
/// value further on (cheaper than shifting lanes: AVX2 needs two shuffles per shift, and
/// shuffles share a port with the multiplications).
///
/// Computing the sines and cosines apart from the kernel keeps the polynomial's constants in
/// registers (AVX2 has 16), and the scalar level's `sincos` (an opaque call that clobbers every
/// vector register) out of the kernel loop (10-20 %, docs/benchmarks.md finding 5).
struct Angles<'a> {
    theta: &'a [f64],
    sin: Aligned,
    cos: Aligned,
}

/// One filled chunk of [`Angles`]: its first `TRIG_CHUNK + V::LANES` sines and cosines, every
/// one written.
struct Chunk<'b> {
    sin: &'b [f64],
    cos: &'b [f64],
}

impl<'a> Angles<'a> {
    #[inline(always)]
    fn new(theta: &'a [f64]) -> Self {
        let empty = Aligned([MaybeUninit::uninit(); TRIG_CHUNK + MAX_LANES]);
        Self { theta, sin: empty, cos: empty }
    }

    /// Fills the buffers for the chunk from angle `start` (a multiple of `TRIG_CHUNK`, reached in
    /// order from 0, so that the values carried over were written by the call before); values
    /// past the chain are `(0, 1)`.
    #[inline(always)]
    fn fill<V: Vector>(&mut self, start: usize) -> Chunk<'_> {
        let l = V::LANES;
        let n = self.theta.len();
        let carried = if start == 0 {
            0
        } else {
            self.sin.0.copy_within(TRIG_CHUNK..TRIG_CHUNK + l, 0);
            self.cos.0.copy_within(TRIG_CHUNK..TRIG_CHUNK + l, 0);
            l
        };
        let end = (start + TRIG_CHUNK + l).min(n);
        let computed = end.saturating_sub(start + carried);
        if computed > 0 {
            let (sin, cos) = (&mut self.sin.0[carried..], &mut self.cos.0[carried..]);
            simd::sin_cos_lanes::<V>(&self.theta[start + carried..end], sin, cos);
        }
        // The last chunk: pad past the chain (values carried over were padded the chunk before).
        let valid = carried + computed;
        if valid < TRIG_CHUNK + l {
            self.sin.0[valid..TRIG_CHUNK + l].fill(MaybeUninit::new(0.0));
            self.cos.0[valid..TRIG_CHUNK + l].fill(MaybeUninit::new(1.0));
        }
        let len = TRIG_CHUNK + l;
        debug_assert!(l <= MAX_LANES, "a level within the buffers");
        // SAFETY: values `0 .. len` are written: `0 .. carried` by the call for the chunk before
        // (as its values `TRIG_CHUNK .. TRIG_CHUNK + l`, which that call wrote), `carried ..
        // valid` by `sin_cos_lanes` (one value per angle) and `valid .. len` by the padding.
        // `MaybeUninit<f64>` has the layout of `f64`, and `len <= TRIG_CHUNK + MAX_LANES`.
        unsafe {
            Chunk {
                sin: core::slice::from_raw_parts(self.sin.0.as_ptr().cast::<f64>(), len),
                cos: core::slice::from_raw_parts(self.cos.0.as_ptr().cast::<f64>(), len),
            }
        }
    }
}

impl Chunk<'_> {
    /// `(s1, c1, s2, c2)`: sines and cosines of the left rotors `j .. j + V::LANES` of a group
    /// (`j` a multiple of `V::LANES` below `TRIG_CHUNK`, counted from the chunk's start) and of
    /// its right rotors, one further on.
    #[inline(always)]
    fn group<V: Vector>(&self, j: usize) -> [V; 4] {
        debug_assert!(j <= TRIG_CHUNK - V::LANES && j.is_multiple_of(V::LANES), "a group of the chunk");
        // The `min` (a conditional move) tells the compiler what the caller guarantees, so it
        // drops the bounds checks (they cost as much as the loads they guard).
        let j = j.min(TRIG_CHUNK - V::LANES);
        let l = V::LANES;
        let (sin, cos) = (&self.sin[..TRIG_CHUNK + l], &self.cos[..TRIG_CHUNK + l]);
        [
            V::load(&sin[j..j + l]),
            V::load(&cos[j..j + l]),
            V::load(&sin[j + 1..j + 1 + l]),
            V::load(&cos[j + 1..j + 1 + l]),
        ]
    }
}

/// Evaluates `K` on every spring of the chain with angles `theta`, `V::LANES` consecutive
/// springs at a time, and hands each group's outputs to `sink.take(first_spring, count, joins,
/// outputs)` (`count < V::LANES` only for the last group; its other lanes are padding to be
/// ignored). `joins` has bit `j` set if spring `first_spring + j` joins two chains laid back to
/// back ([`BackToBack`]); those lanes of every output are already zeroed.
///
/// One pass over chunks of `TRIG_CHUNK` springs: each chunk's sines and cosines first
/// ([`Angles`]), then its groups, the full ones two at a time in a loop without checks of its
/// own (per-group bookkeeping filled the core's window with instructions that wait on nothing,
/// and fewer groups' divisions overlapped: 204 -> 186 ns for energy + gradient of 60 rotors at
/// AVX2, docs/benchmarks.md, seventh round).
///
/// The sines and cosines are not computed group by group inside the loop over springs: each
/// group's chain of dependent operations then runs from the angle to the force, and fewer
/// groups fit the core's window (energy + gradient of 60 rotors 144 -> 160 ns at AVX-512 with
/// the next group's values shifted in by a lane; chunks of 16 or 32 springs were slower too,
/// docs/benchmarks.md, tenth round).
#[inline(always)]
fn stream<V: Vector, K: SpringFn<M>, S: Springs, const M: usize>(
    theta: &[f64],
    springs: &S,
    sink: &mut impl GroupSink<V, M>,
) {
    let n = theta.len();
    if n < 2 {
        return;
    }
    let m = n - 1;
    let slices = springs.slices();
    if let Some(s) = &slices {
        assert!(
            s.rotor_lengths.len() == n && s.stiffness.len() == m && s.rest_lengths.len() == m,
            "one parameter per rotor or spring"
        );
    }
    let rotors = if S::BACK_TO_BACK { springs.chain_rotors() } else { None };
    assert!(rotors.is_none_or(|r| r >= 1 && n.is_multiple_of(r)), "whole chains of at least one rotor");
    let mut state = GroupState {
        slices,
        uniform: springs.uniform(),
        rotors,
        // The next spring that joins two chains (none for one chain).
        join: rotors.map_or(usize::MAX, |r| r - 1),
        exception: 0,
    };
    let mut angles = Angles::new(theta);
    let mut start = 0;
    while start < m {
        let trig = angles.fill::<V>(start);
        let chunk = (m - start).min(TRIG_CHUNK);
        let mut j = 0;
        // Two groups per step, both evaluated before either is handed on: their kernels'
        // instructions sit side by side, and the core overlaps their divisions and long chains
        // better than one loop iteration apart (E + g + K of 60 rotors 272 -> 256 ns at AVX2,
        // docs/benchmarks.md, tenth round).
        while j + 2 * V::LANES <= chunk {
            let (y0, joins0) = state.group::<V, K, S, M>(springs, &trig, start, j, V::LANES);
            let (y1, joins1) = state.group::<V, K, S, M>(springs, &trig, start, j + V::LANES, V::LANES);
            sink.take(start + j, V::LANES, joins0, y0);
            sink.take(start + j + V::LANES, V::LANES, joins1, y1);
            j += 2 * V::LANES;
        }
        while j + V::LANES <= chunk {
            let (y, joins) = state.group::<V, K, S, M>(springs, &trig, start, j, V::LANES);
            sink.take(start + j, V::LANES, joins, y);
            j += V::LANES;
        }
        if j < chunk {
            let (y, joins) = state.group::<V, K, S, M>(springs, &trig, start, j, chunk - j);
            sink.take(start + j, chunk - j, joins, y);
        }
        start += TRIG_CHUNK;
    }
}

/// What [`stream`] carries from group to group: the chain's parameters and where the next
/// exception and join are.
struct GroupState<'a> {
    slices: Option<SpringSlices<'a>>,
    uniform: Option<([f64; 5], &'a [usize])>,
    rotors: Option<usize>,
    join: usize,
    exception: usize,
}

impl GroupState<'_> {
    /// The outputs of the group of springs `p .. p + rest` (`p = start + j`, `rest <=
    /// V::LANES`), and its joins.
    #[inline(always)]
    fn group<V: Vector, K: SpringFn<M>, S: Springs, const M: usize>(
        &mut self,
        springs: &S,
        trig: &Chunk<'_>,
        start: usize,
        j: usize,
        rest: usize,
    ) -> ([V; M], u8) {
        let p = start + j;
        let [s1, c1, s2, c2] = trig.group::<V>(j);
        let [a, r1, r2, k, l0] = match (&self.slices, &self.uniform) {
            // SAFETY: a full group, `p + V::LANES <= m`, and the slices' lengths (`n`, `m`, `m`)
            // were asserted in `stream`. Unchecked because the checks (two per load) were 10 %
            // of the kernel's time (docs/benchmarks.md, fourth round).
            (Some(s), _) if rest == V::LANES => unsafe {
                [
                    V::splat(s.a),
                    V::load(s.rotor_lengths.get_unchecked(p..p + V::LANES)),
                    V::load(s.rotor_lengths.get_unchecked(p + 1..p + 1 + V::LANES)),
                    V::load(s.stiffness.get_unchecked(p..p + V::LANES)),
                    V::load(s.rest_lengths.get_unchecked(p..p + V::LANES)),
                ]
            },
            (Some(s), _) => [
                V::splat(s.a),
                V::load_partial(&s.rotor_lengths[p..p + rest]),
                V::load_partial(&s.rotor_lengths[p + 1..p + 1 + rest]),
                V::load_partial(&s.stiffness[p..p + rest]),
                V::load_partial(&s.rest_lengths[p..p + rest]),
            ],
            (None, Some((params, exceptions))) => {
                while exceptions.get(self.exception).is_some_and(|&e| e < p) {
                    self.exception += 1;
                }
                if exceptions.get(self.exception).is_some_and(|&e| e < p + rest) {
                    gather::<V>(springs, p, rest)
                } else {
                    params.map(V::splat)
                }
            }
            (None, None) => gather::<V>(springs, p, rest),
        };
        let mut y = K::eval([s1, c1, s2, c2, a, r1, r2, k, l0]);
        let mut joins = 0u8;
        if let Some(r) = self.rotors {
            // Springs that exist: the last chain's join would lie past the last spring.
            while self.join < p + rest {
                joins |= 1 << (self.join - p);
                self.join += r;
            }
            if joins != 0 {
                y = y.map(|v| v.keep_lanes(!joins));
            }
        }
        (y, joins)
    }
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

/// Writes the first `count` lanes of `v` to `out[p..]`.
#[inline(always)]
fn put<V: Vector>(v: V, out: &mut [f64], p: usize, count: usize) {
    if count == V::LANES {
        v.store(&mut out[p..p + V::LANES]);
    } else {
        v.store_partial(&mut out[p..p + count]);
    }
}

/// The first `count` lanes of `v` (others zero).
#[inline(always)]
fn first<V: Vector>(v: V, count: usize) -> V {
    if count == V::LANES { v } else { v.keep_first(count) }
}

/// Rotor sums of per-spring pairs, a group at a time: rotor `i` collects the left value of
/// spring `i` and the right value of spring `i - 1` (paper Eq. `eq:prestress8`).
struct RotorSums<V> {
    previous_right: V,
    last_count: usize,
}

impl<V: Vector> RotorSums<V> {
    #[inline(always)]
    fn new() -> Self {
        Self { previous_right: V::splat(0.0), last_count: 0 }
    }
    /// Stores rotors `p .. p + count` of springs `p .. p + count`.
    #[inline(always)]
    fn add(&mut self, out: &mut [f64], p: usize, count: usize, left: V, right: V) {
        put(left + right.previous_lane(self.previous_right), out, p, count);
        self.previous_right = right;
        self.last_count = count;
    }
    /// The last rotor: the right value of the last spring.
    #[inline(always)]
    fn finish(self, out: &mut [f64]) {
        if let Some(last) = out.last_mut()
            && self.last_count > 0
        {
            *last = self.previous_right.lane(self.last_count - 1);
        }
    }
}

/// A driver call with its output closure, run by [`simd::dispatch`] at the detected level.
struct Drive<'a, K, S, F, const M: usize> {
    theta: &'a [f64],
    springs: S,
    run: F,
    kernel: core::marker::PhantomData<K>,
}

/// The output side of a driver, generic over the lane type (a closure cannot be).
trait Visit<const M: usize> {
    type Output;
    fn run<V: Vector, K: SpringFn<M>>(self, theta: &[f64], springs: &impl Springs) -> Self::Output;
}

impl<K: SpringFn<M>, S: Springs, F: Visit<M>, const M: usize> WithLanes for Drive<'_, K, S, F, M> {
    type Output = F::Output;
    #[inline(always)]
    fn run<V: Vector>(self) -> F::Output {
        self.run.run::<V, K>(self.theta, &self.springs)
    }
}

#[inline(always)]
fn run<K: SpringFn<M>, const M: usize, F: Visit<M>>(
    theta: &[f64],
    springs: impl Springs,
    visit: F,
) -> F::Output {
    simd::dispatch(Drive::<K, _, _, M> { theta, springs, run: visit, kernel: core::marker::PhantomData })
}

/// Marks an output a driver does not produce.
const NONE: usize = usize::MAX;

/// The outputs of a driver: energy, gradient, tridiagonal blocks and per-spring values,
/// whichever are asked for, at the kernel output positions `E`, `G` (left, right), `B` (11, 12,
/// 22), `S`, `T` (`NONE`: not produced). Constants, so each driver compiles to only its own work.
struct Outputs<'a, const E: usize, const G: usize, const B: usize, const S: usize, const T: usize> {
    /// One energy per chain laid back to back, if not empty (the total is returned either way).
    energies: &'a mut [f64],
    gradient: &'a mut [f64],
    diag: &'a mut [f64],
    off: &'a mut [f64],
    first: &'a mut [f64],
    second: &'a mut [f64],
}

impl<const E: usize, const G: usize, const B: usize, const S: usize, const T: usize>
    Outputs<'_, E, G, B, S, T>
{
    fn new() -> Self {
        Self {
            energies: &mut [],
            gradient: &mut [],
            diag: &mut [],
            off: &mut [],
            first: &mut [],
            second: &mut [],
        }
    }
}

impl<const M: usize, const E: usize, const G: usize, const B: usize, const S: usize, const T: usize> Visit<M>
    for Outputs<'_, E, G, B, S, T>
{
    type Output = f64;
    #[inline(always)]
    fn run<V: Vector, K: SpringFn<M>>(self, theta: &[f64], springs: &impl Springs) -> f64 {
        let mut sink = Sink::<V, E, G, B, S, T> {
            outputs: self,
            acc: V::splat(0.0),
            total: 0.0,
            chain: 0,
            g_sums: RotorSums::new(),
            d_sums: RotorSums::new(),
        };
        stream::<V, K, _, M>(theta, springs, &mut sink);
        let Sink { outputs, acc, total, chain, g_sums, d_sums } = sink;
        if G != NONE {
            g_sums.finish(outputs.gradient);
        }
        if B != NONE {
            d_sums.finish(outputs.diag);
        }
        if outputs.energies.is_empty() {
            return acc.sum();
        }
        // The last chain (no spring joins it to a next one).
        outputs.energies[chain] = acc.sum();
        total + outputs.energies[chain]
    }
}

/// Where [`stream`] hands each group's outputs.
trait GroupSink<V, const M: usize> {
    /// The outputs `y` of springs `p .. p + count` (see [`stream`]).
    fn take(&mut self, p: usize, count: usize, joins: u8, y: [V; M]);
}

/// [`Outputs`] while a driver runs: the energy summed so far (in lanes, and the chains finished
/// before), and the rotor sums. A type rather than a closure so that its method can be
/// `#[inline(always)]`: [`stream`] calls it at several places, and a closure as large as the one
/// of energy + gradient + stiffness was then left out of line, its vector operations compiled as
/// calls (four times slower).
struct Sink<'a, V, const E: usize, const G: usize, const B: usize, const S: usize, const T: usize> {
    outputs: Outputs<'a, E, G, B, S, T>,
    acc: V,
    total: f64,
    chain: usize,
    g_sums: RotorSums<V>,
    d_sums: RotorSums<V>,
}

impl<
    V: Vector,
    const M: usize,
    const E: usize,
    const G: usize,
    const B: usize,
    const S: usize,
    const T: usize,
> GroupSink<V, M> for Sink<'_, V, E, G, B, S, T>
{
    #[inline(always)]
    fn take(&mut self, p: usize, count: usize, joins: u8, y: [V; M]) {
        let out = &mut self.outputs;
        if E != NONE {
            let e = first(y[E], count);
            if joins == 0 || out.energies.is_empty() {
                self.acc = self.acc + e;
            } else {
                // Each joining spring ends a chain: the lanes before it finish that chain's sum,
                // the lanes after it start the next one's.
                let (mut from, mut rest) = (0u8, joins);
                while rest != 0 {
                    let j = rest.trailing_zeros();
                    let upto = simd::first_lanes(j as usize);
                    let energy = (self.acc + e.keep_lanes(upto & !from)).sum();
                    out.energies[self.chain] = energy;
                    self.total += energy;
                    self.chain += 1;
                    self.acc = V::splat(0.0);
                    from = upto | 1 << j;
                    rest &= rest - 1;
                }
                self.acc = e.keep_lanes(!from);
            }
        }
        if G != NONE {
            self.g_sums.add(out.gradient, p, count, y[G], y[G + 1]);
        }
        if B != NONE {
            self.d_sums.add(out.diag, p, count, y[B], y[B + 2]);
            put(y[B + 1], out.off, p, count);
        }
        if S != NONE {
            put(y[S], out.first, p, count);
        }
        if T != NONE {
            put(y[T], out.second, p, count);
        }
    }
}

/// `sum_p kernel(p)`: the energy.
pub fn sum<K: SpringFn<1>>(theta: &[f64], springs: impl Springs) -> f64 {
    run::<K, 1, _>(theta, springs, Outputs::<0, NONE, NONE, NONE, NONE>::new())
}

/// Rotor sums of per-spring pairs: `out[p] += kernel[0]`, `out[p + 1] += kernel[1]` (the gradient).
pub fn assemble_pairs<K: SpringFn<2>>(theta: &[f64], springs: impl Springs, out: &mut [f64]) {
    assert_eq!(out.len(), theta.len(), "one entry per rotor");
    let outputs = Outputs::<NONE, 0, NONE, NONE, NONE> { gradient: out, ..Outputs::new() };
    run::<K, 2, _>(theta, springs, outputs);
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
    let outputs = Outputs::<NONE, NONE, 0, NONE, NONE> { diag, off, ..Outputs::new() };
    run::<K, 3, _>(theta, springs, outputs);
}

/// One value per spring (lengths, tensions).
pub fn per_spring<K: SpringFn<1>>(theta: &[f64], springs: impl Springs, out: &mut [f64]) {
    assert_eq!(out.len() + 1, theta.len(), "one entry per spring");
    let outputs = Outputs::<NONE, NONE, NONE, 0, NONE> { first: out, ..Outputs::new() };
    run::<K, 1, _>(theta, springs, outputs);
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
    let outputs = Outputs::<NONE, NONE, NONE, 0, 1> { first: left, second: right, ..Outputs::new() };
    run::<K, 2, _>(theta, springs, outputs);
}

/// Energy and gradient in one pass (`K` returns `[E, left, right]`): the gradient into `out`,
/// the energy returned.
pub fn energy_and_gradient<K: SpringFn<3>>(theta: &[f64], springs: impl Springs, out: &mut [f64]) -> f64 {
    assert_eq!(out.len(), theta.len(), "one entry per rotor");
    let outputs = Outputs::<0, 1, NONE, NONE, NONE> { gradient: out, ..Outputs::new() };
    run::<K, 3, _>(theta, springs, outputs)
}

/// Energies and gradients of several chains laid back to back ([`BackToBack`]) in one pass (`K`
/// returns `[E, left, right]`): one energy per chain into `energies`, the gradients into `out`;
/// the total energy returned. Each chain's energy is summed in another order than
/// [`energy_and_gradient`] sums it alone (its springs sit in other lanes), so the two agree to
/// rounding, not bit for bit; the gradients are bit for bit the same.
pub fn energies_and_gradients<K: SpringFn<3>>(
    theta: &[f64],
    springs: impl Springs,
    energies: &mut [f64],
    out: &mut [f64],
) -> f64 {
    assert_eq!(out.len(), theta.len(), "one entry per rotor");
    let chains = springs.chain_rotors().map_or(1, |r| theta.len() / r.max(1));
    assert_eq!(energies.len(), chains, "one energy per chain");
    let outputs = Outputs::<0, 1, NONE, NONE, NONE> { energies, gradient: out, ..Outputs::new() };
    run::<K, 3, _>(theta, springs, outputs)
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
    let outputs = Outputs::<0, 1, 3, NONE, NONE> { gradient: grad, diag, off, ..Outputs::new() };
    run::<K, 6, _>(theta, springs, outputs)
}
