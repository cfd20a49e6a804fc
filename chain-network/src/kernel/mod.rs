//! Per-bond kernels rendered by the symbolic engine (`chain-symbolic`'s `bond` module): for each
//! law a module per bond type (`joint_joint`, `joint_rotor`, `rotor_rotor`), each holding the
//! energy, length, tension, gradient, Hessian block, material part, stress matrix,
//! compatibility row and the fused energy + gradient (+ Hessian) of one bond with every
//! parameter an argument.
//!
//! The kernels are checked in, so this crate needs no build script;
//! `tests/kernels_are_current.rs` regenerates them and fails if they differ (run it with
//! `UPDATE_KERNELS=1` to rewrite them after changing the engine). Each is a unit type
//! implementing [`BondFn<A, M>`], generic over chain-core's [`Lane`] type, so a driver may
//! evaluate several bonds at once in vector lanes. The arguments, per type:
//!
//! | type | arguments | degrees of freedom (gradient order) |
//! | --- | --- | --- |
//! | joint-joint | `[x1, y1, x2, y2, ox, oy, k, l0]` | `x1, y1, x2, y2` |
//! | joint-rotor | `[x1, y1, s2, c2, ox, oy, r2, k, l0]` | `x1, y1, phi2` |
//! | rotor-rotor | `[s1, c1, s2, c2, ox, oy, r1, r2, k, l0]` | `phi1, phi2` |
//!
//! `(x, y)` is a joint's position, `s, c` the sine and cosine of a rotor's angle `phi`
//! (counter-clockwise from `+x`), `r` its length, and `(ox, oy)` the offset of the `to` end (its
//! cell shift, plus its pivot for a rotor, minus the `from` pivot for a rotor-rotor bond). Blocks
//! are upper triangles row by row; a rotor's compatibility entry is `dl / d(r phi)`.

pub use chain_core::simd::Lane;

/// The harmonic law `k (l - l0)^2 / 2`.
#[rustfmt::skip]
pub mod harmonic;

/// The quartic law `k (l^2 - l0^2)^2 / (8 l0^2)` (the paper's Eq. `eq:discretepotential`).
#[rustfmt::skip]
pub mod quartic;

/// The polynomial law `k sum_{j=2..6} c_j (l - l0)^j / j` (`chain_cell::Polynomial`), its
/// coefficients `c2 .. c6` taken after each type's arguments above as `p2 .. p6` (13, 14 and 15
/// arguments).
#[rustfmt::skip]
pub mod polynomial;

/// One rendered per-bond kernel with `A` arguments and `M` outputs, generic over the lane type.
pub trait BondFn<const A: usize, const M: usize> {
    /// The outputs for the arguments `x` (the module doc's table), lane by lane.
    fn eval<L: Lane>(x: [L; A]) -> [L; M];
}

/// Every rendered kernel of one bond type with `A` arguments, `N` degrees of freedom and `H`
/// block entries (`N1 = N + 1`, `F = 1 + N + H`: the fused outputs' counts, spelled out because
/// a const generic cannot be computed from another on stable Rust). Each rendered bond module's
/// `Kernels` implements it.
pub trait BondKernels<const A: usize, const N: usize, const N1: usize, const H: usize, const F: usize> {
    /// The bond's stored energy.
    type Energy: BondFn<A, 1>;
    /// The bond's length.
    type Length: BondFn<A, 1>;
    /// The bond's tension.
    type Tension: BondFn<A, 1>;
    /// The gradient.
    type Gradient: BondFn<A, N>;
    /// The Hessian block.
    type Hessian: BondFn<A, H>;
    /// The material part of the block.
    type Material: BondFn<A, H>;
    /// The stress-matrix part of the block.
    type Stress: BondFn<A, H>;
    /// The compatibility row.
    type Compatibility: BondFn<A, N>;
    /// Energy and gradient fused.
    type EnergyGradient: BondFn<A, N1>;
    /// Energy, gradient and Hessian block fused.
    type EnergyGradientHessian: BondFn<A, F>;
}

/// A spring law's kernels for the three bond types: what [`NetworkModel`](crate::NetworkModel)'s
/// drivers are generic over. Each rendered kernel file's `Law` implements it
/// ([`harmonic::Law`], [`quartic::Law`], [`polynomial::Law`], and the `#[rotor_network]`
/// attribute's own, rendered at compile time for its law). `A1, A2, A3` are the three types'
/// argument counts: the table's 8, 9 and 10, more for a law with parameters of its own (the
/// polynomial's 13, 14 and 15).
pub trait LawKernels<const A1: usize = 8, const A2: usize = 9, const A3: usize = 10>: 'static {
    /// The joint-joint bond's kernels.
    type JointJoint: BondKernels<A1, 4, 5, 10, 15>;
    /// The joint-rotor bond's kernels.
    type JointRotor: BondKernels<A2, 3, 4, 6, 10>;
    /// The rotor-rotor bond's kernels.
    type RotorRotor: BondKernels<A3, 2, 3, 3, 6>;
}
