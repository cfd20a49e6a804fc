//! A chain whose size and parameters are chosen at run time, for sweeps and large chains.
//!
//! Its spring terms come from the same rendered kernels ([`crate::kernel`]) that `#[rotor_chain]`
//! emits for large chains, driven over the springs in vector lanes at the level [`crate::simd`]
//! detects at run time, each angle's `sin_cos` computed once.

use alloc::collections::BTreeSet;
use alloc::vec::Vec;

use chain_geometry::{IndexKind, Key, ParameterError};

use crate::kernel;
use crate::model::layout::{split_bidiagonal, split_tridiagonal};
use crate::model::{
    ChainGeometry, CompatibilityLayout, Potential, SpringNetwork, Stiffness, StiffnessLayout,
};

/// The spring laws a runtime chain offers (a custom law needs the macro, which compiles it).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Law {
    /// `k (l - l0)^2 / 2` (paper Eq. `eq:discretelagrangian`).
    #[default]
    Harmonic,
    /// `k (l^2 - l0^2)^2 / (8 l0^2)` (paper Eq. `eq:discretepotential`).
    Quartic,
}

/// A runtime-sized rotor chain. Build it with [`RuntimeChain::builder`].
#[derive(Clone, Debug, PartialEq)]
pub struct RuntimeChain {
    a: f64,
    mass: f64,
    theta_bar: f64,
    law: Law,
    rotor_lengths: Vec<f64>,
    stiffness: Vec<f64>,
    rest_lengths: Vec<f64>,
    tiles: Tiles,
}

/// The parameters of a block of configurations laid back to back, for [`RuntimeChain::batch`]:
/// [`RuntimeChain::tiled`] for the most copies a block holds, made once when the chain is built
/// (empty where a block holds one configuration). A block of fewer copies uses a prefix. Made per
/// call, they cost each piece of `batch::gradients` three allocations and ~24 KB of writes.
#[derive(Clone, Default, PartialEq)]
struct Tiles([Vec<f64>; 3]);

/// Kept out of a chain's `Debug` output (thousands of repeated values).
impl core::fmt::Debug for Tiles {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "Tiles({} rotors)", self.0[0].len())
    }
}

/// How the uniform state is given: by its angle or by the springs' rest length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Uniform {
    /// Given by its angle `theta_bar`, radians.
    ThetaBar(f64),
    /// Given by the rest length `lbar` of its springs.
    RestLength(f64),
}

/// Builder of a [`RuntimeChain`]; defaults as in the macro: `a = 1`, `mass = 1`, harmonic law.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainBuilder {
    n: usize,
    a: f64,
    r: f64,
    k: f64,
    mass: f64,
    uniform: Uniform,
    law: Law,
    springs: Vec<(usize, Option<f64>, Option<f64>)>,
    rotors: Vec<(usize, f64)>,
}

impl RuntimeChain {
    /// A chain of `n` rotors of length `r`, springs of stiffness `k`, uniform angle `theta_bar`.
    /// Nothing is checked or allocated until [`ChainBuilder::build`].
    /// # Example
    ///
    /// ```
    /// use rotor_chain::prelude::*;
    ///
    /// # fn main() -> Result<(), rotor_chain::ParameterError> {
    /// // n = 60, r = 0.8 a, k = 1e4 M/t^2, theta_bar = 0.58 rad; an impurity spring, a longer lattice.
    /// let chain = RuntimeChain::builder(60, 0.8, 1.0e4, 0.58)
    ///     .lattice_spacing(1.0)
    ///     .spring_constant(29, 1.0e3)         // a stiffness impurity on spring 29
    ///     .spring_rest_length(7, 1.7)         // a length impurity on spring 7
    ///     .spring(40, Some(2.0e4), Some(1.6)) // both on spring 40, in one override
    ///     .build()?;
    /// assert_eq!((chain.spring_constant(29), chain.rest_length(7)), (1.0e3, 1.7));
    /// // A spring overridden twice is refused, as the macro refuses it.
    /// let twice = RuntimeChain::builder(60, 0.8, 1.0e4, 0.58).spring_constant(3, 1.0).spring_rest_length(3, 1.7);
    /// assert!(twice.build().is_err());
    /// assert!(RuntimeChain::builder(60, 0.8, 1.0e4, 0.7).build().is_err()); // past the flipper phase
    /// # Ok(())
    /// # }
    /// ```
    pub fn builder(n: usize, r: f64, k: f64, theta_bar: f64) -> ChainBuilder {
        ChainBuilder {
            n,
            a: 1.0,
            r,
            k,
            mass: 1.0,
            uniform: Uniform::ThetaBar(theta_bar),
            law: Law::Harmonic,
            springs: Vec::new(),
            rotors: Vec::new(),
        }
    }

    /// The spring law.
    pub fn law(&self) -> Law {
        self.law
    }

    /// The springs' parameters as slices, which the kernel drivers load straight into lanes.
    #[inline(always)]
    fn springs(&self) -> kernel::SpringSlices<'_> {
        kernel::SpringSlices {
            a: self.a,
            rotor_lengths: &self.rotor_lengths,
            stiffness: &self.stiffness,
            rest_lengths: &self.rest_lengths,
        }
    }

    /// The parameters of `count` copies of the chain back to back (for [`kernel::BackToBack`]):
    /// rotor lengths repeated, and the chain's springs followed by a joining spring (stiffness 0,
    /// its outputs dropped by the drivers) after every copy but the last.
    fn tiled(&self, count: usize) -> [Vec<f64>; 3] {
        let joined = |values: &[f64], join: f64| {
            let mut tiled = Vec::with_capacity(count * (values.len() + 1));
            for c in 0..count {
                tiled.extend_from_slice(values);
                if c + 1 < count {
                    tiled.push(join);
                }
            }
            tiled
        };
        let l0 = self.rest_lengths.first().copied().unwrap_or(1.0);
        [self.rotor_lengths.repeat(count), joined(&self.stiffness, 0.0), joined(&self.rest_lengths, l0)]
    }

    /// The gradients (and, with `energies`, the energies) of whole configurations laid back to
    /// back, driven as one long chain ([`kernel::BackToBack`]) in blocks of about
    /// [`BATCH_ROTORS`] rotors, so that the tiled parameters stay in the L1 cache.
    #[track_caller]
    fn batch(&self, thetas: &[f64], out: &mut [f64], energies: Option<&mut [f64]>) {
        let n = self.dof_count();
        let count =
            crate::model::batch_count(n, thetas.len(), out.len(), energies.as_deref().map(<[f64]>::len));
        let per_block = (BATCH_ROTORS / n).clamp(1, count.max(1));
        // `per_block > 1` only where the chain made its tiles (`BATCH_ROTORS / n > 1`).
        let [rotor_lengths, stiffness, rest_lengths] = if per_block == 1 {
            [&self.rotor_lengths, &self.stiffness, &self.rest_lengths]
        } else {
            self.tiles.0.each_ref()
        };
        let mut energies = energies.map(|e| e.chunks_mut(per_block));
        for (t, g) in thetas.chunks(per_block * n).zip(out.chunks_mut(per_block * n)) {
            let m = t.len() - 1;
            let springs = kernel::BackToBack {
                springs: kernel::SpringSlices {
                    a: self.a,
                    rotor_lengths: &rotor_lengths[..t.len()],
                    stiffness: &stiffness[..m],
                    rest_lengths: &rest_lengths[..m],
                },
                rotors: n,
            };
            use kernel::{harmonic, quartic};
            match (energies.as_mut().and_then(Iterator::next), self.law) {
                (Some(e), Law::Harmonic) => {
                    kernel::energies_and_gradients::<harmonic::EnergyGradient>(t, springs, e, g);
                }
                (Some(e), Law::Quartic) => {
                    kernel::energies_and_gradients::<quartic::EnergyGradient>(t, springs, e, g);
                }
                (None, Law::Harmonic) => kernel::assemble_pairs::<harmonic::Gradient>(t, springs, g),
                (None, Law::Quartic) => kernel::assemble_pairs::<quartic::Gradient>(t, springs, g),
            }
        }
    }

    /// [`crate::model::check_lengths`] for this chain (inlined: a few compares on the hot path).
    #[inline(always)]
    #[track_caller]
    fn check_lengths(&self, theta: &[f64], rotors: &[(&str, usize)], springs: &[(&str, usize)]) {
        crate::model::check_lengths(self.rotor_lengths.len(), theta.len(), rotors, springs);
    }
}

/// Runs kernel driver `$driver` on `$theta` with the kernel `$kernel` of the chain's law. Each
/// arm monomorphises the driver for that law's kernel, so the kernel inlines.
macro_rules! with_law {
    ($self:ident, $theta:ident, $driver:ident, $kernel:ident $(, $out:expr)*) => {{
        match $self.law {
            Law::Harmonic => kernel::$driver::<kernel::harmonic::$kernel>($theta, $self.springs() $(, $out)*),
            Law::Quartic => kernel::$driver::<kernel::quartic::$kernel>($theta, $self.springs() $(, $out)*),
        }
    }};
}

/// Rotors per block of a batch ([`RuntimeChain::batch`]): long enough that the loop's start and
/// end are a small part of it, short enough that its tiled parameters (24 bytes per rotor) stay
/// in the L1 cache.
const BATCH_ROTORS: usize = 1024;

impl Potential for RuntimeChain {
    fn dof_count(&self) -> usize {
        self.rotor_lengths.len()
    }

    fn inertia(&self, i: usize) -> f64 {
        let r = self.rotor_lengths[i];
        self.mass * r * r
    }

    #[track_caller]
    fn energy(&self, theta: &[f64]) -> f64 {
        self.check_lengths(theta, &[], &[]);
        with_law!(self, theta, sum, Energy)
    }

    #[track_caller]
    fn gradient_into(&self, theta: &[f64], out: &mut [f64]) {
        self.check_lengths(theta, &[("out", out.len())], &[]);
        with_law!(self, theta, assemble_pairs, Gradient, out)
    }

    // No `#[track_caller]` here, unlike its neighbours: with it the AVX2 energy + gradient of
    // `kernel_timing` (n = 60) ran 165 -> 169 ns, three runs alternating with a build without it;
    // the panic still names the slice and the counts, at this line.
    fn energy_and_gradient_into(&self, theta: &[f64], out: &mut [f64]) -> f64 {
        self.check_lengths(theta, &[("out", out.len())], &[]);
        with_law!(self, theta, energy_and_gradient, EnergyGradient, out)
    }

    #[track_caller]
    fn batch_gradient_into(&self, thetas: &[f64], out: &mut [f64]) {
        self.batch(thetas, out, None);
    }

    #[track_caller]
    fn batch_energy_and_gradient_into(&self, thetas: &[f64], energies: &mut [f64], out: &mut [f64]) {
        self.batch(thetas, out, Some(energies));
    }

    /// `1e-12 k_max a^2`: the energy of a spring stretched by a millionth of the lattice spacing.
    fn energy_floor(&self) -> f64 {
        crate::model::chain_energy_floor(self)
    }
}

impl Stiffness for RuntimeChain {
    fn stiffness_layout(&self) -> StiffnessLayout<'_> {
        StiffnessLayout::Tridiagonal
    }

    #[track_caller]
    fn tangent_stiffness_into(&self, theta: &[f64], values: &mut [f64]) {
        self.check_lengths(theta, &[], &[]);
        let (diag, off) = split_tridiagonal(theta.len(), values);
        with_law!(self, theta, assemble_blocks, Hessian, diag, off)
    }

    #[track_caller]
    fn energy_gradient_stiffness_into(&self, theta: &[f64], grad: &mut [f64], values: &mut [f64]) -> f64 {
        self.check_lengths(theta, &[("grad", grad.len())], &[]);
        let (diag, off) = split_tridiagonal(theta.len(), values);
        with_law!(self, theta, energy_gradient_stiffness, EnergyGradientHessian, grad, diag, off)
    }
}

impl SpringNetwork for RuntimeChain {
    fn spring_count(&self) -> usize {
        self.stiffness.len()
    }

    fn spring_constant(&self, p: usize) -> f64 {
        self.stiffness[p]
    }

    fn rest_length(&self, p: usize) -> f64 {
        self.rest_lengths[p]
    }

    #[track_caller]
    fn spring_lengths_into(&self, theta: &[f64], out: &mut [f64]) {
        self.check_lengths(theta, &[], &[("out", out.len())]);
        with_law!(self, theta, per_spring, Length, out)
    }

    #[track_caller]
    fn tensions_into(&self, theta: &[f64], out: &mut [f64]) {
        self.check_lengths(theta, &[], &[("out", out.len())]);
        with_law!(self, theta, per_spring, Tension, out)
    }

    fn compatibility_layout(&self) -> CompatibilityLayout<'_> {
        CompatibilityLayout::Bidiagonal
    }

    #[track_caller]
    fn compatibility_into(&self, theta: &[f64], values: &mut [f64]) {
        self.check_lengths(theta, &[], &[]);
        let (left, right) = split_bidiagonal(theta.len().saturating_sub(1), values);
        with_law!(self, theta, per_spring_pairs, Compatibility, left, right)
    }

    #[track_caller]
    fn material_stiffness_into(&self, theta: &[f64], values: &mut [f64]) {
        self.check_lengths(theta, &[], &[]);
        let (diag, off) = split_tridiagonal(theta.len(), values);
        with_law!(self, theta, assemble_blocks, Material, diag, off)
    }

    #[track_caller]
    fn stress_matrix_into(&self, theta: &[f64], values: &mut [f64]) {
        self.check_lengths(theta, &[], &[]);
        let (diag, off) = split_tridiagonal(theta.len(), values);
        with_law!(self, theta, assemble_blocks, Stress, diag, off)
    }
}

impl ChainGeometry for RuntimeChain {
    fn lattice_spacing(&self) -> f64 {
        self.a
    }
    fn rotor_length(&self, i: usize) -> f64 {
        self.rotor_lengths[i]
    }
    fn mass(&self) -> f64 {
        self.mass
    }
    fn theta_bar(&self) -> f64 {
        self.theta_bar
    }
}

impl ChainBuilder {
    /// Lattice spacing `a` (default 1).
    pub fn lattice_spacing(mut self, a: f64) -> Self {
        self.a = a;
        self
    }
    /// Tip mass `M` (default 1).
    pub fn mass(mut self, mass: f64) -> Self {
        self.mass = mass;
        self
    }
    /// Give the uniform state by the springs' rest length instead of `theta_bar`.
    pub fn rest_length(mut self, rest_length: f64) -> Self {
        self.uniform = Uniform::RestLength(rest_length);
        self
    }
    /// The spring law (default harmonic).
    pub fn law(mut self, law: Law) -> Self {
        self.law = law;
        self
    }
    /// Override spring `p`'s spring constant: an impurity in the stiffness, `k_p = k`.
    pub fn spring_constant(self, p: usize, k: f64) -> Self {
        self.spring(p, Some(k), None)
    }
    /// Override spring `p`'s rest length: an impurity in the length, `l0_p = l0`.
    pub fn spring_rest_length(self, p: usize, l0: f64) -> Self {
        self.spring(p, None, Some(l0))
    }
    /// Override spring `p`'s stiffness and/or rest length (`None` keeps the chain's value). At
    /// least one must be given, and each spring may be overridden once, all its values in one
    /// override, as the macro's `spring(p, k = .., l0 = ..)` ([`ChainBuilder::build`]).
    pub fn spring(mut self, p: usize, k: Option<f64>, l0: Option<f64>) -> Self {
        self.springs.push((p, k, l0));
        self
    }
    /// Override rotor `i`'s length (once per rotor).
    pub fn rotor(mut self, i: usize, r: f64) -> Self {
        self.rotors.push((i, r));
        self
    }

    /// Checks every parameter with the same rules as the macro's compile-time checks
    /// (`chain_geometry`), and allocates the chain.
    ///
    /// # Errors
    /// A [`ParameterError`] carrying the offending value: fewer than 2 or more than
    /// [`chain_geometry::MAX_ROTORS`] rotors, a parameter that is not finite and positive,
    /// `theta_bar` outside the flipper phase, an override of a spring or rotor that does not
    /// exist, that gives no value, or that repeats an earlier override of the same index
    /// (the macro rejects the same), or memory for the chain's parameters that cannot be
    /// allocated (never an abort).
    pub fn build(self) -> Result<RuntimeChain, ParameterError> {
        use chain_geometry as geo;
        let n = geo::check_rotor_count(self.n)?;
        let a = geo::check_positive(Key::LatticeSpacing, self.a)?;
        let r = geo::check_positive(Key::RotorLength, self.r)?;
        let k = geo::check_positive(Key::Stiffness, self.k)?;
        let mass = geo::check_positive(Key::Mass, self.mass)?;
        let (theta_bar, lbar) = match self.uniform {
            Uniform::ThetaBar(t) => {
                let t = geo::check_flipper_phase(a, r, t)?;
                (t, geo::rest_length(a, r, t))
            }
            Uniform::RestLength(l) => {
                let t = geo::theta_bar_from_rest_length(a, r, l)?;
                (geo::check_flipper_phase(a, r, t)?, l)
            }
        };
        let mut seen = BTreeSet::new();
        for &(i, ri) in &self.rotors {
            geo::check_override(IndexKind::Rotor, i, n, true, !seen.insert(i))?;
            geo::check_positive(Key::RotorLength, ri)?;
        }
        seen.clear();
        for &(p, kp, lp) in &self.springs {
            geo::check_override(IndexKind::Spring, p, n - 1, kp.is_some() || lp.is_some(), !seen.insert(p))?;
            if let Some(kp) = kp {
                geo::check_positive(Key::Stiffness, kp)?;
            }
            if let Some(lp) = lp {
                geo::check_positive(Key::RestLength, lp)?;
            }
        }
        let mut rotor_lengths = filled(n, r, n)?;
        let mut stiffness = filled(n - 1, k, n)?;
        let mut rest_lengths = filled(n - 1, lbar, n)?;
        for (i, ri) in self.rotors {
            rotor_lengths[i] = ri;
        }
        for (p, kp, lp) in self.springs {
            if let Some(kp) = kp {
                stiffness[p] = kp;
            }
            if let Some(lp) = lp {
                rest_lengths[p] = lp;
            }
        }
        let mut chain = RuntimeChain {
            a,
            mass,
            theta_bar,
            law: self.law,
            rotor_lengths,
            stiffness,
            rest_lengths,
            tiles: Tiles::default(),
        };
        let copies = BATCH_ROTORS / chain.dof_count().max(1);
        if copies > 1 {
            chain.tiles = Tiles(chain.tiled(copies));
        }
        Ok(chain)
    }
}

/// `len` copies of `value`, or the error of a chain of `n` rotors whose parameters (three vectors)
/// cannot be allocated.
fn filled(len: usize, value: f64, n: usize) -> Result<Vec<f64>, ParameterError> {
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| ParameterError::AllocationFailed { n, bytes: 3 * n * core::mem::size_of::<f64>() })?;
    v.resize(len, value);
    Ok(v)
}
