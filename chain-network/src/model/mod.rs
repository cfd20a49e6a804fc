//! The nonlinear mechanics of a finite patch (issue 36): [`NetworkModel`], built from a
//! [`Patch`] (free, or periodic with its bonds wrapped), node masses, a spring law and overrides,
//! implements chain-core's capability ladder ([`Potential`](chain_core::Potential),
//! [`Stiffness`](chain_core::Stiffness) in the `Upper` sparse layout,
//! [`SpringNetwork`](chain_core::SpringNetwork) in the `Sparse` compatibility layout), so the
//! relaxation, Newton, the modes, the counts at a prestressed state, Verlet, DOP853, damping and
//! the batches run on a network unchanged.
//!
//! # Coordinates
//! The degrees of freedom are numbered as the patch's columns (`Patch::column`): a joint's are its
//! **position** `(x, y)` (not its displacement), a rotor's is its **angle** `phi`,
//! counter-clockwise from `+x` (the cell format's convention). [`NetworkModel::reference`] is the
//! reference configuration. A joint's two degrees of freedom have its mass `M` as inertia, a
//! rotor's has `M r^2`. The compatibility matrix's rotor column is the tip's arc length
//! (`dl / d(r phi)`), as `SpringNetwork` and the linear analyses of this crate have it.
//!
//! # Evaluation
//! Bonds are grouped by type (joint-joint, joint-rotor, rotor-rotor; a rotor-joint bond is read
//! from its joint end) into structs of arrays, and each group is evaluated with the generated
//! kernels of [`crate::kernel`] (`bonds.rs`); every rotor's `sin_cos` is taken once per call.
//! The energy and gradient (every step of a run or a relaxation) evaluate several bonds at once
//! in vector lanes at the level chain-core's `simd` detects (`lanes.rs`), over runs of bonds whose
//! endpoints are contiguous in a structure-of-arrays copy of the coordinates (`stencil.rs`). The
//! passes are generic over the law's kernels and chosen when the model is built (`kernels.rs`).
//! Spring `p` of the model is bond `p` of the patch (`Patch::bonds`).

mod bonds;
mod build;
mod chain;
mod kernels;
mod lanes;
mod law;
mod stencil;
mod traits;

pub use build::NetworkModelBuilder;
pub use chain::ChainView;
pub use law::IntoBondLaw;

use crate::cell::{BondLaw, Polynomial};
use crate::patch::Patch;
use bonds::Group;
use law::Kernel;
use std::sync::OnceLock;

/// A finite patch of a network as a mechanical model. Build one with [`NetworkModel::builder`].
#[derive(Debug)]
pub struct NetworkModel {
    /// The checked-in kernel module of the springs' laws (`law.rs`).
    law: Kernel,
    /// The passes of the law's kernels (the checked-in ones of `law`, or the attribute's).
    kernels: kernels::Kernels,
    inertia: Vec<f64>,
    reference: Vec<f64>,
    /// The rotor index of each degree of freedom (`u32::MAX` for a joint's).
    rotor_of: Vec<u32>,
    /// The degree of freedom of each rotor.
    rotors: Vec<usize>,
    /// `(k, l0)` of each spring, in the patch's bond order.
    springs: Vec<[f64; 2]>,
    groups: [Group; 3],
    /// The bonds as runs over cells, for the hot path (`stencil.rs`).
    stencil: stencil::Stencil,
    length_scale: f64,
    stiffness: OnceLock<bonds::Upper>,
    compatibility: OnceLock<bonds::Rows>,
}

impl NetworkModel {
    /// A builder for the model of `patch` (unit masses, the cell's laws, constants and rest
    /// lengths, until changed).
    pub fn builder<'p, 'c>(patch: &'p Patch<'c>) -> NetworkModelBuilder<'p, 'c> {
        NetworkModelBuilder::new(patch)
    }

    /// The reference configuration: joint positions and rotor angles of the patch's cells, in the
    /// order of the degrees of freedom. At the cell's own rest lengths it is stress-free.
    pub fn reference(&self) -> Vec<f64> {
        self.reference.clone()
    }

    /// The law of spring `p` (the patch's bond `p`), or `None` past the last spring. A harmonic
    /// spring of a model that also has polynomial springs is reported as the polynomial `c2 = 1`
    /// it is evaluated as. A model built with the `#[rotor_network]` attribute's kernels reports
    /// the builder's law, not the attribute's. Looks the spring up among the bonds: O(bonds).
    pub fn spring_law(&self, p: usize) -> Option<BondLaw> {
        let (g, i) =
            self.groups.iter().find_map(|g| g.spring.iter().position(|&s| s == p).map(|i| (g, i)))?;
        Some(match self.law {
            Kernel::Harmonic => BondLaw::Harmonic,
            Kernel::Quartic => BondLaw::Quartic,
            Kernel::Polynomial => BondLaw::Polynomial(Polynomial { coefficients: g.coefficients[i] }),
        })
    }

    /// The number of rotors.
    pub fn rotor_count(&self) -> usize {
        self.rotors.len()
    }

    /// Whether degree of freedom `i` is a rotor's angle.
    pub fn is_rotor(&self, i: usize) -> bool {
        self.rotor_of[i] != u32::MAX
    }

    /// The bytes the model holds on the heap (its arrays' capacities; the sparse patterns once
    /// built by a stiffness or compatibility call included), for the memory per degree of
    /// freedom of docs/benchmarks.md.
    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of_val;
        let vecs = size_of_val(&self.inertia[..])
            + size_of_val(&self.reference[..])
            + size_of_val(&self.rotor_of[..])
            + size_of_val(&self.rotors[..])
            + size_of_val(&self.springs[..]);
        let groups: usize =
            self.groups.iter().map(|g| g.heap_bytes()).sum::<usize>() + self.stencil.heap_bytes();
        let upper = self.stiffness.get().map_or(0, |u| u.heap_bytes());
        let rows = self.compatibility.get().map_or(0, |r| r.heap_bytes());
        vecs + groups + upper + rows
    }

    /// The sines and cosines of the rotors' angles in `x`, rotor by rotor (empty without rotors).
    fn trig(&self, x: &[f64]) -> Vec<[f64; 2]> {
        if self.rotors.is_empty() {
            return Vec::new();
        }
        let angles: Vec<f64> = self.rotors.iter().map(|&d| x[d]).collect();
        let (mut s, mut c) = (vec![0.0; angles.len()], vec![0.0; angles.len()]);
        chain_core::simd::sin_cos_into(&angles, &mut s, &mut c);
        s.into_iter().zip(c).map(|(s, c)| [s, c]).collect()
    }

    /// Panics unless `x` has one value per degree of freedom and each of `outputs` the length
    /// it names: a wrong length is a programming error of the caller.
    #[track_caller]
    fn check(&self, x: usize, outputs: &[(&str, usize, usize)]) {
        let n = self.inertia.len();
        assert!(x == n, "x has {x} values, the network has {n} degrees of freedom");
        for &(name, found, expected) in outputs {
            assert!(found == expected, "{name} has {found} values, expected {expected}");
        }
    }
}
